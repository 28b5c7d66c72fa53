// `libcam dataset`'s images in the formats people have: a JPEG's quality asked for and
// kept across a resumed run, and a float EXR image remapped as floats.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <thread>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using Json = nlohmann::json;

// A one-image COLMAP model of an OPENCV lens, its image named `name`.
void write_model(const fs::path& folder, const std::string& name) {
    fs::create_directories(folder);
    libcam::test::write_whole_file(folder / "cameras.txt", "1 OPENCV 160 120 150 148 80.5 60.2 -0.2 0.04 0 0\n");
    libcam::test::write_whole_file(folder / "images.txt", "1 1 0 0 0 0 0 0 1 " + name + "\n\n");
    libcam::test::write_whole_file(folder / "points3D.txt", "");
}

cv::Mat texture(int type) {
    cv::Mat image(120, 160, CV_32FC3);
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) {
            const float value = 0.5f + 0.4f * std::sin(x * 0.7f) * std::cos(y * 0.55f);
            image.at<cv::Vec3f>(y, x) = cv::Vec3f(value, 1.0f - value, 0.25f + 0.01f * (x % 7));
        }
    }
    cv::Mat converted;
    image.convertTo(converted, type, type == CV_8UC3 ? 255.0 : 1.0);
    return converted;
}

std::map<std::string, std::string> files_under(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) files[fs::relative(entry.path(), folder).string()] = libcam::test::read_whole_file(entry.path());
    }
    return files;
}

std::size_t files_in(const fs::path& folder) {
    std::error_code error;
    std::size_t count = 0;
    for (auto it = fs::directory_iterator(folder, error); !error && it != fs::directory_iterator(); it.increment(error)) ++count;
    return count;
}

// Starts `libcam args...` and kills it (SIGKILL) once `folder` holds `files` entries;
// false when the run ended first.
bool kill_midway(const std::vector<std::string>& args, const fs::path& folder, std::size_t files) {
    std::vector<std::string> words = {LIBCAM_EXE};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t child = 0;
    const int spawned = posix_spawn(&child, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    REQUIRE(spawned == 0);
    int status = 0;
    while (files_in(folder) < files) {
        if (waitpid(child, &status, WNOHANG) == child) return false;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

Json run_json(const std::vector<std::string>& args) {
    const libcam::test::CliResult result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return Json::parse(result.out);
}

}  // namespace

TEST_CASE("dataset: --jpeg-quality sets the JPEG's quality, and a new quality writes the images again", "[dataset]") {
    TempDir dir;
    write_model(dir / "model", "photo.jpg");
    fs::create_directories(dir / "images");
    REQUIRE(cv::imwrite((dir / "images" / "photo.jpg").string(), texture(CV_8UC3), {cv::IMWRITE_JPEG_QUALITY, 100}));
    auto run = [&](const std::string& out, int quality) {
        return run_json({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o",
                         (dir / out).string(), "--json", "--jpeg-quality", std::to_string(quality)});
    };
    run("low", 30);
    run("high", 100);
    const auto low_bytes = fs::file_size(dir / "low" / "images" / "photo.jpg");
    const auto high_bytes = fs::file_size(dir / "high" / "images" / "photo.jpg");
    // The same image encoded by OpenCV at each quality: the sizes libcam's files must have.
    const cv::Mat written = cv::imread((dir / "high" / "images" / "photo.jpg").string());
    std::vector<unsigned char> at30;
    REQUIRE(cv::imencode(".jpg", written, at30, {cv::IMWRITE_JPEG_QUALITY, 30}));
    CHECK(low_bytes < high_bytes / 2);
    CHECK(static_cast<double>(low_bytes) == Approx(static_cast<double>(at30.size())).epsilon(0.15));

    // Run again with the same quality: kept; with another: written again.
    CHECK(run("low", 30)["images_kept"] == 1);
    const Json again = run("low", 90);
    CHECK(again["images_written"] == 1);
    CHECK(fs::file_size(dir / "low" / "images" / "photo.jpg") > low_bytes);

    const libcam::test::CliResult wrong = run_libcam({"dataset", (dir / "model").string(), "-o", (dir / "x").string(),
                                                      "--no-images", "--jpeg-quality", "0"});
    CHECK(wrong.exit_code != 0);
    CHECK(wrong.err.find("--jpeg-quality: expected 1 to 100, got 0") != std::string::npos);
}

TEST_CASE("dataset: a float EXR image is remapped as floats, its values kept in range and not rounded to 8 bits", "[dataset]") {
    TempDir dir;
    write_model(dir / "model", "radiance.exr");
    fs::create_directories(dir / "images");
    const cv::Mat source = texture(CV_32FC3);
    REQUIRE(cv::imwrite((dir / "images" / "radiance.exr").string(), source));
    run_json({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o", (dir / "out").string(),
              "--json", "--interpolation", "linear"});
    const cv::Mat result = cv::imread((dir / "out" / "images" / "radiance.exr").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(result.type() == CV_32FC3);
    // Values stay those of a blend of the source's: in its range, not rounded to 8 bits.
    double low, high;
    cv::minMaxLoc(result.reshape(1), &low, &high);
    CHECK(low >= 0.0);
    CHECK(high <= 1.0 + 1e-6);
    std::size_t fractional = 0;
    for (int y = 0; y < result.rows; ++y) {
        for (int x = 0; x < result.cols; ++x) {
            const float value = result.at<cv::Vec3f>(y, x)[0];
            fractional += std::abs(value * 255 - std::round(value * 255)) > 0.01;
        }
    }
    CHECK(fractional > static_cast<std::size_t>(result.total() / 2));
}

TEST_CASE("dataset: a run killed midway and started again gives the files of a run never stopped", "[dataset]") {
    TempDir dir;
    const int count = 40;
    fs::create_directories(dir / "model");
    fs::create_directories(dir / "images");
    std::string images;
    const cv::Mat picture = texture(CV_8UC3);
    cv::Mat large;
    cv::resize(picture, large, cv::Size(640, 480), 0, 0, cv::INTER_LINEAR);
    for (int i = 0; i < count; ++i) {
        const std::string name = "p" + std::to_string(100 + i) + ".png";
        images += std::to_string(i + 1) + " 1 0 0 0 " + std::to_string(0.1 * i) + " 0 0 1 " + name + "\n\n";
        REQUIRE(cv::imwrite((dir / "images" / name).string(), large + cv::Scalar::all(i)));
    }
    libcam::test::write_whole_file(dir / "model" / "cameras.txt", "1 OPENCV 640 480 600 590 320.5 240.2 -0.2 0.04 0 0\n");
    libcam::test::write_whole_file(dir / "model" / "images.txt", images);
    libcam::test::write_whole_file(dir / "model" / "points3D.txt", "");
    const auto args = [&](const std::string& out) {
        return std::vector<std::string>{"dataset", (dir / "model").string(), "--images", (dir / "images").string(),
                                        "-o", (dir / out).string(), "--threads", "2", "--masks", "--json"};
    };
    run_json(args("whole"));
    // The run's images go to its staging folder until every one is made.
    const fs::path staged = dir / "stopped" / ".libcam-dataset-partial" / "images";
    fs::create_directories(staged);
    const bool killed = kill_midway(args("stopped"), staged, 8);
    if (!killed) WARN("the run ended before it could be killed: the second run below has nothing to finish");
    const std::size_t before = files_in(staged);
    // Stopped in the image phase: nothing but the staging folder in the output.
    if (killed) CHECK(files_in(dir / "stopped") == 1);
    const Json again = run_json(args("stopped"));
    CHECK(again["images_kept"].get<std::size_t>() + again["images_written"].get<std::size_t>() == count);
    if (killed) CHECK(again["images_written"].get<std::size_t>() > 0);
    // The same files, byte for byte: every image and mask, the model, the stamp; none of
    // the killed run's temporary files left.
    CHECK(files_under(dir / "stopped") == files_under(dir / "whole"));
    WARN("killed with " << before << " entries in the staged images/; the second run wrote " << again["images_written"]
                        << " and kept " << again["images_kept"]);
}

TEST_CASE("dataset: a run killed while moving its files into place and started again gives the files of a run never "
          "stopped, and never shows a model without its images", "[dataset]") {
    TempDir dir;
    // Many small copied images (the camera is a pinhole, kept): a finish of hundreds of moves.
    const int count = 160;
    fs::create_directories(dir / "model");
    fs::create_directories(dir / "images");
    std::string images;
    for (int i = 0; i < count; ++i) {
        const std::string name = "p" + std::to_string(1000 + i) + ".png";
        images += std::to_string(i + 1) + " 1 0 0 0 0 0 0 1 " + name + "\n\n";
        REQUIRE(cv::imwrite((dir / "images" / name).string(), cv::Mat(6, 8, CV_8U, cv::Scalar(i % 256))));
    }
    libcam::test::write_whole_file(dir / "model" / "cameras.txt", "1 PINHOLE 8 6 7 7 4 3\n");
    libcam::test::write_whole_file(dir / "model" / "images.txt", images);
    libcam::test::write_whole_file(dir / "model" / "points3D.txt", "");
    const auto args = [&](const std::string& out) {
        return std::vector<std::string>{"dataset", (dir / "model").string(), "--images", (dir / "images").string(),
                                        "-o", (dir / out).string(), "--threads", "2", "--json"};
    };
    run_json(args("whole"));
    // Killed once 40 images are in place: the finish has begun.
    const fs::path staging = dir / "stopped" / ".libcam-dataset-partial";
    const bool killed = kill_midway(args("stopped"), dir / "stopped" / "images", 40);
    if (!killed) WARN("the run ended before it could be killed while finishing");
    const std::size_t moved = files_in(dir / "stopped" / "images");
    if (fs::exists(dir / "stopped" / "sparse" / "0" / "images.bin")) CHECK(moved == count);
    if (fs::exists(dir / "stopped" / ".libcam-dataset")) CHECK(fs::exists(dir / "stopped" / "sparse" / "0" / "images.bin"));
    const Json again = run_json(args("stopped"));
    CHECK(again["images_kept"].get<std::size_t>() + again["images_written"].get<std::size_t>() == count);
    CHECK(files_under(dir / "stopped") == files_under(dir / "whole"));
    CHECK_FALSE(fs::exists(staging));
    WARN("killed with " << moved << " of " << count << " images moved into place; the second run wrote "
                        << again["images_written"] << " and kept " << again["images_kept"]);
}

TEST_CASE("dataset: a progress line on a terminal, none in a log, unless --progress or LIBCAM_PROGRESS says otherwise", "[dataset]") {
    TempDir dir;
    write_model(dir / "model", "photo.png");
    fs::create_directories(dir / "images");
    REQUIRE(cv::imwrite((dir / "images" / "photo.png").string(), texture(CV_8UC3)));
    const std::vector<std::string> run = {"dataset", (dir / "model").string(), "--images", (dir / "images").string()};
    const auto in_a_log = [&](const std::string& out, const std::vector<std::string>& more) {
        std::vector<std::string> args = run;
        args.insert(args.end(), {"-o", (dir / out).string()});
        args.insert(args.end(), more.begin(), more.end());
        const libcam::test::CliResult result = run_libcam(args);
        INFO(result.describe());
        CHECK(result.exit_code == 0);
        return result.err;
    };
    // Not a terminal: stderr stays empty, unless always is asked for: then plain lines, the
    // last when the last image is done, and no terminal codes.
    CHECK(in_a_log("logged", {}).empty());
    const std::string always = in_a_log("always", {"--progress", "always"});
    CHECK_THAT(always, Catch::Matches("(images [0-9]+ of 1, [0-9.]+ images/s, [0-9]+ s left\n)*"
                                      "images 1 of 1, [0-9.]+ images/s, 0 s left\n"));
    {
        const libcam::test::ScopedEnvironment variable("LIBCAM_PROGRESS", "always");
        CHECK_THAT(in_a_log("from-variable", {}), Catch::StartsWith("images 1 of 1, "));
        CHECK(in_a_log("flag-wins", {"--progress", "never"}).empty());
    }
    // On a terminal (util-linux's script gives the program one): images done, rate, time left;
    // nothing with never.
    const std::string script = "/usr/bin/script";
    if (!fs::exists(script)) {
        WARN("skipped the terminal half: no " << script);
        return;
    }
    const auto on_a_terminal = [&](const std::string& out, const std::string& more) {
        std::string command = std::string(LIBCAM_EXE);
        for (const std::string& word : run) command += " " + word;
        const libcam::test::CliResult result =
            libcam::test::run_program(script, {"-qec", command + " -o " + (dir / out).string() + more, "/dev/null"});
        INFO(result.describe());
        CHECK(result.exit_code == 0);
        return result.out;
    };
    const std::string shown = on_a_terminal("shown", "");
    CHECK(shown.find("images 1 of 1, ") != std::string::npos);
    CHECK(shown.find(" images/s, ") != std::string::npos);
    CHECK(shown.find(" s left") != std::string::npos);
    CHECK(on_a_terminal("quiet", " --progress never").find("images 1 of 1") == std::string::npos);
}
