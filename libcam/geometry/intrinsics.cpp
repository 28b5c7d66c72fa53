#include "libcam/geometry/intrinsics.hpp"

#include <cmath>
#include <limits>
#include <utility>
#include <string>

#include "libcam/error.hpp"

namespace libcam {

Mat3 Intrinsics::K() const {
    Mat3 K;
    K << fx, skew, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
    return K;
}

Intrinsics Intrinsics::from_K(const Mat3& K, const char* field) {
    require_finite_all(field, K);
    auto expect = [&](int row, int col, double value) {
        if (K(row, col) != value) {
            throw InvalidArgument(std::string(field) + "[" + std::to_string(row) + "][" +
                                  std::to_string(col) + "]: must be " + format_number(value) +
                                  " in an intrinsic matrix, got " + format_number(K(row, col)));
        }
    };
    expect(1, 0, 0.0);
    expect(2, 0, 0.0);
    expect(2, 1, 0.0);
    expect(2, 2, 1.0);
    Intrinsics intrinsics{K(0, 0), K(1, 1), K(0, 2), K(1, 2), K(0, 1)};
    intrinsics.validate(field);
    return intrinsics;
}

void Intrinsics::validate(const char* field) const {
    // The common case first, without building a message: Camera checks K on every call.
    const bool finite = std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy) &&
                        std::isfinite(skew);
    // A focal length is divided by (normalized_from_pixel): a subnormal one (5e-324) passes
    // "> 0" but has no finite inverse, so the smallest is the smallest normal number.
    constexpr double kSmallest = std::numeric_limits<double>::min();
    if (finite && fx >= kSmallest && fy >= kSmallest) return;
    const std::string prefix(field);
    require_finite((prefix + ".fx").c_str(), fx);
    require_finite((prefix + ".fy").c_str(), fy);
    require_finite((prefix + ".cx").c_str(), cx);
    require_finite((prefix + ".cy").c_str(), cy);
    require_finite((prefix + ".skew").c_str(), skew);
    if (!(fx > 0.0)) throw InvalidArgument(prefix + ".fx: must be > 0, got " + format_number(fx));
    if (!(fy > 0.0)) throw InvalidArgument(prefix + ".fy: must be > 0, got " + format_number(fy));
    for (const auto& [name, value] : {std::pair{".fx", fx}, std::pair{".fy", fy}}) {
        if (value < kSmallest) {
            throw InvalidArgument(prefix + name + ": " + format_number(value) + " is subnormal (a focal length must be at least " +
                                  format_number(kSmallest) + ")");
        }
    }
}

}  // namespace libcam
