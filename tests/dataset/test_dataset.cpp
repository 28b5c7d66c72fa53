// `libcam dataset`, run as a user runs it, on COLMAP models this test writes (an OPENCV
// camera and the RealSense T265's OPENCV_FISHEYE, observations projected by the lens
// formulas written out here), on small images with Gaussian blobs drawn at the
// observations, and on real COLMAP models; the output read back with read_observations
// and checked against a pinhole projection worked out here, the blobs' centroids, and
// COLMAP's own model_analyzer.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/dataset/detail/dataset_views.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using Json = nlohmann::json;

struct World {
    double x, y, z;
};

// A lens written out: OpenCV pixels of a camera-frame point, or false off the lens.
struct Lens {
    std::string colmap_line;  // "1 MODEL W H params" (COLMAP's pixels)
    int width, height;
    double fx, fy, cx, cy;  // OpenCV's pixels
    double k[4];
    bool fisheye;

    bool project(double X, double Y, double Z, double& u, double& v) const {
        if (Z <= 0) return false;
        const double a = X / Z, b = Y / Z, r2 = a * a + b * b;
        double xd, yd;
        if (fisheye) {  // Kannala-Brandt: theta_d = theta (1 + k1 theta^2 + ... + k4 theta^8)
            const double r = std::sqrt(r2), theta = std::atan(r);
            if (theta > 1.45) return false;  // keep to where the polynomial rises
            const double t2 = theta * theta;
            const double theta_d = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
            const double scale = r > 0 ? theta_d / r : 1.0;
            xd = a * scale;
            yd = b * scale;
        } else {  // OpenCV: k1, k2, p1, p2
            const double radial = 1 + k[0] * r2 + k[1] * r2 * r2;
            xd = a * radial + 2 * k[2] * a * b + k[3] * (r2 + 2 * a * a);
            yd = b * radial + k[2] * (r2 + 2 * b * b) + 2 * k[3] * a * b;
        }
        u = fx * xd + cx;
        v = fy * yd + cy;
        return u >= 0 && v >= 0 && u <= width - 1 && v <= height - 1;
    }
};

Lens opencv_lens(int width, int height) {
    const double scale = width / 320.0;
    Lens lens{"", width, height, 300 * scale, 290 * scale, 165.3 * scale, 114.7 * scale, {-0.25, 0.06, 0.001, -0.0015}, false};
    std::ostringstream line;
    line.precision(17);
    line << "1 OPENCV " << width << " " << height << " " << lens.fx << " " << lens.fy << " " << lens.cx + 0.5 << " "
         << lens.cy + 0.5 << " " << lens.k[0] << " " << lens.k[1] << " " << lens.k[2] << " " << lens.k[3];
    lens.colmap_line = line.str();
    return lens;
}

// The T265's left camera (Basalt's kb4 calibration), its image scaled by `scale` (1: the
// real 848x800).
Lens t265_lens(double scale = 1.0) {
    const auto centre = [scale](double c) { return (c + 0.5) * scale - 0.5; };
    Lens lens{"", static_cast<int>(848 * scale), static_cast<int>(800 * scale), 286.60144163375528 * scale,
              286.4617087423328 * scale, centre(422.2765876951761), centre(395.2246466040553),
              {-0.006762412326815424, 0.045170283325720008, -0.043515167278210638, 0.008374959821591333}, true};
    std::ostringstream line;
    line.precision(17);
    line << "1 OPENCV_FISHEYE " << lens.width << " " << lens.height << " " << lens.fx << " " << lens.fy << " "
         << lens.cx + 0.5 << " " << lens.cy + 0.5;
    for (const double k : lens.k) line << " " << k;
    lens.colmap_line = line.str();
    return lens;
}

// Image i: turned by 0.05 i rad about y, moved by (0.2 i, 0.05 i, 0): x_cam = R X + t.
struct ViewPose {
    double qw, qy, tx, ty;
    void apply(const World& p, double& X, double& Y, double& Z) const {
        const double angle = 2 * std::atan2(qy, qw), c = std::cos(angle), s = std::sin(angle);
        X = c * p.x + s * p.z + tx;
        Y = p.y + ty;
        Z = -s * p.x + c * p.z;
    }
};

ViewPose view_pose(int i) { return {std::cos(0.025 * i), std::sin(0.025 * i), -0.2 * i, -0.05 * i}; }

// A model of images named by `names`, of the points of `grid` x `grid` x `depths` spread
// across `spread` (tan of the half angle) at depths 3 to 5, each seen where the lens
// images it. Returns how many observations it holds.
struct Written {
    std::vector<World> points;
    std::size_t observations = 0;
    std::vector<std::pair<int, std::size_t>> seen;  // (view, point) of each observation
};

Written write_model(const fs::path& folder, const Lens& lens, const std::vector<std::string>& names, int grid, double spread,
                    int depths = 3) {
    fs::create_directories(folder);
    Written written;
    for (int d = 0; d < depths; ++d) {
        for (int i = 0; i < grid; ++i) {
            for (int j = 0; j < grid; ++j) {
                const double z = 3.0 + d;
                const double jitter = 0.37 * ((i * 7 + j * 3 + d) % 5) / 5.0;
                written.points.push_back({z * spread * (-1 + 2.0 * (j + jitter) / grid) + 0.2 * names.size() / 2,
                                          z * spread * (-1 + 2.0 * (i + jitter) / grid), z});
            }
        }
    }
    std::ostringstream images;
    images.precision(17);
    std::vector<std::string> tracks(written.points.size());
    for (std::size_t view = 0; view < names.size(); ++view) {
        const ViewPose pose = view_pose(static_cast<int>(view));
        images << view + 1 << " " << pose.qw << " 0 " << pose.qy << " 0 " << pose.tx << " " << pose.ty << " 0 1 "
               << names[view] << "\n";
        int index = 0;
        for (std::size_t p = 0; p < written.points.size(); ++p) {
            double X, Y, Z, u, v;
            pose.apply(written.points[p], X, Y, Z);
            if (!lens.project(X, Y, Z, u, v)) continue;
            images << (index ? " " : "") << u + 0.5 << " " << v + 0.5 << " " << p + 1;
            tracks[p] += " " + std::to_string(view + 1) + " " + std::to_string(index++);
            ++written.observations;
            written.seen.emplace_back(static_cast<int>(view), p);
        }
        images << "\n";
    }
    std::ostringstream points;
    points.precision(17);
    for (std::size_t p = 0; p < written.points.size(); ++p) {
        if (tracks[p].empty()) continue;
        points << p + 1 << " " << written.points[p].x << " " << written.points[p].y << " " << written.points[p].z
               << " 10 20 30 0" << tracks[p] << "\n";
    }
    libcam::test::write_whole_file(folder / "cameras.txt", lens.colmap_line + "\n");
    libcam::test::write_whole_file(folder / "images.txt", images.str());
    libcam::test::write_whole_file(folder / "points3D.txt", points.str());
    return written;
}

Json run_json(const std::vector<std::string>& args, int expected_exit = 0) {
    const libcam::test::CliResult result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == expected_exit);
    return Json::parse(result.out);
}

// Every kept observation is the new pinhole's x = fx X / Z + cx of its point (OpenCV's
// pixels, as read_observations gives them), and as many are kept as the pinhole puts on
// its image.
void check_pinhole_geometry(const fs::path& model, const Written& written, const Json& summary) {
    const libcam::ObservationSet set = libcam::read_observations(model);
    REQUIRE(set.cameras.size() == 1);
    const libcam::Camera& camera = set.cameras[0].camera;
    REQUIRE(camera.lens.type == libcam::LensType::Pinhole);
    const auto& k = camera.intrinsics;
    double worst = 0;
    for (const libcam::Observation& o : set.observations) {
        const libcam::Vec3 X = set.views[o.view].pose.R * set.points[o.point] + set.views[o.view].pose.t;
        const double u = k.fx * X.x() / X.z() + k.cx, v = k.fy * X.y() / X.z() + k.cy;
        worst = std::max(worst, std::hypot(u - o.pixel.x(), v - o.pixel.y()));
    }
    CHECK(worst < 1e-6);
    // The observations the pinhole should keep: those whose point it puts on its image.
    std::size_t on_image = 0;
    for (const auto& [view, point] : written.seen) {
        double X, Y, Z;
        view_pose(view).apply(written.points[point], X, Y, Z);
        const double u = k.fx * X / Z + k.cx, v = k.fy * Y / Z + k.cy;
        on_image += u >= -0.5 && v >= -0.5 && u <= camera.size.width - 0.5 && v <= camera.size.height - 0.5;
    }
    CHECK(set.observations.size() == on_image);
    CHECK(summary["observations_in"].get<std::size_t>() == written.observations);
    CHECK(summary["observations_kept"].get<std::size_t>() == set.observations.size());
    WARN("kept " << set.observations.size() << " of " << written.observations << ", largest error " << worst << " px");
}

}  // namespace

TEST_CASE("dataset: an OPENCV model's observations land where the new pinhole projects their points", "[dataset]") {
    TempDir dir;
    const Lens lens = opencv_lens(1280, 960);
    const Written written = write_model(dir / "in", lens, {"a.png", "b.png", "c.png", "d.png"}, 12, 0.6);
    for (const std::string camera : {"valid", "all", "fov:70", "views"}) {
        const fs::path out = dir / ("out-" + camera.substr(0, 3));
        const Json summary = run_json({"dataset", (dir / "in").string(), "-o", out.string(), "--no-images", "--json",
                                       "--camera", camera, "--text"});
        INFO(camera);
        check_pinhole_geometry(out / "sparse" / "0", written, summary);
        CHECK(summary["cameras"][0]["source_model"] == "OPENCV");
        if (camera == "valid") CHECK(summary["observations_kept"] < summary["observations_in"]);
        if (camera == "all") CHECK(summary["observations_kept"] == summary["observations_in"]);
        if (camera == "views") {  // a lens one pinhole holds well: one view, every observation
            CHECK(summary["cameras"][0]["views"] == 1);
            CHECK(summary["observations_kept"] == summary["observations_in"]);
        }
    }
}

TEST_CASE("dataset: the T265 fisheye's observations land where the new pinhole projects their points", "[dataset]") {
    TempDir dir;
    const Written written = write_model(dir / "in", t265_lens(), {"f0.png", "f1.png", "f2.png"}, 16, 6.0);
    const fs::path out = dir / "out";
    const Json summary = run_json({"dataset", (dir / "in").string(), "-o", out.string(), "--no-images", "--json"});
    check_pinhole_geometry(out / "sparse" / "0", written, summary);
    CHECK(summary["cameras"][0]["source_model"] == "OPENCV_FISHEYE");
    CHECK(summary["observations_kept"] < summary["observations_in"]);  // the periphery no pinhole holds
}

namespace {

// A blob at each of an image's observations: exp(-d^2 / 2 sigma^2), OpenCV's pixels.
cv::Mat blob_image(const Lens& lens, int view, const std::vector<World>& points, int depth, int channels) {
    cv::Mat image(lens.height, lens.width, CV_64F, cv::Scalar(0));
    const double sigma = 1.2;
    for (const World& point : points) {
        double X, Y, Z, u, v;
        view_pose(view).apply(point, X, Y, Z);
        if (!lens.project(X, Y, Z, u, v)) continue;
        for (int y = std::max(0, int(v) - 6); y <= std::min(lens.height - 1, int(v) + 6); ++y) {
            for (int x = std::max(0, int(u) - 6); x <= std::min(lens.width - 1, int(u) + 6); ++x) {
                image.at<double>(y, x) += std::exp(-((x - u) * (x - u) + (y - v) * (y - v)) / (2 * sigma * sigma));
            }
        }
    }
    cv::Mat typed;
    image.convertTo(typed, depth, depth == CV_16U ? 65535.0 : 255.0);
    if (channels == 1) return typed;
    cv::Mat colour;
    cv::merge(std::vector<cv::Mat>(static_cast<std::size_t>(channels), typed), colour);
    return colour;
}

// Points far enough apart that their blobs do not touch (sparse grid).
Written write_blob_model(const fs::path& folder, const fs::path& images, const std::vector<std::string>& names) {
    const Lens lens = opencv_lens(320, 240);
    const Written written = write_model(folder, lens, names, 7, 0.45, 1);
    fs::create_directories(images);
    const int kinds[][2] = {{CV_8U, 1}, {CV_16U, 1}, {CV_8U, 3}};
    for (std::size_t view = 0; view < names.size(); ++view) {
        const auto& kind = kinds[view % 3];
        fs::create_directories((images / names[view]).parent_path());
        REQUIRE(cv::imwrite((images / names[view]).string(),
                            blob_image(lens, static_cast<int>(view), written.points, kind[0], kind[1])));
    }
    return written;
}

// The intensity centroid of the blob around `pixel`, over a window of radius 4.
bool centroid(const cv::Mat& image, const libcam::Vec2& pixel, libcam::Vec2& found) {
    const int cx = static_cast<int>(std::lround(pixel.x())), cy = static_cast<int>(std::lround(pixel.y()));
    const int r = 4;
    if (cx - r < 0 || cy - r < 0 || cx + r >= image.cols || cy + r >= image.rows) return false;
    cv::Mat gray;
    image.convertTo(gray, CV_64F);
    if (gray.channels() > 1) cv::extractChannel(gray, gray, 0);
    double sum = 0, sx = 0, sy = 0;
    for (int y = cy - r; y <= cy + r; ++y) {
        for (int x = cx - r; x <= cx + r; ++x) {
            const double w = gray.at<double>(y, x);
            sum += w;
            sx += w * x;
            sy += w * y;
        }
    }
    if (sum <= 0) return false;
    found = {sx / sum, sy / sum};
    return true;
}

std::map<std::string, std::string> files_under(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) files[fs::relative(entry.path(), folder).string()] = libcam::test::read_whole_file(entry.path());
    }
    return files;
}

}  // namespace

TEST_CASE("dataset: each blob of the undistorted images is at its moved observation", "[dataset]") {
    TempDir dir;
    const std::vector<std::string> names = {"g8.png", "g16.png", "rgb.png", "sub/h8.png"};
    write_blob_model(dir / "scene" / "sparse" / "0", dir / "scene" / "images", names);
    const fs::path out = dir / "out";
    // The images beside the model's grandparent, found without --images.
    const Json summary = run_json({"dataset", (dir / "scene" / "sparse" / "0").string(), "-o", out.string(), "--json",
                                   "--threads", "2"});
    CHECK(summary["images_out"] == names.size());
    const libcam::ObservationSet set = libcam::read_observations(out / "sparse" / "0");
    std::map<std::string, cv::Mat> images;
    for (const std::string& name : names) {
        const cv::Mat source = cv::imread((dir / "scene" / "images" / name).string(), cv::IMREAD_UNCHANGED);
        images[name] = cv::imread((out / "images" / name).string(), cv::IMREAD_UNCHANGED);
        REQUIRE(!images[name].empty());
        CHECK(images[name].type() == source.type());
    }
    double worst = 0;
    std::size_t measured = 0;
    for (const libcam::Observation& o : set.observations) {
        libcam::Vec2 found;
        if (!centroid(images[set.views[o.view].name], o.pixel, found)) continue;
        worst = std::max(worst, (found - o.pixel).norm());
        ++measured;
    }
    CHECK(measured > 100);
    CHECK(worst < 0.1);
    WARN(measured << " blobs, largest centroid distance " << worst << " px");
}

TEST_CASE("dataset: a run started again finishes the rest, the same bytes, and a missing image is named", "[dataset]") {
    TempDir dir;
    const std::vector<std::string> names = {"a.png", "b.png", "c.png", "d.png", "e.png"};
    write_blob_model(dir / "model", dir / "pictures", names);
    const fs::path out = dir / "out";
    const std::vector<std::string> args = {"dataset", (dir / "model").string(), "--images", (dir / "pictures").string(),
                                           "-o", out.string(), "--json", "--threads", "3"};
    run_json(args);
    const auto first = files_under(out);
    fs::remove(out / "images" / "c.png");
    const Json again = run_json(args);
    CHECK(again["images_written"] == 1);
    CHECK(again["images_kept"] == 4);
    CHECK(files_under(out) == first);

    // Another interpolation: the stamp differs, every image is made again.
    std::vector<std::string> linear = args;
    linear.insert(linear.end(), {"--interpolation", "linear"});
    CHECK(run_json(linear)["images_written"] == 5);

    // A missing image: refused before anything is written.
    fs::remove(dir / "pictures" / "b.png");
    const fs::path fresh = dir / "fresh";
    std::vector<std::string> missing = args;
    missing[5] = fresh.string();
    const libcam::test::CliResult result = run_libcam(missing);
    INFO(result.describe());
    CHECK(result.exit_code == 1);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    CHECK(result.err.find("b.png: no such image file") != std::string::npos);
    CHECK_FALSE(fs::exists(fresh));
}

namespace {

// Each observation's residual carried into the output's pixels: J r, with J the map from
// the source camera's pixels to the new camera's at the observation (central differences
// through the rays), and r the source's residual. The output's residual is that to second
// order in r. By (view name, point id), with the pixel each moves to (a point may be
// seen twice in one image).
using Key = std::pair<std::string, std::int64_t>;
struct Carried {
    libcam::Vec2 pixel;
    double error_px;
};

std::map<Key, std::vector<Carried>> carried_errors(const libcam::ObservationSet& in, const libcam::ObservationSet& out) {
    std::map<std::string, int> camera_of_view;
    for (const libcam::ObservedView& view : out.views) camera_of_view[view.name] = view.camera;
    const libcam::Reprojection reprojection = libcam::reproject(in);
    std::vector<libcam::PreparedCamera> sources, targets;
    for (const libcam::ObservedCamera& camera : in.cameras) sources.emplace_back(camera.camera);
    for (const libcam::ObservedCamera& camera : out.cameras) targets.emplace_back(camera.camera);
    std::map<Key, std::vector<Carried>> carried;
    for (std::size_t i = 0; i < in.observations.size(); ++i) {
        const libcam::Observation& o = in.observations[i];
        const libcam::ObservedView& view = in.views[static_cast<std::size_t>(o.view)];
        const libcam::PreparedCamera& source = sources[static_cast<std::size_t>(view.camera)];
        const libcam::PreparedCamera& target = targets[static_cast<std::size_t>(camera_of_view.at(view.name))];
        const auto moved = [&](const libcam::Vec2& pixel) {
            return target.project_camera_point(source.unproject(pixel).direction).pixel;
        };
        const double h = 1e-3;
        Eigen::Matrix2d jacobian;
        jacobian.col(0) = (moved(o.pixel + libcam::Vec2(h, 0)) - moved(o.pixel - libcam::Vec2(h, 0))) / (2 * h);
        jacobian.col(1) = (moved(o.pixel + libcam::Vec2(0, h)) - moved(o.pixel - libcam::Vec2(0, h))) / (2 * h);
        carried[{view.name, in.point_ids[static_cast<std::size_t>(o.point)]}].push_back(
            {moved(o.pixel), (jacobian * reprojection.residuals[i].residual).norm()});
    }
    return carried;
}

}  // namespace

TEST_CASE("dataset: real COLMAP models keep each point's reprojection error", "[sweep][dataset][real]") {
    for (const char* name : {"colmap-halogenname-south-building/sparse/0", "colmap-bartoszek-test_colmap/sparse/0",
                             "colmap-vijayvamsi7-table/final_try_1_workspace/sparse/0",
                             "colmap-consideringname-ggbond-3dgs/distorted/sparse/0"}) {
        const fs::path model = libcam::test::real_data_path(name);
        if (!libcam::test::real_data_present(model)) {
            WARN("skipped: " << model << " is absent");
            continue;
        }
        INFO(name);
        TempDir dir;
        const Json summary = run_json({"dataset", model.string(), "-o", (dir / "out").string(), "--no-images", "--json"});
        const libcam::ObservationSet in = libcam::read_observations(model);
        const libcam::ObservationSet out = libcam::read_observations(dir / "out" / "sparse" / "0");
        CHECK(summary["observations_in"].get<std::size_t>() == in.observations.size());
        CHECK(summary["observations_kept"].get<std::size_t>() == out.observations.size());
        // The ERROR column written is the output's own recomputation.
        const libcam::Reprojection reprojection = libcam::reproject(out);
        REQUIRE(reprojection.summary.per_point_reported);
        CHECK(reprojection.summary.per_point_reported->max_abs_difference < 1e-9);
        // Each point's mean error in the new pixels is its source residuals' carried there.
        const std::map<Key, std::vector<Carried>> carried = carried_errors(in, out);
        struct Sums {
            double output = 0, carried = 0;
            int count = 0;
        };
        std::map<std::int64_t, Sums> sums;
        for (std::size_t i = 0; i < out.observations.size(); ++i) {
            const libcam::Observation& o = out.observations[i];
            const std::int64_t id = out.point_ids[static_cast<std::size_t>(o.point)];
            Sums& sum = sums[id];
            sum.output += reprojection.residuals[i].error_px;
            const std::vector<Carried>& candidates = carried.at({out.views[static_cast<std::size_t>(o.view)].name, id});
            sum.carried += std::min_element(candidates.begin(), candidates.end(), [&](const Carried& a, const Carried& b) {
                               return (a.pixel - o.pixel).norm() < (b.pixel - o.pixel).norm();
                           })->error_px;
            ++sum.count;
        }
        double worst = 0;
        for (const auto& [id, sum] : sums) worst = std::max(worst, std::abs(sum.output - sum.carried) / sum.count);
        CHECK(worst < 0.01);
        WARN(name << ": " << out.observations.size() << " of " << in.observations.size()
                  << " observations kept; largest difference of a point's mean error from its carried one " << worst << " px");
    }
}

TEST_CASE("dataset: COLMAP's model_analyzer reads the output", "[dataset][colmap]") {
    const std::string colmap = COLMAP_PROGRAM;
    if (colmap.empty() || !fs::exists(colmap)) {
        WARN("skipped: no colmap program");
        return;
    }
    TempDir dir;
    write_model(dir / "in", t265_lens(), {"f0.png", "f1.png", "f2.png"}, 16, 6.0);
    for (const bool text : {false, true}) {
        const fs::path out = dir / (text ? "text" : "binary");
        std::vector<std::string> args = {"dataset", (dir / "in").string(), "-o", out.string(), "--no-images", "--json"};
        if (text) args.push_back("--text");
        const Json summary = run_json(args);
        const libcam::test::CliResult analysed =
            libcam::test::run_program(colmap, {"model_analyzer", "--path", (out / "sparse" / "0").string()});
        INFO(analysed.describe());
        CHECK(analysed.exit_code == 0);
        const std::string printed = analysed.out + analysed.err;
        CHECK(printed.find("Cameras: 1") != std::string::npos);
        CHECK(printed.find("Images: 3") != std::string::npos);
        CHECK(printed.find("Observations: " + std::to_string(summary["observations_kept"].get<std::size_t>())) !=
              std::string::npos);
    }
}

namespace {

// Each kept observation at its view's pinhole projection of its point (fx X/Z + cx, the
// view's camera and turned pose as the output model has them); returns the largest distance.
double worst_pinhole_distance(const libcam::ObservationSet& set) {
    double worst = 0;
    for (const libcam::Observation& o : set.observations) {
        const libcam::ObservedView& view = set.views[static_cast<std::size_t>(o.view)];
        const libcam::Camera& camera = set.cameras[static_cast<std::size_t>(view.camera)].camera;
        REQUIRE(camera.lens.type == libcam::LensType::Pinhole);
        const auto& k = camera.intrinsics;
        const libcam::Vec3 X = view.pose.R * set.points[static_cast<std::size_t>(o.point)] + view.pose.t;
        REQUIRE(X.z() > 0);
        worst = std::max(worst, std::hypot(k.fx * X.x() / X.z() + k.cx - o.pixel.x(), k.fy * X.y() / X.z() + k.cy - o.pixel.y()));
    }
    return worst;
}

void write_black_images(const fs::path& folder, const std::vector<std::string>& names, int width, int height) {
    fs::create_directories(folder);
    for (const std::string& name : names) {
        REQUIRE(cv::imwrite((folder / name).string(), cv::Mat(height, width, CV_8U, cv::Scalar(0))));
    }
}

}  // namespace

TEST_CASE("dataset: --camera views splits the T265 fisheye and keeps its observations, COLMAP's undistorter far fewer",
          "[dataset][views]") {
    TempDir dir;
    const std::vector<std::string> names = {"f0.png", "f1.png", "f2.png"};
    const Written written = write_model(dir / "in", t265_lens(), names, 16, 6.0);
    const fs::path out = dir / "out";
    const Json summary =
        run_json({"dataset", (dir / "in").string(), "-o", out.string(), "--no-images", "--json", "--camera", "views"});
    const std::size_t views = summary["cameras"].size();
    CHECK(views > 1);
    CHECK(summary["cameras"][0]["views"] == views);
    CHECK(summary["model_images_out"] == names.size() * views);
    // Every observation the lens makes (each inside its valid domain: the test's lens
    // projected it) is kept, counted once.
    CHECK(summary["observations_in"].get<std::size_t>() == written.observations);
    const std::size_t kept = summary["observations_kept"].get<std::size_t>();
    CHECK(kept >= 0.99 * static_cast<double>(written.observations));
    const libcam::ObservationSet set = libcam::read_observations(out / "sparse" / "0");
    CHECK(set.cameras.size() == views);
    CHECK(set.views.size() == names.size() * views);
    std::size_t per_view = 0;
    for (const Json& camera : summary["cameras"]) per_view += camera["observations"].get<std::size_t>();
    CHECK(per_view == set.observations.size());
    CHECK(set.observations.size() >= kept);  // an observation in two views is in both
    const double worst = worst_pinhole_distance(set);
    CHECK(worst < 1e-6);

    // The same views in NeRF's layout: a frame per view image, with its view's camera and
    // turned pose, as the COLMAP output has them.
    run_json({"dataset", (dir / "in").string(), "-o", (dir / "nerf").string(), "--no-images", "--json", "--camera", "views",
              "--to", "nerf"});
    const libcam::CameraSet nerf = libcam::read_camera_set(dir / "nerf" / "transforms.json");
    REQUIRE(nerf.cameras.size() == set.views.size());
    for (const libcam::ObservedView& view : set.views) {
        const auto frame = std::find_if(nerf.cameras.begin(), nerf.cameras.end(),
                                        [&](const libcam::NamedCamera& c) { return c.name == "images/" + view.name; });
        REQUIRE(frame != nerf.cameras.end());
        const libcam::Camera& camera = set.cameras[static_cast<std::size_t>(view.camera)].camera;
        CHECK(std::abs(frame->file.camera.intrinsics.fx - camera.intrinsics.fx) < 1e-9);
        CHECK(std::abs(frame->file.camera.intrinsics.cx - camera.intrinsics.cx) < 1e-9);
        CHECK(frame->file.camera.size == camera.size);
        CHECK((frame->file.camera.pose.R - view.pose.R).cwiseAbs().maxCoeff() < 1e-12);
        CHECK((frame->file.camera.pose.t - view.pose.t).cwiseAbs().maxCoeff() < 1e-9);
    }

    // COLMAP's own undistortion of the same model, which keeps one pinhole per camera.
    const std::string colmap = COLMAP_PROGRAM;
    if (colmap.empty() || !fs::exists(colmap)) {
        WARN("libcam views: " << kept << " of " << written.observations << " observations kept in " << views
                              << " views; COLMAP skipped: no colmap program");
        return;
    }
    write_black_images(dir / "images", names, 848, 800);
    const libcam::test::CliResult undistorted = libcam::test::run_program(
        colmap, {"image_undistorter", "--image_path", (dir / "images").string(), "--input_path", (dir / "in").string(),
                 "--output_path", (dir / "colmap").string(), "--output_type", "COLMAP"});
    INFO(undistorted.describe());
    REQUIRE(undistorted.exit_code == 0);
    // COLMAP moves every POINTS2D and writes it, on its image or not: those its
    // undistorted images hold are the ones on them.
    const libcam::ObservationSet by_colmap = libcam::read_observations(dir / "colmap" / "sparse");
    std::size_t colmap_kept = 0;
    for (const libcam::Observation& o : by_colmap.observations) {
        const libcam::ImageSize& size =
            by_colmap.cameras[static_cast<std::size_t>(by_colmap.views[static_cast<std::size_t>(o.view)].camera)].camera.size;
        colmap_kept += std::isfinite(o.pixel.x()) && std::isfinite(o.pixel.y()) && o.pixel.x() >= -0.5 &&
                       o.pixel.y() >= -0.5 && o.pixel.x() <= size.width - 0.5 && o.pixel.y() <= size.height - 0.5;
    }
    CHECK(colmap_kept < 0.75 * static_cast<double>(kept));
    WARN("T265 fisheye, " << written.observations << " observations: libcam dataset --camera views keeps " << kept << " in "
                          << views << " views (largest distance from the pinhole projection " << worst
                          << " px); colmap image_undistorter keeps " << colmap_kept << " on its "
                          << by_colmap.cameras[0].camera.size.width << "x" << by_colmap.cameras[0].camera.size.height
                          << " images (of the " << by_colmap.observations.size() << " it writes); " << summary["cameras"][0]["why"]);
}

TEST_CASE("dataset: each view's blobs are at its moved observations, each with a mask, and a stopped run finishes",
          "[dataset][views]") {
    TempDir dir;
    const Lens lens = t265_lens(0.5);
    const Written written = write_model(dir / "scene" / "sparse" / "0", lens, {"a.png"}, 9, 6.0, 1);
    fs::create_directories(dir / "scene" / "images");
    REQUIRE(cv::imwrite((dir / "scene" / "images" / "a.png").string(), blob_image(lens, 0, written.points, CV_8U, 1)));
    const fs::path out = dir / "out";
    const std::vector<std::string> args = {"dataset", (dir / "scene" / "sparse" / "0").string(), "-o", out.string(),
                                           "--json", "--camera", "views", "--masks", "--threads", "2"};
    const Json summary = run_json(args);
    const std::size_t views = summary["cameras"].size();
    REQUIRE(views > 1);
    CHECK(summary["images_out"] == views);
    CHECK(summary["observations_kept"] == summary["observations_in"]);
    const libcam::ObservationSet set = libcam::read_observations(out / "sparse" / "0");
    std::map<std::string, cv::Mat> images;
    for (const libcam::ObservedView& view : set.views) {
        CHECK(view.name == "a_view" + std::to_string(&view - set.views.data()) + ".png");
        const cv::Mat image = cv::imread((out / "images" / view.name).string(), cv::IMREAD_UNCHANGED);
        const cv::Mat mask = cv::imread((out / "masks" / (view.name + ".png")).string(), cv::IMREAD_UNCHANGED);
        REQUIRE(!image.empty());
        REQUIRE(!mask.empty());
        CHECK(mask.type() == CV_8U);
        CHECK(mask.size() == image.size());
        // Black wherever the mask says there is no source; the mask 0 or 255.
        CHECK(cv::countNonZero(mask == 0 & image != 0) == 0);
        CHECK(cv::countNonZero(mask != 0 & mask != 255) == 0);
        CHECK(cv::countNonZero(mask) > 0);
        images[view.name] = image;
    }
    // A blob far off a view's axis is stretched unevenly by the pinhole (1/cos^2 of the
    // angle radially), which moves its centroid off its centre, and the fisheye's periphery
    // packs blobs so close that a neighbour enters the window: the blobs within 35 degrees
    // of their view's axis and 10 px of no other are held to 0.15 px.
    double worst = 0, worst_any = 0;
    std::size_t measured = 0;
    const auto crowded = [&](const libcam::Observation& o) {
        for (const libcam::Observation& other : set.observations) {
            if (&other != &o && other.view == o.view && (other.pixel - o.pixel).norm() < 10) return true;
        }
        return false;
    };
    for (const libcam::Observation& o : set.observations) {
        const libcam::ObservedView& view = set.views[static_cast<std::size_t>(o.view)];
        const auto& k = set.cameras[static_cast<std::size_t>(view.camera)].camera.intrinsics;
        const double off_axis = std::atan(std::hypot((o.pixel.x() - k.cx) / k.fx, (o.pixel.y() - k.cy) / k.fy));
        libcam::Vec2 found;
        if (!centroid(images[view.name], o.pixel, found)) continue;
        worst_any = std::max(worst_any, (found - o.pixel).norm());
        if (off_axis > 35 * M_PI / 180 || crowded(o)) continue;
        worst = std::max(worst, (found - o.pixel).norm());
        ++measured;
    }
    CHECK(measured > 20);
    CHECK(worst < 0.15);
    WARN(views << " views, " << measured << " lone blobs within 35 deg of their view's axis, largest centroid distance "
               << worst << " px (" << worst_any << " px over all)");

    // Started again with a view's image and another's mask gone: those two made again.
    const auto first = files_under(out);
    fs::remove(out / "images" / set.views[1].name);
    fs::remove(out / "masks" / (set.views[0].name + ".png"));
    const Json again = run_json(args);
    CHECK(again["images_written"] == 2);
    CHECK(again["images_kept"] == views - 2);
    CHECK(files_under(out) == first);
}

TEST_CASE("dataset: a mask is 255 exactly where the undistorted image has a source pixel", "[dataset][masks]") {
    TempDir dir;
    const Lens lens = opencv_lens(320, 240);
    write_model(dir / "model", lens, {"a.png", "b.jpg"}, 6, 0.4, 1);
    fs::create_directories(dir / "images");
    for (const char* name : {"a.png", "b.jpg"}) {
        REQUIRE(cv::imwrite((dir / "images" / name).string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(200, 180, 160))));
    }
    for (const std::string interpolation : {"nearest", "cubic"}) {
        const fs::path out = dir / interpolation;
        // all: the pinhole that keeps every source pixel, black in its corners.
        run_json({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o", out.string(), "--json",
                  "--camera", "all", "--masks", "--interpolation", interpolation});
        for (const char* name : {"a.png", "b.jpg"}) {
            INFO(interpolation << " " << name);
            const cv::Mat image = cv::imread((out / "images" / name).string(), cv::IMREAD_GRAYSCALE);
            const cv::Mat mask = cv::imread((out / "masks" / (std::string(name) + ".png")).string(), cv::IMREAD_UNCHANGED);
            REQUIRE(!mask.empty());
            REQUIRE(mask.size() == image.size());
            const int black = cv::countNonZero(mask == 0);
            CHECK(black > 0);
            // JPEG's ringing leaves a few grey levels where the image is black.
            const int threshold = std::string(name) == "b.jpg" ? 40 : 0;
            CHECK(cv::countNonZero((mask == 255) != (image > threshold)) == 0);
            WARN(interpolation << " " << name << ": " << black << " of " << mask.total() << " pixels without a source");
        }
    }
}

TEST_CASE("dataset views: a whole LONLAT panorama is split into pinholes that hold each of its pixels' rays",
          "[dataset][views]") {
    // mrcal's LONLAT over the whole sphere: x = fx lon + cx, y = fy lat + cy.
    const long width = 240, height = 120;
    libcam::Camera panorama;
    panorama.size = {width, height};
    const double f = static_cast<double>(width) / (2 * M_PI);
    panorama.intrinsics = {f, f, (width - 1) / 2.0, (height - 1) / 2.0, 0.0};
    panorama.lens = {libcam::LensType::Lonlat, {}};
    const libcam::LensViews chosen = libcam::choose_views(libcam::PreparedCamera(panorama), {}, 2);
    INFO(chosen.why);
    REQUIRE(chosen.views.size() > 1);
    CHECK(chosen.views.size() <= 6);
    // Each pixel's ray, by the formula above, on some view's image (the view's turn and
    // pinhole applied here), and within 60 degrees of that view's axis.
    std::size_t held = 0;
    for (long y = 0; y < height; ++y) {
        for (long x = 0; x < width; ++x) {
            const double lon = (x - panorama.intrinsics.cx) / f, lat = (y - panorama.intrinsics.cy) / f;
            const libcam::Vec3 ray(std::cos(lat) * std::sin(lon), std::sin(lat), std::cos(lat) * std::cos(lon));
            bool on_a_view = false;
            for (const libcam::LensView& view : chosen.views) {
                const libcam::Vec3 d = view.turn * ray;
                if (d.z() < std::cos(60.0 * M_PI / 180) - 1e-12) continue;
                const auto& k = view.camera.intrinsics;
                const double u = k.fx * d.x() / d.z() + k.cx, v = k.fy * d.y() / d.z() + k.cy;
                on_a_view = on_a_view || (u >= -0.5 && v >= -0.5 && u <= view.camera.size.width - 0.5 &&
                                          v <= view.camera.size.height - 0.5);
            }
            held += on_a_view;
        }
    }
    CHECK(held == static_cast<std::size_t>(width * height));
    WARN(chosen.why);
}

TEST_CASE("dataset views: the T265's factory calibration (kapture's COLMAP cameras) split so every pixel lands on a view",
          "[dataset][views][real]") {
    const fs::path cameras = libcam::test::real_data_path("kapture-samples/t265/colmap/cameras.txt");
    if (!libcam::test::real_data_present(cameras)) {
        WARN("skipped: " << cameras << " is absent");
        return;
    }
    // Its two OPENCV_FISHEYE cameras, one image each at the origin, no points.
    TempDir dir;
    fs::create_directories(dir / "in");
    fs::copy_file(cameras, dir / "in" / "cameras.txt");
    libcam::test::write_whole_file(dir / "in" / "images.txt", "1 1 0 0 0 0 0 0 1 left.png\n\n2 1 0 0 0 0 0 0 2 right.png\n\n");
    libcam::test::write_whole_file(dir / "in" / "points3D.txt", "");
    const Json summary = run_json({"dataset", (dir / "in").string(), "-o", (dir / "out").string(), "--no-images", "--json",
                                   "--camera", "views", "--text"});
    const libcam::ObservationSet out = libcam::read_observations(dir / "out" / "sparse" / "0");
    REQUIRE(out.views.size() == summary["cameras"].size());
    // Each source pixel (every 4th), unprojected by Kannala-Brandt's formula inverted here
    // (Newton's method, where theta_d still rises), on the image of one of its camera's
    // views: the view's turn is its pose's rotation (the source's is the identity).
    std::istringstream lines(libcam::test::read_whole_file(cameras));
    std::string line;
    std::size_t checked = 0, held = 0;
    while (std::getline(lines, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::uint64_t id;
        std::string model;
        double width, height, fx, fy, cx, cy, k[4];
        fields >> id >> model >> width >> height >> fx >> fy >> cx >> cy >> k[0] >> k[1] >> k[2] >> k[3];
        REQUIRE(model == "OPENCV_FISHEYE");
        const std::string name = id == 1 ? "left" : "right";
        std::vector<const libcam::ObservedView*> views;
        for (const libcam::ObservedView& view : out.views) {
            if (view.name.rfind(name + "_view", 0) == 0) views.push_back(&view);
        }
        CHECK(views.size() > 1);
        for (double y = 0; y < height; y += 4) {
            for (double x = 0; x < width; x += 4) {
                const double a = (x + 0.5 - cx) / fx, b = (y + 0.5 - cy) / fy, theta_d = std::hypot(a, b);
                double theta = theta_d;
                bool rising = true;
                for (int i = 0; i < 40; ++i) {
                    const double t2 = theta * theta;
                    const double f = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])))) - theta_d;
                    const double df = 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
                    rising = rising && df > 0;
                    theta -= f / df;
                }
                if (!rising || (theta <= 0 && theta_d > 0)) continue;
                const double s = theta_d > 0 ? std::sin(theta) / theta_d : 0;
                const libcam::Vec3 ray(a * s, b * s, std::cos(theta));
                ++checked;
                for (const libcam::ObservedView* view : views) {
                    const libcam::Vec3 d = view->pose.R * ray;
                    const libcam::Camera& camera = out.cameras[static_cast<std::size_t>(view->camera)].camera;
                    const auto& kv = camera.intrinsics;
                    if (d.z() <= 0) continue;
                    const double u = kv.fx * d.x() / d.z() + kv.cx, v = kv.fy * d.y() / d.z() + kv.cy;
                    if (u >= -0.5 && v >= -0.5 && u <= camera.size.width - 0.5 && v <= camera.size.height - 0.5) {
                        ++held;
                        break;
                    }
                }
            }
        }
    }
    CHECK(checked > 40000);
    CHECK(held == checked);
    WARN(held << " of " << checked << " pixels on a view; " << summary["cameras"][0]["why"]);
}
