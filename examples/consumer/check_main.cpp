// Runs the worked examples of `libcam demo` with an installed libcam::check: each example
// camera's look-at formula against OpenCV's and mrcal's projections.

#include <cstdio>

#include "libcam/check/worked_examples.hpp"

int main() {
    int checks = 0, failed = 0;
    for (const libcam::WorkedExample& example : libcam::check_worked_examples()) {
        for (const libcam::WorkedExampleCheck& check : example.checks) {
            ++checks;
            if (!check.pass()) ++failed;
        }
    }
    std::printf("checks %d failed %d\n", checks, failed);
    return failed == 0 && checks > 0 ? 0 : 1;
}
