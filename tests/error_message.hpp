#pragma once
// The message of the FileError a call must throw, for tests that compare it whole.

#include <catch2/catch.hpp>
#include <string>

#include "libcam/error.hpp"

namespace libcam::test {

template <class Read>
std::string file_error_of(Read&& read) {
    try {
        read();
    } catch (const FileError& error) {
        return error.what();
    }
    FAIL("no FileError");
    return {};
}

}  // namespace libcam::test
