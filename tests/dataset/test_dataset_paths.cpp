// `libcam dataset` never reads or writes outside its folders: an image name from a file that
// leads out of the images folder (absolute, through "..") is refused before anything is
// written, naming the model file, the image, the field and the value; an output folder
// whose subfolders are symbolic links leading out of it is refused; an image task line made
// by hand cannot write outside a plan's staging folder.

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "cli_runner.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/dataset/dataset_tasks.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::CliResult;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using libcam::test::write_whole_file;

const std::string kCameras = "1 OPENCV 24 18 22 21 11.5 8.5 -0.1 0.01 0 0\n";

cv::Mat small_picture(int seed) {
    cv::Mat image(18, 24, CV_8UC3);
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(x * 9 + seed), uchar(y * 13), 90);
    }
    return image;
}

// A text model of one OPENCV camera, one image per name.
void write_text_model(const fs::path& folder, const std::vector<std::string>& names) {
    fs::create_directories(folder);
    std::string images;
    for (std::size_t i = 0; i < names.size(); ++i) images += std::to_string(i + 1) + " 1 0 0 0 0 0 0 1 " + names[i] + "\n\n";
    write_whole_file(folder / "cameras.txt", kCameras);
    write_whole_file(folder / "images.txt", images);
    write_whole_file(folder / "points3D.txt", "");
}

// The same as COLMAP's binary files, written by libcam's writer (which takes any name).
void write_binary_model(const fs::path& folder, const std::vector<std::string>& names) {
    fs::create_directories(folder);
    libcam::Camera camera;
    camera.size = {24, 18};
    camera.intrinsics = {22, 21, 11.5, 8.5, 0};
    std::vector<libcam::ColmapImage> images;
    for (std::size_t i = 0; i < names.size(); ++i) images.push_back({i + 1, 1, names[i], libcam::Pose{}, {}, ""});
    const libcam::ColmapModelBytes bytes = libcam::write_colmap_files({{1, camera, "PINHOLE"}}, images, {}, true);
    write_whole_file(folder / "cameras.bin", bytes.cameras);
    write_whole_file(folder / "images.bin", bytes.images);
    write_whole_file(folder / "points3D.bin", bytes.points3d);
}

CliResult dataset(const TempDir& dir, const fs::path& model, const fs::path& out, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"dataset", model.string(), "--images", (dir / "images").string(), "-o", out.string()};
    args.insert(args.end(), more.begin(), more.end());
    return run_libcam(args);
}

std::map<std::string, std::string> files_under(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (!entry.is_directory()) files[fs::relative(entry.path(), folder).string()] = libcam::test::read_whole_file(entry.path());
    }
    return files;
}

}  // namespace

TEST_CASE("dataset paths: a NAME leading out of the images folder is refused naming the file, the image and the value, "
          "before anything is written", "[dataset][paths]") {
    TempDir dir;
    fs::create_directories(dir / "deep" / "images");
    REQUIRE(cv::imwrite((dir / "deep" / "images" / "good.png").string(), small_picture(1)));
    // Where each name would lead, a file that must stay as it is.
    const fs::path above = dir / "deep" / "x.png", absolute = dir / "abs" / "x.png";
    fs::create_directories(absolute.parent_path());
    REQUIRE(cv::imwrite(above.string(), small_picture(2)));
    REQUIRE(cv::imwrite(absolute.string(), small_picture(3)));
    const std::string above_bytes = libcam::test::read_whole_file(above);
    const std::string absolute_bytes = libcam::test::read_whole_file(absolute);
    const std::string rule = "; libcam dataset reads and writes each image under its name, relative to the images folder\n";
    const std::map<std::string, std::string> refused = {
        {"../x.png", "'../x.png' leads out of the images folder through '..'" + rule},
        {"sub/../../x.png", "'sub/../../x.png' leads out of the images folder through '..'" + rule},
        {"..", "'..' leads out of the images folder through '..'" + rule},
        {absolute.string(), "'" + absolute.string() + "' is an absolute path" + rule},
        {"sub/..", "'sub/..' names a folder, not an image file\n"},
    };
    for (const auto& [name, why] : refused) {
        INFO(name);
        const fs::path model = dir / ("model" + std::to_string(name.size()));
        write_text_model(model, {"good.png", name});
        const fs::path out = dir / "deep" / "out";
        const CliResult result = run_libcam({"dataset", model.string(), "--images", (dir / "deep" / "images").string(),
                                             "-o", out.string()});
        INFO(result.describe());
        CHECK(result.exit_code == 1);
        CHECK(result.err == "libcam: error: " + (model / "images.txt").string() + ": line 3: image 2: NAME: " + why);
        CHECK(result.out.empty());
        CHECK_FALSE(fs::exists(out));
    }
    CHECK(libcam::test::read_whole_file(above) == above_bytes);
    CHECK(libcam::test::read_whole_file(absolute) == absolute_bytes);
}

TEST_CASE("dataset paths: images.bin's names are held to the same rule, control characters shown as \\xNN", "[dataset][paths]") {
    TempDir dir;
    const auto error_of = [&](const std::string& name) {
        write_binary_model(dir / "model", {"a.png", name});
        const CliResult result = run_libcam({"dataset", (dir / "model").string(), "-o", (dir / "out").string(), "--no-images"});
        INFO(result.describe());
        CHECK(result.exit_code == 1);
        CHECK_FALSE(fs::exists(dir / "out"));
        return result.err;
    };
    // images.bin: the image count (8 bytes), then image 1: id, pose, camera, "a.png\0", no points.
    const std::string second = (dir / "model" / "images.bin").string() + ": byte " + std::to_string(8 + 4 + 56 + 4 + 6 + 8) +
                               ": image 2: NAME: ";
    CHECK(error_of("/etc/x.png") == "libcam: error: " + second + "'/etc/x.png' is an absolute path; libcam dataset reads "
                                                             "and writes each image under its name, relative to the images folder\n");
    CHECK(error_of("a\nb.png") == "libcam: error: " + second +
                                      "'a\\x0ab.png' holds a control character (\\x0a): not a file name libcam dataset writes\n");
    CHECK(error_of("") == "libcam: error: " + second + "missing or empty\n");
    CHECK(error_of("caf\xe9/") == "libcam: error: " + second + "'caf\\xe9/' names a folder, not an image file\n");
    // A name as long as a hostile file makes it: its start shown.
    CHECK(error_of("/" + std::string(5000, 'x')) == "libcam: error: " + second + "'/" + std::string(199, 'x') +
                                                         "... (5001 bytes)' is an absolute path; libcam dataset reads "
                                                         "and writes each image under its name, relative to the images folder\n");
}

TEST_CASE("dataset paths: names inside the images folder are kept, made plain, and two images of one name are refused",
          "[dataset][paths]") {
    TempDir dir;
    const std::vector<std::string> names = {"sub/dir/a.png", "a..b.png", "./c.png", "d/./e.png"};
    const std::vector<std::string> plain = {"sub/dir/a.png", "a..b.png", "c.png", "d/e.png"};
    write_text_model(dir / "model", names);
    for (std::size_t i = 0; i < plain.size(); ++i) {
        fs::create_directories((dir / "images" / plain[i]).parent_path());
        REQUIRE(cv::imwrite((dir / "images" / plain[i]).string(), small_picture(static_cast<int>(i))));
    }
    const CliResult result = dataset(dir, dir / "model", dir / "out", {"--text"});
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    for (const std::string& name : plain) CHECK(fs::is_regular_file(dir / "out" / "images" / name));
    const std::string images_txt = libcam::test::read_whole_file(dir / "out" / "sparse" / "0" / "images.txt");
    for (const std::string& name : plain) CHECK(images_txt.find(" 1 " + name + "\n") != std::string::npos);
    CHECK(images_txt.find("./") == std::string::npos);

    const auto error_of = [&](const std::vector<std::string>& model_names) {
        write_text_model(dir / "twice", model_names);
        const CliResult refused = dataset(dir, dir / "twice", dir / "out2");
        CHECK(refused.exit_code == 1);
        CHECK_FALSE(fs::exists(dir / "out2"));
        return refused.err;
    };
    const std::string where = (dir / "twice" / "images.txt").string();
    CHECK(error_of({"c.png", "./c.png"}) == "libcam: error: " + where + ": line 3: image 2: NAME: 'c.png' is also the name of " +
                                                where + ": line 1: image 1; the output keeps one image per name\n");
    CHECK(error_of({"d", "d/e.png"}) == "libcam: error: " + where + ": line 3: image 2: NAME: 'd/e.png' makes a folder of " +
                                            where + ": line 1: image 1's name 'd'; an image cannot be a folder too\n");
}

TEST_CASE("dataset paths: an output whose images folder, or a folder in it, is a symbolic link leading out is refused",
          "[dataset][paths]") {
    TempDir dir;
    write_text_model(dir / "model", {"a.png", "sub/b.png"});
    fs::create_directories(dir / "images" / "sub");
    REQUIRE(cv::imwrite((dir / "images" / "a.png").string(), small_picture(1)));
    REQUIRE(cv::imwrite((dir / "images" / "sub" / "b.png").string(), small_picture(2)));
    fs::create_directories(dir / "elsewhere");
    const auto refused = [&](const fs::path& out, const std::string& why) {
        const auto before = files_under(out);
        const CliResult result = dataset(dir, dir / "model", out);
        INFO(result.describe());
        CHECK(result.exit_code == 1);
        CHECK(result.err == "libcam: error: " + why + "\n");
        CHECK(files_under(out) == before);
        CHECK(fs::is_empty(dir / "elsewhere"));
    };
    const std::string rule = ": libcam dataset writes only inside its output folder ";
    const fs::path elsewhere = fs::canonical(dir / "elsewhere");

    fs::create_directories(dir / "out1");
    fs::create_directory_symlink(dir / "elsewhere", dir / "out1" / "images");
    refused(dir / "out1", (dir / "out1" / "images").string() + ": a symbolic link leading out of the output folder (to " +
                              elsewhere.string() + ")" + rule + (dir / "out1").string());

    fs::create_directories(dir / "out2" / "images");
    fs::create_directory_symlink(dir / "elsewhere", dir / "out2" / "images" / "sub");
    refused(dir / "out2", (dir / "out2" / "images" / "sub").string() + ": a symbolic link leading out of the output folder (to " +
                              elsewhere.string() + ")" + rule + (dir / "out2").string());

    fs::create_directories(dir / "out3");
    fs::create_directory_symlink(dir / "elsewhere", dir / "out3" / ".libcam-dataset-partial");
    refused(dir / "out3", (dir / "out3" / ".libcam-dataset-partial").string() +
                              ": a symbolic link, where libcam dataset keeps a run's unfinished work: remove it");

    fs::create_directories(dir / "out4");
    fs::create_directory_symlink(dir / "nowhere", dir / "out4" / "masks");
    const CliResult masks = dataset(dir, dir / "model", dir / "out4", {"--masks"});
    CHECK(masks.err == "libcam: error: " + (dir / "out4" / "masks").string() + ": a symbolic link to nothing" + rule +
                           (dir / "out4").string() + "\n");
    CHECK_FALSE(fs::exists(dir / "nowhere"));

    // A link to another folder inside the output is followed.
    fs::create_directories(dir / "out5" / "kept");
    fs::create_directory_symlink(dir / "out5" / "kept", dir / "out5" / "images");
    const CliResult inside = dataset(dir, dir / "model", dir / "out5");
    INFO(inside.describe());
    CHECK(inside.exit_code == 0);
    CHECK(fs::is_regular_file(dir / "out5" / "kept" / "sub" / "b.png"));
}

TEST_CASE("dataset paths: a task line made by hand writes nothing outside a plan's staging folder", "[dataset][paths][tasks]") {
    TempDir dir;
    write_text_model(dir / "model", {"a.png", "sub/b.png"});
    fs::create_directories(dir / "images" / "sub");
    REQUIRE(cv::imwrite((dir / "images" / "a.png").string(), small_picture(1)));
    REQUIRE(cv::imwrite((dir / "images" / "sub" / "b.png").string(), small_picture(2)));
    libcam::DatasetOptions options;
    options.model = dir / "model";
    options.images = dir / "images";
    options.output = dir / "out";
    options.masks = true;
    const libcam::DatasetPlan plan = libcam::plan_dataset(options);
    REQUIRE(plan.tasks.size() == 2);
    const libcam::ImageTask& task = plan.tasks[1];
    CHECK(task.target_path == dir / "out" / ".libcam-dataset-partial" / "images" / "sub" / "b.png");
    libcam::MapCache maps;
    const auto refused = [&](libcam::ImageTask crafted, const std::string& expected) {
        const std::string line = libcam::image_task_json(crafted);
        try {
            libcam::run_image_task(libcam::image_task_from_json(line), maps);
            FAIL("ran: " << line);
        } catch (const libcam::FileError& error) {
            CHECK(std::string(error.what()).find(expected) != std::string::npos);
            INFO(error.what());
        }
    };
    libcam::ImageTask crafted = task;
    crafted.target_path = dir / "evil.png";
    refused(crafted, "target_path: not in a staging folder a plan made");
    crafted.target_path = dir / "out" / ".libcam-dataset-partial" / "images" / ".." / ".." / ".." / "evil.png";
    refused(crafted, "leads out of the staging folder's images/ through '..'");
    crafted.target_path = dir / "out" / ".libcam-dataset-partial" / "sparse" / "0" / "images.bin";
    refused(crafted, "target_path: not a plain name under images/");
    crafted = task;
    crafted.mask_path = dir / "evil.png";
    refused(crafted, "mask_path: not " + (dir / "out" / ".libcam-dataset-partial" / "masks" / "sub" / "b.png.png").string());
    // A staging folder no plan made (no stamp in it).
    fs::create_directories(dir / "fake" / ".libcam-dataset-partial");
    crafted = task;
    crafted.target_path = dir / "fake" / ".libcam-dataset-partial" / "images" / "evil.png";
    crafted.mask_path.clear();
    refused(crafted, "target_path: not in a staging folder a plan made");
    // A folder in the staging folder replaced by a link leading out of it.
    fs::create_directories(dir / "elsewhere");
    fs::create_directories(dir / "out" / ".libcam-dataset-partial" / "images");
    fs::create_directory_symlink(dir / "elsewhere", dir / "out" / ".libcam-dataset-partial" / "images" / "sub");
    refused(task, (dir / "out" / ".libcam-dataset-partial" / "images" / "sub").string() +
                      ": a symbolic link leading out of the output folder");
    CHECK_FALSE(fs::exists(dir / "evil.png"));
    CHECK(fs::is_empty(dir / "elsewhere"));
    CHECK(fs::is_empty(dir / "fake" / ".libcam-dataset-partial"));
    // The plan's own task runs.
    libcam::run_image_task(plan.tasks[0], maps);
    CHECK(fs::is_regular_file(dir / "out" / ".libcam-dataset-partial" / "images" / "a.png"));
}
