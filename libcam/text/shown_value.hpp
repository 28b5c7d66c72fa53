#pragma once
// How a message shows text that came from a file (a word, a key, a name), in one place:
// a file may hold any bytes, and a message must stay one printable line that a terminal
// shows as it is, whatever the file held.

#include <cstddef>
#include <string>
#include <string_view>

namespace libcam {

// The most characters of one value a message shows; a longer value is cut.
constexpr std::size_t kShownValueLength = 60;
// The most characters of a reader's message (a value that did not go through shown_value
// is cut with it): the longest libcam writes, listing every format, is under 1000.
constexpr std::size_t kShownMessageLength = 2000;

// `bytes` as a message may print them: UTF-8 text is kept, but for control characters
// (\t, \n, \r, \x01, \u0085) and the invisible ones that reorder or break a line
// (\u202e, \u2028), which are written as escapes; a byte that is not UTF-8 is written
// \xNN. Past `max_characters` characters the text is cut and "..." follows.
std::string printable_text(std::string_view bytes, std::size_t max_characters = std::string_view::npos);

// A value from a file in a message: in '' (printable_text, at most kShownValueLength
// characters, then "..." and the value's length): 'abc', 'a\x01b', 'aaa...' (5000 bytes).
// A JSON string is shown in JSON's quotes: quote '"'.
std::string shown_value(std::string_view bytes, char quote = '\'');

}  // namespace libcam
