// libcam: graphics cameras <-> calibrated cameras, proven against OpenCV and mrcal.
//
// Exit codes: 0 success, 1 a failure (bad value, unreadable file, failed check),
// 2 a usage error (unknown flag, malformed number). Errors are one line on stderr.

#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <opencv2/core/utility.hpp>

#include "commands.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/version.hpp"
#include "parse.hpp"

namespace libcam::cli {

void emit(const std::string& text, const std::string& path) {
    if (path.empty()) {
        std::cout << text << std::flush;
    } else {
        write_file_atomically(path, text);
    }
}

}  // namespace libcam::cli

namespace {

// OpenCV prints every cv::Exception to stderr before throwing it; libcam reports the
// error itself, in one line.
int quiet_opencv_errors(int, const char*, const char*, const char*, int, void*) { return 0; }

}  // namespace

int main(int argc, char** argv) {
    using namespace libcam::cli;
    cv::redirectError(quiet_opencv_errors);
    libcam::register_interop_formats();  // mrcal .cameramodel files (libmrcal's parser)

    CLI::App app{"libcam: graphics cameras <-> calibrated cameras, checked against OpenCV and mrcal"};
    app.set_version_flag("--version", std::string("libcam ") + LIBCAM_VERSION);
    app.require_subcommand(1);
    std::map<CLI::App*, Runner> runners;
    for (auto add : {add_convert, add_info, add_rays, add_project, add_remap, add_derive, add_render_plan, add_verify,
                     add_fit, add_bench, add_demo, add_formats, add_models}) {
        Runner run = add(app);
        runners[app.get_subcommands({}).back()] = std::move(run);
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::CallForAllHelp& help) {
        return app.exit(help);
    } catch (const CLI::CallForVersion& version) {
        return app.exit(version);
    } catch (const CLI::ParseError& error) {
        std::cerr << "libcam: usage error: " << error.what() << " (see --help)\n";
        return 2;
    }

    try {
        for (const auto& [command, run] : runners) {
            if (command->parsed()) return run();
        }
        return 2;
    } catch (const UsageError& error) {
        std::cerr << "libcam: usage error: " << error.what() << " (see --help)\n";
        return 2;
    } catch (const libcam::Error& error) {
        std::cerr << "libcam: error: " << error.what() << "\n";
        return 1;
    } catch (const std::exception& error) {
        std::cerr << "libcam: error: " << error.what() << "\n";
        return 1;
    }
}
