#pragma once
// The words of a whitespace-separated text file (VisualSfM's .nvm, Bundler's bundle.out),
// read one by one with the line each is on, for messages that say where a bad value is:
// "<source>: line L: <what>: expected a number, got 'abc'".

#include <cstddef>
#include <string>
#include <string_view>

namespace libcam::detail {

class WordReader {
public:
    WordReader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

    // The next word; fails "cut short" naming `what` at the end of the text.
    std::string_view word(std::string_view what);
    // The next word without taking it; empty at the end of the text.
    std::string_view peek();
    // The next word as a finite number, or an integer in [min, max].
    double number(std::string_view what);
    long long integer(std::string_view what, long long min, long long max);
    // A count of items that take at least `bytes_each` bytes of the text left: a count the
    // file cannot hold is refused before anything is allocated for it.
    std::size_t count(std::string_view what, std::size_t bytes_each);
    // Skips lines that start with '#' (after blanks), where the format allows comments.
    void skip_comment_lines();
    // Whether only blanks are left.
    bool at_end();

    [[noreturn]] void fail(std::string_view what) const;
    int line() const { return line_; }
    const std::string& source() const { return source_; }

private:
    void skip_blanks();

    std::string_view text_;
    std::size_t at_ = 0;
    int line_ = 1;
    const std::string& source_;
};

}  // namespace libcam::detail
