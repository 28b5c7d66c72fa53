// The batch kernels for AVX2 with FMA (x86-64-v3): four doubles or eight floats per
// instruction.
#define LIBCAM_KERNEL_TARGET avx2
#define LIBCAM_KERNEL_TARGET_ENUM Avx2
#define LIBCAM_KERNEL_PRAGMA "avx2,fma"
#include "libcam/camera/detail/kernels_for_target.hpp"
