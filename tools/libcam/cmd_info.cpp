// libcam info FILE: every camera a file holds, with what a user checks first: name,
// model, size, K, coefficients, the field of view through the lens, where it has rays,
// and the pose.

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera_options.hpp"
#include "commands.hpp"
#include "libcam/camera/field_of_view.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/io/ocamcalib.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam::cli {

namespace {

using Json = nlohmann::ordered_json;

std::string vec_text(const Vec3& v) { return format_number(v.x() + 0.0) + " " + format_number(v.y() + 0.0) + " " + format_number(v.z() + 0.0); }

std::string axis_text(const AxisFieldOfView& axis) { return format_short(axis.degrees, 5) + " deg"; }

// Each axis's angle is through the lens; it spans the image edge to edge unless the lens has
// no ray for the pixels at that edge, and then it stops at the last pixel that has one.
std::string fov_text(const FieldOfView& fov) {
    const std::string horizontal = "horizontal " + axis_text(fov.horizontal);
    const std::string vertical = "vertical " + axis_text(fov.vertical);
    if (fov.horizontal.edge_to_edge && fov.vertical.edge_to_edge)
        return horizontal + ", " + vertical + " (through the lens, edge to edge)";
    const auto span = [](const AxisFieldOfView& axis) {
        return std::string(axis.edge_to_edge ? " (edge to edge)" : " (to the last pixel with a ray)");
    };
    return horizontal + span(fov.horizontal) + ", " + vertical + span(fov.vertical) + ", through the lens";
}

// The field of view of each distinct calibration (image size, K and lens, compared bit for
// bit), worked out once: the views of a reconstruction mostly share a few calibrations, and
// each takes a millisecond or more.
class CalibrationFields {
public:
    const FieldOfView& of(const Camera& camera) {
        camera.validate();
        std::vector<double> values{static_cast<double>(camera.size.width), static_cast<double>(camera.size.height),
                                   camera.intrinsics.fx, camera.intrinsics.fy, camera.intrinsics.cx,
                                   camera.intrinsics.cy, camera.intrinsics.skew, static_cast<double>(camera.lens.type)};
        values.insert(values.end(), camera.lens.coefficients.begin(), camera.lens.coefficients.end());
        std::string key(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
        const auto known = fields_.find(key);
        if (known != fields_.end()) return known->second;
        return fields_.emplace(std::move(key), field_of_view(PreparedCamera(camera))).first->second;
    }

private:
    std::map<std::string, FieldOfView> fields_;
};

std::string camera_text(std::size_t index, const NamedCamera& named, const FieldOfView& fov) {
    const Camera& camera = named.file.camera;
    const LensInfo& lens = lens_info(camera.lens.type);
    const Intrinsics& k = camera.intrinsics;
    std::ostringstream out;
    out << "camera " << index << (named.name.empty() ? "" : ": " + named.name)
        << (named.intrinsics_name.empty() ? "" : " (intrinsics " + named.intrinsics_name + ")") << "\n";
    out << "  model     " << lens.name << "\n";
    out << "  size      " << camera.size.width << "x" << camera.size.height << "\n";
    out << "  K         fx " << format_number(k.fx) << ", fy " << format_number(k.fy) << ", cx " << format_number(k.cx)
        << ", cy " << format_number(k.cy) << ", skew " << format_number(k.skew) << "\n";
    if (!camera.lens.coefficients.empty()) {
        out << "  dist      ";
        const auto names = lens.coefficients.view();
        for (std::size_t i = 0; i < camera.lens.coefficients.size(); ++i) {
            const std::string name = i < names.size() ? std::string(names[i]) : "c" + std::to_string(i);
            if (i > 0) out << ", ";
            if (i == 12 && camera.lens.type == LensType::SplinedStereographic) {
                out << "... (" << camera.lens.coefficients.size() - 4 << " control values)";
                break;
            }
            out << name << " " << format_number(camera.lens.coefficients[i]);
        }
        out << "\n";
    }
    out << "  fov       " << fov_text(fov) << "\n";
    out << "  rays      up to " << format_short(fov.valid_angle_deg, 5) << " deg from the optical axis; "
        << (fov.rayless_fraction == 0 ? std::string("every pixel has one")
                                      : format_short(100 * fov.rayless_fraction, 3) + "% of the pixels have none")
        << "\n";
    if (named.unposed) {
        out << "  pose      none: the file lists this view without a pose (not aligned or not reconstructed)\n";
    } else {
        out << "  pose      world to camera: rvec " << vec_text(camera.pose.rvec()) << ", t " << vec_text(camera.pose.t)
            << "; centre " << vec_text(camera.pose.centre()) << "\n";
    }
    return out.str();
}

// OCamCalib's files carry invpol, a polynomial fitted to the projection, which the toolbox's C
// world2cam evaluates; libcam projects exactly. How far invpol lands from each pixel.
std::optional<InverseMiss> inverse_miss(const std::string& file, const CameraSet& set, const NamedCamera& named) {
    if (set.format != CameraFormat::OcamCalib && set.format != CameraFormat::PyOcamCalib) return std::nullopt;
    const std::optional<OcamCalibInverse> inverse = read_ocamcalib_inverse(file);
    if (!inverse) return std::nullopt;
    return ocamcalib_inverse_miss(named.file.camera, *inverse);
}

std::string inverse_text(const InverseMiss& miss) {
    return "  invpol    the file's fitted inverse polynomial (what OCamCalib's C world2cam evaluates) lands up to " +
           format_short(miss.within_half_side, 3) + " px from the exact projection within min(width, height) / 2 of "
           "the centre, " + format_short(miss.whole_image, 3) + " px over the image (at pixel " +
           format_number(miss.worst_pixel.x()) + ", " + format_number(miss.worst_pixel.y()) + ")\n";
}

Json camera_json(std::size_t index, const NamedCamera& named, const FieldOfView& fov) {
    const Camera& camera = named.file.camera;
    const Intrinsics& k = camera.intrinsics;
    const auto vec = [](const Vec3& v) { return Json::array({v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}); };
    return {{"index", index},
            {"name", named.name},
            {"intrinsics_name", named.intrinsics_name},
            {"posed", !named.unposed},
            {"model", lens_info(camera.lens.type).name},
            {"image_size", {camera.size.width, camera.size.height}},
            {"K", {{k.fx, k.skew, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}}},
            {"dist", camera.lens.coefficients},
            {"fov_deg", {{"horizontal", fov.horizontal.degrees}, {"vertical", fov.vertical.degrees}}},
            {"fov_edge_to_edge", {{"horizontal", fov.horizontal.edge_to_edge}, {"vertical", fov.vertical.edge_to_edge}}},
            {"valid_angle_deg", fov.valid_angle_deg},
            {"rayless_fraction", fov.rayless_fraction},
            {"rvec", vec(camera.pose.rvec())},
            {"t", vec(camera.pose.t)},
            {"camera_center", vec(camera.pose.centre())}};
}

}  // namespace

Runner add_info(CLI::App& app) {
    CLI::App* command = add_command(app, "info");
    struct Flags {
        std::string file;
        FileSelection selection;
        bool json = false;
    };
    auto flags = std::make_shared<Flags>();
    command->add_option("FILE", flags->file, "Camera file, or a COLMAP model's folder (any format libcam reads)")
        ->required();
    flags->selection.add_to(*command);
    command->add_flag("--json", flags->json, "Print {\"file\", \"format\", \"cameras\": [...]}");
    return [flags] {
        CameraSet set = flags->selection.read_set(flags->file);
        std::size_t first = 0;
        if (!flags->selection.camera.empty()) {
            // Only the camera asked for, keeping its index in the file.
            const NamedCamera& chosen = select_camera(set, flags->selection.camera, flags->file);
            const std::size_t index = static_cast<std::size_t>(&chosen - set.cameras.data());
            set.cameras = {chosen};
            first = index;
        }
        CalibrationFields fields;
        if (flags->json) {
            Json out = {{"file", flags->file}, {"format", to_string(set.format)}, {"cameras", Json::array()}};
            for (std::size_t i = 0; i < set.cameras.size(); ++i) {
                Json camera = camera_json(first + i, set.cameras[i], fields.of(set.cameras[i].file.camera));
                if (const auto miss = inverse_miss(flags->file, set, set.cameras[i])) {
                    camera["invpol_miss_px"] = {{"within_half_side", miss->within_half_side},
                                                {"whole_image", miss->whole_image},
                                                {"worst_pixel", {miss->worst_pixel.x(), miss->worst_pixel.y()}}};
                }
                out["cameras"].push_back(camera);
            }
            emit(out.dump(2) + "\n", "");
            return 0;
        }
        std::ostringstream out;
        out << flags->file << ": " << to_string(set.format) << ", " << set.cameras.size()
            << (set.cameras.size() == 1 ? " camera" : " cameras") << "\n";
        for (std::size_t i = 0; i < set.cameras.size(); ++i) {
            out << "\n" << camera_text(first + i, set.cameras[i], fields.of(set.cameras[i].file.camera));
            if (const auto miss = inverse_miss(flags->file, set, set.cameras[i])) out << inverse_text(*miss);
        }
        emit(out.str(), "");
        return 0;
    };
}

}  // namespace libcam::cli
