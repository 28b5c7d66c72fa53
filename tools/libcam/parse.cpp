#include "parse.hpp"

#include <charconv>
#include <cmath>

namespace libcam::cli {

namespace {

[[noreturn]] void fail(std::string_view flag, std::string_view text, const std::string& what) {
    throw UsageError(std::string(flag) + ": " + what + ", got '" + std::string(text) + "'");
}

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string_view::npos) return parts;
        start = end + 1;
    }
}

}  // namespace

double parse_number(std::string_view flag, std::string_view text) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error == std::errc::invalid_argument || stop != end) fail(flag, text, "expected a number");
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) fail(flag, text, "expected a finite number");
    return value;
}

std::vector<double> parse_numbers(std::string_view flag, std::string_view text, std::size_t count) {
    const std::vector<std::string_view> parts = split(text, ',');
    if (parts.size() != count) {
        fail(flag, text, "expected " + std::to_string(count) + " comma-separated numbers, found " +
                             std::to_string(parts.size()));
    }
    std::vector<double> values;
    for (std::string_view part : parts) {
        double value = 0.0;
        const char* end = part.data() + part.size();
        const auto [stop, error] = std::from_chars(part.data(), end, value);
        if (part.empty() || error == std::errc::invalid_argument || stop != end) {
            fail(flag, text, "'" + std::string(part) + "' is not a number");
        }
        if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
            fail(flag, text, "'" + std::string(part) + "' is not a finite number");
        }
        values.push_back(value);
    }
    return values;
}

Vec3 parse_vec3(std::string_view flag, std::string_view text) {
    const std::vector<double> v = parse_numbers(flag, text, 3);
    return {v[0], v[1], v[2]};
}

Vec2 parse_vec2(std::string_view flag, std::string_view text) {
    const std::vector<double> v = parse_numbers(flag, text, 2);
    return {v[0], v[1]};
}

ImageSize parse_size(std::string_view flag, std::string_view text) {
    const std::vector<std::string_view> parts = split(text, 'x');
    if (parts.size() != 2) fail(flag, text, "expected WIDTHxHEIGHT, e.g. 1920x1080");
    long sides[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        const char* end = parts[i].data() + parts[i].size();
        const auto [stop, error] = std::from_chars(parts[i].data(), end, sides[i]);
        if (parts[i].empty() || error != std::errc() || stop != end) {
            fail(flag, text, "expected WIDTHxHEIGHT with positive integers");
        }
        if (sides[i] < 1 || sides[i] > kMaxImageSide) {
            fail(flag, text, "each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
        }
    }
    return {sides[0], sides[1]};
}

}  // namespace libcam::cli
