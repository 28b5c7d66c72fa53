// libFuzzer target for the dataset's image task read from its JSON line
// (dataset/dataset_tasks.hpp: what another process or machine receives). Properties checked
// on every input:
//   - image_task_from_json returns a task or throws a libcam::Error; anything else (a crash,
//     a sanitizer report, another exception type, a leak) fails the run;
//   - a task it returns, written again and read back, is written the same.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "libcam/error.hpp"
#include "libcam/dataset/dataset_tasks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::string written;
    try {
        written = libcam::image_task_json(libcam::image_task_from_json(text, "fuzz"));
    } catch (const libcam::Error&) {
        return 0;  // refused, with a message
    }
    if (libcam::image_task_json(libcam::image_task_from_json(written, "fuzz: written")) != written) std::abort();
    return 0;
}
