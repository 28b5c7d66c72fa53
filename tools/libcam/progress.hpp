#pragma once
// When a long command (fit, dataset) reports its progress on stderr. By default
// ("auto") a command decides by the clock or the terminal: fit after its first second,
// dataset when stderr is a terminal. A script, a log or a test that must know what stderr
// holds says so instead, with --progress always|never or LIBCAM_PROGRESS (the flag wins),
// so that what is printed never depends on how fast the machine is.

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace libcam::cli {

enum class ProgressMode { Auto, Always, Never };

// Adds --progress WHEN to the command; `auto_means` says, in the help, what auto does there.
void add_progress_option(CLI::App* command, std::string& when, std::string_view auto_means);

// The mode the flag's value asks for, or LIBCAM_PROGRESS's when the flag was not given
// (empty); auto when neither is. Throws UsageError naming the flag or the variable.
ProgressMode progress_mode(const std::string& when);

}  // namespace libcam::cli
