#include "libcam/io/detail/metashape_format.hpp"

#include <Eigen/LU>
#include <pugixml.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <filesystem>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/pose.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/xml_source.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/shown_value.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

// The file's fields, read with messages that name the line of their element.
class Source : public XmlSource {
public:
    using XmlSource::XmlSource;

    // The numbers of an element's text, exactly `count` of them ("<where> <element>").
    std::vector<double> numbers(const pugi::xml_node& element, std::size_t count, const std::string& where) const {
        std::vector<double> values;
        std::string_view rest = element.text().get();
        while (true) {
            const auto start = rest.find_first_not_of(" \t\r\n");
            if (start == std::string_view::npos) break;
            rest.remove_prefix(start);
            const std::string_view word = rest.substr(0, rest.find_first_of(" \t\r\n"));
            double value = 0.0;
            const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
            if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
                fail(element, where + " <" + element.name() + ">: must be a finite number, got " + shown_value(word));
            }
            if (values.size() == count) {
                fail(element, where + " <" + element.name() + ">: expected " + std::to_string(count) + " numbers, got more");
            }
            values.push_back(value);
            rest.remove_prefix(word.size());
        }
        if (values.size() != count) {
            fail(element, where + " <" + element.name() + ">: expected " + std::to_string(count) + " numbers, got " +
                              std::to_string(values.size()));
        }
        return values;
    }

    // A child element's one number, or `fallback` where the element is absent.
    double number_or(const pugi::xml_node& parent, const char* name, double fallback, const std::string& where) const {
        const pugi::xml_node element = parent.child(name);
        return element ? numbers(element, 1, where)[0] : fallback;
    }

    // An image side: a whole number of pixels, from an attribute or an element's text.
    long side(const pugi::xml_node& node, std::string_view text, const std::string& field) const {
        long value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > kMaxImageSide) {
            fail(node, field + ": must be a whole number of pixels in [1, " + std::to_string(kMaxImageSide) +
                           "], got " + shown_value(text));
        }
        return value;
    }
};

// A calibration's numbers as Metashape writes them (absent ones are 0).
struct Calibration {
    std::string type = "frame";
    ImageSize size;
    double f = 0.0, cx = 0.0, cy = 0.0, b1 = 0.0, b2 = 0.0;
    double k1 = 0.0, k2 = 0.0, k3 = 0.0, k4 = 0.0, p1 = 0.0, p2 = 0.0;
};

Calibration read_terms(const Source& source, const pugi::xml_node& calibration, Calibration out, const std::string& where) {
    const pugi::xml_node f = calibration.child("f");
    if (!f) source.fail(calibration, where + ": <calibration> has no <f>");
    out.f = source.numbers(f, 1, where)[0];
    double* const terms[] = {&out.cx, &out.cy, &out.b1, &out.b2, &out.k1, &out.k2,
                             &out.k3, &out.k4, &out.p1, &out.p2};
    const char* const names[] = {"cx", "cy", "b1", "b2", "k1", "k2", "k3", "k4", "p1", "p2"};
    for (std::size_t i = 0; i < std::size(names); ++i) *terms[i] = source.number_or(calibration, names[i], 0.0, where);
    return out;
}

ImageSize resolution(const Source& source, const pugi::xml_node& element, const std::string& where) {
    return {source.side(element, element.attribute("width").value(), where + " <resolution> width"),
            source.side(element, element.attribute("height").value(), where + " <resolution> height")};
}

// Metashape's camera as libcam's (the header says how each term maps).
Camera camera_from(const Source& source, const pugi::xml_node& node, const Calibration& c, const std::string& where) {
    Camera camera;
    camera.size = c.size;
    const double centre_x = 0.5 * static_cast<double>(c.size.width) - 0.5;
    const double centre_y = 0.5 * static_cast<double>(c.size.height) - 0.5;
    camera.intrinsics = {c.f + c.b1, c.f, centre_x + c.cx, centre_y + c.cy, c.b2};
    const auto refuse = [&](const std::string& what) {
        throw NotRepresentable(source.name() + ": " + where + ": " + what);
    };
    if (c.type == "frame") {
        camera.lens = simplest_equal_lens({LensType::BrownK4, {c.k1, c.k2, c.p2, c.p1, c.k3, c.k4}});
    } else if (c.type == "fisheye") {
        if (c.p1 != 0.0 || c.p2 != 0.0) {
            refuse("a fisheye sensor's tangential terms (p1 = " + format_number(c.p1) + ", p2 = " + format_number(c.p2) +
                   ") have no libcam model (FISHEYE is Kannala-Brandt's radial polynomial only)");
        }
        camera.lens = {LensType::Fisheye, {c.k1, c.k2, c.k3, c.k4}};
    } else if (c.type == "spherical") {
        if (c.b1 != 0.0 || c.b2 != 0.0 || c.k1 != 0.0 || c.k2 != 0.0 || c.k3 != 0.0 || c.k4 != 0.0 || c.p1 != 0.0 ||
            c.p2 != 0.0) {
            refuse("a spherical sensor with distortion or affinity terms has no libcam model (LONLAT has none)");
        }
        camera.lens = {LensType::Lonlat, {}};
    } else {
        source.fail(node, where + ": camera type '" + c.type + "' is refused: libcam reads frame, fisheye and "
                                  "spherical sensors");
    }
    return validated_camera(camera, source.name() + ": " + where);
}

// x_out = scale R x + t: Metashape's chunk and component transforms.
struct Similarity {
    double scale = 1.0;
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();

    // This applied after `inner`.
    Similarity after(const Similarity& inner) const {
        return {scale * inner.scale, R * inner.R, scale * (R * inner.t) + t};
    }
};

Similarity read_similarity(const Source& source, const pugi::xml_node& transform, const std::string& where) {
    Similarity out;
    if (!transform) return out;
    if (const pugi::xml_node rotation = transform.child("rotation")) {
        const std::vector<double> r = source.numbers(rotation, 9, where + " <transform>");
        for (int i = 0; i < 9; ++i) out.R(i / 3, i % 3) = r[static_cast<std::size_t>(i)];
    }
    if (const pugi::xml_node translation = transform.child("translation")) {
        const std::vector<double> t = source.numbers(translation, 3, where + " <transform>");
        out.t = Vec3(t[0], t[1], t[2]);
    }
    out.scale = source.number_or(transform, "scale", 1.0, where + " <transform>");
    if (!(out.scale > 0.0)) source.fail(transform, where + " <transform> <scale>: must be > 0, got " + format_number(out.scale));
    return out;
}

// A camera's world-to-camera pose from its 4x4 camera-to-chunk (or -component) matrix
// and the similarity taking that frame to the world. The similarity's scale stretches the
// camera's position but not its axes: the world point X_world = s R M X_cam + T seen
// from the camera is X_cam = (R M)^T (X_world - T) / s, and projection x = X/Z does not
// see the 1/s, so libcam's pose is the rigid part (R M)^T, -(R M)^T T.
Pose camera_pose(const Source& source, const pugi::xml_node& transform, const Similarity& to_world,
                 const std::string& where) {
    const std::vector<double> m = source.numbers(transform, 16, where);
    if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
        source.fail(transform, where + " <transform>: the last row must be 0 0 0 1, got " + format_number(m[12]) + " " +
                                   format_number(m[13]) + " " + format_number(m[14]) + " " + format_number(m[15]));
    }
    Similarity camera;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) camera.R(i, j) = m[static_cast<std::size_t>(4 * i + j)];
        camera.t(i) = m[static_cast<std::size_t>(4 * i + 3)];
    }
    const Similarity world = to_world.after(camera);
    return Pose::from_centre(world.R.transpose(), world.t);
}

struct Sensor {
    std::string label;
    std::optional<Camera> camera;  // none: the sensor has no calibration
};

std::string sensor_where(const pugi::xml_node& sensor) {
    return std::string("sensor ") + sensor.attribute("id").value() + " ('" + sensor.attribute("label").value() + "')";
}

// The adjusted calibration where there is one (what alignment solved), else the initial.
pugi::xml_node chosen_calibration(const pugi::xml_node& sensor) {
    pugi::xml_node initial;
    for (const pugi::xml_node calibration : sensor.children("calibration")) {
        if (std::string_view(calibration.attribute("class").value()) == "adjusted") return calibration;
        if (!initial) initial = calibration;
    }
    return initial;
}

// A sensor's or calibration's type, where it states one: one of Metashape's
// (Metashape.Sensor.Type: frame, fisheye, spherical, cylindrical, rpc), whether or not
// libcam has its model (camera_from says which it reads).
void check_type(const Source& source, const pugi::xml_node& node, const std::string& where) {
    const pugi::xml_attribute type = node.attribute("type");
    if (!type) return;
    for (const std::string_view known : {"frame", "fisheye", "spherical", "cylindrical", "rpc"}) {
        if (type.value() == known) return;
    }
    source.fail(node, where + " <" + node.name() + "> type: '" + type.value() +
                          "' is not one of Metashape's sensor types (frame, fisheye, spherical, cylindrical, rpc)");
}

// What a sensor states, checked whether or not the camera made of it uses it: its type
// and size, and each of its calibrations' (a sensor without a calibration is skipped,
// and the adjusted calibration's size stands for the sensor's).
void check_sensor(const Source& source, const pugi::xml_node& sensor, const std::string& where) {
    check_type(source, sensor, where);
    if (const pugi::xml_node size = sensor.child("resolution")) resolution(source, size, where);
    for (const pugi::xml_node calibration : sensor.children("calibration")) {
        check_type(source, calibration, where);
        if (const pugi::xml_node size = calibration.child("resolution")) resolution(source, size, where);
    }
}

Sensor read_sensor(const Source& source, const pugi::xml_node& sensor) {
    const std::string where = sensor_where(sensor);
    check_sensor(source, sensor, where);
    const pugi::xml_node calibration = chosen_calibration(sensor);
    if (!calibration) return {sensor.attribute("label").value(), std::nullopt};
    Calibration terms;
    terms.type = calibration.attribute("type") ? calibration.attribute("type").value() : sensor.attribute("type").as_string("frame");
    const pugi::xml_node size = calibration.child("resolution") ? calibration.child("resolution") : sensor.child("resolution");
    if (!size) source.fail(sensor, where + ": no <resolution>");
    terms.size = resolution(source, size, where);
    return {sensor.attribute("label").value(), camera_from(source, calibration, read_terms(source, calibration, terms, where), where)};
}

// A chunk's aligned cameras, then those not aligned whose sensor is calibrated (unposed);
// where it has neither, its calibrated sensors.
void read_chunk(const Source& source, const pugi::xml_node& chunk, std::vector<NamedCamera>& out) {
    std::map<std::string, Sensor, std::less<>> sensors;
    std::vector<std::string> sensor_order;
    for (const pugi::xml_node sensor : chunk.child("sensors").children("sensor")) {
        const std::string id = sensor.attribute("id").value();
        if (sensors.contains(id)) source.fail(sensor, sensor_where(sensor) + ": sensor id " + id + " given twice");
        sensors.emplace(id, read_sensor(source, sensor));
        sensor_order.push_back(id);
    }
    const Similarity chunk_to_world = read_similarity(source, chunk.child("transform"), "chunk");
    std::map<std::string, Similarity, std::less<>> components;
    for (const pugi::xml_node component : chunk.child("components").children("component")) {
        const std::string where = std::string("component ") + component.attribute("id").value();
        components[component.attribute("id").value()] =
            chunk_to_world.after(read_similarity(source, component.child("transform"), where));
    }
    std::vector<pugi::xml_node> cameras;  // camera groups (folders) hold cameras too
    for (const pugi::xml_node node : chunk.child("cameras").children()) {
        if (std::string_view(node.name()) == "camera") cameras.push_back(node);
        if (std::string_view(node.name()) == "group") {
            for (const pugi::xml_node camera : node.children("camera")) cameras.push_back(camera);
        }
    }
    const std::size_t first = out.size();
    std::vector<NamedCamera> unaligned;
    for (const pugi::xml_node camera : cameras) {
        const std::string where = std::string("camera ") + camera.attribute("id").value() + " ('" +
                                  camera.attribute("label").value() + "')";
        const auto sensor = sensors.find(std::string_view(camera.attribute("sensor_id").value()));
        if (sensor == sensors.end()) {
            source.fail(camera, where + ": sensor_id '" + camera.attribute("sensor_id").value() + "' is not a sensor");
        }
        const pugi::xml_node transform = camera.child("transform");
        if (!transform) {
            // Not aligned: its sensor's calibration without a pose, where the sensor has one.
            if (sensor->second.camera) {
                unaligned.push_back({camera.attribute("label").value(), {*sensor->second.camera, {}},
                                     sensor->second.label, true});
            }
            continue;
        }
        if (!sensor->second.camera) {
            source.fail(camera, where + ": its sensor '" + sensor->second.label + "' has no calibration");
        }
        Similarity to_world = chunk_to_world;
        if (const pugi::xml_attribute component_id = camera.attribute("component_id")) {
            const auto component = components.find(std::string_view(component_id.value()));
            if (component == components.end()) {
                source.fail(camera, where + ": component_id '" + component_id.value() + "' is not a component");
            }
            to_world = component->second;
        }
        Camera posed = *sensor->second.camera;
        posed.pose = camera_pose(source, transform, to_world, where);
        out.push_back({camera.attribute("label").value(), {validated_camera(posed, source.name() + ": " + where), {}},
                       sensor->second.label});
    }
    out.insert(out.end(), std::make_move_iterator(unaligned.begin()), std::make_move_iterator(unaligned.end()));
    if (out.size() != first) return;
    for (const std::string& id : sensor_order) {
        const Sensor& sensor = sensors.at(id);
        if (sensor.camera) out.push_back({sensor.label, {*sensor.camera, {}}, sensor.label});
    }
}

// Export Calibration's file: <calibration><projection>frame</projection><width>... .
NamedCamera read_calibration_file(const Source& source, const pugi::xml_node& root) {
    Calibration terms;
    const pugi::xml_node projection = root.child("projection");
    if (projection) terms.type = projection.text().get();
    const pugi::xml_node width = root.child("width");
    const pugi::xml_node height = root.child("height");
    if (!width || !height) source.fail(root, "<calibration>: no <width> and <height>");
    terms.size = {source.side(width, width.text().get(), "<calibration> <width>"),
                  source.side(height, height.text().get(), "<calibration> <height>")};
    return {std::string(), {camera_from(source, root, read_terms(source, root, terms, "<calibration>"), "<calibration>"), {}}};
}

// ---- PhotoScan before 1.0: <collection> -------------------------------------------------

// The collection's <transform>: 16 numbers, row by row, [s R | t; 0 0 0 1], the cameras'
// frame to the world. The scale is the cube root of the 3x3 block's determinant.
Similarity collection_similarity(const Source& source, const pugi::xml_node& transform) {
    Similarity out;
    if (!transform) return out;
    const std::vector<double> m = source.numbers(transform, 16, "<collection>");
    Mat3 scaled;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) scaled(i, j) = m[static_cast<std::size_t>(4 * i + j)];
        out.t(i) = m[static_cast<std::size_t>(4 * i + 3)];
    }
    const double determinant = scaled.determinant();
    out.scale = std::cbrt(determinant);
    out.R = nearest_rotation_if_rounded(scaled / out.scale);
    const bool rotation = determinant > 0.0 && (out.R.transpose() * out.R - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-6;
    if (!rotation || m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
        source.fail(transform, "<collection> <transform>: not a rotation with a scale and a translation, [s R | t; 0 0 "
                               "0 1] (the 3x3 block's determinant is " + format_number(determinant) + ")");
    }
    return out;
}

// A camera's own <calibration> in Agisoft Lens's terms (the header says how they map).
Camera collection_camera(const Source& source, const pugi::xml_node& calibration, const std::string& where) {
    const pugi::xml_node width = calibration.child("width");
    const pugi::xml_node height = calibration.child("height");
    if (!width || !height) source.fail(calibration, where + " <calibration>: no <width> and <height>");
    for (const char* const required : {"fx", "fy", "cx", "cy"}) {
        if (!calibration.child(required)) source.fail(calibration, where + " <calibration>: no <" + required + ">");
    }
    const auto term = [&](const char* name) { return source.number_or(calibration, name, 0.0, where); };
    if (term("k4") != 0.0) {
        source.fail(calibration.child("k4"), where + " <k4>: PhotoScan's calibration before 1.0 has no k4 (got " +
                                                 format_number(term("k4")) + ")");
    }
    Camera camera;
    camera.size = {source.side(width, width.text().get(), where + " <calibration> <width>"),
                   source.side(height, height.text().get(), where + " <calibration> <height>")};
    // Agisoft's pixel (0, 0) is the top-left pixel's corner: OpenCV's is half a pixel on.
    camera.intrinsics = {term("fx"), term("fy"), term("cx") - 0.5, term("cy") - 0.5, term("skew")};
    camera.lens = simplest_equal_lens({LensType::OpenCv5, {term("k1"), term("k2"), term("p1"), term("p2"), term("k3")}});
    return validated_camera(camera, source.name() + ": " + where);
}

// PhotoScan's (0.9's) Export Cameras: each camera with its own calibration; posed cameras
// first, then those without a <transform> (not aligned), unposed.
std::vector<NamedCamera> read_collection(const Source& source, const pugi::xml_node& root) {
    const Similarity to_world = collection_similarity(source, root.child("transform"));
    std::vector<NamedCamera> posed, unposed;
    for (const pugi::xml_node camera : root.child("cameras").children("camera")) {
        const std::string where = std::string("camera '") + camera.attribute("label").value() + "'";
        const pugi::xml_node calibration = camera.child("calibration");
        if (!calibration) continue;  // no calibration: nothing to read
        NamedCamera named{camera.attribute("label").value(), {collection_camera(source, calibration, where), {}}};
        if (const pugi::xml_node transform = camera.child("transform")) {
            named.file.camera.pose = camera_pose(source, transform, to_world, where);
            named.file.camera = validated_camera(named.file.camera, source.name() + ": " + where);
            posed.push_back(std::move(named));
        } else {
            named.unposed = true;
            unposed.push_back(std::move(named));
        }
    }
    posed.insert(posed.end(), std::make_move_iterator(unposed.begin()), std::make_move_iterator(unposed.end()));
    if (posed.empty()) source.fail(root, "PhotoScan's <collection>: no camera with a <calibration>");
    return posed;
}

}  // namespace

std::vector<NamedCamera> read_metashape(std::string_view text, const ReadContext& context) {
    pugi::xml_document document;
    load_xml(document, text, context.source);
    const Source source(text, context.source);
    const pugi::xml_node root = document.document_element();
    const std::string_view name = root.name();
    if (name == "calibration") return {read_calibration_file(source, root)};
    if (name == "collection") return read_collection(source, root);
    if (name != "document") {
        source.fail(root, "expected Metashape's <document> or <calibration>, or PhotoScan's <collection> (before 1.0), "
                          "got <" + std::string(name) + ">");
    }
    std::vector<NamedCamera> cameras;
    for (const pugi::xml_node chunk : root.children("chunk")) read_chunk(source, chunk, cameras);
    if (cameras.empty()) source.fail(root, "<document>: no aligned camera and no calibrated sensor");
    return cameras;
}

bool claims_metashape(const DocumentNode& outline) {
    if (const DocumentNode* document = outline.find("document")) return document->find("chunk") != nullptr;
    if (const DocumentNode* collection = outline.find("collection")) return collection->find("cameras") != nullptr;
    if (const DocumentNode* calibration = outline.find("calibration")) return calibration->find("projection") != nullptr;
    return false;
}

}  // namespace libcam

// ---- writing ---------------------------------------------------------------------------

namespace libcam {

namespace {

// A camera's terms in Metashape's names (the inverse of camera_from).
Calibration metashape_terms(const Camera& camera) {
    Calibration c;
    c.size = camera.size;
    const Intrinsics& K = camera.intrinsics;
    c.f = K.fy;
    c.b1 = K.fx - K.fy;
    c.b2 = K.skew;
    c.cx = K.cx - (0.5 * static_cast<double>(camera.size.width) - 0.5);
    c.cy = K.cy - (0.5 * static_cast<double>(camera.size.height) - 0.5);
    const std::vector<double>& k = camera.lens.coefficients;
    switch (camera.lens.type) {
        case LensType::Pinhole: return c;
        case LensType::OpenCv4:
        case LensType::OpenCv5:
        case LensType::BrownK4:
            c.k1 = k[0];
            c.k2 = k[1];
            c.p2 = k[2];  // OpenCV's p1 is Metashape's P2
            c.p1 = k[3];
            c.k3 = k.size() > 4 ? k[4] : 0.0;
            c.k4 = k.size() > 5 ? k[5] : 0.0;
            return c;
        case LensType::Fisheye:
            c.type = "fisheye";
            c.k1 = k[0];
            c.k2 = k[1];
            c.k3 = k[2];
            c.k4 = k[3];
            return c;
        case LensType::Lonlat:
            // fx and fy a few ulps apart are one focal length rounded twice (a file that
            // holds it as a sensor width and a focal length, as Blender's does).
            if (std::abs(c.b1) <= 1e-12 * std::abs(K.fy)) c.b1 = 0.0;
            if (c.b1 != 0.0 || c.b2 != 0.0) {
                throw NotRepresentable("a Metashape spherical sensor has one focal length and no skew; this camera's "
                                       "fx = " + format_number(K.fx) + ", fy = " + format_number(K.fy) +
                                       ", skew = " + format_number(K.skew));
            }
            c.type = "spherical";
            return c;
        // Every other model, named so that the compiler asks here about a new one.
        case LensType::OpenCv8:
        case LensType::OpenCv12:
        case LensType::OpenCv14:
        case LensType::Stereographic:
        case LensType::Latlon:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Mei:
        case LensType::Fov:
        case LensType::ThinPrismFisheye:
        case LensType::RadTanThinPrismFisheye:
        case LensType::Equisolid:
        case LensType::EquidistantRadial:
        case LensType::EquisolidRadial:
        case LensType::StereographicRadial:
        case LensType::Cahvor:
        case LensType::Cahvore:
        case LensType::LensPolynomial:
        case LensType::SplinedStereographic:
        case LensType::Cylindrical:
        case LensType::Ptlens:
        case LensType::OcamCalib:
        case LensType::Division:
        case LensType::ThetaPolynomial:
        case LensType::FTheta:
        case LensType::FThetaForward:
            detail::refuse_lens(CameraFormat::Metashape, camera.lens.type);
    }
    detail::refuse_lens(CameraFormat::Metashape, camera.lens.type);
}

void add_number(pugi::xml_node parent, const char* name, double value) {
    parent.append_child(name).text().set(format_number(value).c_str());
}

// The terms of a calibration, in the order Metashape writes them; zeros left out, as it does.
void add_terms(pugi::xml_node node, const Calibration& c) {
    add_number(node, "f", c.f);
    const std::pair<const char*, double> terms[] = {{"cx", c.cx}, {"cy", c.cy}, {"b1", c.b1}, {"b2", c.b2},
                                                    {"k1", c.k1}, {"k2", c.k2}, {"k3", c.k3}, {"k4", c.k4},
                                                    {"p1", c.p1}, {"p2", c.p2}};
    for (const auto& [name, value] : terms) {
        if (value != 0.0) add_number(node, name, value);
    }
}

void add_resolution(pugi::xml_node parent, const ImageSize& size) {
    pugi::xml_node resolution = parent.append_child("resolution");
    resolution.append_attribute("width") = static_cast<long long>(size.width);
    resolution.append_attribute("height") = static_cast<long long>(size.height);
}

std::string text_of(const pugi::xml_document& document) {
    std::ostringstream out;
    document.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

std::string calibration_file(const Calibration& c) {
    pugi::xml_document document;
    pugi::xml_node root = document.append_child("calibration");
    root.append_child("projection").text().set(c.type.c_str());
    root.append_child("width").text().set(static_cast<long long>(c.size.width));
    root.append_child("height").text().set(static_cast<long long>(c.size.height));
    add_terms(root, c);
    return text_of(document);
}

std::string cameras_file(const Camera& camera, const Calibration& c, const WriteOptions& options) {
    pugi::xml_document document;
    pugi::xml_node root = document.append_child("document");
    root.append_attribute("version") = "1.5.0";
    pugi::xml_node chunk = root.append_child("chunk");
    chunk.append_attribute("label") = "Chunk 1";
    chunk.append_attribute("enabled") = "true";
    pugi::xml_node sensors = chunk.append_child("sensors");
    sensors.append_attribute("next_id") = 1;
    pugi::xml_node sensor = sensors.append_child("sensor");
    sensor.append_attribute("id") = 0;
    sensor.append_attribute("label") = options.camera_name.c_str();
    sensor.append_attribute("type") = c.type.c_str();
    add_resolution(sensor, c.size);
    pugi::xml_node calibration = sensor.append_child("calibration");
    calibration.append_attribute("type") = c.type.c_str();
    calibration.append_attribute("class") = "adjusted";
    add_resolution(calibration, c.size);
    add_terms(calibration, c);
    pugi::xml_node cameras = chunk.append_child("cameras");
    cameras.append_attribute("next_id") = 1;
    cameras.append_attribute("next_group_id") = 0;
    pugi::xml_node node = cameras.append_child("camera");
    node.append_attribute("id") = 0;
    node.append_attribute("sensor_id") = 0;
    node.append_attribute("label") = std::filesystem::path(options.image_name).stem().string().c_str();
    // Camera to world, row by row: [R^T | C; 0 0 0 1].
    const Mat3 Rt = camera.pose.R.transpose();
    const Vec3 centre = camera.pose.centre();
    std::string matrix;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) matrix += format_number(Rt(i, j)) + " ";
        matrix += format_number(centre(i)) + " ";
    }
    matrix += "0 0 0 1";
    node.append_child("transform").text().set(matrix.c_str());
    return text_of(document);
}

}  // namespace

std::string format_metashape(const Camera& camera, const WriteOptions& options) {
    const Calibration terms = metashape_terms(camera);
    return options.drop_pose ? calibration_file(terms) : cameras_file(camera, terms, options);
}

}  // namespace libcam
