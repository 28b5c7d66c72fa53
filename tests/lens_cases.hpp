#pragma once
// The cameras the lens-model tests run on: for each model a mild and a strong lens, and
// the real wide lens (6016x4016, OPENCV8). Inputs only; expected values come from OpenCV, mrcal or
// formulas worked by hand in the tests.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <opencv2/calib3d.hpp>
#include <string>
#include <vector>

#include "colmap_reference.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/convert/colmap_models.hpp"
#include "libcam/camera/example_cameras.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/lens/lens_models.hpp"
#include "unified_reference.hpp"

namespace libcam::test {

struct LensCase {
    std::string name;
    Camera camera;
};

inline Camera lens_camera(LensType type, std::vector<double> coefficients, ImageSize size = {1600, 1200},
                          double fx = 900.0, double fy = 910.0) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = {fx, fy, 0.5 * static_cast<double>(size.width - 1) + 13.0,
                         0.5 * static_cast<double>(size.height - 1) - 7.0, 0.0};
    camera.lens = {type, std::move(coefficients)};
    return camera;
}

// A camera with a real calibration's K (fx, fy, cx, cy) and lens.
inline Camera real_camera(LensType type, std::vector<double> coefficients, ImageSize size, std::array<double, 4> k) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = {k[0], k[1], k[2], k[3], 0.0};
    camera.lens = {type, std::move(coefficients)};
    return camera;
}

// An OCAMCALIB camera from the numbers of a calib_results.txt the OCamCalib toolbox
// wrote: pol a0..a4 (pixels, a0 < 0), the centre (row, column), the affine c d e and the
// image's height and width. The model's K is f = -a0 at the centre (column, row), its
// k_i = -a_i f^(i - 1) (libcam/lens/ocamcalib.hpp).
inline Camera ocamcalib_camera(std::array<double, 5> pol, double row, double column, std::array<double, 3> cde,
                               int height, int width) {
    const double f = -pol[0];
    std::vector<double> coefficients = {cde[0], cde[1], cde[2]};
    for (int i = 1; i <= 5; ++i) coefficients.push_back(i < 5 ? -pol[static_cast<std::size_t>(i)] * std::pow(f, i - 1) : 0.0);
    return real_camera(LensType::OcamCalib, coefficients, {width, height}, {f, f, column, row});
}

// An FTHETA camera from the numbers of a DriveWorks rig or NCore: the backward polynomial
// b0..b5 in pixels (b0 = 0), the principal point, the affine c d e, max_angle and the image
// size. The model's K is f = 1 / b1 at the principal point, its k_i = b_i f^i
// (libcam/lens/ftheta.hpp).
inline Camera ftheta_camera(std::array<double, 6> b, double cx, double cy, std::array<double, 3> cde, double max_angle,
                            int width, int height) {
    const double f = 1 / b[1];
    std::vector<double> coefficients = {cde[0], cde[1], cde[2]};
    for (int i = 1; i <= 5; ++i) coefficients.push_back(b[static_cast<std::size_t>(i)] * std::pow(f, i));
    coefficients.push_back(max_angle);
    return real_camera(LensType::FTheta, coefficients, {width, height}, {f, f, cx, cy});
}

// The real wide lens: 6016x4016, OPENCV8, fx 2074, k1 0.479, k4 0.767 (the library's
// example camera "wide", one copy for the command line, the benchmarks and the tests).
inline Camera wide_reference_camera() { return example_camera("wide"); }

// A SPLINED_STEREOGRAPHIC lens's coefficients (order, Nx, Ny, fov_x_deg, control
// points): at each knot u (the grid's spacing and centre as mrcal lays them out) the
// control point radial * u |u|^2 plus a wobble of the given size that varies from knot
// to knot, as a fitted spline's do.
inline std::vector<double> splined_coefficients(int order, int nx, int ny, int fov_x_deg, double radial, double wobble) {
    const double u_edge = 2 * std::tan(fov_x_deg / 4.0 * std::numbers::pi / 180);
    const double spacing = 2 * u_edge / (nx - 1 - (order == 2 ? 1 : 2));
    std::vector<double> k{double(order), double(nx), double(ny), double(fov_x_deg)};
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const double ux = (i - (nx - 1) / 2.0) * spacing, uy = (j - (ny - 1) / 2.0) * spacing;
            const double cubic = radial * (ux * ux + uy * uy);
            k.push_back(cubic * ux + wobble * std::sin(1.7 * i + 0.3 * j));
            k.push_back(cubic * uy + wobble * std::cos(0.9 * j - 1.1 * i));
        }
    }
    return k;
}

// Every model at mild and strong distortion (the strong ones fold over inside or near
// the image: the valid domain matters).
inline std::vector<LensCase> lens_cases() {
    std::vector<LensCase> cases{
        {"PINHOLE", lens_camera(LensType::Pinhole, {})},
        {"OPENCV4 mild", lens_camera(LensType::OpenCv4, {-0.05, 0.01, 2e-4, -3e-4})},
        {"OPENCV4 strong", lens_camera(LensType::OpenCv4, {-0.45, 0.05, 1.5e-3, -1e-3})},
        {"OPENCV5 mild", lens_camera(LensType::OpenCv5, {0.03, -0.01, -1e-4, 2e-4, 0.002})},
        {"OPENCV5 strong", lens_camera(LensType::OpenCv5, {-0.28, 0.07, 8e-4, -6e-4, -0.008})},
        {"OPENCV8 mild", lens_camera(LensType::OpenCv8, {0.1, 0.02, 1e-4, -1e-4, 0.001, 0.12, 0.015, 0.0005})},
        {"OPENCV8 wide", wide_reference_camera()},
        {"OPENCV12 mild", lens_camera(LensType::OpenCv12, {-0.04, 0.008, 1e-4, 1e-4, 0.0, 0.01, 0.0, 0.0, 1e-3, -2e-4,
                                                            -5e-4, 1e-4})},
        {"OPENCV12 strong", lens_camera(LensType::OpenCv12, {0.6, 0.05, 5e-4, -4e-4, 2e-4, 0.95, 0.15, 0.003, 4e-3,
                                                              -1e-3, -3e-3, 8e-4})},
        {"OPENCV14 mild", lens_camera(LensType::OpenCv14, {-0.04, 0.008, 1e-4, 1e-4, 0.0, 0.01, 0.0, 0.0, 1e-3, -2e-4,
                                                            -5e-4, 1e-4, 0.01, -0.02})},
        {"OPENCV14 strong", lens_camera(LensType::OpenCv14, {0.6, 0.05, 5e-4, -4e-4, 2e-4, 0.95, 0.15, 0.003, 4e-3,
                                                              -1e-3, -3e-3, 8e-4, -0.05, 0.04})},
        {"FISHEYE mild", lens_camera(LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}, {1600, 1200}, 420, 421)},
        {"FISHEYE strong", lens_camera(LensType::Fisheye, {0.08, -0.06, 0.012, -0.002}, {1600, 1200}, 300, 300)},
        {"STEREOGRAPHIC", lens_camera(LensType::Stereographic, {}, {1600, 1200}, 300, 310)},
        {"LONLAT", lens_camera(LensType::Lonlat, {}, {2000, 1000}, 318, 318)},
        {"LATLON", lens_camera(LensType::Latlon, {}, {1000, 2000}, 318, 318)},
        // basalt's calibrations of real cameras: EuRoC's cam0 (752x480, about 150
        // degrees) and TUM-VI's cam0 (512x512, about 195 degrees).
        {"DOUBLE_SPHERE mild", real_camera(LensType::DoubleSphere, {-0.2409573942178872, 0.566996899163044}, {752, 480},
                                           {349.7560023050409, 348.72454229977035, 365.89440762590147, 249.32995565708703})},
        {"DOUBLE_SPHERE strong",
         real_camera(LensType::DoubleSphere, {-0.17213086034353242, 0.5931177593944744}, {512, 512},
                     {158.28600034966976, 158.2743455478755, 254.96116578191652, 256.8894394501779})},
        // alpha below 1/2: every normalised point has a ray; the lens sees 136 degrees off the axis.
        {"DOUBLE_SPHERE alpha 0.4", lens_camera(LensType::DoubleSphere, {0.1, 0.4}, {1600, 1200}, 300, 300)},
        // UCM with xi and K of the MEI calibrations VINS-Fusion ships for a MYNT EYE
        // (xi 1.45) and EuRoC (xi 3.63), without their distortion: the pinhole outside the
        // sphere, the rim 858 and 612 px from the centre; and xi 0.8, an unbounded image.
        {"UCM xi 1.45", real_camera(LensType::Ucm, {1.4456544769803834}, {752, 480},
                                    {895.94371861807986, 897.41581479032754, 372.21680816143993, 238.33534175557006})},
        {"UCM xi 3.63", real_camera(LensType::Ucm, {3.6313355285286337}, {752, 480},
                                    {2138.7619122017772, 2131.5886210259278, 361.19856633263799, 248.27644773395667})},
        {"UCM xi 0.8", lens_camera(LensType::Ucm, {0.8}, {1600, 1200}, 400, 400)},
        // basalt's EUCM calibrations of the same two cameras as DOUBLE_SPHERE's above.
        {"EUCM mild", real_camera(LensType::Eucm, {0.5903365915227143, 1.127468196965374}, {752, 480},
                                  {460.76484651566468, 459.4051018049483, 365.8937161309615, 249.33499869752445})},
        {"EUCM strong", real_camera(LensType::Eucm, {0.6291060871161842, 1.0418067403139693}, {512, 512},
                                    {191.14799816648748, 191.13150946585135, 254.95857715233118, 256.8815466235898})},
        // alpha below 1/2 and beta below 1: an unbounded image.
        {"EUCM alpha 0.4", lens_camera(LensType::Eucm, {0.4, 0.7}, {1600, 1200}, 300, 300)},
        // The MEI calibrations VINS-Fusion ships (camodocal's files): a MYNT EYE (k1 < 0)
        // and EuRoC's cam0 (xi 3.63, k2 15.5); and xi 1 with a mild distortion, an
        // unbounded image (q = tan(theta / 2) in the direction of the point: stereographic).
        // (For xi < 1 the denominator of q cancels near the domain's edge, where no
        // evaluation in float comes within the harness's 16 eps of double: the extremes
        // tests measure such points against their condition number.)
        {"MEI xi 1.45", real_camera(LensType::Mei,
                                    {1.4456544769803834, -0.34363053357673362, 0.062347376791548004,
                                     0.0012608078788285675, -0.00021374139252651483},
                                    {752, 480}, {895.94371861807986, 897.41581479032754, 372.21680816143993, 238.33534175557006})},
        {"MEI xi 3.63", real_camera(LensType::Mei,
                                    {3.6313355285286337, 1.1757726639872075, 15.491281051140213,
                                     -0.00081237172954550494, 0.00067297684030310243},
                                    {752, 480}, {2138.7619122017772, 2131.5886210259278, 361.19856633263799, 248.27644773395667})},
        {"MEI xi 1", lens_camera(LensType::Mei, {1.0, -0.05, 0.01, 1e-3, -5e-4}, {1600, 1200}, 400, 400)},
        // basalt's FOV test camera (basalt-headers' LookAtCamera::getTestProjections, 752x480);
        // a mild lens; and omega 2.5, whose image disc |m| < pi / omega reaches 180 degrees.
        {"FOV basalt", real_camera(LensType::Fov, {0.9259487501905697}, {752, 480}, {379.045, 379.008, 505.512, 509.969})},
        {"FOV mild", lens_camera(LensType::Fov, {0.3}, {1600, 1200}, 900, 910)},
        {"FOV wide", lens_camera(LensType::Fov, {2.5}, {1600, 1200}, 250, 250)},
        // DIVISION: a mild barrel lens (k of RealityCapture's size, made up), a strong one
        // whose ray turns past 90 degrees at |m| = 1 / sqrt(0.5) inside the image, and a
        // pincushion lens that folds at 1 / (2 sqrt(0.2)) = 1.118 (48.2 degrees off the axis).
        {"DIVISION mild", lens_camera(LensType::Division, {-0.05}, {1600, 1200}, 900, 905)},
        {"DIVISION barrel", lens_camera(LensType::Division, {-0.5}, {1600, 1200}, 400, 400)},
        {"DIVISION pincushion", lens_camera(LensType::Division, {0.2}, {1600, 1200}, 900, 900)},
        // COLMAP's model tests' parameters (models_test.cc: fx fy cx cy 651.123 655.123
        // 386.123 511.123 in COLMAP's pixels, whose centres are at +0.5, on the 800x800
        // grid those tests sweep); and the FIORD fisheye's KB4 coefficients (COLMAP
        // OPENCV_FISHEYE, 3264x3264) with small decentering and prism terms made up.
        {"THIN_PRISM_FISHEYE colmap", real_camera(LensType::ThinPrismFisheye,
                                                  {-0.471, 0.223, -0.001, 0.001, 0.001, 0.02, -0.02, 0.001},
                                                  {800, 800}, {651.123, 655.123, 385.623, 510.623})},
        {"THIN_PRISM_FISHEYE fiord", real_camera(LensType::ThinPrismFisheye,
                                                 {0.024943212941115993, 0.0049984956352712093, 2e-4, -1e-4,
                                                  -0.017541641442409061, 0.0045520708951808514, 3e-4, -2e-4},
                                                 {3264, 3264}, {991, 991, 1611.5, 1616.5})},
        // Strong decentering, made up: the valid radius is where p1 p2 sx1 sy1 could first
        // fold the image (about 1.1 rad), well inside the radial part's fold.
        {"THIN_PRISM_FISHEYE decentered",
         lens_camera(LensType::ThinPrismFisheye, {0.02, 0.005, 0.04, -0.03, -0.01, 0.002, 0.01, -0.01}, {1600, 1200},
                     300, 300)},
        {"RAD_TAN_THIN_PRISM_FISHEYE colmap",
         real_camera(LensType::RadTanThinPrismFisheye,
                     {-0.0232, 0.0924, -0.0591, 0.003, 0.0048, -0.0009, 0.0002, 0.0005, -0.0009, -0.0001, 0.00007, -0.00017},
                     {800, 800}, {651.123, 655.123, 385.623, 510.623})},
        {"RAD_TAN_THIN_PRISM_FISHEYE fiord",
         real_camera(LensType::RadTanThinPrismFisheye,
                     {0.024943212941115993, 0.0049984956352712093, -0.017541641442409061, 0.0045520708951808514, 0, 0,
                      -1e-4, 2e-4, 3e-4, -1e-5, -2e-4, 1e-5},
                     {3264, 3264}, {991, 991, 1611.5, 1616.5})},
        // Blender's default FISHEYE_EQUISOLID camera (10.5 mm on a 36 mm sensor across
        // 1920 px: f = 560 px), and a short one that sees far behind itself.
        {"EQUISOLID blender", real_camera(LensType::Equisolid, {}, {1920, 1080}, {560, 560, 959.5, 539.5})},
        {"EQUISOLID wide", lens_camera(LensType::Equisolid, {}, {1600, 1200}, 250, 250)},
        // mrcal's projection tests' CAHVOR (test-projections.py: a strong barrel lens,
        // 1 + r0 = 0.363, its axis tilted by 2 mrad), on the image its principal point
        // centres; and a made-up lens tilted by 22 mrad whose fold (t = 1.34, 53 degrees
        // off the axis) lies inside the image.
        {"CAHVOR mrcal", real_camera(LensType::Cahvor, {-0.001, 0.002, -0.637, -0.002, 0.016}, {3942, 2172},
                                     {4842.918, 4842.771, 1970.528, 1085.302})},
        {"CAHVOR folding", lens_camera(LensType::Cahvor, {0.02, -0.01, 0, -0.2, 0.005}, {1920, 1080}, 800, 800)},
        // mrcal's projection tests' CAHVORE (the CAHVOR above with E = 0.01 0.02 0.03 and a
        // linearity of 0.4), and a made-up fisheye, nearly equidistant (linearity 0.1: at
        // exactly 0 chi switches from sin to tan, so its derivative in the linearity is 0 but
        // a central difference across 0 is not), with a small tilt and entrance-pupil terms,
        // whose image corners lie past 90 degrees.
        {"CAHVORE mrcal", real_camera(LensType::Cahvore, {-0.001, 0.002, -0.637, -0.002, 0.016, 0.01, 0.02, 0.03, 0.4},
                                      {3942, 2172}, {4842.918, 4842.771, 1970.528, 1085.302})},
        {"CAHVORE fisheye", lens_camera(LensType::Cahvore, {0.003, -0.002, 0.0, 0.01, -0.001, 0.02, 0.01, 0.0, 0.1},
                                        {1600, 1200}, 400, 400)},
        // Blender's default FISHEYE_LENS_POLYNOMIAL (fitted by Blender to its 50 mm
        // perspective camera; m in mm: f = 1920 px / 36 mm), and a fisheye whose corners
        // lie 142 degrees off the axis (theta = 2e-6 + 0.09 r + 4e-5 r^3, 1600 px over 36
        // mm). Both have k0 != 0, as fitted polynomials do: the harness's differences in k0
        // then stay off the axis, where k0 = 0 would have a one-sided derivative.
        {"FISHEYE_LENS_POLYNOMIAL blender",
         real_camera(LensType::LensPolynomial,
                     {-1.1735143712967577e-05, -0.019988736953434998, -3.3525322965709175e-06, 3.099275275886036e-06,
                      -2.6064646454854524e-08},
                     {1920, 1080}, {1920.0 / 36, 1920.0 / 36, 959.5, 539.5})},
        {"FISHEYE_LENS_POLYNOMIAL fisheye", real_camera(LensType::LensPolynomial, {-2e-6, -0.09, 0.0, -4e-5, 0.0}, {1200, 1600},
                                                        {1600.0 / 36, 1600.0 / 36, 599.5, 799.5})},
        // mrcal's splined model: a cubic spline over 12 x 10 knots across 200 degrees
        // (barrel, corners 113 degrees off the axis) and a quadratic one over 11 x 9 knots
        // across 120 degrees (pincushion); see splined_coefficients. The quadratic's knot
        // counts are odd so that the axis, which the tests differentiate at, lies in the
        // middle of a patch: across a patch's edge a quadratic spline has no second
        // derivative, and central differences lose their accuracy there. mrcal's own
        // splined calibrations are checked in test_lens_models.
        {"SPLINED_STEREOGRAPHIC cubic", real_camera(LensType::SplinedStereographic,
                                                    splined_coefficients(3, 12, 10, 200, -0.01, 0.002), {1600, 1200},
                                                    {500, 500, 799.5, 599.5})},
        {"SPLINED_STEREOGRAPHIC quadratic", real_camera(LensType::SplinedStereographic,
                                                        splined_coefficients(2, 11, 9, 120, 0.03, 0.001), {800, 600},
                                                        {600, 600, 399.5, 299.5})},
        // A full turn across 2000 px (f = 318 px per radian: 360 degrees) and 57.5 degrees
        // up and down; and a 120 x 64 degree panorama of a 1920x1080 render.
        {"CYLINDRICAL 360", lens_camera(LensType::Cylindrical, {}, {2000, 1000}, 318, 318)},
        {"CYLINDRICAL 120", real_camera(LensType::Cylindrical, {}, {1920, 1080}, {916.7, 916.7, 959.5, 539.5})},
        // PTLENS: lensfun's calibrations rescaled as lensfun does
        // (rescale_polynomial_coefficients): the Pentax-F 28-80mm of slr-pentax.xml at
        // 30.89 mm on a crop-1.534 1500x1000 image (lensfun's regression test), and the
        // EF 24-70mm f/2.8L II at 24 mm (a = 0.02964, b = -0.07853, c = 0.02943, real
        // focal 24.46704, lensfun's test_modifier_coord_distortion) on a 6000x4000 full frame.
        {"PTLENS mild", real_camera(LensType::Ptlens, {-0.2533388789718433, 0.2053082153302514, -0.1273322761814234},
                                    {1500, 1000}, {2005.78304744325, 2005.78304744325, 749.5, 499.5})},
        {"PTLENS strong", real_camera(LensType::Ptlens, {0.23259372609028295, -0.3081239087359973, 0.0577364487081396},
                                      {6000, 4000}, {4077.84, 4077.84, 2999.5, 1999.5})},
        // OCamCalib's calibrations: a 640x400 fisheye (ches00/360-SL-Metasurface, 64
        // degrees off the axis at 200 px) and a catadioptric omnicam seeing 113 degrees off
        // the axis at 384 px (premnirmal/Homing-in-Scale-Space), with their affines.
        {"OCAMCALIB fisheye", ocamcalib_camera({-1.890172e+02, 0.0, 2.564080e-03, -5.912461e-06, 2.369445e-08},
                                               199.772421, 320.450876, {1.000124, -0.000228, -0.000155}, 400, 640)},
        {"OCAMCALIB omnicam", ocamcalib_camera({-1.534670e+02, 0.0, 1.034692e-03, 5.138226e-06, -5.694855e-09},
                                               382.828814, 456.345673, {1.000651, -0.000625, 0.000431}, 768, 1024)},
        // ---- THETA_POLYNOMIAL: WoodScape's published front camera (its
        // scripts/calibration/front.json: coefficients in pixels, fx = 1, cx = 640 + 3.942 -
        // 0.5, cy = 483 - 3.093 - 0.5), and a lens that folds at theta = 1.25 rad inside its
        // image (rho' = 1 + 0.2 theta - 0.9 theta^2 + 0.08 theta^3 = 0 there, by hand).
        {"THETA_POLYNOMIAL woodscape", real_camera(LensType::ThetaPolynomial, {339.749, -31.988, 48.275, -7.201},
                                                   {1280, 966}, {1.0, 1.0, 643.442, 479.407})},
        {"THETA_POLYNOMIAL folding", lens_camera(LensType::ThetaPolynomial, {1.0, 0.1, -0.3, 0.02}, {1600, 1200}, 300, 300)},
        // ---- FTHETA: the front camera of the DriveWorks rig NVIDIA's Cosmos world-scenario
        // documentation prints (3848x2168, cx 1919.420, cy 1078.106, polynomial "0 0.000538
        // 2.356e-09 1.907e-12 1.204e-16", pixeldistance-to-angle; its corners 70 degrees off
        // the axis), bounded at 80 degrees; and a made-up lens that sees 109 degrees off the
        // axis (max_angle 1.9) with a skewed affine, theta = r - 0.02 r^3 (folding at
        // r = 1 / sqrt(0.06) = 4.08, past max_angle at r = 2.075).
        // The wide one first: under the sanitizers only each model's first case runs, and
        // it must see behind the camera as the model can.
        {"FTHETA wide", lens_camera(LensType::FTheta, {1.002, 0.001, -0.002, 1.0, 0.0, -0.02, 0.0, 0.0, 1.9}, {1600, 1200},
                                    300, 300)},
        {"FTHETA driveworks", ftheta_camera({0.0, 0.000538, 2.356e-09, 1.907e-12, 1.204e-16, 0.0}, 1919.420, 1078.106,
                                            {1.0, 0.0, 0.0}, 80 * std::numbers::pi / 180, 3848, 2168)},
        // ---- FTHETA_FORWARD, made up: a forward polynomial in pixels 1200 t - 15 t^2 - 40 t^3
        // + 6 t^4 (f = 1200, k = a / f) on a 3840x2160 sensor with a skewed affine, bounded at
        // 1.4 rad (its corners lie past it, 2.1 rad out); and a lens that sees 126 degrees
        // off the axis (max_angle 2.2; rho = t - 0.03 t^3 grows until t = 3.33).
        // The wide one first, as FTHETA's.
        {"FTHETA_FORWARD wide", lens_camera(LensType::FThetaForward, {0.999, -0.002, 0.001, 1.0, 0.0, -0.03, 0.0, 0.0, 2.2},
                                            {1600, 1200}, 300, 300)},
        {"FTHETA_FORWARD ncore", real_camera(LensType::FThetaForward,
                                             {1.0002, 0.0001, -0.0003, 1.0, -15.0 / 1200, -40.0 / 1200, 6.0 / 1200, 0.0, 1.4},
                                             {3840, 2160}, {1200, 1200, 1919.5, 1079.5})},
        // ---- BROWN_K4, made up in the shape of Metashape's adjusted frame calibrations
        // (each radial term an order below the one before, P1 P2 near 1e-4; written in
        // OpenCV's order): a mild lens that never folds over, and a strong one whose k4 < 0
        // folds r R(r) over at r = 1.08, inside the image's corners (r = 1.1 there).
        {"BROWN_K4 mild", lens_camera(LensType::BrownK4, {-0.08, 0.02, 1.5e-4, -2e-4, -0.003, 4e-4})},
        {"BROWN_K4 strong", lens_camera(LensType::BrownK4, {-0.3, 0.09, 9e-4, -7e-4, -0.02, -0.02})},
        // ---- fisheye projections with PanoTools' polynomial: lensfun's calibrations
        // (lensfun's data/db, the snapshot of real-data's SOURCES.md) rescaled as lensfun
        // does (rescale_polynomial_coefficients), at a calibrated focal length, each on its
        // crop factor's sensor: the Samyang 7.5mm UMC Fish-eye MFT (mil-samyang.xml, 4000x3000)
        // and the Sigma 4.5mm circular fisheye (slr-sigma.xml, real focal 4.53319 mm,
        // 3000x2000); the Olympus M.Zuiko 8mm Fisheye Pro (poly3, mil-olympus.xml, 4000x3000)
        // and the Pentax-DA Fish-Eye 10-17mm at 10 mm (slr-pentax.xml, 3000x2000); the Olympus
        // 9mm Body Cap Lens (poly3, mil-olympus.xml, 4000x3000) and the Samyang 8mm f/2.8 UMC
        // Fish-eye (mil-samyang.xml, real focal 8.405 mm, 6000x4000).
        {"EQUIDISTANT_RADIAL mild",
         real_camera(LensType::EquidistantRadial, {-0.020079011891564337, 0.010734186087350687, -0.020400525146287707, 0.0},
                     {4000, 3000}, {1773.5666334899324, 1773.5666334899324, 1999.5, 1499.5})},
        {"EQUIDISTANT_RADIAL strong",
         real_camera(LensType::EquidistantRadial, {-0.002046058244986695, -0.015289347349700973, -0.060417027183450156, 0.0},
                     {3000, 2000}, {579.49279089, 579.49279089, 1499.5, 999.5})},
        {"EQUISOLID_RADIAL mild", real_camera(LensType::EquisolidRadial, {0.0, -0.008025759286564408, 0.0, 0.0}, {4000, 3000},
                                              {1858.818847557283, 1858.818847557283, 1999.5, 1499.5})},
        {"EQUISOLID_RADIAL strong",
         real_camera(LensType::EquisolidRadial, {-0.07397021605533176, 0.20647795493636048, -0.11773464496154998, 0.0},
                     {3000, 2000}, {1283.3328333333334, 1283.3328333333334, 1499.5, 999.5})},
        {"STEREOGRAPHIC_RADIAL mild", real_camera(LensType::StereographicRadial, {0.0, -0.058021862921437156, 0.0, 0.0},
                                                  {4000, 3000}, {2144.838447486735, 2144.838447486735, 1999.5, 1499.5})},
        {"STEREOGRAPHIC_RADIAL strong",
         real_camera(LensType::StereographicRadial, {0.02113944511397237, -0.08110521189647818, 0.014214620915856051, 0.0},
                     {6000, 4000}, {2148.878333333333, 2148.878333333333, 2999.5, 1999.5})},
    };
    return cases;
}

// The build the test script runs under AddressSanitizer and UndefinedBehaviorSanitizer
// looks for memory errors and undefined behaviour: every model's code meets them on its
// first example camera, so there the heaviest generic sweeps take one camera per model
// (sanitized_subset) and the release build, which checks the numbers, takes them all.
// LIBCAM_SANITIZED_BUILD: set by tests/CMakeLists.txt, whose files are not instrumented themselves.
#if defined(__SANITIZE_ADDRESS__) || defined(LIBCAM_SANITIZED_BUILD)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// Points along one side of a sweep's grid: under the sanitizers a third of them (at
// least 9), which keeps every kind of pixel (centre, folds, edges, corners, past the
// image) at a ninth of the cost; the release build checks the numbers on them all.
inline int sweep_side(int points) { return kSanitizedBuild ? std::max(9, points / 3) : points; }

// The cases as given, or under the sanitizers the first of each lens model.
inline std::vector<LensCase> sanitized_subset(std::vector<LensCase> cases) {
    if (!kSanitizedBuild) return cases;
    std::vector<LensType> seen;
    std::erase_if(cases, [&](const LensCase& c) {
        if (std::find(seen.begin(), seen.end(), c.camera.lens.type) != seen.end()) return true;
        seen.push_back(c.camera.lens.type);
        return false;
    });
    return cases;
}

// Radial-only lenses that fold over inside the image, the fold worked by hand: d(r) has
// its maximum d_max at r_max, and a pixel has a ray in the valid domain exactly when
// |m| < d_max (m its normalised point).
struct FoldCase {
    const char* name;
    Camera camera;
    double d_max;
};

inline std::vector<FoldCase> fold_cases() {
    const double r4 = std::sqrt(1 / 1.5), theta = std::sqrt(1 / 0.6);
    return {
        // d = r (1 - 0.5 r^2): r_max = sqrt(1/1.5), d_max = r_max (1 - 0.5 r_max^2) = 2/3 r_max.
        {"OPENCV4 k1 = -0.5", lens_camera(LensType::OpenCv4, {-0.5, 0, 0, 0}, {1600, 1200}, 900, 900), r4 * 2 / 3},
        // d = r / (1 + 0.5 r^2): r_max = sqrt 2, d_max = sqrt(2) / 2.
        {"OPENCV8 k4 = 0.5", lens_camera(LensType::OpenCv8, {0, 0, 0, 0, 0, 0.5, 0, 0}, {1600, 1200}, 900, 900),
         std::sqrt(2.0) / 2},
        // theta_d = theta (1 - 0.2 theta^2): theta_max = sqrt(1/0.6), d_max = 2/3 theta_max.
        {"FISHEYE k1 = -0.2", lens_camera(LensType::Fisheye, {-0.2, 0, 0, 0}, {1600, 1200}, 700, 700), theta * 2 / 3},
    };
}

// A grid of nx by ny OpenCV pixels spanning the whole image, corners included:
// libcam's one pixel grid (geometry/pixel_grid.hpp).
inline std::vector<Vec2> pixel_grid(const ImageSize& size, int nx, int ny) { return PixelGrid{nx, ny}.pixels(size); }

// The lens's valid_radius (lens/model_support.hpp), an input the tests sample within.
inline double valid_radius_of(const Lens& lens) {
    return visit_lens_model<double>(lens.type, [&]<class Model>() { return double(Model::parameters(lens.coefficients).valid_radius); });
}

// The largest angle off the axis the lens images (lens_models.hpp's valid_angle).
inline double valid_angle_of(const Lens& lens) {
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        return valid_angle<Model>(lens.coefficients, valid_radius_of(lens));
    });
}

// How far off the axis the tests sample a lens whose centre moves with a coefficient
// (Model::blind_angle: no pixel sees the directions within |k0| of FISHEYE_LENS_POLYNOMIAL's
// axis): twice that angle, and at least 1e-3 rad, beyond the reach of the central
// differences in k0. 0 for every other model.
inline double axis_margin_of(const Lens& lens) {
    // THETA_POLYNOMIAL's theta^2 term is m = k2 |u| u about the axis: differentiable there
    // (the Jacobian is k1 / z) but not twice, so central differences across the axis are
    // off by about k2 h. Its samples stay 1e-3 rad off the axis, as the blind models' do.
    if (lens.type == LensType::ThetaPolynomial && lens.coefficients.size() > 1 && lens.coefficients[1] != 0.0) {
        return 1e-3;
    }
    // FTHETA's r^2 term likewise (theta = k1 r + k2 r^2 + ...).
    if ((lens.type == LensType::FTheta || lens.type == LensType::FThetaForward) && lens.coefficients.size() > 4 &&
        lens.coefficients[4] != 0.0) {
        return 1e-3;
    }
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        if constexpr (requires { Model::blind_angle(std::span<const double>(lens.coefficients)); }) {
            return std::max(2 * blind_angle<Model>(lens.coefficients), 1e-3);
        } else {
            return 0.0;
        }
    });
}

// Where the domain ends towards azimuth phi, as an angle off the axis (lens_models.hpp's
// edge_angle: valid_angle but for a domain that is not round, SPLINED_STEREOGRAPHIC's).
inline double edge_angle_of(const Lens& lens, double azimuth) {
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        return edge_angle<Model>(lens.coefficients, valid_radius_of(lens), azimuth);
    });
}

// The domain's edge as the tests sample it: the angle off the axis for a model that sees
// behind the camera (the nearest edge of a domain that is not round), the radius of
// (x/z, y/z) for a perspective one.
inline double domain_edge_of(const Lens& lens) {
    if (!lens_info(lens.type).sees_behind_camera) return valid_radius_of(lens);
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        if constexpr (requires { Model::edge_angle(std::span<const double>(lens.coefficients), 0.0); }) {
            double nearest = std::numbers::pi;
            for (int i = 0; i < 720; ++i) nearest = std::min(nearest, edge_angle_of(lens, std::numbers::pi * i / 360));
            return nearest;
        } else {
            return valid_angle_of(lens);
        }
    });
}

// Which reference library has a model: the table says (test_lens_models checks the
// table's mrcal names against libmrcal's own list, and its OpenCV rows against OpenCV).
inline bool in_opencv(LensType type) { return lens_info(type).opencv != OpenCvFunction::None; }
inline bool in_mrcal(LensType type) { return !lens_info(type).mrcal.empty(); }
// PanoTools' radial polynomial on a projection (PTLENS and the fisheye *_RADIAL models):
// its reference is the formula itself in long double (reference_project); no library has it.
constexpr bool panotools_polynomial(LensType type) {
    return type == LensType::Ptlens || type == LensType::EquidistantRadial || type == LensType::EquisolidRadial ||
           type == LensType::StereographicRadial;
}
// A model only COLMAP has (THIN_PRISM_FISHEYE, RAD_TAN_THIN_PRISM_FISHEYE): its reference
// is COLMAP's formula (colmap_reference.hpp), in front of the camera.
inline bool colmap_only(LensType type) {
    return !has_paper_formulas(type) && !in_opencv(type) && !in_mrcal(type) && !lens_info(type).colmap.empty();
}

// The pixels of camera-frame rays by the reference library that has the model: OpenCV
// for its models (z > 0; cv::omnidir's UCM and MEI inside the valid angle), mrcal for
// its own. FISHEYE rays past 90 degrees, which
// cv::fisheye cannot take, go through libcam's projection (itself checked against
// theta_d's formula in test_lens_models).
// DOUBLE_SPHERE, UCM and EUCM, which neither library has (cv::omnidir's UCM is checked
// in test_unified.cpp), go through their papers' formulas in long double
// (unified_reference.hpp); their points outside the domain get infinity. The models only
// COLMAP has go through COLMAP's formulas (z > 0) and, as FISHEYE, libcam's projection
// behind the camera.
inline std::vector<Vec2> reference_project(const Camera& camera, const std::vector<Vec3>& rays) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    if (colmap_only(camera.lens.type)) {
        const ColmapCamera colmap = colmap_from_camera(camera);
        const PreparedCamera prepared(camera);
        std::vector<Vec2> pixels;
        for (const Vec3& ray : rays) {
            if (ray.z() > 0) {
                const std::optional<Eigen::Vector2d> pixel = colmap_img_from_cam(colmap.model, colmap.params, ray);
                pixels.push_back(pixel ? Vec2(*pixel - Vec2::Constant(kColmapPixelShift)) : Vec2::Constant(kInfinity));
            } else {
                const Projection p = prepared.project_camera_point(ray);
                pixels.push_back(p.valid ? p.pixel : Vec2::Constant(kInfinity));
            }
        }
        return pixels;
    }
    if (has_paper_formulas(camera.lens.type)) {
        std::vector<Vec2> pixels;
        for (const Vec3& ray : rays) {
            pixels.push_back(paper_pixel(camera, ray).value_or(Vec2::Constant(std::numeric_limits<double>::infinity())));
        }
        return pixels;
    }
    if (panotools_polynomial(camera.lens.type)) {
        // PanoTools' polynomial on the lens's own projection, the formula in long double:
        // m = P(theta) (1 + c r + b r^2 + a r^3 + k2 r^4) (X, Y) / |(X, Y)|, r = P(theta),
        // P = tan (PTLENS), theta (EQUIDISTANT_RADIAL), 2 sin(theta / 2) (EQUISOLID_RADIAL),
        // 2 tan(theta / 2) (STEREOGRAPHIC_RADIAL); nothing past the fold or the projection's edge.
        const PreparedCamera prepared(camera);
        const std::vector<double>& k = camera.lens.coefficients;
        const long double a = k[0], b = k[1], c = k[2], k2 = k.size() > 3 ? k[3] : 0.0;
        std::vector<Vec2> pixels;
        for (const Vec3& ray : rays) {
            const long double x = ray.x(), y = ray.y(), z = ray.z(), rho = std::hypot(x, y);
            const long double theta = std::atan2(rho, z);
            long double r = 0;
            switch (camera.lens.type) {
                case LensType::Ptlens: r = rho / z; break;
                case LensType::EquidistantRadial: r = theta; break;
                case LensType::EquisolidRadial: r = 2 * std::sin(theta / 2); break;
                default: r = 2 * std::tan(theta / 2); break;
            }
            const long double factor = 1 + r * (c + r * (b + r * (a + r * k2)));
            const bool inside = (camera.lens.type != LensType::Ptlens || z > 0) && r < prepared.valid_radius() &&
                                (rho > 0 || z > 0);
            const long double scale = rho > 0 ? r * factor / rho : 0;
            pixels.push_back(inside ? Vec2(static_cast<double>(camera.intrinsics.fx * x * scale + camera.intrinsics.cx),
                                           static_cast<double>(camera.intrinsics.fy * y * scale + camera.intrinsics.cy))
                                    : Vec2::Constant(kInfinity));
        }
        return pixels;
    }
    if (camera.lens.type == LensType::BrownK4) {
        // Metashape's frame camera (its manual's appendix "Camera models") in OpenCV's order,
        // in long double: m = u (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8) + OpenCV's tangential
        // terms, u = (x/z, y/z); nothing behind the camera or past the fold.
        const PreparedCamera prepared(camera);
        const std::vector<double>& k = camera.lens.coefficients;
        std::vector<Vec2> pixels;
        for (const Vec3& ray : rays) {
            const long double x = static_cast<long double>(ray.x()) / ray.z(), y = static_cast<long double>(ray.y()) / ray.z();
            const long double r2 = x * x + y * y;
            const long double radial = 1 + k[0] * r2 + k[1] * r2 * r2 + k[4] * r2 * r2 * r2 + k[5] * r2 * r2 * r2 * r2;
            const long double mx = x * radial + 2 * k[2] * x * y + k[3] * (r2 + 2 * x * x);
            const long double my = y * radial + k[2] * (r2 + 2 * y * y) + 2 * k[3] * x * y;
            const bool inside = ray.z() > 0 && std::sqrt(r2) < prepared.valid_radius();
            const Intrinsics& K = camera.intrinsics;
            pixels.push_back(inside ? Vec2(static_cast<double>(K.fx * mx + K.skew * my + K.cx),
                                           static_cast<double>(K.fy * my + K.cy))
                                    : Vec2::Constant(kInfinity));
        }
        return pixels;
    }
    if (camera.lens.type == LensType::OcamCalib) {
        // Scaramuzza's world2cam without its invpol, as his MATLAB world2cam solves it: the
        // sensor radius r whose ray (r (X, Y) / rho, g(r)) meets the point is the first
        // positive root of rho g(r) - Z r, g(r) = 1 + k1 r + ... + k5 r^5, found by a scan
        // and bisection in long double; then the affine [1 e; d c] and K.
        const PreparedCamera prepared(camera);
        const std::vector<double>& k = camera.lens.coefficients;
        const long double radius_limit = std::isfinite(prepared.valid_radius()) ? prepared.valid_radius() : 1e9L;
        // The scan's radii, from 1e-15 of the limit up to it in 2000 geometric steps: the
        // same for every ray, so computed once (powl per step per ray was most of the time).
        std::vector<long double> scan(2001);
        for (int i = 0; i <= 2000; ++i) scan[static_cast<std::size_t>(i)] = radius_limit * std::pow(1e-15L, 1 - i / 2000.0L);
        std::vector<Vec2> pixels;
        for (const Vec3& ray : rays) {
            const long double X = ray.x(), Y = ray.y(), Z = ray.z(), rho = std::hypot(X, Y);
            const auto f = [&](long double r) {
                long double g = k[7];
                for (int i = 6; i >= 3; --i) g = g * r + k[static_cast<std::size_t>(i)];
                return rho * (1 + r * g) - Z * r;
            };
            if (!(rho > 0)) {
                pixels.push_back(Z > 0 ? Vec2(camera.intrinsics.cx, camera.intrinsics.cy) : Vec2::Constant(kInfinity));
                continue;
            }
            long double low = 0, high = -1;
            for (std::size_t i = 0; i < scan.size() && high < 0; ++i) {
                if (f(scan[i]) <= 0) high = scan[i];
                else low = scan[i];
            }
            if (high < 0 || high >= radius_limit) {
                pixels.push_back(Vec2::Constant(kInfinity));
                continue;
            }
            for (int i = 0; i < 200; ++i) {
                const long double middle = (low + high) / 2;
                if (middle == low || middle == high) break;  // adjacent: no step changes them
                (f(middle) > 0 ? low : high) = middle;
            }
            const long double r = (low + high) / 2, nx = r * X / rho, ny = r * Y / rho;
            const long double mx = nx + k[2] * ny, my = k[1] * nx + k[0] * ny;
            pixels.push_back(Vec2(static_cast<double>(camera.intrinsics.fx * mx + camera.intrinsics.cx),
                                  static_cast<double>(camera.intrinsics.fy * my + camera.intrinsics.cy)));
        }
        return pixels;
    }
    if (!in_opencv(camera.lens.type)) return mrcal_project_points(camera, rays);
    // cv::omnidir evaluates its formula on every point: those past the valid angle get
    // infinity. cv::projectPoints and cv::fisheye take points in front of the camera.
    // OpenCV's projections read fx, fy, cx and cy from K and leave out its skew (K(0, 1)):
    // a skewed camera is projected without it, and the skew added as K adds it, times the
    // distorted y.
    const bool omnidir = lens_info(camera.lens.type).opencv == OpenCvFunction::Omnidir;
    const double limit = std::cos(valid_angle_of(camera.lens));
    Camera unskewed = camera;
    unskewed.intrinsics.skew = 0.0;
    std::vector<Vec2> pixels = opencv_project_points(unskewed, rays);
    const Intrinsics& k = camera.intrinsics;
    if (k.skew != 0.0) {
        for (Vec2& pixel : pixels) pixel.x() += k.skew * (pixel.y() - k.cy) / k.fy;
    }
    std::optional<PreparedCamera> prepared;  // behind the camera only: preparing a camera takes time
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (omnidir) {
            if (!(rays[i].z() > limit * rays[i].norm())) pixels[i] = Vec2::Constant(std::numeric_limits<double>::infinity());
        } else if (rays[i].z() <= 0) {
            if (!prepared) prepared.emplace(camera);
            const Projection p = prepared->project_camera_point(rays[i]);
            pixels[i] = p.valid ? p.pixel : Vec2::Constant(std::numeric_limits<double>::infinity());
        }
    }
    return pixels;
}

// The name of what reference_project projects a model's rays with, in the same order of
// choice, for the tables that print it.
inline std::string reference_library(LensType type) {
    if (colmap_only(type)) return "COLMAP's formulas";
    if (has_paper_formulas(type)) return "its paper's formulas";
    if (panotools_polynomial(type)) return "PanoTools' polynomial";
    if (type == LensType::BrownK4) return "Metashape's formula";
    if (type == LensType::OcamCalib) return "Scaramuzza's world2cam";
    if (!in_opencv(type)) return "mrcal_project";
    switch (lens_info(type).opencv) {
        case OpenCvFunction::Fisheye: return "cv::fisheye::projectPoints";
        case OpenCvFunction::Omnidir: return "cv::omnidir::projectPoints";
        default: return "cv::projectPoints";
    }
}

// A camera against the library that defines its model: the rays libcam unprojects through
// a grid of the image, projected back by reference_project; the farthest any lands from
// its pixel, over the pixels whose ray libcam gives (`rays` of `pixels`).
struct ReferenceAgreement {
    double worst_px = 0.0;
    std::size_t rays = 0;
    std::size_t pixels = 0;
};

inline ReferenceAgreement against_reference(const Camera& camera, int nx = 41, int ny = 31) {
    const std::vector<Vec2> pixels = pixel_grid(camera.size, nx, ny);
    const std::vector<Unprojection> rays = PreparedCamera(camera).unproject(pixels);
    std::vector<Vec3> directions;
    std::vector<Vec2> expected;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!rays[i].valid) continue;
        directions.push_back(rays[i].direction);
        expected.push_back(pixels[i]);
    }
    ReferenceAgreement agreement{0.0, directions.size(), pixels.size()};
    const std::vector<Vec2> back = reference_project(camera, directions);
    for (std::size_t i = 0; i < back.size(); ++i) {
        const double miss = (back[i] - expected[i]).norm();
        agreement.worst_px = std::max(agreement.worst_px, std::isnan(miss) ? std::numeric_limits<double>::infinity() : miss);
    }
    return agreement;
}

}  // namespace libcam::test
