#include "libcam/camera/detail/fill_values.hpp"

// GCC compiles each function below for AVX-512, AVX2 and plain x86-64 and picks one
// when the program is loaded (target_clones). The loops call nothing, so no inline
// function is ever compiled for an instruction set the CPU may lack.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define LIBCAM_FOR_EVERY_X86_WIDTH __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define LIBCAM_FOR_EVERY_X86_WIDTH
#endif

namespace libcam::detail {

LIBCAM_FOR_EVERY_X86_WIDTH void fill_values(float* out, std::size_t n, float value) {
    for (std::size_t i = 0; i < n; ++i) out[i] = value;
}

LIBCAM_FOR_EVERY_X86_WIDTH void fill_values(double* out, std::size_t n, double value) {
    for (std::size_t i = 0; i < n; ++i) out[i] = value;
}

}  // namespace libcam::detail
