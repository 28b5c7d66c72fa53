#pragma once
// Internal to libcam (camera/unprojector.cpp): where a lens's valid domain maps in the
// normalised image plane, worked out once per camera so that most pixels' validity is
// settled without the full solver.

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/camera/unprojector.hpp"

namespace libcam::detail {

// The largest |m| of the image's corners.
double largest_corner_radius(const Camera& camera);

// The rim as its radius against its polar angle, if every ray from the centre crosses it
// once (its angle increases all the way round); empty otherwise. Sorted by angle, with
// the last sample repeated before the first and the first after the last, 2 pi apart.
DomainRim rim_by_angle(const std::vector<Vec2>& rim);

// True when m lies past the rim by more than 0.01 % of its radius there.
bool beyond_rim(const DomainRim& rim, const Vec2& m);

// The radius R of the disc of undistorted points to certify: just inside the valid
// radius, or where that is unbounded, far enough for the radial part to reach twice the
// largest |m| in the image.
template <class Model>
double disc_to_certify(const Camera& camera, const typename Model::Parameters& lens) {
    if (std::isfinite(lens.valid_radius)) return lens.valid_radius * (1 - 1e-9);
    const double target = 2 * largest_corner_radius(camera);
    double radius = 1, slope = 0;
    for (int i = 0; i < 64 && Model::radial_distortion(lens, radius, slope) < target; ++i) radius *= 2;
    return radius;
}

// The image of the disc |u| <= radius under distort, sampled on 64 rings (the rim at 4096
// directions, the rings inside at 1024):
// the smallest |m| on its rim and the largest anywhere. nullopt where distort is not
// defined on the whole disc.
struct DiscImage {
    double rim_inner = std::numeric_limits<double>::infinity();
    double outer = 0;
    std::vector<Vec2> rim;  // the image of the circle itself, in the order of the angle
};

// The sampled directions' cosines and sines, worked out once for every ring and every
// disc (a lens whose domain is not a whole disc is sampled on up to 64 discs).
struct RingDirections {
    static constexpr int kAngles = 4096;
    std::vector<double> cosine, sine;
    RingDirections() : cosine(kAngles), sine(kAngles) {
        for (int a = 0; a < kAngles; ++a) {
            const double angle = 2 * std::numbers::pi * a / kAngles;
            cosine[static_cast<std::size_t>(a)] = std::cos(angle);
            sine[static_cast<std::size_t>(a)] = std::sin(angle);
        }
    }
};
const RingDirections& ring_directions();

template <class Model>
std::optional<DiscImage> image_of_disc(const typename Model::Parameters& lens, double radius) {
    constexpr int kRings = 64, kAngles = RingDirections::kAngles;
    const RingDirections& directions = ring_directions();
    DiscImage image;
    image.rim.reserve(kAngles);
    // The rim first: where distort is undefined on a disc it is most often undefined
    // there, and the disc is given up after one ring instead of the whole disc.
    // The rim is sampled at every direction (its samples are the rim the caller keeps);
    // the rings inside, which give only the largest |m| and whether distort is defined,
    // at every fourth: 1024 directions, 6e-3 rad apart, still finer than the rings'
    // own spacing (1/64 of the radius), which is what bounds how far a sample can miss
    // the largest |m|. A quarter of the work (`libcam info` works this out once per
    // calibration, and a project can hold a hundred).
    constexpr std::size_t kInsideStride = 4;
    for (int ring = kRings; ring >= 1; --ring) {
        const double r = radius * ring / kRings;
        const std::size_t stride = ring == kRings ? 1 : kInsideStride;
        for (std::size_t a = 0; a < static_cast<std::size_t>(kAngles); a += stride) {
            Vec2 m;
            if (!Model::distort(lens, Vec2(r * directions.cosine[a], r * directions.sine[a]), m)) return std::nullopt;
            if (ring == kRings) {
                image.rim_inner = std::min(image.rim_inner, m.norm());
                image.rim.push_back(m);
            }
            image.outer = std::max(image.outer, m.norm());
        }
    }
    return image;
}

// Radii of normalised points that settle validity without the full solver:
//  - every m with |m| < certified has a ray in the valid domain. Why: distort is
//    continuous on a disc |u| <= R inside the domain and maps 0 to 0; the image C of
//    the circle |u| = R winds once around 0 (the model's own premise that the terms
//    beyond the radial one are small) and keeps a distance min |C| from it, so the disc
//    |m| < min |C| lies inside C, and each of its points has a preimage with |u| < R
//    (the degree of the map);
//  - no m with |m| > no_ray has one: the whole valid domain maps inside |m| <= no_ray
//    (known only for a bounded domain; infinite otherwise);
//  - no m past the rim (the image of the domain's edge, when it is star-shaped) has one.
// The radii are 0.1 % inside the sampled extremes, which covers the map between samples
// many times over. certified is 0 if no disc can be certified.
struct DomainBounds {
    double certified = 0;
    double no_ray = std::numeric_limits<double>::infinity();
    DomainRim rim;
};



template <class Model>
DomainBounds domain_bounds(const Camera& camera, const typename Model::Parameters& lens) {
    DomainBounds bounds;
    double radius = disc_to_certify<Model>(camera, lens);
    for (int attempt = 0; attempt < 64; ++attempt, radius *= 0.9) {
        if (const std::optional<DiscImage> image = image_of_disc<Model>(lens, radius)) {
            bounds.certified = image->rim_inner * (1 - 1e-3);
            // The disc is the whole domain only if it is the valid radius itself.
            if (attempt == 0 && std::isfinite(lens.valid_radius)) {
                bounds.no_ray = image->outer * (1 + 1e-3);
                bounds.rim = rim_by_angle(image->rim);
            }
            return bounds;
        }
    }
    return bounds;
}

}  // namespace libcam::detail
