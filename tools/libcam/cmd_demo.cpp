// libcam demo: the built-in example. Converts the two worked example cameras to
// calibrated cameras and checks every ray against OpenCV (projectPoints,
// undistortPoints, Rodrigues) and mrcal (mrcal_project): libcam/check/worked_examples.hpp.

#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "libcam/check/worked_examples.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam::cli {

namespace {

// "(a, b, c)" with six significant digits.
std::string vec(const Eigen::VectorXd& v) {
    std::string out = "(";
    for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_short(v(i), 6);
    return out + ")";
}

void print_example(const WorkedExample& example) {
    const Camera& camera = example.camera;
    std::cout << "\n" << example.title << "\n";
    std::cout << "  K    = " << vec(camera.intrinsics.K().reshaped<Eigen::RowMajor>()) << "\n";
    std::cout << "  R    = " << vec(camera.pose.R.reshaped<Eigen::RowMajor>()) << "\n";
    std::cout << "  t    = " << vec(camera.pose.t) << "\n";
    std::cout << "  rvec = " << vec(camera.pose.rvec()) << "\n";
    std::cout << "  P    = " << vec(camera.P().reshaped<Eigen::RowMajor>()) << "\n";
    for (const WorkedExamplePixel& pixel : example.pixels) {
        std::cout << "  pixel " << vec(pixel.bottom_left_pixel) << ": d = " << vec(pixel.look_at_direction)
                  << "   OpenCV pixel " << vec(pixel.opencv_pixel) << "\n";
    }
}

}  // namespace

Runner add_demo(CLI::App& app) {
    add_command(app, "demo");
    return [] {
        std::cout << "libcam demo: the two worked example cameras, converted to K, R, t and checked against "
                     "OpenCV and mrcal\n"
                     "(pixels counted from the bottom-left, as the look-at formula counts them; "
                     "d = alpha u + beta v + w)\n";
        std::vector<WorkedExampleCheck> checks;
        for (const WorkedExample& example : check_worked_examples()) {
            print_example(example);
            for (WorkedExampleCheck check : example.checks) {
                check.name = example.name + ": " + check.name;
                checks.push_back(check);
            }
        }
        std::cout << "\n" << std::left << std::setw(56) << "check" << std::setw(14) << "max error" << std::setw(12)
                  << "tolerance" << "result\n";
        bool all_pass = true;
        for (const WorkedExampleCheck& check : checks) {
            std::cout << std::setw(56) << check.name << std::setw(14) << format_short(check.max_error) << std::setw(12)
                      << format_short(check.tolerance, 6) << (check.pass() ? "pass" : "FAIL") << "\n";
            all_pass = all_pass && check.pass();
        }
        std::cout << (all_pass ? "\nall checks pass\n" : "\nSOME CHECKS FAILED\n");
        return all_pass ? 0 : 1;
    };
}

}  // namespace libcam::cli
