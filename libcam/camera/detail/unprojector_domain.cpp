// What unprojector_domain.hpp declares: the parts that are not templates on the model.

#include "libcam/camera/detail/unprojector_domain.hpp"

#include <algorithm>

namespace libcam::detail {

const RingDirections& ring_directions() {
    static const RingDirections directions;
    return directions;
}

double largest_corner_radius(const Camera& camera) {
    const double right = static_cast<double>(camera.size.width) - 0.5;
    const double bottom = static_cast<double>(camera.size.height) - 0.5;
    double largest = 0;
    for (const Vec2& corner : {Vec2(-0.5, -0.5), Vec2(right, -0.5), Vec2(-0.5, bottom), Vec2(right, bottom)}) {
        largest = std::max(largest, camera.intrinsics.normalized_from_pixel(corner).norm());
    }
    return largest;
}

DomainRim rim_by_angle(const std::vector<Vec2>& rim) {
    const std::size_t n = rim.size();
    double turned = 0;
    std::size_t first = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& a = rim[k];
        const Vec2& b = rim[(k + 1) % n];
        const double step = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // angle from a to b
        if (!(step > 0)) return {};
        turned += step;
        if (std::atan2(b.y(), b.x()) < std::atan2(rim[first].y(), rim[first].x())) first = (k + 1) % n;
    }
    if (std::abs(turned - 2 * std::numbers::pi) > 1e-6) return {};
    DomainRim out;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& m = rim[(first + k) % n];
        out.angle.push_back(std::atan2(m.y(), m.x()));
        out.radius.push_back(m.norm());
    }
    out.angle.insert(out.angle.begin(), out.angle.back() - 2 * std::numbers::pi);
    out.radius.insert(out.radius.begin(), out.radius.back());
    out.angle.push_back(out.angle[1] + 2 * std::numbers::pi);
    out.radius.push_back(out.radius[1]);
    return out;
}

bool beyond_rim(const DomainRim& rim, const Vec2& m) {
    if (rim.angle.empty()) return false;
    const double angle = std::atan2(m.y(), m.x());
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(rim.angle.begin(), rim.angle.end(), angle) - rim.angle.begin());
    if (i == 0 || i >= rim.angle.size()) return false;
    const double t = (angle - rim.angle[i - 1]) / (rim.angle[i] - rim.angle[i - 1]);
    const double radius = rim.radius[i - 1] + t * (rim.radius[i] - rim.radius[i - 1]);
    return m.norm() > radius * (1 + 1e-4);
}

}  // namespace libcam::detail
