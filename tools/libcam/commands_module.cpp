// The commands module (commands_module.hpp): the whole `libcam` program, every command,
// loaded by the light program for the commands that need OpenCV, mrcal, Ceres or images.
// Everything in it is hidden but the three entries below.

#include <opencv2/core/utility.hpp>
#include <type_traits>
#include <vector>

#include "commands.hpp"
#include "commands_module.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/report/image.hpp"
#include "libcam/report/reprojection_heatmap.hpp"
#include "libcam/version.hpp"

namespace {

using namespace libcam::cli;

// OpenCV prints every cv::Exception to stderr before throwing it; libcam reports the
// error itself, in one line.
int quiet_opencv_errors(int, const char*, const char*, const char*, int, void*) { return 0; }

// The commands only the module runs; it runs the light ones too (light_commands()).
constexpr CommandAdder kModuleCommands[] = {
    {"remap", add_remap}, {"dataset", add_dataset}, {"render-plan", add_render_plan}, {"verify", add_verify},
    {"fit", add_fit},     {"calibrate", add_calibrate}, {"uncertainty", add_uncertainty}, {"bench", add_bench},
    {"demo", add_demo},   {"rectify", add_rectify},
};

void write_reprojection_heatmap(const std::string& path, const libcam::ObservationSet& set,
                                const libcam::Reprojection& reprojection) {
    libcam::write_png(path, libcam::reprojection_heatmap(set, reprojection));
}

}  // namespace

#define LIBCAM_MODULE_ENTRY extern "C" __attribute__((visibility("default")))

LIBCAM_MODULE_ENTRY const char* libcam_commands_version() { return LIBCAM_VERSION; }

LIBCAM_MODULE_ENTRY int libcam_run_commands(int argc, char** argv) {
    cv::redirectError(quiet_opencv_errors);
    libcam::register_interop_formats();  // this copy of libcam::io's table: mrcal .cameramodel
    set_reprojection_heatmap_writer(write_reprojection_heatmap);
    std::vector<CommandAdder> all(light_commands().begin(), light_commands().end());
    all.insert(all.end(), std::begin(kModuleCommands), std::end(kModuleCommands));
    return run_commands(all, argc, argv);
}

LIBCAM_MODULE_ENTRY void libcam_install_formats(libcam::CameraFormatInstaller install) {
    cv::redirectError(quiet_opencv_errors);
    libcam::register_interop_formats(install);
}

// The entries have the types the program calls them with.
static_assert(std::is_same_v<decltype(&libcam_commands_version), VersionEntry>);
static_assert(std::is_same_v<decltype(&libcam_run_commands), RunEntry>);
static_assert(std::is_same_v<decltype(&libcam_install_formats), InstallFormatsEntry>);
