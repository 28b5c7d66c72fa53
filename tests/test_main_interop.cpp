// The Catch2 main of the test programs that link libcam::interop: it plugs mrcal's file
// format into libcam::io before any test runs, as the `libcam` program does.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "libcam/interop/formats.hpp"
#include "simd_target_check.hpp"

int main(int argc, char** argv) {
    if (const int skip = libcam::test::skip_code_for_simd_target()) return skip;
    libcam::register_interop_formats();
    return Catch::Session().run(argc, argv);
}
