#pragma once
// The image flags the commands that turn images share (remap, rectify); only the commands
// module, which links libcam::interop, includes this.

#include <string>

#include "libcam/error.hpp"
#include "libcam/interop/image_remap.hpp"
#include "parse.hpp"

namespace libcam::cli {

// --interpolation's value; a usage error naming the flag and the choices otherwise.
inline Interpolation interpolation_flag(const std::string& text) {
    try {
        return interpolation_from_string(text);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--") + error.what());
    }
}

}  // namespace libcam::cli
