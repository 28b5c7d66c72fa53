#include "libcam/io/detail/word_reader.hpp"

#include <charconv>
#include <cmath>

#include "libcam/error.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam::detail {

void WordReader::skip_blanks() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\r' || text_[at_] == '\n')) {
        if (text_[at_] == '\n') ++line_;
        ++at_;
    }
}

bool WordReader::at_end() {
    skip_blanks();
    return at_ >= text_.size();
}

void WordReader::skip_comment_lines() {
    while (!at_end() && text_[at_] == '#') {
        while (at_ < text_.size() && text_[at_] != '\n') ++at_;
    }
}

std::string_view WordReader::word(std::string_view what) {
    if (at_end()) fail(std::string(what) + ": the file is cut short");
    const std::size_t start = at_;
    while (at_ < text_.size() && text_[at_] != ' ' && text_[at_] != '\t' && text_[at_] != '\r' && text_[at_] != '\n') {
        ++at_;
    }
    return text_.substr(start, at_ - start);
}

std::string_view WordReader::peek() {
    if (at_end()) return {};
    const std::size_t start = at_;
    const int line = line_;
    const std::string_view next = word("");
    at_ = start;
    line_ = line;
    return next;
}

double WordReader::number(std::string_view what) {
    const std::string_view text = word(what);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc::invalid_argument || end != text.data() + text.size()) {
        fail(std::string(what) + ": expected a number, got " + shown_value(text));
    }
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
        fail(std::string(what) + ": must be finite, got " + printable_text(text, kShownValueLength));
    }
    return value;
}

long long WordReader::integer(std::string_view what, long long min, long long max) {
    const std::string_view text = word(what);
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc::invalid_argument || end != text.data() + text.size()) {
        fail(std::string(what) + ": expected an integer, got " + shown_value(text));
    }
    if (error == std::errc::result_out_of_range || value < min || value > max) {
        fail(std::string(what) + ": must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
             printable_text(text, kShownValueLength));
    }
    return value;
}

std::size_t WordReader::count(std::string_view what, std::size_t bytes_each) {
    const std::size_t left = text_.size() - at_;
    const auto value = static_cast<std::size_t>(integer(what, 0, 1LL << 40));
    if (value > left / bytes_each + 1) {
        fail(std::string(what) + ": " + std::to_string(value) + " is more than the " + std::to_string(left) +
             " bytes left can hold");
    }
    return value;
}

void WordReader::fail(std::string_view what) const {
    throw FileError(source_ + ": line " + std::to_string(line_) + ": " + std::string(what));
}

}  // namespace libcam::detail
