#include "libcam/io/detail/lensfun_format.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/io/detail/xml_source.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace detail {

double lensfun_interpolate(std::optional<double> y1, double y2, double y3, std::optional<double> y4, double t) {
    const double tangent2 = y1 ? (y3 - *y1) * 0.5 : y3 - y2;
    const double tangent3 = y4 ? (*y4 - y2) * 0.5 : y3 - y2;
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * y2 + (t3 - 2 * t2 + t) * tangent2 + (-2 * t3 + 3 * t2) * y3 + (t3 - t2) * tangent3;
}

}  // namespace detail

namespace {

// One <distortion> element: its model, focal lengths and terms (a b c, or k1 k2).
struct Distortion {
    std::string model;
    double focal = 0.0;
    double real_focal = 0.0;
    std::array<double, 3> terms{};
};

struct LensEntry {
    std::vector<std::string> names;  // every <model>, the untranslated first
    std::string type = "rectilinear";
    double crop_factor = 1.0;
    double aspect_ratio = 1.5;
    double min_focal = 0.0, max_focal = 0.0;
    double centre_x = 0.0, centre_y = 0.0;
    std::vector<Distortion> distortion;  // the lens's first model's entries, in file order
    pugi::xml_node node;
};

class Source : public XmlSource {
public:
    using XmlSource::XmlSource;

    double number(const pugi::xml_node& node, std::string_view text, const std::string& field) const {
        while (!text.empty() && std::string_view(" \t\r\n").find(text.front()) != std::string_view::npos) text.remove_prefix(1);
        while (!text.empty() && std::string_view(" \t\r\n").find(text.back()) != std::string_view::npos) text.remove_suffix(1);
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
            fail(node, field + ": must be a finite number, got " + shown_value(text));
        }
        return value;
    }
};

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

// "4:3" or "1.333": lensfun's aspect ratio, at least 1.
double aspect_ratio(const Source& source, const pugi::xml_node& node, std::string_view text, const std::string& field) {
    const auto colon = text.find(':');
    const double ratio = colon == std::string_view::npos
                             ? source.number(node, text, field)
                             : source.number(node, text.substr(0, colon), field) / source.number(node, text.substr(colon + 1), field);
    if (!(ratio >= 1.0) || !std::isfinite(ratio)) {
        source.fail(node, field + ": must be at least 1 (the longer side over the shorter), got " + shown_value(text));
    }
    return ratio;
}

// A calibration element's model: one of lensfun's for that element, "none" where the
// attribute is absent. lensfun's database parser refuses the whole file on any other
// ("Bad attribute value", database.cpp at 0.3.95), so this reader refuses it too rather
// than skip the entry and interpolate the rest.
std::string calibration_model(const Source& source, const pugi::xml_node& element, const std::string& where,
                              std::initializer_list<std::string_view> known) {
    const pugi::xml_attribute attribute = element.attribute("model");
    const std::string model = attribute ? attribute.value() : "none";
    std::string names;
    for (const std::string_view name : known) {
        if (name == model) return model;
        names += (names.empty() ? "" : ", ") + std::string(name);
    }
    source.fail(element, where + " <" + element.name() + "> model: '" + model + "' is not one of lensfun's (" + names +
                             ")");
}

// The models of a calibration's tca and vignetting entries, which libcam does not use
// but lensfun checks.
void check_other_models(const Source& source, const pugi::xml_node& calibration, const std::string& where) {
    for (const pugi::xml_node tca : calibration.children("tca")) {
        calibration_model(source, tca, where, {"none", "linear", "poly3", "acm"});
    }
    for (const pugi::xml_node vignetting : calibration.children("vignetting")) {
        calibration_model(source, vignetting, where, {"none", "pa", "acm"});
    }
}

// The terms a distortion model's attributes hold, lensfun's names for each place.
Distortion read_distortion(const Source& source, const pugi::xml_node& element, const std::string& where) {
    Distortion out;
    out.model = calibration_model(source, element, where, {"none", "poly3", "poly5", "ptlens", "acm"});
    const std::string field = where + " <distortion>";
    const pugi::xml_attribute focal = element.attribute("focal");
    if (!focal) source.fail(element, field + ": has no focal");
    out.focal = source.number(element, focal.value(), field + " focal");
    if (!(out.focal > 0.0)) source.fail(element, field + " focal: must be > 0, got " + format_number(out.focal));
    static constexpr std::array<std::array<const char*, 2>, 3> kNames = {{{"a", "k1"}, {"b", "k2"}, {"c", "k3"}}};
    for (std::size_t i = 0; i < kNames.size(); ++i) {
        for (const char* name : kNames[i]) {
            if (const pugi::xml_attribute term = element.attribute(name)) {
                out.terms[i] = source.number(element, term.value(), field + " " + name);
            }
        }
    }
    const pugi::xml_attribute real_focal = element.attribute("real-focal");
    if (real_focal) {
        out.real_focal = source.number(element, real_focal.value(), field + " real-focal");
        if (!(out.real_focal > 0.0)) {
            source.fail(element, field + " real-focal: must be > 0, got " + format_number(out.real_focal));
        }
    } else if (out.model == "ptlens") {
        out.real_focal = out.focal * (1.0 - out.terms[0] - out.terms[1] - out.terms[2]);
    } else if (out.model == "poly3") {
        out.real_focal = out.focal * (1.0 - out.terms[0]);
    } else {
        out.real_focal = out.focal;
    }
    return out;
}

LensEntry read_lens(const Source& source, const pugi::xml_node& node) {
    LensEntry lens;
    lens.node = node;
    for (const pugi::xml_node model : node.children("model")) lens.names.emplace_back(model.text().get());
    if (lens.names.empty()) source.fail(node, "<lens> has no <model>");
    const std::string where = "lens '" + lens.names.front() + "'";
    if (const pugi::xml_node type = node.child("type")) lens.type = lower(type.text().get());
    if (const pugi::xml_node crop = node.child("cropfactor")) {
        lens.crop_factor = source.number(crop, crop.text().get(), where + " <cropfactor>");
        if (!(lens.crop_factor > 0.0)) source.fail(crop, where + " <cropfactor>: must be > 0, got " + format_number(lens.crop_factor));
    }
    if (const pugi::xml_node aspect = node.child("aspect-ratio")) {
        lens.aspect_ratio = aspect_ratio(source, aspect, aspect.text().get(), where + " <aspect-ratio>");
    }
    if (const pugi::xml_node focal = node.child("focal")) {
        for (const pugi::xml_attribute attribute : focal.attributes()) {
            const double value = source.number(focal, attribute.value(), where + " <focal> " + attribute.name());
            const std::string name = attribute.name();
            if (name == "min" || name == "value") lens.min_focal = value;
            if (name == "max" || name == "value") lens.max_focal = value;
        }
    }
    if (const pugi::xml_node centre = node.child("center")) {
        if (const auto x = centre.attribute("x")) lens.centre_x = source.number(centre, x.value(), where + " <center> x");
        if (const auto y = centre.attribute("y")) lens.centre_y = source.number(centre, y.value(), where + " <center> y");
    }
    // lensfun 0.3.95 puts every calibration of a lens in one set, with the lens's crop
    // factor and aspect ratio (lfLens::GetCalibrationSetForAttributes), whatever the
    // <calibration> element's attributes say.
    for (const pugi::xml_node calibration : node.children("calibration")) {
        check_other_models(source, calibration, where);
        for (const pugi::xml_node element : calibration.children("distortion")) {
            Distortion entry = read_distortion(source, element, where);
            if (entry.model == "none") continue;
            if (!lens.distortion.empty() && entry.model != lens.distortion.front().model) continue;  // as lensfun
            lens.distortion.push_back(entry);
        }
    }
    return lens;
}

// The lens `wanted` names: one whose model name it is (any case), else the one lens whose
// names contain it; the file's one lens when `wanted` is empty.
// One lens of several of one name, calibrated on different sensors: the one whose
// calibration covers `crop` most closely (lensfun's rule, GetClosestCalibrationSet).
const LensEntry& select_by_crop(const Source& source, const std::vector<const LensEntry*>& found,
                                std::optional<double> crop) {
    std::string crops;
    for (const LensEntry* lens : found) crops += (crops.empty() ? "" : ", ") + format_number(lens->crop_factor);
    const std::string what = source.name() + ": '" + found.front()->names.front() + "' names " +
                             std::to_string(found.size()) + " lenses, calibrated on crop factors " + crops;
    if (!crop) throw InvalidArgument(what + ": give the crop factor (--crop-factor)");
    const LensEntry* best = nullptr;
    for (const LensEntry* lens : found) {
        const double ratio = *crop / lens->crop_factor;
        if (ratio >= 0.96 && (!best || ratio < *crop / best->crop_factor)) best = lens;
    }
    if (!best) throw NotRepresentable(what + ", none of which covers crop factor " + format_number(*crop));
    return *best;
}

const LensEntry& select_lens(const Source& source, const std::vector<LensEntry>& lenses, const std::string& wanted,
                             std::optional<double> crop) {
    if (lenses.empty()) throw FileError(source.name() + ": holds no <lens>");
    if (wanted.empty()) {
        if (lenses.size() == 1) return lenses.front();
        throw InvalidArgument(source.name() + ": holds " + std::to_string(lenses.size()) +
                              " lenses: name one (--lens \"MODEL\"), e.g. '" + lenses.front().names.front() + "'");
    }
    const std::string key = lower(wanted);
    std::vector<const LensEntry*> exact, partial;
    for (const LensEntry& lens : lenses) {
        bool is_exact = false, is_partial = false;
        for (const std::string& name : lens.names) {
            const std::string candidate = lower(name);
            is_exact |= candidate == key;
            is_partial |= candidate.find(key) != std::string::npos;
        }
        if (is_exact) exact.push_back(&lens);
        if (is_partial) partial.push_back(&lens);
    }
    const std::vector<const LensEntry*>& found = exact.empty() ? partial : exact;
    if (found.size() == 1) return *found.front();
    const bool one_name = std::all_of(found.begin(), found.end(), [&](const LensEntry* lens) {
        return lens->names.front() == found.front()->names.front();
    });
    if (one_name && !found.empty()) return select_by_crop(source, found, crop);
    if (found.empty()) throw InvalidArgument(source.name() + ": no lens is named '" + wanted + "'");
    std::string names;
    for (std::size_t i = 0; i < found.size() && i < 4; ++i) names += (i ? "', '" : "'") + found[i]->names.front();
    throw InvalidArgument(source.name() + ": '" + wanted + "' names " + std::to_string(found.size()) + " lenses (" + names +
                          (found.size() > 4 ? "', ...)" : "')") + ": give more of the name");
}

// The distortion at `focal` as lfLens::InterpolateDistortion makes it.
Distortion interpolate(const std::vector<Distortion>& entries, double focal) {
    const Distortion* spline[4] = {nullptr, nullptr, nullptr, nullptr};
    double distance[4] = {-HUGE_VAL, -HUGE_VAL, HUGE_VAL, HUGE_VAL};
    for (const Distortion& entry : entries) {
        const double df = focal - entry.focal;
        if (df == 0.0) return entry;
        // lensfun's __insert_spline: the two nearest below (0, 1) and above (2, 3).
        if (df < 0) {
            if (df > distance[1]) {
                distance[0] = distance[1], spline[0] = spline[1];
                distance[1] = df, spline[1] = &entry;
            } else if (df > distance[0]) {
                distance[0] = df, spline[0] = &entry;
            }
        } else if (df < distance[2]) {
            distance[3] = distance[2], spline[3] = spline[2];
            distance[2] = df, spline[2] = &entry;
        } else if (df < distance[3]) {
            distance[3] = df, spline[3] = &entry;
        }
    }
    if (!spline[1] || !spline[2]) return spline[1] ? *spline[1] : *spline[2];
    Distortion out;
    out.model = spline[1]->model;
    out.focal = focal;
    const double t = (focal - spline[1]->focal) / (spline[2]->focal - spline[1]->focal);
    const auto value = [&](int i, auto member) -> std::optional<double> {
        if (!spline[i]) return std::nullopt;
        return member(*spline[i]);
    };
    const auto spline_of = [&](auto member) {
        return detail::lensfun_interpolate(value(0, member), *value(1, member), *value(2, member), value(3, member), t);
    };
    out.real_focal = spline_of([](const Distortion& d) { return d.real_focal; });
    // The terms fall roughly as 1 / f: lensfun interpolates term times focal length, then
    // divides by the focal length asked for (lens.cpp, __parameter_scales).
    for (std::size_t i = 0; i < out.terms.size(); ++i) {
        out.terms[i] = spline_of([i](const Distortion& d) { return d.terms[i] * d.focal; }) / focal;
    }
    return out;
}

struct Selection {
    double focal = 0.0;
    double crop_factor = 0.0;
    ImageSize size;
};

Selection selection(const Source& source, const LensEntry& lens, const ReadOptions& options) {
    const std::string where = source.name() + ": lens '" + lens.names.front() + "'";
    Selection out;
    if (!options.size) {
        throw InvalidArgument(where + ": a lens database records no image size; give the size (--image-size WxH)");
    }
    out.size = *options.size;
    if (options.focal_mm) {
        out.focal = *options.focal_mm;
        if (!(out.focal > 0.0) || !std::isfinite(out.focal)) {
            throw InvalidArgument(where + ": the focal length must be > 0 mm, got " + format_number(out.focal));
        }
    } else if (lens.min_focal > 0.0 && lens.min_focal == lens.max_focal) {
        out.focal = lens.min_focal;
    } else if (lens.min_focal == 0.0 && lens.max_focal == 0.0 && !lens.distortion.empty() &&
               std::all_of(lens.distortion.begin(), lens.distortion.end(),
                           [&](const Distortion& d) { return d.focal == lens.distortion.front().focal; })) {
        out.focal = lens.distortion.front().focal;  // no <focal>: a prime calibrated at one focal length
    } else if (lens.max_focal > 0.0) {
        throw InvalidArgument(where + ": zooms from " + format_number(lens.min_focal) + " to " +
                              format_number(lens.max_focal) + " mm: give the focal length (--focal MM)");
    } else {
        throw InvalidArgument(where + ": is calibrated at several focal lengths: give the focal length (--focal MM)");
    }
    out.crop_factor = options.crop_factor.value_or(lens.crop_factor);
    if (!(out.crop_factor > 0.0) || !std::isfinite(out.crop_factor)) {
        throw InvalidArgument(where + ": the crop factor must be > 0, got " + format_number(out.crop_factor));
    }
    return out;
}

// The radial polynomial in units of the real focal length: r (1 + c r + k1 r^2 + a r^3
// + k2 r^4), ptlens's odd terms a and c, poly3's and poly5's even k1 and k2.
struct Radial {
    double a = 0.0, c = 0.0, k1 = 0.0, k2 = 0.0;
};

// The lens model of a lensfun lens type with that distortion, or a refusal saying why.
// lensfun distorts a fisheye's own projection (mod-coord.cpp: its geometry step, then its
// distortion), which is what the *_RADIAL models are (lens/fisheye_radial.hpp).
Lens lens_of_type(const std::string& where, const std::string& type, Radial radial, bool projection_only) {
    if (projection_only) radial = {};
    const bool odd = radial.a != 0.0 || radial.c != 0.0;
    if (type == "rectilinear") {
        if (odd) return {LensType::Ptlens, {radial.a, radial.k1, radial.c}};
        return simplest_equal_lens({LensType::OpenCv4, {radial.k1, radial.k2, 0.0, 0.0}});
    }
    // An equidistant lens without odd terms comes back as FISHEYE (simplest_equal_lens).
    static const std::map<std::string, LensType> kFisheyes = {{"fisheye", LensType::EquidistantRadial},
                                                              {"equisolid", LensType::EquisolidRadial},
                                                              {"stereographic", LensType::StereographicRadial}};
    if (const auto fisheye = kFisheyes.find(type); fisheye != kFisheyes.end()) {
        return simplest_equal_lens({fisheye->second, {radial.a, radial.k1, radial.c, radial.k2}});
    }
    static const std::map<std::string, LensType> kPanoramas = {{"equirectangular", LensType::Lonlat},
                                                               {"panoramic", LensType::Cylindrical}};
    const auto found = kPanoramas.find(type);
    if (found == kPanoramas.end()) {
        throw NotRepresentable(where + ": lens type '" + type + "' has no libcam model (libcam reads rectilinear, "
                               "fisheye, equisolid, stereographic, equirectangular and panoramic lenses)");
    }
    if (odd || radial.k1 != 0.0 || radial.k2 != 0.0) {
        throw NotRepresentable(where + ": a lens of type " + type + " with distortion has no libcam model (" +
                               std::string(lens_info(found->second).name) +
                               " has no coefficients); read its projection alone (--projection-only) or not at all");
    }
    return {found->second, {}};
}

NamedCamera lens_camera(const Source& source, const LensEntry& lens, const ReadOptions& options) {
    const Selection chosen = selection(source, lens, options);
    const std::string where = source.name() + ": lens '" + lens.names.front() + "' at " + format_number(chosen.focal) + " mm";
    // Without a calibration that applies, lensfun corrects no distortion and takes the
    // nominal focal length for the real one: the projection alone, and only when asked for.
    const bool calibrated = chosen.crop_factor / lens.crop_factor >= 0.96 && !lens.distortion.empty();
    if (!calibrated && !options.lens_projection_only) {
        if (lens.distortion.empty()) {
            throw NotRepresentable(where + ": the database has no distortion calibration for this lens");
        }
        throw NotRepresentable(where + ": calibrated on a sensor of crop factor " + format_number(lens.crop_factor) +
                               ", which does not cover crop factor " + format_number(chosen.crop_factor) +
                               " (lensfun corrects nothing below 0.96 times the calibration's)");
    }
    const Distortion d =
        calibrated ? interpolate(lens.distortion, chosen.focal) : Distortion{"none", chosen.focal, chosen.focal, {}};
    const double width = chosen.size.width, height = chosen.size.height;
    // lensfun's NormScale (modifier.cpp), inverted: pixels per unit of the real focal length.
    const double focal_pixels = d.real_focal * std::hypot(width, height) * chosen.crop_factor / std::hypot(36.0, 24.0);
    const double half_short_side_mm = std::hypot(36.0, 24.0) / lens.crop_factor / std::hypot(lens.aspect_ratio, 1.0) / 2.0;
    const double s = d.real_focal / half_short_side_mm;
    Radial radial;
    if (d.model == "poly3") {
        radial.k1 = d.terms[0] * s * s / std::pow(1.0 - d.terms[0], 3);
    } else if (d.model == "poly5") {
        radial.k1 = d.terms[0] * s * s;
        radial.k2 = d.terms[1] * std::pow(s, 4);
    } else if (d.model == "ptlens") {
        const double scale = 1.0 - d.terms[0] - d.terms[1] - d.terms[2];
        radial.a = d.terms[0] * std::pow(s, 3) / std::pow(scale, 4);
        radial.k1 = d.terms[1] * s * s / std::pow(scale, 3);
        radial.c = d.terms[2] * s / std::pow(scale, 2);
    } else if (d.model != "none") {
        throw NotRepresentable(where + ": distortion model '" + d.model + "' is refused: libcam reads poly3, poly5 "
                               "and ptlens (acm, Adobe's, measures r in another unit)");
    }
    Camera camera;
    camera.size = chosen.size;
    const double short_side = std::min(width - 1.0, height - 1.0);
    camera.intrinsics = {focal_pixels, focal_pixels, (width - 1.0) / 2.0 + short_side / 2.0 * lens.centre_x,
                         (height - 1.0) / 2.0 + short_side / 2.0 * lens.centre_y, 0.0};
    camera.lens = lens_of_type(where, lens.type, radial, options.lens_projection_only);
    return {lens.names.front() + " at " + format_number(chosen.focal) + " mm", {validated_camera(camera, where), std::nullopt}};
}

}  // namespace

std::vector<NamedCamera> read_lensfun(std::string_view text, const ReadContext& context) {
    const Source source(text, context.source);
    pugi::xml_document document;
    load_xml(document, text, context.source);
    const pugi::xml_node root = document.child("lensdatabase");
    if (!root) throw FileError(context.source + ": has no <lensdatabase>");
    std::vector<LensEntry> lenses;
    for (const pugi::xml_node node : root.children("lens")) lenses.push_back(read_lens(source, node));
    return {lens_camera(source, select_lens(source, lenses, context.options.lens, context.options.crop_factor), context.options)};
}

bool claims_lensfun(const DocumentNode& outline) { return outline.find("lensdatabase") != nullptr; }

}  // namespace libcam
