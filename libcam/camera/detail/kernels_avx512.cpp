// The batch kernels for AVX-512 (F, DQ, VL, BW: x86-64-v4): eight doubles or sixteen
// floats per instruction. GCC's default tuning keeps loops at 256 bits even with
// AVX-512; the whole width is asked for.
#define LIBCAM_KERNEL_TARGET avx512
#define LIBCAM_KERNEL_TARGET_ENUM Avx512
#define LIBCAM_KERNEL_PRAGMA "avx2,fma,avx512f,avx512dq,avx512vl,avx512bw,prefer-vector-width=512"
#include "libcam/camera/detail/kernels_for_target.hpp"
