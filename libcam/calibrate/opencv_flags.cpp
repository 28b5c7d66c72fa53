#include "libcam/calibrate/opencv_flags.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// One of calibrateCamera's flags: its bit (calib3d.hpp's value), its name without CALIB_,
// and what libcam holds for it, or why it is refused.
struct OpenCvFlag {
    unsigned long bit;
    std::string_view name;
    bool square_pixels;
    std::string_view zero_coefficient;
    std::string_view refused;
};

constexpr std::string_view kModelFlag = "it chooses OpenCV's model: name the model with --model instead";

constexpr std::array<OpenCvFlag, 18> kFlags = {{
    {1UL << 0, "USE_INTRINSIC_GUESS", false, "", "libcam starts from the boards, not from a guess"},
    {1UL << 1, "FIX_ASPECT_RATIO", true, "", ""},
    {1UL << 2, "FIX_PRINCIPAL_POINT", false, "", "libcam holds no principal point fixed"},
    {1UL << 3, "ZERO_TANGENT_DIST", false, "p1", ""},
    {1UL << 4, "FIX_FOCAL_LENGTH", false, "", "it needs a guess of the focal length to hold"},
    {1UL << 5, "FIX_K1", false, "k1", ""},
    {1UL << 6, "FIX_K2", false, "k2", ""},
    {1UL << 7, "FIX_K3", false, "k3", ""},
    {1UL << 11, "FIX_K4", false, "k4", ""},
    {1UL << 12, "FIX_K5", false, "k5", ""},
    {1UL << 13, "FIX_K6", false, "k6", ""},
    {1UL << 14, "RATIONAL_MODEL", false, "", kModelFlag},
    {1UL << 15, "THIN_PRISM_MODEL", false, "", kModelFlag},
    {1UL << 16, "FIX_S1_S2_S3_S4", false, "", "libcam fits no thin-prism model"},
    {1UL << 17, "USE_LU", false, "", "it chooses OpenCV's solver, not what is fitted"},
    {1UL << 18, "TILTED_MODEL", false, "", kModelFlag},
    {1UL << 19, "FIX_TAUX_TAUY", false, "", "libcam fits no tilted model"},
    {1UL << 20, "USE_QR", false, "", "it chooses OpenCV's solver, not what is fitted"},
}};

std::string upper(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return out;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
    return text;
}

void hold(const OpenCvFlag& flag, HeldParameters& held) {
    if (!flag.refused.empty()) {
        throw InvalidArgument("--opencv-flags: CALIB_" + std::string(flag.name) + " is not taken: " +
                              std::string(flag.refused));
    }
    held.square_pixels = held.square_pixels || flag.square_pixels;
    std::vector<std::string> zero;
    if (!flag.zero_coefficient.empty()) zero.emplace_back(flag.zero_coefficient);
    if (flag.zero_coefficient == "p1") zero.emplace_back("p2");
    for (const std::string& name : zero) {
        if (std::find(held.zero_coefficients.begin(), held.zero_coefficients.end(), name) == held.zero_coefficients.end()) {
            held.zero_coefficients.push_back(name);
        }
    }
}

// A number: every bit of it one of kFlags.
void hold_number(std::string_view item, unsigned long value, HeldParameters& held) {
    for (const OpenCvFlag& flag : kFlags) {
        if ((value & flag.bit) == 0) continue;
        hold(flag, held);
        value &= ~flag.bit;
    }
    if (value != 0) {
        throw InvalidArgument("--opencv-flags: " + printable_text(item, 40) + " holds bits that are none of calibrateCamera's "
                              "flags (" + std::to_string(value) + ")");
    }
}

}  // namespace

HeldParameters held_by_opencv_flags(std::string_view text) {
    HeldParameters held;
    if (trimmed(text).empty()) throw InvalidArgument("--opencv-flags: empty: give OpenCV's flags, e.g. FIX_ASPECT_RATIO or 2");
    while (true) {
        const std::size_t comma = text.find(',');
        const std::string_view item = trimmed(text.substr(0, comma));
        if (item.empty()) throw InvalidArgument("--opencv-flags: an empty item in the list");
        unsigned long value = 0;
        const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (error == std::errc() && end == item.data() + item.size()) {
            hold_number(item, value, held);
        } else {
            std::string name = upper(item);
            if (name.rfind("CALIB_", 0) == 0) name.erase(0, 6);
            const auto* flag = std::find_if(kFlags.begin(), kFlags.end(), [&](const OpenCvFlag& f) { return f.name == name; });
            if (flag == kFlags.end()) {
                std::string taken;
                for (const OpenCvFlag& f : kFlags) {
                    if (f.refused.empty()) taken += (taken.empty() ? "" : ", ") + std::string(f.name);
                }
                throw InvalidArgument("--opencv-flags: " + printable_text(item, 40) + " is none of calibrateCamera's flags; taken: " +
                                      taken + ", or their sum as a number");
            }
            hold(*flag, held);
        }
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return held;
}

}  // namespace libcam
