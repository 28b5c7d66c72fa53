// A `libcam dataset` run that fails leaves an existing output byte for byte as it was and a
// new one recognisably unfinished (nothing but the staging folder); started again it keeps
// the images it made and finishes. Stopped in the image phase or while finishing, the same
// run started again ends in the output of a run never stopped.

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cli_runner.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/dataset/dataset_tasks.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::CliResult;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using libcam::test::write_whole_file;
using Json = nlohmann::json;

const std::vector<std::string> kNames = {"a.png", "b.png", "sub/c.png", "d.png"};
const std::string kStaging = ".libcam-dataset-partial";

cv::Mat picture(int seed) {
    cv::Mat image(18, 24, CV_8UC3);
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(x * 9 + seed), uchar(y * 13), uchar(seed));
    }
    return image;
}

// A text model of two cameras (OPENCV and one already a pinhole, whose images are copied),
// its four images, one in a subfolder, and a point seen in two of them.
void write_scene(const fs::path& dir) {
    fs::create_directories(dir / "model");
    write_whole_file(dir / "model" / "cameras.txt",
                     "1 OPENCV 24 18 22 21 11.5 8.5 -0.1 0.01 0 0\n2 PINHOLE 24 18 20 20 12 9\n");
    write_whole_file(dir / "model" / "images.txt",
                     "1 1 0 0 0 0 0 0 1 a.png\n11.5 8.5 1\n2 1 0 0 0 0.1 0 0 1 b.png\n11 8 1\n"
                     "3 1 0 0 0 0.2 0 0 2 sub/c.png\n\n4 1 0 0 0 0.3 0 0 1 d.png\n\n");
    write_whole_file(dir / "model" / "points3D.txt", "1 0 0 1 200 100 50 0.5 1 0 2 0\n");
    fs::create_directories(dir / "images" / "sub");
    for (std::size_t i = 0; i < kNames.size(); ++i) {
        REQUIRE(cv::imwrite((dir / "images" / kNames[i]).string(), picture(static_cast<int>(10 * i))));
    }
}

// Every file and folder under `folder` but the staging folder, with each file's bytes.
std::map<std::string, std::string> files_under(const fs::path& folder) {
    std::map<std::string, std::string> files;
    std::error_code error;
    if (!fs::exists(folder, error)) return files;
    for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it) {
        const std::string name = fs::relative(it->path(), folder).string();
        if (name == kStaging) {
            it.disable_recursion_pending();
            continue;
        }
        files[name] = it->is_directory() ? "(folder)" : libcam::test::read_whole_file(it->path());
    }
    return files;
}

std::vector<std::string> args(const fs::path& dir, const fs::path& out, std::vector<std::string> more = {}) {
    std::vector<std::string> words = {"dataset", (dir / "model").string(), "--images", (dir / "images").string(),
                                      "-o", out.string(), "--masks", "--json"};
    words.insert(words.end(), more.begin(), more.end());
    return words;
}

Json finished_run(const std::vector<std::string>& words) {
    const CliResult result = run_libcam(words);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    const Json summary = Json::parse(result.out);
    CHECK(summary["finished"] == true);
    return summary;
}

libcam::DatasetOptions options_for(const fs::path& dir, const fs::path& out) {
    libcam::DatasetOptions options;
    options.model = dir / "model";
    options.images = dir / "images";
    options.output = out;
    options.masks = true;
    options.threads = 2;
    return options;
}

}  // namespace

TEST_CASE("dataset staging: a failed run over a good output leaves it byte for byte, and started again it keeps its images "
          "and finishes", "[dataset][staging]") {
    TempDir dir;
    write_scene(dir.path());
    const fs::path out = dir / "out";
    finished_run(args(dir.path(), out));
    const auto good = files_under(out);
    REQUIRE(good.count("sparse/0/images.bin") == 1);
    REQUIRE(good.count("masks/sub/c.png.png") == 1);
    const std::vector<std::string> linear = args(dir.path(), out, {"--interpolation", "linear"});

    // One image missing and one unreadable: refused before anything is written.
    const std::string b_bytes = libcam::test::read_whole_file(dir / "images" / "b.png");
    fs::remove(dir / "images" / "b.png");
    write_whole_file(dir / "images" / "d.png", "not a picture");
    const CliResult missing = run_libcam(linear);
    INFO(missing.describe());
    CHECK(missing.exit_code == 1);
    CHECK(missing.err == "libcam: error: " + (dir / "model" / "images.txt").string() + ": line 3: image 2: " +
                             (dir / "images" / "b.png").string() +
                             ": no such image file (missing: 1 of the model's images): nothing was written\n");
    CHECK(files_under(out) == good);
    CHECK_FALSE(fs::exists(out / kStaging));

    // The unreadable one alone: the others are made, the output is as it was.
    write_whole_file(dir / "images" / "b.png", b_bytes);
    const CliResult failed = run_libcam(linear);
    INFO(failed.describe());
    CHECK(failed.exit_code == 1);
    CHECK(Json::parse(failed.out)["finished"] == false);
    CHECK(Json::parse(failed.out)["images_failed"] == 1);
    CHECK(failed.err == "libcam: error: " + (dir / "images" / "d.png").string() + ": not an image OpenCV can read\n" +
                            "libcam: error: 1 of 4 images failed: " + out.string() + " is as it was; this run's work is kept in " +
                            (out / kStaging).string() + ", and running the same command again finishes it\n");
    CHECK(files_under(out) == good);
    CHECK(fs::is_regular_file(out / kStaging / "images" / "sub" / "c.png"));

    // Mended and started again: the three staged images kept, the fourth made.
    REQUIRE(cv::imwrite((dir / "images" / "d.png").string(), picture(30)));
    const Json again = finished_run(linear);
    CHECK(again["images_kept"] == 3);
    CHECK(again["images_written"] == 1);
    CHECK_FALSE(fs::exists(out / kStaging));
    // The same files as one run never stopped.
    finished_run(args(dir.path(), dir / "whole", {"--interpolation", "linear"}));
    CHECK(files_under(out) == files_under(dir / "whole"));
    CHECK(files_under(out) != good);
}

TEST_CASE("dataset staging: a failed run into a new output leaves nothing that claims to be finished", "[dataset][staging]") {
    TempDir dir;
    write_scene(dir.path());
    write_whole_file(dir / "images" / "a.png", "");
    for (const std::string to : {"colmap", "nerf"}) {
        INFO(to);
        const fs::path out = dir / to;
        const CliResult failed = run_libcam(args(dir.path(), out, {"--to", to}));
        INFO(failed.describe());
        CHECK(failed.exit_code == 1);
        // Nothing but the staging folder: no model, no images, no stamp.
        CHECK(files_under(out).empty());
        CHECK(fs::is_directory(out / kStaging / "images"));
    }
    REQUIRE(cv::imwrite((dir / "images" / "a.png").string(), picture(0)));
    for (const std::string to : {"colmap", "nerf"}) {
        const Json again = finished_run(args(dir.path(), dir / to, {"--to", to}));
        CHECK(again["images_kept"] == 3);
        CHECK(again["images_written"] == 1);
    }
    CHECK(fs::is_regular_file(dir / "colmap" / "sparse" / "0" / "images.bin"));
    CHECK(fs::is_regular_file(dir / "nerf" / "transforms.json"));
    CHECK(fs::is_regular_file(dir / "nerf" / "sparse_pc.ply"));
    CHECK(fs::is_regular_file(dir / "nerf" / "masks" / "a.png.png"));
}

TEST_CASE("dataset staging: stopped in the image phase, planning again lists the rest, and finishing early moves nothing",
          "[dataset][staging]") {
    TempDir dir;
    write_scene(dir.path());
    const fs::path out = dir / "out";
    const libcam::DatasetPlan plan = libcam::plan_dataset(options_for(dir.path(), out));
    REQUIRE(plan.tasks.size() == 4);
    CHECK_FALSE(plan.summary.finished);
    libcam::MapCache maps;
    libcam::run_image_task(plan.tasks[0], maps);
    libcam::run_image_task(plan.tasks[3], maps);
    // Not every image is there: nothing is moved.
    try {
        libcam::finish_dataset(plan);
        FAIL("finished with two images missing");
    } catch (const libcam::FileError& error) {
        CHECK(std::string(error.what()) ==
              (out / kStaging).string() + ": 4 of the run's 8 image files are not written yet (the first: " +
                  plan.tasks[1].target_path.string() + "): nothing was moved into " + out.string() +
                  "; run the rest of the tasks, or the same run again");
    }
    CHECK(files_under(out).empty());

    const libcam::DatasetPlan again = libcam::plan_dataset(options_for(dir.path(), out));
    REQUIRE(again.tasks.size() == 2);
    CHECK(again.summary.images_kept == 2);
    CHECK(again.tasks[0].target_path == plan.tasks[1].target_path);
    CHECK(again.tasks[1].target_path == plan.tasks[2].target_path);
    for (const libcam::ImageTask& task : again.tasks) libcam::run_image_task(task, maps);
    const libcam::DatasetSummary summary = libcam::finish_dataset(again);
    CHECK(summary.finished);
    CHECK(summary.images_written == 2);
    CHECK(summary.images_kept == 2);
    CHECK_FALSE(fs::exists(out / kStaging));
    libcam::make_pinhole_dataset(options_for(dir.path(), dir / "whole"));
    CHECK(files_under(out) == files_under(dir / "whole"));
    CHECK_THROWS_WITH(libcam::finish_dataset(again),
                      (out / kStaging).string() + ": no unfinished dataset here (finished already, or never planned)");
}

TEST_CASE("dataset staging: a move that fails while finishing leaves no model in the output, and the same run again finishes, "
          "keeping the images already moved", "[dataset][staging]") {
    TempDir dir;
    write_scene(dir.path());
    const fs::path out = dir / "out";
    libcam::DatasetOptions earlier = options_for(dir.path(), out);
    earlier.interpolation = libcam::Interpolation::Nearest;
    REQUIRE(libcam::make_pinhole_dataset(earlier).finished);

    const libcam::DatasetPlan plan = libcam::plan_dataset(options_for(dir.path(), out));
    REQUIRE(plan.tasks.size() == 4);  // the earlier run's images are of other cameras' maps
    libcam::MapCache maps;
    for (const libcam::ImageTask& task : plan.tasks) libcam::run_image_task(task, maps);
    // A folder where the third image goes: its move fails after the first two.
    fs::remove(out / "images" / "sub" / "c.png");
    fs::create_directories(out / "images" / "sub" / "c.png" / "in-the-way");
    CHECK_THROWS_WITH(libcam::finish_dataset(plan),
                      Catch::StartsWith((out / "images" / "sub" / "c.png").string() + ": cannot move it into place from " +
                                        (out / kStaging / "images" / "sub" / "c.png").string()) &&
                          Catch::EndsWith("; the run's work is kept in " + (out / kStaging).string() +
                                          ", and the same run started again finishes it"));
    // No model and no stamp claim the images now in the output.
    CHECK_FALSE(fs::exists(out / "sparse" / "0" / "images.bin"));
    CHECK_FALSE(fs::exists(out / ".libcam-dataset"));

    fs::remove_all(out / "images" / "sub" / "c.png");
    const libcam::DatasetPlan again = libcam::plan_dataset(options_for(dir.path(), out));
    CHECK(again.tasks.empty());
    CHECK(again.summary.images_kept == 4);
    CHECK(libcam::finish_dataset(again).finished);
    libcam::make_pinhole_dataset(options_for(dir.path(), dir / "whole"));
    CHECK(files_under(out) == files_under(dir / "whole"));
}
