#include "libcam/io/detail/realitycapture_format.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/io/detail/xml_source.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

constexpr std::string_view kXcrNamespace = "http://www.capturingreality.com/ns/xcr/1.1#";

// The rdf:Description holding xcr: values, and the prefix the file binds to the namespace.
class Description {
public:
    Description(pugi::xml_node node, std::string prefix, std::string source)
        : node_(node), prefix_(std::move(prefix)), source_(std::move(source)) {}

    // A value's text, from the attribute or the child element of that name; none if absent.
    std::optional<std::string> text(std::string_view name) const {
        const std::string qualified = prefix_ + ":" + std::string(name);
        if (const pugi::xml_attribute attribute = node_.attribute(qualified.c_str())) return std::string(attribute.value());
        if (const pugi::xml_node element = node_.child(qualified.c_str())) return std::string(element.text().get());
        return std::nullopt;
    }

    // `count` finite numbers (separated by white space) of a value.
    std::vector<double> numbers(std::string_view name, std::size_t count) const {
        const std::optional<std::string> value = text(name);
        if (!value) fail(name, "missing");
        std::vector<double> out;
        std::string_view rest = *value;
        while (true) {
            const auto start = rest.find_first_not_of(" \t\r\n");
            if (start == std::string_view::npos) break;
            rest.remove_prefix(start);
            const std::string_view word = rest.substr(0, rest.find_first_of(" \t\r\n"));
            double number = 0.0;
            const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), number);
            if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(number)) {
                fail(name, "must be finite numbers, got " + shown_value(word));
            }
            if (out.size() == count) fail(name, "expected " + std::to_string(count) + " numbers, got more");
            out.push_back(number);
            rest.remove_prefix(word.size());
        }
        if (out.size() != count) {
            fail(name, "expected " + std::to_string(count) + " numbers, got " + std::to_string(out.size()));
        }
        return out;
    }

    double number(std::string_view name) const { return numbers(name, 1)[0]; }
    double number_or(std::string_view name, double fallback) const { return text(name) ? number(name) : fallback; }

    [[noreturn]] void fail(std::string_view name, const std::string& what) const {
        throw FileError(source_ + ": " + prefix_ + ":" + std::string(name) + ": " + what);
    }
    [[noreturn]] void refuse(std::string_view name, const std::string& what) const {
        throw NotRepresentable(source_ + ": " + prefix_ + ":" + std::string(name) + ": " + what);
    }

private:
    pugi::xml_node node_;
    std::string prefix_;
    std::string source_;
};

// The prefix an element or one of its ancestors binds to RealityCapture's namespace.
std::optional<std::string> xcr_prefix(pugi::xml_node node) {
    for (; node; node = node.parent()) {
        for (const pugi::xml_attribute attribute : node.attributes()) {
            const std::string_view name = attribute.name();
            if (name.starts_with("xmlns:") && attribute.value() == kXcrNamespace) return std::string(name.substr(6));
        }
    }
    return std::nullopt;
}

bool is_description(const pugi::xml_node& node) {
    const std::string_view name = node.name();
    return name == "Description" || name.ends_with(":Description");
}

// The first rdf:Description (at any depth, in document order) in whose scope the xcr
// namespace is bound. Walked without recursion: a file may nest deeply.
std::optional<Description> find_description(const pugi::xml_node& root, const std::string& source) {
    pugi::xml_node node = root.first_child();
    while (node) {
        if (node.type() == pugi::node_element && is_description(node)) {
            if (const std::optional<std::string> prefix = xcr_prefix(node)) return Description(node, *prefix, source);
        }
        if (node.first_child()) {
            node = node.first_child();
            continue;
        }
        while (node && !node.next_sibling()) node = node.parent();
        if (node) node = node.next_sibling();
    }
    return std::nullopt;
}

// RealityCapture's distortion as libcam's lens (the header says how the terms map).
Lens lens_of(const Description& file) {
    const std::string model = file.text("DistortionModel").value_or("perspective");
    const std::vector<double> c =
        file.text("DistortionCoeficients") ? file.numbers("DistortionCoeficients", 6) : std::vector<double>(6, 0.0);
    const double k1 = c[0], k2 = c[1], k3 = c[2], k4 = c[3], t1 = c[4], t2 = c[5];
    const bool radial = model.starts_with("brown");
    const bool tangential = model == "brown3t2" || model == "brown4t2";
    if (model != "perspective" && model != "division" && model != "brown3" && model != "brown4" && !tangential) {
        file.fail("DistortionModel", "must be perspective, brown3, brown4, brown3t2, brown4t2 or division, got " +
                                         shown_value(model));
    }
    // A coefficient the model does not use must be 0: it would otherwise be dropped.
    const auto unused = [&](std::size_t index, const char* name) {
        if (c[index] != 0.0) {
            file.fail("DistortionCoeficients", std::string(name) + " = " + format_number(c[index]) + " is not a term of " +
                                                   model);
        }
    };
    if (model == "division") {
        for (std::size_t i = 1; i < 6; ++i) unused(i, "a coefficient past k1");
        if (k1 != 0.0) {
            file.refuse("DistortionCoeficients", "division with k1 = " + format_number(k1) +
                                                     ": the unit of RealityCapture's division coefficient is not "
                                                     "documented, so it is not read as libcam's DIVISION");
        }
        return {};
    }
    if (!radial) {
        for (std::size_t i = 0; i < 6; ++i) unused(i, "a coefficient");
        return {};
    }
    if (model == "brown3" || model == "brown3t2") unused(3, "k4");
    if (!tangential) {
        unused(4, "t1");
        unused(5, "t2");
    }
    return realitycapture_brown_lens(k1, k2, k3, k4, t1, t2);
}

Intrinsics intrinsics_of(const Description& file, ImageSize size) {
    const double skew = file.number_or("Skew", 0.0);
    if (skew != 0.0) file.refuse("Skew", "a skew of " + format_number(skew) + " is not read (its unit is not documented)");
    return realitycapture_intrinsics(file.number("FocalLength35mm"), file.number_or("AspectRatio", 1.0),
                                     file.number_or("PrincipalPointU", 0.0), file.number_or("PrincipalPointV", 0.0), size);
}

Pose pose_of(const Description& file) {
    if (!file.text("Rotation") && !file.text("Position")) return {};
    const std::vector<double> r = file.numbers("Rotation", 9);
    const std::vector<double> centre = file.numbers("Position", 3);
    Mat3 R;
    for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = r[static_cast<std::size_t>(i)];
    return Pose::from_centre(R, Vec3(centre[0], centre[1], centre[2]));
}

}  // namespace

Intrinsics realitycapture_intrinsics(double focal_35mm, double aspect, double u, double v, ImageSize size) {
    const double longer = static_cast<double>(std::max(size.width, size.height));
    const double fx = focal_35mm * longer / 36.0;
    return {fx, aspect * fx, 0.5 * static_cast<double>(size.width) - 0.5 + u * longer,
            0.5 * static_cast<double>(size.height) - 0.5 + v * longer, 0.0};
}

Lens realitycapture_brown_lens(double k1, double k2, double k3, double k4, double t1, double t2) {
    return simplest_equal_lens({LensType::BrownK4, {k1, k2, t2, t1, k3, k4}});
}

bool claims_realitycapture_xmp(const DocumentNode& outline) {
    return outline.find("x:xmpmeta") != nullptr || outline.find("rdf:RDF") != nullptr;
}

std::vector<NamedCamera> read_realitycapture_xmp(std::string_view text, const ReadContext& context) {
    pugi::xml_document document;
    load_xml(document, text, context.source);
    const std::optional<Description> file = find_description(document, context.source);
    if (!file) {
        throw FileError(context.source + ": no rdf:Description in RealityCapture's namespace (" +
                        std::string(kXcrNamespace) + ")");
    }
    if (!context.options.size) {
        throw FileError(context.source + ": RealityCapture's XMP does not hold the image size, which its focal length "
                                         "and principal point are relative to: give it (--image-size WxH)");
    }
    Camera camera;
    camera.size = *context.options.size;
    camera.intrinsics = intrinsics_of(*file, camera.size);
    camera.lens = lens_of(*file);
    camera.pose = pose_of(*file);
    return {{std::string(), {validated_camera(camera, context.source), std::nullopt}}};
}

}  // namespace libcam
