// `libcam bench`, run as a user runs it, on a tiny grid (seconds, not minutes): valid
// JSON with the documented keys, a row for every method and library, a PNG, and usage
// errors. Times are printed, never asserted.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include "cli_runner.hpp"
#include "libcam/camera/simd.hpp"

using namespace libcam;
using namespace libcam::test;
using nlohmann::json;

namespace {

const std::vector<std::string> kRowKeys = {"op",        "library",   "method", "scalar", "model",  "threads",
                                           "simd",      "ns_per_point", "median_px", "p99_px", "max_px", "invalid_fraction"};

json bench_json(const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"bench", "--grid", "9x7", "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return json::parse(result.out);
}

// "op library method scalar" of every row.
std::set<std::string> row_names(const json& out) {
    std::set<std::string> names;
    for (const json& row : out["rows"]) {
        names.insert(row["op"].get<std::string>() + " " + row["library"].get<std::string>() + " " +
                     row["method"].get<std::string>() + " " + row["scalar"].get<std::string>());
    }
    return names;
}

}  // namespace

TEST_CASE("bench --json: every row has the documented keys, and every method and library has a row") {
    const json out = bench_json({"--case", "mild"});
    REQUIRE(out.contains("rows"));
    REQUIRE(out["rows"].is_array());
    for (const json& row : out["rows"]) {
        for (const std::string& key : kRowKeys) {
            INFO(row.dump() << " key " << key);
            CHECK(row.contains(key));
        }
        CHECK(row["ns_per_point"].is_number());
        CHECK(row["ns_per_point"].get<double>() > 0);
        CHECK(row["model"] == "OPENCV8");
        CHECK(row["max_px"].is_number());
    }
    const std::set<std::string> names = row_names(out);
    for (const char* expected : {"unproject libcam exact double", "unproject libcam fast double", "unproject libcam lut double",
                                 "unproject libcam exact float", "unproject libcam fast float", "unproject libcam lut float",
                                 "unproject opencv default double", "unproject opencv 100it-eps1e-14 double",
                                 "unproject mrcal mrcal_unproject double", "project libcam batch double",
                                 "project libcam batch float", "project libcam interleaved double",
                                 "project opencv projectPoints double",
                                 "project mrcal mrcal_project double", "unproject libcam camera double",
                                 "project libcam camera double"}) {
        INFO(expected);
        CHECK(names.count(expected) == 1);
    }
    // The public call (PreparedCamera) is the exact method: the same worst error.
    const auto max_of = [&](const std::string& method) {
        for (const json& row : out["rows"]) {
            if (row["op"] == "unproject" && row["library"] == "libcam" && row["method"] == method && row["scalar"] == "double") {
                return row["max_px"].get<double>();
            }
        }
        return -1.0;
    };
    CHECK(max_of("camera") == max_of("exact"));
    CHECK(max_of("camera") <= 1e-9);
}

TEST_CASE("bench on a FISHEYE lens: OpenCV's fisheye functions, no mrcal rows (mrcal lacks the model)") {
    const json out = bench_json({"--case", "fisheye", "--threads", "1"});
    const std::set<std::string> names = row_names(out);
    CHECK(names.count("unproject opencv default double") == 1);
    CHECK(names.count("project opencv fisheye::projectPoints double") == 1);
    for (const std::string& name : names) CHECK(name.find("mrcal") == std::string::npos);
}

TEST_CASE("bench --plot writes a PNG and --save-json the JSON beside the table, for a camera read with --from") {
    TempDir dir;
    const std::string camera = (dir / "camera.yaml").string();
    REQUIRE(run_libcam({"convert", "--fov", "70", "--size", "64x48", "--to", "opencv-yaml", "-o", camera}).exit_code == 0);
    const std::string png = (dir / "speed.png").string(), saved = (dir / "speed.json").string();
    const CliResult result =
        run_libcam({"bench", "--from", camera, "--grid", "5x4", "--threads", "1", "--plot", png, "--save-json", saved});
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    CHECK(result.out.find("ns/point") != std::string::npos);
    const std::string bytes = read_whole_file(png);
    REQUIRE(bytes.size() > 8);
    CHECK(bytes.substr(1, 3) == "PNG");
    const json out = json::parse(read_whole_file(saved));
    CHECK(out["rows"].size() > 5);
    CHECK(out["rows"][0]["model"] == "PINHOLE");
}

TEST_CASE("bench --maps: libcam's maps both ways in double and float, and OpenCV's for the lenses it has them for") {
    TempDir dir;
    const auto camera_file = [&](const std::string& name, const std::string& distortion) {
        const std::string path = (dir / name).string();
        write_whole_file(path, "%YAML:1.0\nimage_width: 160\nimage_height: 120\ncamera_matrix: !!opencv-matrix\n"
                               "  rows: 3\n  cols: 3\n  dt: d\n  data: [100, 0, 79.5, 0, 100, 59.5, 0, 0, 1]\n" +
                                   distortion);
        return path;
    };
    const std::string radial = camera_file(
        "radial.yaml", "distortion_coefficients: !!opencv-matrix\n  rows: 1\n  cols: 5\n  dt: d\n"
                       "  data: [-0.3, 0.1, 0.001, -0.0005, 0.0]\n");
    const std::string fisheye = camera_file(
        "fisheye.yaml", "distortion_model: fisheye\ndistortion_coefficients: !!opencv-matrix\n  rows: 4\n  cols: 1\n"
                        "  dt: d\n  data: [0.05, -0.01, 0.002, -0.0003]\n");
    for (const auto& [path, opencv_maps] :
         {std::pair{radial, std::vector<std::string>{"initUndistortRectifyMap 32FC2", "initUndistortRectifyMap 32F x2",
                                                     "initInverseRectificationMap 32FC2"}},
          std::pair{fisheye, std::vector<std::string>{"fisheye::initUndistortRectifyMap 32F x2"}}}) {
        INFO(path);
        const json out = bench_json({"--from", path, "--maps", "--threads", "1,2"});
        std::set<std::string> maps;
        for (const json& row : out["rows"]) {
            REQUIRE(row["op"] == "map");  // --maps: the map rows alone
            const std::string method = row["method"].get<std::string>();
            maps.insert(row["library"].get<std::string>() + " " + method + " " + row["scalar"].get<std::string>() + " " +
                        std::to_string(row["threads"].get<int>()));
            CHECK(row["ns_per_point"].get<double>() > 0);
            CHECK(row["ratio_to_opencv"].get<double>() > 0);
            if (row["library"] == "libcam") {
                INFO(method << " " << row["scalar"]);
                const bool in_float = row["scalar"] == "float";
                // Each map entry sent back through the target lands on its pixel: exact to
                // rounding (a float's, 160 px wide: 1e-5 px), fast within its documented 0.01 px.
                CHECK(row["max_px"].get<double>() <= (method.ends_with("fast") ? 0.01 : in_float ? 1e-4 : 1e-9));
                // The same pixels without a source as the exact double map, and its values:
                // the same bits in double, rounded once in float.
                CHECK(row["defined_differently"].get<double>() == 0);
                const double from_exact = row["max_from_exact_px"].get<double>();
                if (method.ends_with("fast")) CHECK(from_exact <= 0.01);
                else CHECK(from_exact <= (in_float ? 2e-5 : 0.0));
            }
        }
        std::set<std::string> expected;
        for (const char* threads : {"1", "2"}) {
            for (const char* scalar : {" double ", " float "}) {
                for (const char* method : {"exact", "inverse-exact", "inverse-fast"}) {
                    expected.insert(std::string("libcam ") + method + scalar + threads);
                }
            }
            for (const std::string& method : opencv_maps) expected.insert("opencv " + method + " float " + threads);
        }
        CHECK(maps == expected);
    }
}

TEST_CASE("bench --clock cpu: the same rows timed by the thread's CPU time, said in the JSON, wall by default") {
    const json cpu = bench_json({"--case", "mild", "--threads", "1", "--simd", "best", "--clock", "cpu"});
    CHECK(cpu["clock"] == "cpu");
    const json wall = bench_json({"--case", "mild", "--threads", "1", "--simd", "best"});
    CHECK(wall["clock"] == "wall");
    CHECK(row_names(cpu) == row_names(wall));
    for (const json& row : cpu["rows"]) {
        INFO(row.dump());
        CHECK(row["threads"] == 1);
        CHECK(row["ns_per_point"].get<double>() >= 0);
    }
}

TEST_CASE("bench usage errors exit 2 with one line on stderr and nothing on stdout") {
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"bench", "--repeat", "2"},
             {"bench", "--grid", "1x5"},
             {"bench", "--case", "nonesuch"},
             {"bench", "--threads", "0"},
             {"bench", "--simd", "avx9"},
             {"bench", "--simd", ""},
             {"bench", "--clock", "sundial"},
             {"bench", "--clock", "cpu"},  // its default threads, 1,2
         }) {
        const CliResult result = run_libcam(args);
        INFO(result.describe());
        CHECK(result.exit_code == 2);
        CHECK(result.out.empty());
        CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    }
}

TEST_CASE("bench --simd all: libcam's one-thread batch rows once per instruction set this CPU runs, the same errors") {
    const std::vector<SimdTarget> supported = supported_simd_targets();
    const json out = bench_json({"--case", "mild", "--simd", "all", "--threads", "1,2"});
    REQUIRE(out.contains("simd"));
    CHECK(out["simd"]["supported"].size() == supported.size());
    CHECK(out["simd"]["in_use"] == std::string(simd_target_name(supported.back())));
    std::map<std::string, std::set<std::string>> sets_of;  // "op method scalar" -> the sets of its one-thread rows
    std::map<std::string, std::set<double>> worst_of;       // and their worst errors
    for (const json& row : out["rows"]) {
        if (row["library"] != "libcam" || row["method"] == "camera") continue;
        const std::string name = row["op"].get<std::string>() + " " + row["method"].get<std::string>() + " " +
                                 row["scalar"].get<std::string>();
        if (row["threads"] == 2) {
            CHECK(row["simd"] == out["simd"]["in_use"]);  // more threads: the set in use only
            continue;
        }
        sets_of[name].insert(row["simd"].get<std::string>());
        worst_of[name].insert(row["max_px"].get<double>());
    }
    // exact, fast and lut, and the projection, in double and float; the interleaved projection
    // and exact unprojection in double
    REQUIRE(sets_of.size() == 10);
    CHECK(sets_of.count("unproject interleaved-exact double") == 1);
    for (const auto& [name, sets] : sets_of) {
        INFO(name);
        CHECK(sets.size() == supported.size());
        CHECK(worst_of[name].size() == 1);  // every set gives the same bits, so the same worst error
    }
}

TEST_CASE("LIBCAM_SIMD naming no instruction set: one line naming the variable and the value, exit 1") {
    const libcam::test::ScopedEnvironment simd("LIBCAM_SIMD", "avx9");
    const CliResult result = run_libcam({"bench", "--case", "mild", "--grid", "5x5"});
    INFO(result.describe());
    CHECK(result.exit_code == 1);
    CHECK(result.out.empty());
    CHECK(result.err.rfind("libcam: error: LIBCAM_SIMD: 'avx9' is not one of sse2", 0) == 0);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
}
