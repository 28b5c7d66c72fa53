#pragma once
// libcam reports misuse and bad data by exceptions of its own types, each with a
// message that names the field and the value, so a caller (or the CLI) can show
// one clear line without knowing where the check happened.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "libcam/text/number_format.hpp"  // format_number, quoted by the messages below

namespace libcam {

// Base of every libcam exception. Its message is kept as one printable line however it was
// built (printable_text, at most four times kShownMessageLength characters, a bound well
// past any message libcam writes: the readers cut theirs at kShownMessageLength before
// saying what the file was read as): a name or a key from a file that reached it without
// shown_value cannot break the line, hide text from the terminal, or make it grow without
// bound.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message);
    explicit Error(const char* message);
};

// A value that is out of range, not finite, or inconsistent with another value.
class InvalidArgument : public Error {
public:
    using Error::Error;
};

// A camera file that cannot be read, parsed or written.
class FileError : public Error {
public:
    using Error::Error;
};

// A camera that cannot be expressed in the requested form (e.g. an off-centre
// principal point asked for as a look-at camera, skew asked for in mrcal's format).
class NotRepresentable : public Error {
public:
    using Error::Error;
};

// Throws InvalidArgument("<field>: must be finite, got <value>") unless value is finite.
void require_finite(const char* field, double value);

template <class Vector>
void require_finite_all(const char* field, const Vector& v) {
    for (long i = 0; i < static_cast<long>(v.size()); ++i) {
        const double value = v.data()[i];
        if (!std::isfinite(value)) {
            throw InvalidArgument(std::string(field) + ": component " + std::to_string(i) +
                                  " must be finite, got " + format_number(value));
        }
    }
}

}  // namespace libcam
