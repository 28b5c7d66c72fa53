// libcam rays: the ray through each pixel, by the calibrated path R^T K^-1 [x, y, 1]
// and, for a look-at camera, by the look-at formula, with the angle between them; and
// libcam project, the other way: the pixel of each world point.

#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera_options.hpp"
#include "commands.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

struct RayRow {
    Vec2 pixel;  // as the user gave it
    Ray ray;
    std::optional<Vec3> look_at_direction;  // unit
};

// The look-at camera to run the look-at formula on: the file's own, or any axis on which the
// calibrated camera is one.
std::optional<LookAtCamera> graphics_camera_of(const CameraFile& file) {
    if (file.look_at_camera) return file.look_at_camera;
    const FovDescription description = describe_fov(file.camera);
    if (!description.is_look_at_camera()) return std::nullopt;
    return to_look_at_camera(file.camera, description.fov_axes.front());
}

// + 0.0 prints zeros as 0, not -0.
nlohmann::json vec_json(const Vec3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }

std::string format_json(const std::vector<RayRow>& rows) {
    nlohmann::json out;
    out["rays"] = nlohmann::json::array();
    for (const RayRow& row : rows) {
        nlohmann::json entry;
        entry["pixel"] = {row.pixel.x(), row.pixel.y()};
        entry["valid"] = row.ray.valid;
        entry["origin"] = vec_json(row.ray.origin);
        entry["direction"] = row.ray.valid ? vec_json(row.ray.direction) : nlohmann::json(nullptr);
        entry["direction_look_at"] = row.look_at_direction ? vec_json(*row.look_at_direction) : nlohmann::json(nullptr);
        entry["angle_rad"] = row.ray.valid && row.look_at_direction
                                 ? nlohmann::json(angle_between(row.ray.direction, *row.look_at_direction))
                                 : nlohmann::json(nullptr);
        out["rays"].push_back(entry);
    }
    return out.dump(2) + "\n";
}

std::string format_table(const std::vector<RayRow>& rows) {
    // Ten significant digits; + 0.0 prints zeros as 0, not -0.
    const auto number = [](double value) { return format_short(value + 0.0, 10); };
    const auto vec = [&](const Vec3& v) { return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")"; };
    std::ostringstream out;
    for (const RayRow& row : rows) {
        out << "pixel (" << format_short(row.pixel.x(), 10) << ", " << format_short(row.pixel.y(), 10) << ")\n";
        out << "  origin             " << vec(row.ray.origin) << "\n";
        out << "  direction          " << (row.ray.valid ? vec(row.ray.direction) : "none (outside the lens model's domain)")
            << "\n";
        if (row.look_at_direction) {
            out << "  direction_look_at  " << vec(*row.look_at_direction) << "\n";
            if (row.ray.valid) {
                out << "  angle_rad          "
                    << format_short(angle_between(row.ray.direction, *row.look_at_direction), 10) << "\n";
            }
        }
    }
    out << "directions are unit vectors in world coordinates; direction = R^T K^-1 [x, y, 1], "
           "direction_look_at = alpha u + beta v + w (the look-at formula)\n";
    return out.str();
}

struct ProjectedRow {
    Vec3 point;
    Projection projection;  // the pixel in the user's row convention
};

std::string format_projections_json(const std::vector<ProjectedRow>& rows) {
    nlohmann::json out;
    out["pixels"] = nlohmann::json::array();
    for (const ProjectedRow& row : rows) {
        const Vec2& p = row.projection.pixel;
        out["pixels"].push_back({{"point", vec_json(row.point)},
                                 {"valid", row.projection.valid},
                                 {"pixel", row.projection.valid ? nlohmann::json{p.x() + 0.0, p.y() + 0.0}
                                                                : nlohmann::json(nullptr)}});
    }
    return out.dump(2) + "\n";
}

std::string format_projections(const std::vector<ProjectedRow>& rows) {
    const auto number = [](double value) { return format_short(value + 0.0, 12); };
    std::ostringstream out;
    for (const ProjectedRow& row : rows) {
        out << "point (" << number(row.point.x()) << ", " << number(row.point.y()) << ", " << number(row.point.z())
            << ")  pixel ";
        if (row.projection.valid) {
            out << "(" << number(row.projection.pixel.x()) << ", " << number(row.projection.pixel.y()) << ")\n";
        } else {
            out << "none (behind the camera or outside the lens model's domain)\n";
        }
    }
    return out.str();
}

}  // namespace

Runner add_project(CLI::App& app) {
    CLI::App* command = add_command(app, "project");
    struct Flags {
        CameraOptions camera;
        std::vector<std::string> points;
        bool json = false;
    };
    auto flags = std::make_shared<Flags>();
    flags->camera.add_to(*command);
    command->add_option("--points", flags->points, "World points x,y,z")->required()->expected(1, -1);
    command->add_flag("--json", flags->json, "Print JSON (pixel null where the point has none)");

    return [flags] {
        std::vector<Vec3> points;
        for (const std::string& text : flags->points) points.push_back(parse_vec3("--points", text));
        const PixelOrigin origin = flags->camera.origin();
        const CameraFile file = flags->camera.camera();
        const PreparedCamera camera(file.camera);
        std::vector<ProjectedRow> rows;
        for (const Vec3& point : points) {
            Projection projection = camera.project(point);
            projection.pixel = user_pixel(projection.pixel, origin, file.camera.size);
            rows.push_back({point, projection});
        }
        emit(flags->json ? format_projections_json(rows) : format_projections(rows), "");
        return 0;
    };
}

Runner add_rays(CLI::App& app) {
    CLI::App* command = add_command(app, "rays");
    struct Flags {
        CameraOptions camera;
        std::vector<std::string> pixels;
        bool json = false;
    };
    auto flags = std::make_shared<Flags>();
    flags->camera.add_to(*command);
    command
        ->add_option("--pixels", flags->pixels,
                     "Pixels x,y (centres at integers; the image edges are at -0.5 and W-0.5)")
        ->required()
        ->expected(1, -1);
    command->add_flag("--json", flags->json, "Print JSON");

    return [flags] {
        std::vector<Vec2> pixels;
        for (const std::string& text : flags->pixels) pixels.push_back(parse_vec2("--pixels", text));
        const PixelOrigin origin = flags->camera.origin();
        const CameraFile file = flags->camera.camera();
        const std::optional<LookAtCamera> look_at_camera = graphics_camera_of(file);

        std::vector<RayRow> rows;
        const PreparedCamera camera(file.camera);
        for (const Vec2& pixel : pixels) {
            RayRow row{pixel, camera.ray(opencv_pixel(pixel, origin, file.camera.size)), std::nullopt};
            if (look_at_camera) row.look_at_direction = look_at_camera->look_at_ray(pixel, origin).normalized();
            rows.push_back(row);
        }
        emit(flags->json ? format_json(rows) : format_table(rows), "");
        return 0;
    };
}

}  // namespace libcam::cli
