#include "libcam/camera/simd.hpp"

#include <atomic>
#include <cstdlib>
#include <string>

#include "libcam/error.hpp"

namespace libcam {

namespace {

constexpr int kNotForced = -1;
std::atomic<int> forced_target{kNotForced};

bool cpu_runs(SimdTarget target) {
#if defined(__x86_64__) && defined(__GNUC__)
    switch (target) {
        case SimdTarget::Sse2: return true;
        // libgcc's checks include the operating system's support (the saved register state).
        case SimdTarget::Avx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
        case SimdTarget::Avx512:
            return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                   __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
                   __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }
    return false;
#else
    return target == SimdTarget::Sse2;
#endif
}

std::string target_list() {
    std::string names;
    for (SimdTarget target : kSimdTargets) {
        if (!simd_target_compiled(target)) continue;
        names += (names.empty() ? "" : ", ") + std::string(simd_target_name(target));
    }
    return names;
}

void require_supported(SimdTarget target, const std::string& field) {
    if (!simd_target_compiled(target)) {
        throw InvalidArgument(field + ": " + std::string(simd_target_name(target)) +
                              " is not compiled into this build (it has " + target_list() + ")");
    }
    if (!cpu_runs(target)) {
        throw InvalidArgument(field + ": " + std::string(simd_target_name(target)) + " is not supported by this CPU");
    }
}

SimdTarget best_supported() {
    SimdTarget best = SimdTarget::Sse2;
    for (SimdTarget target : kSimdTargets) {
        if (simd_target_supported(target)) best = target;
    }
    return best;
}

// LIBCAM_SIMD's target, read once.
std::optional<SimdTarget> environment_target() {
    static const std::optional<SimdTarget> target = []() -> std::optional<SimdTarget> {
        const char* value = std::getenv("LIBCAM_SIMD");
        if (value == nullptr || *value == '\0') return std::nullopt;
        const std::optional<SimdTarget> named = simd_target_from_name(value);
        if (!named) {
            throw InvalidArgument("LIBCAM_SIMD: '" + std::string(value) + "' is not one of " + target_list());
        }
        require_supported(*named, "LIBCAM_SIMD");
        return named;
    }();
    return target;
}

}  // namespace

std::optional<SimdTarget> simd_target_from_name(std::string_view name) {
    for (SimdTarget target : kSimdTargets) {
        if (simd_target_name(target) == name) return target;
    }
    return std::nullopt;
}

bool simd_target_compiled(SimdTarget target) {
#if defined(LIBCAM_SIMD_DISPATCH)
    (void)target;
    return true;
#else
    return target == SimdTarget::Sse2;
#endif
}

bool simd_target_supported(SimdTarget target) { return simd_target_compiled(target) && cpu_runs(target); }

std::vector<SimdTarget> supported_simd_targets() {
    std::vector<SimdTarget> targets;
    for (SimdTarget target : kSimdTargets) {
        if (simd_target_supported(target)) targets.push_back(target);
    }
    return targets;
}

SimdTarget simd_target() {
    const int forced = forced_target.load(std::memory_order_relaxed);
    if (forced != kNotForced) return static_cast<SimdTarget>(forced);
    if (const std::optional<SimdTarget> from_environment = environment_target()) return *from_environment;
    static const SimdTarget best = best_supported();
    return best;
}

void set_simd_target(std::optional<SimdTarget> target) {
    if (target) require_supported(*target, "SIMD target");
    forced_target.store(target ? static_cast<int>(*target) : kNotForced, std::memory_order_relaxed);
}

}  // namespace libcam
