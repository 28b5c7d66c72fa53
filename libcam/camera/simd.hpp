#pragma once
// The instruction sets the batch engine (Projector, Unprojector, and what is built on
// them: rays, ray images, remap maps) is compiled for, and the one it runs on.
//
// The portable build runs on any x86-64, whose vector unit is SSE2 (two doubles or four
// floats per instruction). Its batch kernels are compiled three times: for SSE2, for
// AVX2 with FMA (four doubles), and for AVX-512 (eight), and each batch call runs the
// best set this CPU has. Every set computes each point with the same IEEE operations in
// the same order (no fused multiply-add: see camera/detail/kernels_for_target.hpp), so every
// target gives the same bits, and the same bits as the one-point calls.
//
// A target can be forced, for tests and for measuring one against another: by the
// environment variable LIBCAM_SIMD (sse2, avx2 or avx512) read at the first batch
// call, or by set_simd_target() at any time.

#include <optional>
#include <string_view>
#include <vector>

namespace libcam {

enum class SimdTarget { Sse2, Avx2, Avx512 };

inline constexpr SimdTarget kSimdTargets[] = {SimdTarget::Sse2, SimdTarget::Avx2, SimdTarget::Avx512};

constexpr std::string_view simd_target_name(SimdTarget target) {
    switch (target) {
        case SimdTarget::Sse2: return "sse2";
        case SimdTarget::Avx2: return "avx2";
        case SimdTarget::Avx512: return "avx512";
    }
    return "?";
}

std::optional<SimdTarget> simd_target_from_name(std::string_view name);

// Whether this build has kernels for the target (builds for another CPU family, the
// sanitizer builds and -march=native builds have one set, called sse2).
bool simd_target_compiled(SimdTarget target);

// Whether the target is compiled and this CPU and operating system run it.
bool simd_target_supported(SimdTarget target);

// The supported targets, SSE2 first.
std::vector<SimdTarget> supported_simd_targets();

// The target the batch calls use: the forced one, else LIBCAM_SIMD's, else the best
// supported. Throws InvalidArgument when LIBCAM_SIMD names no target or one this CPU
// does not run.
SimdTarget simd_target();

// Forces a target for every later batch call (nullopt: back to LIBCAM_SIMD or the best).
// Throws InvalidArgument for a target this CPU does not run. Not meant to be called
// while another thread runs a batch call (that call may use either target; both give
// the same bits).
void set_simd_target(std::optional<SimdTarget> target);

}  // namespace libcam
