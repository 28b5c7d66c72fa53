// `libcam dataset` split into a plan and image tasks (dataset_tasks.hpp): a task's JSON
// holds every field to the last bit, a MapCache builds each camera's map once, and the
// tasks run one by one from their JSON write the files make_pinhole_dataset writes.

#include <catch2/catch.hpp>
#include <atomic>
#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "cli_runner.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/dataset/dataset_tasks.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::TempDir;
using libcam::test::write_whole_file;

libcam::Camera opencv_camera(double k1) {
    libcam::Camera camera;
    camera.size = {48, 36};
    camera.intrinsics = {50.0 / 3.0 * 3.1, 44.1, 23.7, 17.9, 0.0};
    camera.lens = {libcam::LensType::OpenCv4, {k1, 0.04, 1e-4 / 3.0, -2e-4}};
    return camera;
}

libcam::ImageTask example_task() {
    libcam::ImageTask task;
    task.source = opencv_camera(-0.2 / 3.0);
    task.camera = task.source;
    task.camera.lens = {};
    task.camera.intrinsics = {40.0 / 7.0 * 7.3, 40.0 / 7.0 * 7.3, 23.5, 17.5, 0.0};
    // A view's turn: a yaw, its zeros signed as the view's formula leaves them (-0 kept, not
    // read back as the integer 0).
    task.turn = Eigen::AngleAxisd(0.3 / 7.0, libcam::Vec3::UnitY()).toRotationMatrix();
    task.turn(0, 1) = -0.0;
    task.interpolation = libcam::Interpolation::Lanczos;
    task.jpeg_quality = 77;
    task.source_path = "/data/photos/a b/caf\xc3\xa9 \"1\".jpg";
    task.target_path = "/data/out/images/a b/caf\xc3\xa9 \"1\".jpg";
    task.mask_path = "/data/out/masks/a b/caf\xc3\xa9 \"1\".jpg.png";
    return task;
}

// Every file under `folder`, by its path relative to it, with its bytes.
std::map<std::string, std::string> files_under(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files[fs::relative(entry.path(), folder).string()] = libcam::test::read_whole_file(entry.path());
        }
    }
    return files;
}

// A COLMAP text model of a wide fisheye (144 degrees off the axis at its corners: several
// views) and an OPENCV lens, four small images among them, one in a subfolder.
void write_scene(const fs::path& dir) {
    fs::create_directories(dir / "model");
    fs::create_directories(dir / "images" / "sub");
    write_whole_file(dir / "model" / "cameras.txt",
                     "1 OPENCV_FISHEYE 80 60 20 20 39.5 29.5 0 0 0 0\n2 OPENCV 48 36 46 44 23.7 17.9 -0.2 0.04 0 0\n");
    write_whole_file(dir / "model" / "images.txt",
                     "1 1 0 0 0 0 0 0 1 f1.png\n\n2 1 0 0 0 1 0 0 1 sub/f2.png\n\n"
                     "3 1 0 0 0 0 0 1 2 o1.jpg\n\n4 0 1 0 0 0 1 0 2 o2.png\n\n");
    write_whole_file(dir / "model" / "points3D.txt", "");
    const auto picture = [](int width, int height, int seed) {
        cv::Mat image(height, width, CV_8UC3);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                image.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>((x * 7 + seed) % 256),
                                                      static_cast<uchar>((y * 11 + 3 * seed) % 256),
                                                      static_cast<uchar>(((x ^ y) * 5) % 256));
            }
        }
        return image;
    };
    REQUIRE(cv::imwrite((dir / "images" / "f1.png").string(), picture(80, 60, 1)));
    REQUIRE(cv::imwrite((dir / "images" / "sub" / "f2.png").string(), picture(80, 60, 2)));
    REQUIRE(cv::imwrite((dir / "images" / "o1.jpg").string(), picture(48, 36, 3)));
    REQUIRE(cv::imwrite((dir / "images" / "o2.png").string(), picture(48, 36, 4)));
}

libcam::DatasetOptions scene_options(const fs::path& dir, const std::string& out) {
    libcam::DatasetOptions options;
    options.model = dir / "model";
    options.images = dir / "images";
    options.output = dir / out;
    options.views = true;
    options.masks = true;
    options.threads = 2;
    return options;
}

}  // namespace

TEST_CASE("dataset tasks: a task's JSON holds every field to the last bit", "[dataset][tasks]") {
    const libcam::ImageTask task = example_task();
    const std::string json = libcam::image_task_json(task);
    CHECK(json.find('\n') == std::string::npos);
    const libcam::ImageTask back = libcam::image_task_from_json(json);
    CHECK(back.source.size == task.source.size);
    CHECK(back.source.lens == task.source.lens);
    CHECK(back.source.intrinsics.K() == task.source.intrinsics.K());
    CHECK(back.camera.lens == task.camera.lens);
    CHECK(back.camera.intrinsics.K() == task.camera.intrinsics.K());
    CHECK(back.turn == task.turn);
    CHECK(std::signbit(back.turn(0, 1)));
    CHECK(back.copy == task.copy);
    CHECK(back.interpolation == task.interpolation);
    CHECK(back.jpeg_quality == 77);
    CHECK(back.source_path == task.source_path);
    CHECK(back.target_path == task.target_path);
    CHECK(back.mask_path == task.mask_path);
    CHECK(libcam::image_task_json(back) == json);

    libcam::ImageTask copied = task;
    copied.copy = true;
    copied.mask_path.clear();
    const libcam::ImageTask copied_back = libcam::image_task_from_json(libcam::image_task_json(copied));
    CHECK(copied_back.copy);
    CHECK(copied_back.mask_path.empty());
}

TEST_CASE("dataset tasks: a damaged task is refused naming the field", "[dataset][tasks]") {
    const std::string json = libcam::image_task_json(example_task());
    const auto refused = [](const std::string& text, const std::string& expected) {
        try {
            libcam::image_task_from_json(text, "task.json");
            FAIL("accepted: " << text);
        } catch (const libcam::FileError& error) {
            INFO(error.what());
            CHECK(std::string(error.what()).find(expected) != std::string::npos);
        }
    };
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = json;
        text.replace(text.find(from), from.size(), to);
        return text;
    };
    refused(replaced("\"jpeg_quality\": 77", "\"jpeg_quality\": 0"), "task.json: \"jpeg_quality\"");
    refused(replaced("\"interpolation\": \"lanczos\"", "\"interpolation\": \"bicubic\""), "\"interpolation\": ");
    refused(replaced("\"target_path\"", "\"target\""), "\"target_path\": missing");
    refused(replaced("\"turn\": [", "\"turn\": [1, "), "\"turn\": ");
    refused(replaced("\"model\":\"OPENCV4\"", "\"model\":\"NO_SUCH_LENS\""), "\"source.model\"");
    refused("[1, 2]", "expected an image task");
    refused(json.substr(0, json.size() / 2), "not valid JSON");
}

TEST_CASE("dataset tasks: a map cache builds each camera's map once and keeps the last few", "[dataset][tasks]") {
    libcam::ImageTask a = example_task();
    a.interpolation = libcam::Interpolation::Cubic;
    libcam::ImageTask a_other_image = a;
    a_other_image.source_path = "/elsewhere/b.png";
    a_other_image.jpeg_quality = 50;
    libcam::ImageTask b = a;
    b.source = opencv_camera(-0.1);

    libcam::MapCache cache(1, 1);
    const auto map_a = cache.map_for(a);
    REQUIRE(map_a);
    CHECK(map_a->xy.cols == 48);
    CHECK(cache.map_for(a_other_image) == map_a);
    CHECK(cache.builds() == 1);
    const auto map_b = cache.map_for(b);
    CHECK(map_b != map_a);
    CHECK(cache.builds() == 2);
    CHECK(cache.size() == 1);
    CHECK(map_a->xy.cols == 48);  // dropped from the cache, still alive for its user
    cache.map_for(a);
    CHECK(cache.builds() == 3);

    libcam::ImageTask copied = a;
    copied.copy = true;
    CHECK(cache.map_for(copied) == nullptr);
    CHECK(cache.builds() == 3);

    // Workers asking for one map at once wait for the one building it.
    libcam::MapCache shared(2, 1);
    std::vector<std::thread> workers;
    std::atomic<int> same{0};
    shared.map_for(b);
    for (int w = 0; w < 4; ++w) workers.emplace_back([&] { same += shared.map_for(a) == shared.map_for(a) ? 1 : 0; });
    for (std::thread& worker : workers) worker.join();
    CHECK(same == 4);
    CHECK(shared.builds() == 2);
}

TEST_CASE("dataset tasks: a plan's tasks run one by one from their JSON give make_pinhole_dataset's files, and planning again lists only what is missing",
          "[dataset][tasks]") {
    TempDir dir;
    write_scene(dir.path());
    const libcam::DatasetSummary whole = libcam::make_pinhole_dataset(scene_options(dir.path(), "whole"));
    REQUIRE(whole.images_failed == 0);
    REQUIRE(whole.model_images_out > 4);  // the fisheye's images split into views

    libcam::DatasetPlan plan = libcam::plan_dataset(scene_options(dir.path(), "tasks"));
    REQUIRE(plan.tasks.size() == whole.model_images_out);
    CHECK(plan.summary.images_kept == 0);
    bool turned = false, copied = false;
    libcam::MapCache maps(2, 1);
    for (const libcam::ImageTask& task : plan.tasks) {
        turned = turned || task.turn != libcam::Mat3::Identity();
        copied = copied || task.copy;
        libcam::run_image_task(libcam::image_task_from_json(libcam::image_task_json(task)), maps);
    }
    CHECK(turned);
    CHECK_FALSE(copied);
    CHECK(libcam::finish_dataset(plan).images_written == plan.tasks.size());
    // One map per camera: the views of the fisheye and the OPENCV lens, each built once.
    CHECK(maps.builds() == whole.cameras.size());

    const auto expected = files_under(dir / "whole");
    const auto written = files_under(dir / "tasks");
    REQUIRE(expected.size() == written.size());
    for (const auto& [name, bytes] : expected) {
        INFO(name);
        REQUIRE(written.count(name) == 1);
        CHECK(written.at(name) == bytes);
    }

    // One image and another's mask lost from the output: planning again lists those two.
    const libcam::ImageTask& lost_image = plan.tasks.front();
    const libcam::ImageTask& lost_mask = plan.tasks.back();
    const fs::path staging = plan.staging.folder;
    fs::remove(dir / "tasks" / lost_image.target_path.lexically_relative(staging));
    fs::remove(dir / "tasks" / lost_mask.mask_path.lexically_relative(staging));
    const libcam::DatasetPlan again = libcam::plan_dataset(scene_options(dir.path(), "tasks"));
    REQUIRE(again.tasks.size() == 2);
    CHECK(again.summary.images_kept == plan.tasks.size() - 2);
    CHECK(again.tasks.front().target_path == lost_image.target_path);
    CHECK(again.tasks.back().target_path == lost_mask.target_path);
    for (const libcam::ImageTask& task : again.tasks) libcam::run_image_task(task, maps);
    libcam::finish_dataset(again);
    CHECK(files_under(dir / "tasks") == expected);
}
