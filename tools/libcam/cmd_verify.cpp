// libcam verify FILE: checks a camera file against OpenCV and mrcal over a grid of
// pixels (libcam/check/verify.hpp) and prints one table, or JSON; --heatmap draws one
// check's error over the image. Exit 0 when every check is inside its tolerance.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera_options.hpp"
#include "commands.hpp"
#include "json_output.hpp"
#include "libcam/error.hpp"
#include "libcam/check/verify.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/report/verify_heatmap.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

std::string check_names_list() {
    std::string list;
    for (std::string_view name : verify_check_names()) list += (list.empty() ? "" : ", ") + std::string(name);
    return list;
}

VerifyOptions options_from_flags(const std::string& grid_text) {
    ImageSize grid;
    try {
        grid = parse_size("--grid", grid_text);
    } catch (const UsageError&) {
        throw UsageError("--grid: expected COLUMNSxROWS with integers, e.g. 200x150, got '" + grid_text + "'");
    }
    if (grid.width < 2 || grid.height < 2 || grid.width > kMaxVerifyGridSide || grid.height > kMaxVerifyGridSide) {
        throw UsageError("--grid: each side must be in [2, " + std::to_string(kMaxVerifyGridSide) +
                         "] (the grid runs from one edge of the image to the other), got '" + grid_text + "'");
    }
    VerifyOptions options;
    options.grid_columns = grid.width;
    options.grid_rows = grid.height;
    return options;
}

void require_check_name(const std::string& name) {
    for (std::string_view known : verify_check_names()) {
        if (known == name) return;
    }
    throw UsageError("--check: unknown check '" + name + "'; one of: " + check_names_list());
}

std::string status(const VerifyCheck& check) {
    if (check.skipped()) return "skipped";
    if (check.informational()) return "info";
    return check.pass() ? "pass" : "FAIL";
}

// ---------------------------------------------------------------------------------
// The table.

using Row = std::vector<std::string>;

Row table_row(const VerifyCheck& check) {
    const bool measured = !check.skipped() && check.stats.count > 0;
    auto stat = [&](double value) { return measured ? format_short(value) : std::string("-"); };
    return {check.name,
            check.library,
            stat(check.stats.median_px),
            stat(check.stats.p99_px),
            stat(check.stats.max_px),
            check.tolerance_px ? format_short(*check.tolerance_px) : "none",
            status(check)};
}

std::string format_rows(const std::vector<Row>& rows) {
    std::vector<std::size_t> widths(rows.front().size(), 0);
    for (const Row& row : rows) {
        for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
    }
    std::ostringstream out;
    for (const Row& row : rows) {
        for (std::size_t c = 0; c < row.size(); ++c) {
            out << std::left << std::setw(static_cast<int>(c + 1 < row.size() ? widths[c] + 2 : 0)) << row[c];
        }
        out << "\n";
    }
    return out.str();
}

std::string format_header(const std::string& file, const VerifyReport& report) {
    std::ostringstream out;
    out << "libcam verify " << file << ": " << lens_info(report.lens_type).name << " " << report.image_size.width << "x"
        << report.image_size.height << "\n";
    out << "grid " << report.options.grid_columns << "x" << report.options.grid_rows
        << " pixel centres, corners included; points at depths";
    for (double depth : report.options.depths) out << " " << format_short(depth, 6);
    out << " along each ray\n";
    const std::size_t invalid =
        static_cast<std::size_t>(std::count(report.pixel_valid.begin(), report.pixel_valid.end(), false));
    out << "libcam flags " << invalid << " of " << report.pixels.size() << " grid pixels invalid ("
        << format_short(100.0 * report.invalid_fraction) << "%): no ray in the lens model's valid domain\n\n";
    return out.str();
}

// Checks skipped for the same reason share one line: the reason is usually the model.
std::string format_notes(const VerifyReport& report) {
    std::vector<std::pair<std::string, std::string>> skipped;  // reason, names
    std::ostringstream out;
    for (const VerifyCheck& check : report.checks) {
        if (check.skipped()) {
            auto same = std::find_if(skipped.begin(), skipped.end(), [&](const auto& s) { return s.first == *check.skipped_because; });
            if (same == skipped.end()) skipped.emplace_back(*check.skipped_because, check.name);
            else same->second += ", " + check.name;
        } else if (!check.note.empty()) {
            out << "  " << check.name << ": " << check.note << "\n";
        }
    }
    for (const auto& [reason, names] : skipped) out << "  skipped " << names << ": " << reason << "\n";
    return out.str().empty() ? "" : "\nnotes:\n" + out.str();
}

std::string format_opencv_summary(const VerifyReport& report) {
    if (!report.opencv_default) return "";
    const OpenCvDefaultSummary& s = *report.opencv_default;
    std::ostringstream out;
    out << "\nwhere OpenCV's default undistortPoints goes wrong (" << s.function << ", reprojected by OpenCV):\n"
        << "  median " << format_short(s.median_px) << " px, worst " << format_short(s.max_px) << " px at pixel ("
        << format_short(s.worst_pixel.x(), 6) << ", " << format_short(s.worst_pixel.y(), 6) << ")\n"
        << "  " << format_short(100.0 * s.fraction_over_0_1px) << "% of the pixels libcam unprojects are off by more than 0.1 px, "
        << format_short(100.0 * s.fraction_over_1px) << "% by more than 1 px\n";
    return out.str();
}

std::string format_verdict(const VerifyReport& report) {
    std::string failed;
    for (const VerifyCheck& check : report.checks) {
        if (!check.pass()) failed += " " + check.name;
    }
    return failed.empty() ? "\npass: every check is within its tolerance (info rows are for comparison only)\n"
                          : "\nFAIL: outside tolerance:" + failed + "\n";
}

std::string format_table(const std::string& file, const VerifyReport& report) {
    std::vector<Row> rows{{"check", "library", "median px", "p99 px", "max px", "tolerance", "result"}};
    for (const VerifyCheck& check : report.checks) rows.push_back(table_row(check));
    return format_header(file, report) + format_rows(rows) + format_notes(report) + format_opencv_summary(report) +
           format_verdict(report);
}

// ---------------------------------------------------------------------------------
// JSON, keys in the order written ("pass" first).


Json check_json(const VerifyCheck& check) {
    const bool measured = !check.skipped() && check.stats.count > 0;
    Json out;
    out["name"] = check.name;
    out["library"] = check.library;
    put_error_stats(out, check.stats, measured, {"median_px", "p99_px", "max_px"});
    out["pass"] = check.pass();
    out["status"] = status(check);
    out["tolerance_px"] = check.tolerance_px ? Json(*check.tolerance_px) : Json(nullptr);
    out["count"] = check.stats.count;
    out["note"] = check.skipped() ? *check.skipped_because : check.note;
    return out;
}

Json summary_json(const std::optional<OpenCvDefaultSummary>& summary) {
    if (!summary) return nullptr;
    return {{"function", summary->function},
            {"median_px", finite_or_null(summary->median_px)},
            {"max_px", finite_or_null(summary->max_px)},
            {"worst_pixel", {summary->worst_pixel.x(), summary->worst_pixel.y()}},
            {"fraction_over_0_1px", summary->fraction_over_0_1px},
            {"fraction_over_1px", summary->fraction_over_1px}};
}

std::string format_json(const VerifyReport& report) {
    Json out;
    out["pass"] = report.pass();
    out["checks"] = Json::array();
    for (const VerifyCheck& check : report.checks) out["checks"].push_back(check_json(check));
    out["model"] = lens_info(report.lens_type).name;
    out["image_size"] = {report.image_size.width, report.image_size.height};
    out["grid"] = {report.options.grid_columns, report.options.grid_rows};
    out["depths"] = report.options.depths;
    out["invalid_fraction"] = report.invalid_fraction;
    out["opencv_default_summary"] = summary_json(report.opencv_default);
    return out.dump(2) + "\n";
}

}  // namespace

Runner add_verify(CLI::App& app) {
    CLI::App* command = add_command(app, "verify");
    struct Flags {
        std::string file;
        std::string grid = "200x150";
        bool json = false;
        std::string heatmap;
        std::string check = std::string(verify_check::unproject_libcam);
        FileSelection selection;
    };
    auto flags = std::make_shared<Flags>();
    command->add_option("FILE", flags->file, "Camera file (any format libcam reads: libcam info lists its cameras)")
        ->required();
    flags->selection.add_to(*command);
    command->add_option("--grid", flags->grid, "COLUMNSxROWS pixel centres from edge to edge, each in [2, 2000]")
        ->capture_default_str();
    command->add_flag("--json", flags->json,
                      "Print {\"pass\", \"checks\": [{\"name\", \"library\", \"median_px\", \"p99_px\", \"max_px\", "
                      "\"pass\", ...}], ...}");
    CLI::Option* heatmap = command->add_option("--heatmap", flags->heatmap, "Write a PNG of one check's error over the image");
    command->add_option("--check", flags->check, "The check the heatmap shows: " + check_names_list())
        ->capture_default_str()
        ->needs(heatmap);

    return [flags] {
        const VerifyOptions options = options_from_flags(flags->grid);
        require_check_name(flags->check);
        const Camera camera = flags->selection.read(flags->file).camera;
        const VerifyReport report = verify_camera(camera, options);
        // The picture first: a failure to write it leaves nothing on stdout.
        if (!flags->heatmap.empty()) write_png(flags->heatmap, verify_heatmap(report, flags->check));
        emit(flags->json ? format_json(report) : format_table(flags->file, report), "");
        return report.pass() ? 0 : 1;
    };
}

}  // namespace libcam::cli
