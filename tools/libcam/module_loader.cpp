#include "module_loader.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "commands_module.hpp"
#include "commands_module_dir.hpp"
#include "libcam/error.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/version.hpp"

namespace libcam::cli {

namespace {

namespace fs = std::filesystem;

// Where the module may be: beside the program (a build tree), then where `cmake --install`
// puts it relative to the program, so that an installed tree can move.
std::vector<fs::path> module_candidates() {
    std::error_code error;
    const fs::path program = fs::read_symlink("/proc/self/exe", error);
    if (error) throw FileError("the program's own path (/proc/self/exe): " + error.message());
    const fs::path folder = program.parent_path();
    return {folder / kCommandsModuleFile, (folder / LIBCAM_COMMANDS_MODULE_DIR / kCommandsModuleFile).lexically_normal()};
}

// The module and the program share C++ types: they must come from the same version.
void check_version(void* handle, const fs::path& path) {
    const auto version = reinterpret_cast<VersionEntry>(dlsym(handle, kVersionEntry));
    const std::string found = version == nullptr ? "an unknown version" : std::string("libcam ") + version();
    if (found != std::string("libcam ") + LIBCAM_VERSION) {
        throw FileError(path.string() + ": the commands module of " + found + ", and this program is libcam " +
                        LIBCAM_VERSION);
    }
}

void* open_module(const fs::path& path, const std::string& needed_by) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) throw FileError(needed_by + " needs " + path.string() + ", which does not load: " + dlerror());
    check_version(handle, path);
    return handle;
}

// The module, loaded on the first call and kept (the readers it installs live in it).
void* commands_module(const std::string& needed_by) {
    static std::mutex mutex;
    static void* handle = nullptr;
    const std::lock_guard lock(mutex);
    if (handle != nullptr) return handle;
    const std::vector<fs::path> candidates = module_candidates();
    for (const fs::path& path : candidates) {
        if (fs::exists(path)) return handle = open_module(path, needed_by);
    }
    throw FileError(needed_by + " needs the commands module " + kCommandsModuleFile + ", which is neither at " +
                    candidates[0].string() + " nor at " + candidates[1].string());
}

template <class Entry>
Entry module_entry(const char* name, const std::string& needed_by) {
    void* handle = commands_module(needed_by);
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, name));
    if (entry == nullptr) throw FileError(needed_by + ": the commands module has no " + name);
    return entry;
}

}  // namespace

int run_in_commands_module(std::string_view command, int argc, char** argv) {
    RunEntry run = nullptr;
    try {
        run = module_entry<RunEntry>(kRunEntry, "libcam " + std::string(command));
    } catch (const Error& error) {
        std::cerr << "libcam: error: " << error.what() << "\n";
        return 1;
    }
    return run(argc, argv);
}

void load_format_from_commands_module(CameraFormat format) {
    const std::string needed_by = "the " + std::string(to_string(format)) + " format";
    module_entry<InstallFormatsEntry>(kInstallFormatsEntry, needed_by)(install_camera_format);
}

}  // namespace libcam::cli
