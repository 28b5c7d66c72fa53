// libcam's cameras rendered by Blender: each camera written as libcam's Blender script,
// small glowing spheres rendered through it by Cycles, and each sphere's image centroid
// measured against where libcam projects it. Also Blender's own world_to_camera_view
// against libcam's projection. Skipped, saying so, where Blender is not installed.

#include <catch2/catch.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "libcam/camera/camera.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/io/detail/blender_format.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/remap/render_plan.hpp"
#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "real_cameras.hpp"

using namespace libcam;
using libcam::test::real_cameras_folder;
using libcam::test::real_cameras_present;
namespace fs = std::filesystem;

namespace {

const fs::path kRenderScript = LIBCAM_BLENDER_RENDER_SCRIPT;
const fs::path kRealCameras = real_cameras_folder();

// Blender: $LIBCAM_BLENDER, or `blender` on the PATH.
std::optional<fs::path> blender_program() {
    if (const char* given = std::getenv("LIBCAM_BLENDER"); given != nullptr && *given != '\0') return fs::path(given);
    const char* path = std::getenv("PATH");
    std::stringstream folders(path == nullptr ? "" : path);
    for (std::string folder; std::getline(folders, folder, ':');) {
        const fs::path candidate = fs::path(folder) / "blender";
        if (!folder.empty() && fs::exists(candidate)) return candidate;
    }
    return std::nullopt;
}

// Blender, or nothing after saying the test is skipped; in CI (CI set), where the test
// command installs Blender, its absence fails the test.
std::optional<fs::path> blender_or_skip() {
    std::optional<fs::path> blender = blender_program();
    if (blender) return blender;
    const char* ci = std::getenv("CI");
    if (ci != nullptr && *ci != '\0') FAIL("Blender is not installed, though the test command installs Debian's blender");
    WARN("skipped: Blender is not installed (the test command installs Debian's blender)");
    return std::nullopt;
}

struct RenderCase {
    std::string name;
    Camera camera;
    double bound;  // px
    int samples = 64;
};

// A camera looking from `eye` along a direction turned from the world's axes, so that the
// world matrix Blender is given is not trivial.
Camera posed(ImageSize size, Intrinsics k, Lens lens) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = k;
    camera.lens = std::move(lens);
    camera.pose = Pose::from_rvec(Vec3(0.3, -0.5, 0.2), Vec3(0.4, -1.2, 2.5));
    return camera;
}

Camera centred(ImageSize size, double fx, double fy, Lens lens) {
    return posed(size, {fx, fy, size.centre_x(), size.centre_y(), 0.0}, std::move(lens));
}

std::vector<RenderCase> render_cases() {
    constexpr double pi = std::numbers::pi;
    const Lens pinhole{LensType::Pinhole, {}};
    const Lens equidistant{LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
    std::vector<RenderCase> cases = {
        {"pinhole, landscape", centred({640, 480}, 520, 520, pinhole), 0.05},
        {"pinhole, portrait", centred({480, 640}, 450, 450, pinhole), 0.05},
        {"pinhole, fx != fy", centred({640, 480}, 500, 560, pinhole), 0.05},
        {"pinhole, principal point 10% off centre", posed({640, 480}, {520, 520, 383.5, 191.5, 0}, pinhole), 0.05},
        // 16 samples: 0.035 px measured on this large image (Cycles is deterministic).
        {"pinhole, 4000x3000", centred({4000, 3000}, 3100, 3100, pinhole), 0.05, 16},
        // FISHEYE_EQUIDISTANT: theta = r fov / 2, r = 1 at the image's edges.
        {"equidistant fisheye, 180 degrees", centred({600, 600}, 600 / pi, 600 / pi, equidistant), 0.1},
        {"equidistant fisheye, 200 degrees", centred({600, 600}, 600 / (200 * pi / 180), 600 / (200 * pi / 180), equidistant),
         0.1},
        {"FISHEYE_LENS_POLYNOMIAL", centred({640, 480}, 640 / 36.0, 640 / 36.0,
                                            {LensType::LensPolynomial, {0.0, -0.06, 1e-4, -3e-5, 2e-7}}),
         0.1},
        {"equisolid", centred({640, 480}, 180, 180, {LensType::Equisolid, {}}), 0.1},
        // fx != fy through the pixel aspect (Cycles' equisolid and polynomial sensor follows
        // it), the axis off centre through the shift; small images, few samples (about half
        // a second each).
        {"equisolid, fx != fy, principal point off centre",
         posed({320, 240}, {150, 210, 171.3, 108.8, 0}, {LensType::Equisolid, {}}), 0.1, 16},
        // An equidistant fisheye whose fields of view across and down differ (W / fx != H / fy):
        // written as the polynomial fisheye theta = r.
        {"equidistant fisheye, W / fx != H / fy, principal point off centre",
         posed({320, 240}, {70, 85, 171.3, 108.8, 0}, equidistant), 0.1, 16},
        {"FISHEYE_LENS_POLYNOMIAL, fx != fy, principal point off centre",
         posed({320, 240}, {320 / 36.0, 0.8 * 320 / 36.0, 150.3, 128.6, 0},
               {LensType::LensPolynomial, {0.0, -0.06, 1e-4, -3e-5, 2e-7}}),
         0.1, 16},
        {"equirectangular, the whole sphere", centred({720, 360}, 720 / (2 * pi), 360 / pi, {LensType::Lonlat, {}}), 0.1},
        {"equirectangular, a band", posed({640, 360}, {640 / (pi / 2 + pi / 3), 360 / (pi / 4 + pi / 6), 640 * 0.6 - 0.5,
                                                       360 * (1 - 0.6) - 0.5, 0},
                                          {LensType::Lonlat, {}}),
         0.1},
    };
    return cases;
}

struct Sphere {
    Vec3 centre;       // world
    double radius;     // world
    Vec2 expected;     // px: the centroid of the sphere's image by libcam's projection
    Vec2 low, high;    // px: the corners of the box around its image
};

struct SphereImage {
    Vec2 centroid, low, high;
};

// Two unit vectors across `axis`.
std::pair<Vec3, Vec3> across(const Vec3& axis) {
    const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 a = axis.cross(helper).normalized();
    return {a, axis.cross(a)};
}

// The centroid of the sphere's image: the area centroid of the polygon its outline (the
// cone of rays touching it) projects to. A sphere off the axis images as an oval whose
// centroid is not the projection of its centre.
std::optional<SphereImage> sphere_image(const PreparedCamera& camera, const Vec3& eye, const Vec3& centre, double radius) {
    const Vec3 offset = centre - eye;
    const double distance = offset.norm();
    const Vec3 axis = offset / distance;
    const double half_angle = std::asin(radius / distance);
    const auto [a, b] = across(axis);
    constexpr int kSides = 720;
    std::vector<Vec2> outline;
    for (int i = 0; i < kSides; ++i) {
        const double phi = 2 * std::numbers::pi * i / kSides;
        const Vec3 ray = std::cos(half_angle) * axis + std::sin(half_angle) * (std::cos(phi) * a + std::sin(phi) * b);
        const Projection p = camera.project(eye + ray);
        if (!p.valid) return std::nullopt;
        outline.push_back(p.pixel);
    }
    double area = 0;
    Vec2 moment = Vec2::Zero(), low = outline.front(), high = outline.front();
    for (int i = 0; i < kSides; ++i) {
        low = low.cwiseMin(outline[static_cast<std::size_t>(i)]);
        high = high.cwiseMax(outline[static_cast<std::size_t>(i)]);
        const Vec2& p = outline[static_cast<std::size_t>(i)];
        const Vec2& q = outline[static_cast<std::size_t>((i + 1) % kSides)];
        const double cross = p.x() * q.y() - q.x() * p.y();
        area += cross;
        moment += (p + q) * cross;
    }
    return SphereImage{moment / (3 * area), low, high};
}

// Spheres seen through a grid of the image's pixels (inset from the edges), 4 px in
// radius on the image, 8 m away; only where Blender renders (a fisheye's circle).
std::vector<Sphere> spheres_for(const Camera& lens) {
    const PreparedCamera camera(lens);
    const Vec3 eye = lens.pose.centre();
    const double w = static_cast<double>(lens.size.width), h = static_cast<double>(lens.size.height);
    // Blender's equidistant fisheye renders black past the circle theta = fov / 2.
    const bool blender_fisheye = lens.lens.type == LensType::Fisheye &&
                                 std::all_of(lens.lens.coefficients.begin(), lens.lens.coefficients.end(),
                                             [](double k) { return k == 0.0; });
    std::vector<Sphere> spheres;
    constexpr int kColumns = 6, kRows = 5;
    for (int j = 0; j < kRows; ++j) {
        for (int i = 0; i < kColumns; ++i) {
            const Vec2 pixel(w * (0.1 + 0.8 * i / (kColumns - 1)), h * (0.1 + 0.8 * j / (kRows - 1)));
            const Unprojection u = camera.unproject(pixel);
            if (!u.valid) continue;
            const Vec3 camera_ray = u.direction.normalized();
            const Vec3 world_ray = lens.pose.R.transpose() * camera_ray;
            const double angle = std::acos(std::clamp(camera_ray.z(), -1.0, 1.0));
            if (blender_fisheye && angle > 0.5 * (w / lens.intrinsics.fx) * 0.97) continue;
            // 4 px: the angle one pixel subtends here, measured by projecting a step across.
            const Vec3 centre = eye + 8.0 * world_ray;
            const Vec3 sideways = across(world_ray).first;
            const Projection step = camera.project(eye + 8.0 * (world_ray + 1e-4 * sideways));
            const Projection here = camera.project(centre);
            if (!step.valid || !here.valid) continue;
            const double px_per_radian = (step.pixel - here.pixel).norm() / 1e-4;
            const double radius = 8.0 * std::sin(4.0 / px_per_radian);
            const std::optional<SphereImage> image = sphere_image(camera, eye, centre, radius);
            if (image) spheres.push_back({centre, radius, image->centroid, image->low, image->high});
        }
    }
    return spheres;
}

// The R channel of a linear EXR, rows from the top.
std::vector<float> read_red(const fs::path& path, ImageSize size) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    REQUIRE(width == size.width);
    REQUIRE(height == size.height);
    std::vector<float> red(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    Imf::FrameBuffer frame;
    char* origin = reinterpret_cast<char*>(red.data() - window.min.x - window.min.y * width);
    frame.insert("R", Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * static_cast<std::size_t>(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return red;
}

// The brightness-weighted centroid of the pixels of the sphere's box, 3 px wider on each
// side (Cycles' pixel filter spreads its edge by 1.5 px).
std::optional<Vec2> measured_centroid(const std::vector<float>& red, ImageSize size, const Sphere& sphere) {
    double total = 0;
    Vec2 moment = Vec2::Zero();
    const int x0 = static_cast<int>(std::floor(sphere.low.x())) - 3, x1 = static_cast<int>(std::ceil(sphere.high.x())) + 3;
    const int y0 = static_cast<int>(std::floor(sphere.low.y())) - 3, y1 = static_cast<int>(std::ceil(sphere.high.y())) + 3;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            if (x < 0 || y < 0 || x >= size.width || y >= size.height) return std::nullopt;  // cut by the edge
            const double value = red[static_cast<std::size_t>(y) * static_cast<std::size_t>(size.width) +
                                     static_cast<std::size_t>(x)];
            total += value;
            moment += value * Vec2(x, y);
        }
    }
    if (!(total > 10)) return std::nullopt;  // a 4 px sphere covers about 50 pixels
    return moment / total;
}

// Runs render_points.py on the manifest in `dir`; fails the test with Blender's log when
// Blender fails.
void run_blender(const fs::path& blender, const fs::path& dir, const nlohmann::json& manifest) {
    const fs::path manifest_path = dir / "manifest.json", log = dir / "blender.log";
    std::ofstream(manifest_path) << manifest.dump();
    const std::string command = "\"" + blender.string() + "\" -b --factory-startup -noaudio -P \"" +
                                kRenderScript.string() + "\" -- \"" + manifest_path.string() + "\" > \"" +
                                log.string() + "\" 2>&1";
    const int status = std::system(command.c_str());
    if (status != 0) {
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        FAIL("blender exited with " << status << ":\n" << text.str().substr(0, 4000));
    }
}

nlohmann::json sphere_list(const std::vector<Sphere>& spheres) {
    nlohmann::json list = nlohmann::json::array();
    for (const Sphere& s : spheres) list.push_back({s.centre.x(), s.centre.y(), s.centre.z(), s.radius});
    return list;
}

// The largest distance between a sphere's measured centroid and its expected one, over
// the spheres whose box lies inside the image; and how many those were.
std::pair<double, int> worst_centroid(const std::vector<float>& red, ImageSize size, const std::vector<Sphere>& spheres) {
    double worst = 0;
    int measured = 0;
    for (const Sphere& s : spheres) {
        const std::optional<Vec2> centroid = measured_centroid(red, size, s);
        if (!centroid) continue;
        worst = std::max(worst, (*centroid - s.expected).norm());
        ++measured;
    }
    return {worst, measured};
}

}  // namespace

TEST_CASE("Blender renders through libcam's cameras: each sphere's centroid where libcam projects it",
          "[blender]") {
    const std::optional<fs::path> blender = blender_or_skip();
    if (!blender) return;
    test::TempDir dir;
    const std::vector<RenderCase> cases = render_cases();
    nlohmann::json manifest;
    manifest["renders"] = nlohmann::json::array();
    manifest["views"] = nlohmann::json::array();
    // Each camera renders its own spheres (one Blender run for every camera).
    std::vector<std::vector<Sphere>> spheres;
    std::vector<std::vector<Vec3>> view_points;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const RenderCase& c = cases[i];
        spheres.push_back(spheres_for(c.camera));
        const fs::path script = dir.path() / ("camera" + std::to_string(i) + ".py");
        std::ofstream(script) << format_blender_script(c.camera, WriteOptions{});
        manifest["renders"].push_back({{"camera_script", script.string()},
                                       {"output", (dir.path() / ("render" + std::to_string(i) + ".exr")).string()},
                                       {"samples", c.samples},
                                       {"spheres", sphere_list(spheres.back())}});
        // Blender's own projection of points spread over a pinhole's view.
        if (c.camera.lens.type == LensType::Pinhole) {
            std::vector<Vec3> points;
            const PreparedCamera camera(c.camera);
            for (int k = 0; k < 1000; ++k) {
                const Vec2 pixel(std::fmod(k * 0.6180339887 * c.camera.size.width, double(c.camera.size.width)),
                                 std::fmod(k * 0.7548776662 * c.camera.size.height, double(c.camera.size.height)));
                const Vec3 ray = c.camera.pose.R.transpose() * camera.unproject(pixel).direction.normalized();
                points.push_back(c.camera.pose.centre() + (1.0 + k % 7) * ray);
            }
            nlohmann::json list = nlohmann::json::array();
            for (const Vec3& p : points) list.push_back({p.x(), p.y(), p.z()});
            manifest["views"].push_back({{"camera_script", script.string()}, {"points", list},
                                         {"output", (dir.path() / ("view" + std::to_string(i) + ".json")).string()}});
            view_points.push_back(points);
        } else {
            view_points.emplace_back();
        }
    }
    run_blender(*blender, dir.path(), manifest);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const RenderCase& c = cases[i];
        CAPTURE(c.name);
        const PreparedCamera camera(c.camera);
        if (!view_points[i].empty()) {
            std::ifstream in(dir.path() / ("view" + std::to_string(i) + ".json"));
            const nlohmann::json seen = nlohmann::json::parse(in);
            double worst = 0;
            for (std::size_t k = 0; k < view_points[i].size(); ++k) {
                // world_to_camera_view: (0, 0) at the bottom-left corner, (1, 1) the top-right.
                const double u = seen[k][0], v = seen[k][1];
                const Vec2 theirs(u * c.camera.size.width - 0.5, (1 - v) * c.camera.size.height - 0.5);
                const Projection ours = camera.project(view_points[i][k]);
                REQUIRE(ours.valid);
                worst = std::max(worst, (theirs - ours.pixel).norm());
            }
            // Blender computes in float: 1e-3 px per 1000 px of the image's longer side.
            const double bound = 1e-3 * std::max(1.0, std::max(c.camera.size.width, c.camera.size.height) / 1000.0);
            WARN(c.name << ": Blender's world_to_camera_view and libcam agree to " << worst << " px on 1000 points (bound "
                        << bound << ")");
            CHECK(worst < bound);
        }
        const std::vector<float> red = read_red(dir.path() / ("render" + std::to_string(i) + ".exr"), c.camera.size);
        const auto [worst, measured] = worst_centroid(red, c.camera.size, spheres[i]);
        WARN(c.name << ": " << measured << " spheres' centroids within " << worst << " px of libcam's projection (bound "
                    << c.bound << ")");
        CHECK(measured >= static_cast<int>(spheres[i].size()) * 3 / 4);
        CHECK(worst <= c.bound);
    }
}

TEST_CASE("tools/blender/export_cameras.py: a scene's cameras, and an animated one frame by frame, read by libcam",
          "[blender]") {
    const std::optional<fs::path> blender = blender_or_skip();
    if (!blender) return;
    test::TempDir dir;
    // The scene: Blender's default camera set by hand, and a second camera moving from
    // (0, 0, 0) at frame 1 to (0, 0, 3) at frame 3, linearly.
    const std::string setup = R"py(
import math, bpy
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 1280, 720, 50
scene.frame_start, scene.frame_end = 1, 3
camera = scene.camera
camera.location = (1, 2, 3)
camera.rotation_euler = (math.pi / 2, 0, 0)
camera.data.lens, camera.data.sensor_fit, camera.data.sensor_height = 35, "VERTICAL", 18
camera.data.shift_x, camera.data.shift_y = 0.1, -0.05
moving = bpy.data.objects.new("Moving", bpy.data.cameras.new("Moving"))
scene.collection.objects.link(moving)
for frame, z in ((1, 0.0), (3, 3.0)):
    moving.location = (0, 0, z)
    moving.keyframe_insert("location", frame=frame)
for curve in moving.animation_data.action.fcurves:
    for point in curve.keyframe_points:
        point.interpolation = "LINEAR"
)py";
    const fs::path setup_path = dir.path() / "setup.py";
    std::ofstream(setup_path) << setup;
    const fs::path output = dir.path() / "cameras.json";
    const fs::path log = dir.path() / "blender.log";
    const std::string command = "\"" + blender->string() + "\" -b --factory-startup -noaudio -P \"" +
                                setup_path.string() + "\" -P \"" + std::string(LIBCAM_BLENDER_EXPORT_SCRIPT) +
                                "\" -- \"" + output.string() + "\" --all > \"" + log.string() + "\" 2>&1";
    REQUIRE(std::system(command.c_str()) == 0);
    const CameraSet set = read_camera_set(output);
    REQUIRE(set.format == CameraFormat::BlenderJson);
    std::vector<std::string> names;
    for (const NamedCamera& named : set.cameras) names.push_back(named.name);
    CHECK(names == std::vector<std::string>{"Camera", "Moving@1", "Moving@2", "Moving@3"});
    // 1280x720 at 50%: 640x360. The sensor fitted down, 18 mm over 360 px at 35 mm:
    // fy = 35 x 360 / 18 = 700 = fx (square pixels). The shift's unit is the fitted side
    // (360 px): cx = 319.5 - 0.1 x 360 = 283.5; cy = 179.5 + (-0.05) x 360 = 161.5.
    const Camera& still = set.cameras[0].file.camera;
    CHECK(still.size == ImageSize{640, 360});
    CHECK(still.intrinsics.fx == Approx(700).epsilon(1e-6));  // Blender's settings are float32
    CHECK(still.intrinsics.fy == Approx(700).epsilon(1e-6));
    CHECK(still.intrinsics.cx == Approx(283.5).epsilon(1e-6));
    CHECK(still.intrinsics.cy == Approx(161.5).epsilon(1e-6));
    // Turned a quarter about X, Blender's camera looks along +Y with +Z up: libcam's x, y,
    // z axes are the world's X, -Z and Y (rows of R); the centre is (1, 2, 3).
    Mat3 expected_R;
    expected_R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    CHECK((still.pose.R - expected_R).cwiseAbs().maxCoeff() < 1e-6);
    CHECK((still.pose.centre() - Vec3(1, 2, 3)).norm() < 1e-6);
    CHECK((set.cameras[2].file.camera.pose.centre() - Vec3(0, 0, 1.5)).norm() < 1e-6);  // frame 2, halfway
    CHECK((set.cameras[3].file.camera.pose.centre() - Vec3(0, 0, 3)).norm() < 1e-6);
}

TEST_CASE("Real lenses through a render plan: Blender renders the plan's camera, the warp makes the lens's image, and "
          "each sphere lands where the lens projects it",
          "[blender][real]") {
    const std::optional<fs::path> blender = blender_or_skip();
    if (!blender || !real_cameras_present()) return;
    struct Lens {
        const char* file;
        int bin;
        LensType render;  // the plan's render camera (render_plan.hpp)
    };
    // The T265's fisheye (163 degrees) needs Blender's fisheye; mrcal's OPENCV8 test lens
    // and EuRoC's radial-tangential lens fit in a pinhole with margins.
    const Lens lenses[] = {{"basalt/t265_kb4_calib.json", 1, LensType::Fisheye},
                           {"mrcal/cam0.opencv8.cameramodel", 8, LensType::Pinhole},
                           {"open_vins/euroc_mav/kalibr_imucam_chain.yaml", 1, LensType::Pinhole}};
    test::TempDir dir;
    nlohmann::json manifest;
    manifest["renders"] = nlohmann::json::array();
    std::vector<Camera> cameras;
    std::vector<RenderPlan> plans;
    std::vector<std::vector<Sphere>> spheres;
    for (std::size_t i = 0; i < std::size(lenses); ++i) {
        Camera lens = read_camera_file(kRealCameras / lenses[i].file).camera;
        if (lenses[i].bin > 1) lens = binned(lens, lenses[i].bin);
        plans.push_back(plan_render(PreparedCamera(lens), 2));
        CAPTURE(lenses[i].file, plans.back().why);
        CHECK(plans.back().needs_warp);
        CHECK(plans.back().render.lens.type == lenses[i].render);
        spheres.push_back(spheres_for(lens));
        cameras.push_back(lens);
        const fs::path script = dir.path() / ("plan" + std::to_string(i) + ".py");
        std::ofstream(script) << format_blender_script(plans.back().render, WriteOptions{});
        manifest["renders"].push_back({{"camera_script", script.string()},
                                       {"output", (dir.path() / ("plan" + std::to_string(i) + ".exr")).string()},
                                       {"samples", 64},
                                       {"spheres", sphere_list(spheres.back())}});
    }
    run_blender(*blender, dir.path(), manifest);
    for (std::size_t i = 0; i < std::size(lenses); ++i) {
        CAPTURE(lenses[i].file, plans[i].why);
        const PreparedCamera lens(cameras[i]);
        const Camera& render = plans[i].render;
        std::vector<float> rendered = read_red(dir.path() / ("plan" + std::to_string(i) + ".exr"), render.size);
        const cv::Mat render_image(static_cast<int>(render.size.height), static_cast<int>(render.size.width), CV_32F,
                                   rendered.data());
        const RemapMap warp = build_remap_map(lens, PreparedCamera(render), {Mat3::Identity(), UnprojectMethod::Exact, 2});
        // Every lens pixel with a ray has a source in the render.
        std::size_t with_ray = 0;
        std::vector<Vec2> pixels;
        for (long y = 0; y < cameras[i].size.height; ++y) {
            for (long x = 0; x < cameras[i].size.width; ++x) pixels.emplace_back(x, y);
        }
        for (const Unprojection& ray : lens.unproject(pixels, 2)) with_ray += ray.valid ? 1 : 0;
        CHECK(warp.with_source == with_ray);
        const cv::Mat warped = remap_image(render_image, warp, Interpolation::Linear);
        REQUIRE(warped.isContinuous());
        const std::vector<float> red(warped.ptr<float>(), warped.ptr<float>() + warped.total());
        const auto [worst, measured] = worst_centroid(red, cameras[i].size, spheres[i]);
        WARN(lenses[i].file << " through a " << render.size.width << "x" << render.size.height << " "
                            << lens_info(render.lens.type).name << " render: " << measured
                            << " spheres' centroids within " << worst << " px of the lens's projection (bound 0.1)");
        CHECK(measured >= static_cast<int>(spheres[i].size()) * 3 / 4);
        CHECK(worst <= 0.1);
    }
}

TEST_CASE("render-plan --fit-blender: a lens Blender's polynomial fisheye fits is rendered with the fit, and the "
          "spheres land where the lens projects them",
          "[blender]") {
    const std::optional<fs::path> blender = blender_or_skip();
    if (!blender) return;
    test::TempDir dir;
    // A Kannala-Brandt fisheye with mild coefficients, 640x480, 300 px per radian.
    Camera lens;
    lens.size = {640, 480};
    lens.intrinsics = {300, 300, 319.5, 239.5, 0};
    lens.lens = {LensType::Fisheye, {0.02, -0.004, 0.0, 0.0}};
    lens.pose = Pose::from_rvec(Vec3(0.2, 0.1, -0.3), Vec3(0.5, -1, 2));
    const fs::path lens_file = dir.path() / "lens.json";
    write_camera_file(lens_file, lens, CameraFormat::Json);
    const test::CliResult r = test::run_program(LIBCAM_EXE, {"render-plan", "--from", lens_file.string(), "-o",
                                                             (dir.path() / "plan").string(), "--fit-blender"});
    REQUIRE(r.exit_code == 0);
    INFO(r.out);
    CHECK_THAT(r.out, Catch::Contains("FISHEYE_LENS_POLYNOMIAL fitted to the lens reproduces it within"));
    CHECK_FALSE(fs::exists(dir.path() / "plan" / "warp.exr"));
    const Camera render = read_camera_file(dir.path() / "plan" / "render.json").camera;
    REQUIRE(render.lens.type == LensType::LensPolynomial);
    const std::vector<Sphere> spheres = spheres_for(lens);
    nlohmann::json manifest;
    manifest["renders"] = nlohmann::json::array({{{"camera_script", (dir.path() / "plan" / "render.py").string()},
                                                  {"output", (dir.path() / "fit.exr").string()},
                                                  {"samples", 64},
                                                  {"spheres", sphere_list(spheres)}}});
    run_blender(*blender, dir.path(), manifest);
    const auto [worst, measured] = worst_centroid(read_red(dir.path() / "fit.exr", lens.size), lens.size, spheres);
    WARN("a mild fisheye through Blender's fitted polynomial fisheye: " << measured << " spheres' centroids within "
                                                                        << worst << " px of the lens's projection (bound 0.1)");
    CHECK(measured >= static_cast<int>(spheres.size()) * 3 / 4);
    CHECK(worst <= 0.1);
}

TEST_CASE("NeRF's lego scene: libcam's camera for camera_angle_x is the one Blender renders with that angle",
          "[blender][real]") {
    const std::optional<fs::path> blender = blender_or_skip();
    if (!blender || !real_cameras_present()) return;
    const fs::path file = kRealCameras / "nerf-synthetic-blender/transforms_train.json";
    ReadOptions options;
    options.size = ImageSize{800, 800};
    const Camera camera = read_camera_file(file, {}, std::nullopt, options).camera;
    // Blender given the file's own numbers, as NeRF's render script set them: the angle
    // (camera.data.angle_x, the sensor fitted to the width of a square image) and the
    // first frame's camera-to-world matrix. Not through libcam's writer.
    std::ifstream in(file);
    const nlohmann::json transforms = nlohmann::json::parse(in);
    std::ostringstream script;
    script.precision(17);
    script << "import bpy, mathutils\n"
              "scene = bpy.context.scene\n"
              "scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 800, 800, 100\n"
              "camera = scene.camera\n"
              "camera.data.type = 'PERSP'\n"
              "camera.data.sensor_fit = 'AUTO'\n"
              "camera.data.angle_x = "
           << transforms.at("camera_angle_x").get<double>() << "\ncamera.matrix_world = mathutils.Matrix("
           << transforms.at("frames").at(0).at("transform_matrix").dump() << ")\n";
    test::TempDir dir;
    const fs::path script_path = dir.path() / "lego_camera.py";
    std::ofstream(script_path) << script.str();
    const std::vector<Sphere> spheres = spheres_for(camera);
    nlohmann::json manifest;
    manifest["renders"] = nlohmann::json::array({{{"camera_script", script_path.string()},
                                                  {"output", (dir.path() / "lego.exr").string()},
                                                  {"samples", 64},
                                                  {"spheres", sphere_list(spheres)}}});
    run_blender(*blender, dir.path(), manifest);
    const auto [worst, measured] = worst_centroid(read_red(dir.path() / "lego.exr", camera.size), camera.size, spheres);
    WARN("NeRF lego, first frame: " << measured << " spheres' centroids within " << worst
                                    << " px of libcam's projection (bound 0.05)");
    CHECK(measured >= static_cast<int>(spheres.size()) * 3 / 4);
    CHECK(worst <= 0.05);
}
