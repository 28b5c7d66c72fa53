#pragma once
// For the test mains: the engine's tests run once more per instruction set, with
// LIBCAM_SIMD naming it (tests/CMakeLists.txt). On a CPU without that set the program
// says so and exits with 77, which ctest counts as skipped.

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "libcam/camera/simd.hpp"

namespace libcam::test {

// 77 when LIBCAM_SIMD names a target this build or CPU does not run, else 0.
inline int skip_code_for_simd_target() {
    const char* value = std::getenv("LIBCAM_SIMD");
    if (value == nullptr || *value == '\0') return 0;
    const std::optional<SimdTarget> target = simd_target_from_name(value);
    if (target && simd_target_supported(*target)) {
        std::printf("batch kernels: %s (LIBCAM_SIMD)\n", value);
        return 0;
    }
    std::printf("skipped: LIBCAM_SIMD=%s is not compiled into this build or not run by this CPU\n", value);
    return 77;
}

}  // namespace libcam::test
