#pragma once
// What a shell command (a peer's program: python3 with mrcal, Hugin's pano_trafo,
// mrgingham) prints on its standard output; the test fails unless it exits 0.

#include <cstdio>
#include <string>

#include <catch2/catch.hpp>

namespace libcam::test {

inline std::string shell_output(const std::string& command) {
    std::FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
    const int status = pclose(pipe);
    INFO(command);
    REQUIRE(status == 0);
    return output;
}

}  // namespace libcam::test
