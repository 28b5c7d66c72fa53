#pragma once
// The lenses the generic lens-model harness (test_lens_harness.cpp) runs on: every example
// camera of lens_cases.hpp (a mild and a strong lens per model, the real wide lens; under
// the sanitizers the first of each model, lens_cases.hpp's sanitized_subset) and
// the radial-only lenses of fold_cases() that fold over inside the image. A model added
// to the table needs only its example cameras added to lens_cases(); the harness refuses
// a row without one.
//
// Also the fold-over radius worked by hand for the lenses whose radial part has a
// single coefficient, an expected value independent of the library's root search.

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "lens_cases.hpp"

namespace libcam::test {

inline std::vector<LensCase> harness_cases() {
    std::vector<LensCase> cases = sanitized_subset(lens_cases());
    for (const FoldCase& fold : fold_cases()) cases.push_back({fold.name, fold.camera});
    return cases;
}

// Whether every coefficient but `index` is zero.
inline bool only_nonzero(const std::vector<double>& coefficients, std::size_t index) {
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
        if ((i == index) != (coefficients[i] != 0)) return false;
    }
    return true;
}

// The fold-over radius of a lens whose distortion is one radial coefficient, by hand;
// nullopt for any other lens.
//   OpenCV's models, k1 < 0 alone: d(r) = r (1 + k1 r^2), d'(r) = 1 + 3 k1 r^2 = 0 at
//     r = sqrt(-1 / (3 k1)). For k1 = -0.5: d/dr (r - 0.5 r^3) = 1 - 1.5 r^2 = 0 at sqrt(2/3).
//   OpenCV's rational models, k4 > 0 alone: d(r) = r / (1 + k4 r^2),
//     d'(r) = (1 - k4 r^2) / (1 + k4 r^2)^2 = 0 at r = 1 / sqrt(k4).
//   FISHEYE, k1 < 0 alone: theta_d = theta (1 + k1 theta^2), the same root in theta, if
//     below pi (FISHEYE's bound when it does not fold).
inline std::optional<double> hand_worked_fold_radius(const LensInfo& info, const Lens& lens) {
    const std::vector<double>& k = lens.coefficients;
    constexpr std::size_t kK1 = 0, kK4 = 5;  // OpenCV's order: k1 k2 p1 p2 k3 k4 ...
    const bool k1_alone = !k.empty() && only_nonzero(k, kK1) && k[kK1] < 0;
    if (info.family == LensFamily::Perspective) {
        if (k1_alone) return std::sqrt(-1 / (3 * k[kK1]));
        if (k.size() > kK4 && only_nonzero(k, kK4) && k[kK4] > 0) return 1 / std::sqrt(k[kK4]);
    }
    if (info.family == LensFamily::Fisheye && k1_alone) {
        const double theta = std::sqrt(-1 / (3 * k[kK1]));
        if (theta < std::numbers::pi) return theta;
    }
    return std::nullopt;
}

}  // namespace libcam::test
