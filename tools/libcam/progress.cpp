#include "progress.hpp"

#include <cstdlib>

#include "parse.hpp"

namespace libcam::cli {

namespace {

constexpr const char* kVariable = "LIBCAM_PROGRESS";

ProgressMode mode_named(std::string_view word, const std::string& where) {
    if (word == "auto") return ProgressMode::Auto;
    if (word == "always") return ProgressMode::Always;
    if (word == "never") return ProgressMode::Never;
    throw UsageError(where + ": expected auto, always or never, got '" + std::string(word) + "'");
}

}  // namespace

void add_progress_option(CLI::App* command, std::string& when, std::string_view auto_means) {
    command->add_option("--progress", when,
                        "When to report progress on stderr: auto (" + std::string(auto_means) +
                            "), always, or never (default: the environment variable " + kVariable + ", else auto)");
}

ProgressMode progress_mode(const std::string& when) {
    if (!when.empty()) return mode_named(when, "--progress");
    const char* variable = std::getenv(kVariable);
    if (variable == nullptr || *variable == '\0') return ProgressMode::Auto;
    return mode_named(variable, kVariable);
}

}  // namespace libcam::cli
