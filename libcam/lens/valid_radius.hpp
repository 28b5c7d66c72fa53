#pragma once
// Where a radial distortion stops being one-to-one. A radial model maps the undistorted
// radius r to the distorted one
//
//     d(r) = r P(r^2) / Q(r^2)       (P, Q polynomials with P(0) = Q(0) = 1)
//
// (OpenCV's rational model: P = 1 + k1 s + k2 s^2 + k3 s^3, Q = 1 + k4 s + k5 s^2 + k6 s^3;
// Kannala-Brandt: r is the angle theta, P = 1 + k1 s + ... + k4 s^4, Q = 1). Past the
// first r where d'(r) = 0 the image folds over: two rays land on one pixel, and past a
// root of Q the model has a pole. See "On the Maximum Radius of Polynomial Lens
// Distortion" (Leotta et al., WACV 2022). The model is valid only below that radius.
//
// d'(r) = N(r^2) / Q(r^2)^2 with N(s) = (P(s) + 2 s P'(s)) Q(s) - 2 s P(s) Q'(s), and
// N(0) = 1 > 0, so the valid radius is sqrt of the smallest positive root of N or Q.

#include <span>

namespace libcam {

// The smallest r > 0 where d'(r) reaches 0 or Q(r^2) reaches 0; +infinity if there is
// none. Coefficients in increasing powers of s = r^2, each starting with 1. A double
// root of N (d' touching 0 without changing sign) counts as a bound too: conservative.
double radial_valid_radius(std::span<const double> p, std::span<const double> q);

// The smallest positive real root of the polynomial c0 + c1 s + c2 s^2 + ...; +infinity
// if there is none.
double smallest_positive_root(std::span<const double> coefficients);

}  // namespace libcam
