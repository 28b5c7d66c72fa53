#pragma once
// The subcommands of the `libcam` program. Each registers its flags on the app and
// returns the function that runs it; the runner returns the exit code.

#include <CLI/CLI.hpp>
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace libcam::cli {

using Runner = std::function<int()>;

Runner add_convert(CLI::App& app);
Runner add_rays(CLI::App& app);
Runner add_project(CLI::App& app);
Runner add_demo(CLI::App& app);
Runner add_verify(CLI::App& app);
Runner add_fit(CLI::App& app);
Runner add_calibrate(CLI::App& app);
Runner add_uncertainty(CLI::App& app);
Runner add_bench(CLI::App& app);
Runner add_info(CLI::App& app);
Runner add_remap(CLI::App& app);
Runner add_rectify(CLI::App& app);
Runner add_dataset(CLI::App& app);
Runner add_derive(CLI::App& app);
Runner add_render_plan(CLI::App& app);
Runner add_formats(CLI::App& app);
Runner add_models(CLI::App& app);
Runner add_reproject(CLI::App& app);

// Every subcommand, in the order --help lists them. A light one needs libcam::core and
// libcam::io alone and runs in the program itself; the others run in the commands module
// (commands_module.hpp).
struct CommandInfo {
    std::string_view name;
    std::string_view description;
    bool light;
    // A flag that sends a light command to the commands module (reproject's --heatmap,
    // drawn with OpenCV); empty: none.
    std::string_view module_flag = {};
};
const CommandInfo* find_command(std::string_view name);  // nullptr: no such command

// Whether the command line runs in the commands module: a command that is not light, or a
// light one given its module flag.
bool runs_in_module(const CommandInfo& command, int argc, char** argv);

}  // namespace libcam::cli

namespace libcam {
struct ObservationSet;
struct Reprojection;
}  // namespace libcam

namespace libcam::cli {

// reproject --heatmap's picture, which the commands module draws (libcam::report): the
// module sets it when it starts; the program alone never needs it (main sends --heatmap
// to the module).
using ReprojectionHeatmapWriter = void (*)(const std::string& path, const ObservationSet& set,
                                           const Reprojection& reprojection);
void set_reprojection_heatmap_writer(ReprojectionHeatmapWriter writer);

// The subcommand `name` with its description from the table.
CLI::App* add_command(CLI::App& app, std::string_view name);

// The subcommand a command line names (its first word that is not a flag); empty if none.
std::string_view subcommand_of(int argc, char** argv);

struct CommandAdder {
    std::string_view name;
    Runner (*add)(CLI::App& app);
};

// The commands the program runs itself, the light ones of the table (the commands module
// runs these and the rest).
std::span<const CommandAdder> light_commands();

// Parses and runs a command line: `here` are the commands this binary runs; the table's
// others are listed by --help only. Returns the exit code; errors are one line on stderr.
int run_commands(std::span<const CommandAdder> here, int argc, char** argv);

// Writes text to stdout, or atomically to `path` when it is not empty.
void emit(const std::string& text, const std::string& path);

}  // namespace libcam::cli
