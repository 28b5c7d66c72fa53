#pragma once
// The subcommands of the `libcam` program. Each registers its flags on the app and
// returns the function that runs it; the runner returns the exit code.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace libcam::cli {

using Runner = std::function<int()>;

Runner add_convert(CLI::App& app);
Runner add_rays(CLI::App& app);
Runner add_project(CLI::App& app);
Runner add_demo(CLI::App& app);
Runner add_verify(CLI::App& app);
Runner add_fit(CLI::App& app);
Runner add_bench(CLI::App& app);
Runner add_info(CLI::App& app);
Runner add_remap(CLI::App& app);
Runner add_derive(CLI::App& app);
Runner add_render_plan(CLI::App& app);
Runner add_formats(CLI::App& app);
Runner add_models(CLI::App& app);

// Writes text to stdout, or atomically to `path` when it is not empty.
void emit(const std::string& text, const std::string& path);

}  // namespace libcam::cli
