#pragma once
// Internal to libcam (camera/unprojector.cpp): filling an array with one value at the
// full store width of the CPU it runs on. The portable build's own loops store 16 bytes
// at a time (SSE2); memset, dispatched by glibc, stores 64 on a CPU with AVX-512, and for
// a frame of rays that stays in the cache that is twice the speed.

#include <cstddef>

namespace libcam::detail {

void fill_values(float* out, std::size_t n, float value);
void fill_values(double* out, std::size_t n, double value);

}  // namespace libcam::detail
