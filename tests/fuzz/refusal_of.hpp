#pragma once
// For the fuzz targets that check that several readers of one file agree: what a reader
// says when it refuses the input.

#include <string>

#include "libcam/error.hpp"

namespace libcam::fuzz {

// The message of the libcam::Error `read` throws, or "" where it returns. Any other
// exception goes on (the fuzzer reports it).
template <class Read>
std::string refusal_of(Read&& read) {
    try {
        read();
    } catch (const libcam::Error& error) {
        return error.what();
    }
    return {};
}

}  // namespace libcam::fuzz
