// libcam bench: the speed/accuracy trade of every unprojection and projection method of
// libcam, OpenCV and mrcal, measured on the same pixels in one run (libcam/check/bench.hpp),
// printed as a table, as JSON, and drawn as time against worst error
// (libcam/report/bench_plot.hpp).

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench_cases.hpp"
#include "camera_options.hpp"
#include "commands.hpp"
#include "json_output.hpp"
#include "libcam/camera/simd.hpp"
#include "libcam/check/bench.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/report/bench_plot.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

struct BenchFlags {
    std::string from;
    FileSelection selection;
    std::vector<std::string> cases;
    std::string grid = "601x401";
    int repeat = 5;
    std::string threads = "1,2";
    std::string simd = "all";
    std::string clock = "wall";
    bool full_frame = false;
    bool maps = false;
    bool json = false;
    std::string json_file;
    std::string plot;
};

constexpr int kMinRepeat = 5;

// "mild, strong or wide": the built-in cases' names, the last after `last_separator`.
std::string case_names(const std::vector<BenchCase>& cases, const std::string& last_separator) {
    std::string names;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        names += (i == 0 ? "" : i + 1 == cases.size() ? last_separator : ", ") + cases[i].name;
    }
    return names;
}

std::vector<BenchCase> chosen_cases(const BenchFlags& flags) {
    if (!flags.from.empty()) return {{flags.from, flags.selection.read(flags.from).camera}};
    std::vector<BenchCase> all = builtin_bench_cases();
    if (flags.cases.empty()) return flags.maps ? map_bench_cases() : all;
    for (const BenchCase& map_case : map_bench_cases()) {
        const bool listed = std::any_of(all.begin(), all.end(), [&](const BenchCase& c) { return c.name == map_case.name; });
        if (!listed) all.push_back(map_case);
    }
    std::vector<BenchCase> chosen;
    for (const std::string& name : flags.cases) {
        const auto found = std::find_if(all.begin(), all.end(), [&](const BenchCase& c) { return c.name == name; });
        if (found == all.end()) throw UsageError("--case: expected " + case_names(all, " or ") + ", got '" + name + "'");
        chosen.push_back(*found);
    }
    return chosen;
}

// "all": every instruction set this CPU runs; "best": the one in use; or a list of names.
std::vector<SimdTarget> simd_targets_from(const std::string& text) {
    if (text == "all") return supported_simd_targets();
    if (text == "best") return {};
    std::vector<SimdTarget> targets;
    std::istringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        const std::optional<SimdTarget> target = simd_target_from_name(item);
        if (!target) throw UsageError("--simd: expected all, best or a list of sse2, avx2, avx512, got '" + text + "'");
        if (!simd_target_supported(*target)) {
            throw UsageError("--simd: " + item + " is not compiled into this build or not run by this CPU");
        }
        targets.push_back(*target);
    }
    if (targets.empty()) throw UsageError("--simd: expected all, best or a list such as sse2,avx2");
    return targets;
}

BenchSettings settings_from(const BenchFlags& flags) {
    BenchSettings settings;
    const ImageSize grid = parse_size("--grid", flags.grid);
    if (grid.width < 2 || grid.height < 2) throw UsageError("--grid: needs at least 2x2 pixels (the corners), got '" + flags.grid + "'");
    settings.grid_x = static_cast<int>(grid.width);
    settings.grid_y = static_cast<int>(grid.height);
    if (flags.repeat < kMinRepeat) throw UsageError("--repeat: at least " + std::to_string(kMinRepeat) + ", got " + std::to_string(flags.repeat));
    settings.repeat = flags.repeat;
    settings.threads.clear();
    std::istringstream list(flags.threads);
    for (std::string item; std::getline(list, item, ',');) {
        const double count = parse_number("--threads", item);
        if (count < 1 || count > 256 || count != static_cast<int>(count)) {
            throw UsageError("--threads: expected whole numbers in [1, 256], got '" + flags.threads + "'");
        }
        settings.threads.push_back(static_cast<int>(count));
    }
    if (settings.threads.empty()) throw UsageError("--threads: expected a list such as 1,2");
    settings.simd_targets = simd_targets_from(flags.simd);
    if (flags.clock != "wall" && flags.clock != "cpu") throw UsageError("--clock: expected wall or cpu, got '" + flags.clock + "'");
    settings.clock = flags.clock == "cpu" ? BenchClock::ThreadCpu : BenchClock::Wall;
    const bool one_thread = settings.threads == std::vector<int>(settings.threads.size(), 1);
    if (settings.clock == BenchClock::ThreadCpu && !one_thread) {
        throw UsageError("--clock cpu: a thread's CPU time measures one-thread rows only: add --threads 1, got '" +
                         flags.threads + "'");
    }
    settings.full_frame = flags.full_frame;
    settings.maps = flags.maps;
    return settings;
}

nlohmann::json row_json(const BenchRow& row) {
    nlohmann::json out;
    out["op"] = row.op;
    out["library"] = row.library;
    out["method"] = row.method;
    out["scalar"] = row.scalar;
    out["model"] = row.model;
    out["camera"] = row.camera;
    out["threads"] = row.threads;
    out["simd"] = row.simd;
    out["ns_per_point"] = finite_or_null<nlohmann::json>(row.ns_per_point);
    const bool measured = row.error && row.error->count > 0;
    put_error_stats(out, measured ? *row.error : ErrorStats{}, measured, {"median_px", "p99_px", "max_px"});
    out["invalid_fraction"] = finite_or_null<nlohmann::json>(row.invalid_fraction);
    if (row.op == "map") {
        out["ratio_to_opencv"] = finite_or_null<nlohmann::json>(row.ratio);
        out["max_from_exact_px"] = finite_or_null<nlohmann::json>(row.max_from_exact_px.value_or(std::numeric_limits<double>::quiet_NaN()));
        out["defined_differently"] = row.defined_differently;
    }
    return out;
}

struct CaseResult {
    BenchCase bench_case;
    BenchResult result;
};

std::string format_json(const std::vector<CaseResult>& results, const BenchSettings& settings) {
    nlohmann::json out;
    out["clock"] = settings.clock == BenchClock::ThreadCpu ? "cpu" : "wall";
    out["simd"] = {{"in_use", simd_target_name(simd_target())}, {"supported", nlohmann::json::array()}};
    for (SimdTarget target : supported_simd_targets()) out["simd"]["supported"].push_back(simd_target_name(target));
    out["rows"] = nlohmann::json::array();
    out["cameras"] = nlohmann::json::array();
    for (const CaseResult& r : results) {
        for (const BenchRow& row : r.result.rows) out["rows"].push_back(row_json(row));
        const Camera& camera = r.bench_case.camera;
        out["cameras"].push_back({{"camera", r.bench_case.name},
                                  {"model", lens_info(camera.lens.type).name},
                                  {"image_size", {camera.size.width, camera.size.height}},
                                  {"grid", {settings.grid_x, settings.grid_y}},
                                  {"repeat", settings.repeat},
                                  {"table_build_ms", {{"double", r.result.table_build_ms_double}, {"float", r.result.table_build_ms_float}}}});
    }
    return out.dump(2) + "\n";
}

// `digits` significant digits; "-" where there is no finite value.
std::string number_text(double value, int digits) { return std::isfinite(value) ? format_short(value, digits) : "-"; }

// A row's error statistic; "-" where nothing was measured.
std::string error_text(const BenchRow& row, double ErrorStats::*statistic) {
    return row.error && row.error->count > 0 ? number_text((*row.error).*statistic, 3) : "-";
}

// The map rows: time per target pixel, over OpenCV's undistortion map, and accuracy.
void format_map_table(std::ostream& out, const std::vector<BenchRow>& rows) {
    out << std::setw(8) << "library" << std::setw(42) << "map" << std::setw(7) << "scalar" << std::setw(8) << "threads"
        << std::setw(7) << "simd" << std::setw(11) << "ns/pixel" << std::setw(9) << "/ OpenCV" << std::setw(11) << "max px"
        << std::setw(13) << "vs exact px" << std::setw(10) << "differ" << "no source\n";
    for (const BenchRow& row : rows) {
        const std::string vs_exact = row.max_from_exact_px ? number_text(*row.max_from_exact_px, 3) : "-";
        out << std::setw(8) << row.library << std::setw(42) << row.method << std::setw(7) << row.scalar << std::setw(8)
            << row.threads << std::setw(7) << row.simd << std::setw(11) << number_text(row.ns_per_point, 4) << std::setw(9)
            << number_text(row.ratio, 3) << std::setw(11) << error_text(row, &ErrorStats::max_px) << std::setw(13) << vs_exact
            << std::setw(10) << (number_text(100 * row.defined_differently, 3) + "%")
            << number_text(100 * row.invalid_fraction, 3) << "%\n";
    }
}

// What the times are: the wall clock's, or the running thread's CPU time.
std::string clock_note(const BenchSettings& settings) {
    return settings.clock == BenchClock::ThreadCpu ? "; times: the CPU time of the thread that ran each" : "";
}

std::string format_maps(const std::vector<CaseResult>& results, const BenchSettings& settings) {
    std::ostringstream out;
    out << std::left;
    out << "batch kernels: " << simd_target_name(simd_target()) << " in use" << clock_note(settings) << "\n";
    for (const CaseResult& r : results) {
        const Camera& camera = r.bench_case.camera;
        out << "camera " << r.bench_case.name << ": " << lens_info(camera.lens.type).name << ", " << camera.size.width << "x"
            << camera.size.height << "; maps between it and a pinhole with its K and size\n";
        format_map_table(out, r.result.rows);
        out << "\n";
    }
    out << "map: exact, float: libcam's map to the pinhole (undistorting); inverse-*: the pinhole's pixels in the lens "
           "image (distorting). ns/pixel: median time per target pixel, map allocated afresh each time; / OpenCV: over "
           "initUndistortRectifyMap 32FC2 (fisheye::initUndistortRectifyMap for FISHEYE) at the same threads; max px: "
           "farthest a sampled target pixel is sent back by its map entry (unprojected exactly, projected by the "
           "target); vs exact px: farthest from libcam's exact double map where both give a source; differ: sampled "
           "pixels where one gives a source and the other not; no source: none on the source image\n";
    return out.str();
}

std::string format_table(const std::vector<CaseResult>& results, const BenchSettings& settings) {
    if (settings.maps) return format_maps(results, settings);
    std::ostringstream out;
    out << std::left;
    out << "batch kernels: " << simd_target_name(simd_target()) << " in use; this CPU runs";
    for (SimdTarget target : supported_simd_targets()) out << " " << simd_target_name(target);
    out << " (simd column: the set each libcam row ran on)" << clock_note(settings) << "\n";
    for (const CaseResult& r : results) {
        const Camera& camera = r.bench_case.camera;
        out << "camera " << r.bench_case.name << ": " << lens_info(camera.lens.type).name << ", " << camera.size.width << "x"
            << camera.size.height << ", grid " << settings.grid_x << "x" << settings.grid_y << ", median of "
            << settings.repeat << " interleaved runs; libcam table built in " << number_text(r.result.table_build_ms_double, 3)
            << " ms (double), " << number_text(r.result.table_build_ms_float, 3) << " ms (float)\n";
        // The model column fits the longest name (RAD_TAN_THIN_PRISM_FISHEYE) and a space.
        // The method column fits the longest (OpenCV's map functions), and a space.
        int model_width = 15, method_width = 23;
        for (const BenchRow& row : r.result.rows) {
            model_width = std::max(model_width, static_cast<int>(row.model.size()) + 2);
            method_width = std::max(method_width, static_cast<int>(row.method.size()) + 2);
        }
        out << std::setw(16) << "op" << std::setw(8) << "library" << std::setw(method_width) << "method" << std::setw(7) << "scalar"
            << std::setw(8) << "threads" << std::setw(7) << "simd" << std::setw(model_width) << "model" << std::setw(11) << "ns/point" << std::setw(11)
            << "median px" << std::setw(11) << "p99 px" << std::setw(11) << "max px"
            << "invalid\n";
        for (const BenchRow& row : r.result.rows) {
            out << std::setw(16) << row.op << std::setw(8) << row.library << std::setw(method_width) << row.method << std::setw(7)
                << row.scalar << std::setw(8) << row.threads << std::setw(7) << row.simd << std::setw(model_width) << row.model << std::setw(11)
                << number_text(row.ns_per_point, 4) << std::setw(11) << error_text(row, &ErrorStats::median_px)
                << std::setw(11) << error_text(row, &ErrorStats::p99_px) << std::setw(11)
                << error_text(row, &ErrorStats::max_px) << number_text(100 * row.invalid_fraction, 3) << "%\n";
        }
        out << "\n";
    }
    out << "error: distance in px from the pixel to the projection of the result by libcam (checked against OpenCV "
           "and mrcal in the tests); invalid: flagged, not finite, or a ray outside the lens's domain\n";
    return out.str();
}

}  // namespace

Runner add_bench(CLI::App& app) {
    CLI::App* command = add_command(app, "bench");
    auto flags = std::make_shared<BenchFlags>();
    command->add_option("--from", flags->from, "Camera file to measure (default: the built-in cases)");
    flags->selection.add_to(*command);
    command->add_option("--case", flags->cases,
                        "Built-in cases to run: " + case_names(builtin_bench_cases(), ", ") + " (default: all)")
        ->excludes("--from");
    command->add_option("--grid", flags->grid, "Pixels across x down, corners included (default 601x401)");
    command->add_option("--repeat", flags->repeat, "Timed repetitions per method, interleaved (default and minimum 5)");
    command->add_option("--threads", flags->threads, "Thread counts for libcam's batch paths (default 1,2)");
    command->add_option("--simd", flags->simd,
                        "Instruction sets libcam's one-thread batch rows run on, each forced in turn: all (every set "
                        "this CPU runs, default), best (the one in use), or a list such as sse2,avx2");
    command->add_option("--clock", flags->clock,
                        "How each repetition is timed: wall (the wall clock, default) or cpu (the CPU time of the "
                        "thread that runs it, which other programs on a busy machine do not lengthen; with --threads 1)");
    command->add_flag("--full-frame", flags->full_frame,
                      "Also time every pixel's ray for the lens and for a pinhole with the same K, against memset");
    command->add_flag("--maps", flags->maps,
                      "Instead, time building the remap maps between the lens and a pinhole with the same K and size, "
                      "in double and float: undistorting (exact) and distorting (inverse-exact, inverse-fast), against "
                      "OpenCV's maps (default cases: hd, wide, fisheye)");
    command->add_flag("--json", flags->json, "Print JSON: {\"rows\": [...], \"cameras\": [...]}");
    command->add_option("--save-json", flags->json_file, "Also write the JSON to this file (the table still goes to stdout)");
    command->add_option("--plot", flags->plot, "Write a PNG: time per point against worst error, per camera");

    return [flags] {
        const BenchSettings settings = settings_from(*flags);
        const std::vector<BenchCase> cases = chosen_cases(*flags);
        std::vector<CaseResult> results;
        for (const BenchCase& bench_case : cases) {
            results.push_back({bench_case, run_bench(bench_case.name, bench_case.camera, settings)});
        }
        if (!flags->plot.empty()) {
            std::vector<BenchRow> rows;
            for (const CaseResult& r : results) rows.insert(rows.end(), r.result.rows.begin(), r.result.rows.end());
            write_png(flags->plot, plot_speed_accuracy(rows));
        }
        if (!flags->json_file.empty()) write_file_atomically(flags->json_file, format_json(results, settings));
        emit(flags->json ? format_json(results, settings) : format_table(results, settings), "");
        return 0;
    };
}

}  // namespace libcam::cli
