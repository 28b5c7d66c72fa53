#pragma once
// Reading the JSON of other tools (basalt's calibration, NeRF's transforms.json): a value
// with the key path a user knows it by, so that every error names the file, the key and
// the value: "<source>: \"value0.intrinsics[0].fx\": expected a number, got \"a\"".
// Internal to libcam::io (its readers link nlohmann JSON privately).

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "libcam/error.hpp"

namespace libcam {

// The JSON document of another tool's file; FileError "<source>: not valid JSON: ..."
// otherwise.
inline nlohmann::json parse_json_document(std::string_view text, const std::string& source) {
    try {
        return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::exception& error) {
        throw FileError(source + ": not valid JSON: " + error.what());
    }
}

struct JsonField {
    const nlohmann::json& value;
    std::string name;
    const std::string& source;

    [[noreturn]] void fail(const std::string& what) const { throw FileError(source + ": \"" + name + "\": " + what); }

    std::string child(std::string_view key) const { return name.empty() ? std::string(key) : name + "." + std::string(key); }

    JsonField at(std::string_view key) const {
        if (!value.is_object()) fail("expected an object");
        const auto found = value.find(key);
        if (found == value.end()) JsonField{value, child(key), source}.fail("missing");
        return {*found, child(key), source};
    }
    JsonField at(std::size_t index) const {
        if (!value.is_array() || index >= value.size()) fail("expected an array of at least " + std::to_string(index + 1));
        return {value[index], name + "[" + std::to_string(index) + "]", source};
    }
    // Whether the object has the key with a value that is not null.
    bool has(std::string_view key) const {
        if (!value.is_object()) return false;
        const auto found = value.find(key);
        return found != value.end() && !found->is_null();
    }
    double number() const {
        if (!value.is_number()) fail("expected a number, got " + value.dump());
        const double x = value.get<double>();
        if (!std::isfinite(x)) fail("must be finite, got " + value.dump());
        return x;
    }
    int integer(long long min, long long max) const {
        if (!value.is_number_integer()) fail("expected an integer, got " + value.dump());
        const long long x = value.get<long long>();
        if (x < min || x > max) fail("must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + value.dump());
        return static_cast<int>(x);
    }
    // A number with no fraction (instant-ngp writes sizes as 1080.0) in [min, max].
    long whole_number(long min, long max) const {
        const double x = number();
        if (x != std::floor(x) || x < static_cast<double>(min) || x > static_cast<double>(max)) {
            fail("expected a whole number in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                 value.dump());
        }
        return static_cast<long>(x);
    }
    std::string text() const {
        if (!value.is_string()) fail("expected a string, got " + value.dump());
        return value.get<std::string>();
    }
    std::size_t size() const {
        if (!value.is_array()) fail("expected an array");
        return value.size();
    }
};

}  // namespace libcam
