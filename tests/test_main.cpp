#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "simd_target_check.hpp"

int main(int argc, char** argv) {
    if (const int skip = libcam::test::skip_code_for_simd_target()) return skip;
    return Catch::Session().run(argc, argv);
}
