// The batch kernels for the portable baseline: the build's own flags (SSE2 on x86-64).
#define LIBCAM_KERNEL_TARGET sse2
#define LIBCAM_KERNEL_TARGET_ENUM Sse2
#include "libcam/camera/detail/kernels_for_target.hpp"
