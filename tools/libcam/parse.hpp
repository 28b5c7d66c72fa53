#pragma once
// Strict parsing of command-line values: the whole text must be the value, numbers
// must be finite, vectors must have the right count. Errors name the flag and the text.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam::cli {

// A malformed command line: the program prints it and exits 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

double parse_number(std::string_view flag, std::string_view text);
std::vector<double> parse_numbers(std::string_view flag, std::string_view text, std::size_t count);
Vec3 parse_vec3(std::string_view flag, std::string_view text);
Vec2 parse_vec2(std::string_view flag, std::string_view text);
ImageSize parse_size(std::string_view flag, std::string_view text);  // "WxH"

}  // namespace libcam::cli
