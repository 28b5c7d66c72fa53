// The batch kernels for one instruction set: included once by each of
// kernels_sse2.cpp, kernels_avx2.cpp and kernels_avx512.cpp, which define
// LIBCAM_KERNEL_TARGET (sse2, avx2, avx512) and LIBCAM_KERNEL_TARGET_ENUM first.
//
// How one source gives three instruction sets safely. Every header is included first,
// outside the target region, so that their inline functions (Eigen, the lens models,
// Lane) are compiled for the portable baseline wherever they are not inlined: the
// linker keeps one copy of each, and a copy built for AVX2 would crash a CPU without
// it. Then `#pragma GCC target` compiles the kernels (projector_kernel.inl,
// unprojector_kernel.inl, map_kernel.inl), in a namespace of their own, for the target:
// GCC inlines the baseline functions into them (a function may take in one built for a
// subset of its instruction set) and vectorises the loops over points at the target's
// width. The command line's -mavx2 would instead compile every inline function of the
// file for AVX2. A helper the loops call per point must therefore be inlined into them
// (gnu::always_inline where GCC might not: a call would run the baseline's scalar copy).
//
// The kernel files are compiled with -ffp-contract=off (libcam/CMakeLists.txt): GCC would
// otherwise fuse a * b + c into one FMA instruction where the target has it, which
// rounds once instead of twice, and the targets would give different bits.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "libcam/camera/detail/batch_kernels.hpp"
#include "libcam/camera/detail/kernels.hpp"
#include "libcam/camera/detail/point_scale.hpp"
#include "libcam/camera/detail/unprojector_domain.hpp"
#include "libcam/camera/detail/unprojector_table.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_models.hpp"
#include "libcam/lens/undistort.hpp"

#if !defined(LIBCAM_KERNEL_TARGET) || !defined(LIBCAM_KERNEL_TARGET_ENUM)
#error "define LIBCAM_KERNEL_TARGET and LIBCAM_KERNEL_TARGET_ENUM before including kernels_for_target.hpp"
#endif

#if defined(LIBCAM_KERNEL_PRAGMA)
#define LIBCAM_PRAGMA(text) _Pragma(#text)
#define LIBCAM_TARGET_PRAGMA(isa) LIBCAM_PRAGMA(GCC target(isa))
#pragma GCC push_options
LIBCAM_TARGET_PRAGMA(LIBCAM_KERNEL_PRAGMA)
#endif

namespace libcam::kernels::LIBCAM_KERNEL_TARGET {
namespace {

using namespace libcam::detail;

#include "libcam/camera/detail/projector_kernel.inl"
#include "libcam/camera/detail/unprojector_kernel.inl"
#include "libcam/camera/detail/map_kernel.inl"

}  // namespace
}  // namespace libcam::kernels::LIBCAM_KERNEL_TARGET

#if defined(LIBCAM_KERNEL_PRAGMA)
#pragma GCC pop_options
#endif

// Outside the region: the table that hands the kernels to the baseline code.
namespace libcam::kernels {

template <>
const KernelSet<float>& compiled_kernels<SimdTarget::LIBCAM_KERNEL_TARGET_ENUM, float>() {
    static constexpr KernelSet<float> set{&LIBCAM_KERNEL_TARGET::project<float, LIBCAM_KERNEL_TARGET::Layout::Arrays>,
                                          &LIBCAM_KERNEL_TARGET::project<float, LIBCAM_KERNEL_TARGET::Layout::Interleaved>,
                                          &LIBCAM_KERNEL_TARGET::unproject<float>,
                                          &LIBCAM_KERNEL_TARGET::map<float>};
    return set;
}

template <>
const KernelSet<double>& compiled_kernels<SimdTarget::LIBCAM_KERNEL_TARGET_ENUM, double>() {
    static constexpr KernelSet<double> set{&LIBCAM_KERNEL_TARGET::project<double, LIBCAM_KERNEL_TARGET::Layout::Arrays>,
                                           &LIBCAM_KERNEL_TARGET::project<double, LIBCAM_KERNEL_TARGET::Layout::Interleaved>,
                                           &LIBCAM_KERNEL_TARGET::unproject<double>,
                                           &LIBCAM_KERNEL_TARGET::map<double>};
    return set;
}

}  // namespace libcam::kernels
