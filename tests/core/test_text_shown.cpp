// How messages show text from files (text/shown_value.hpp) and how libcam tells UTF-8 from
// the other Unicode encodings (text/utf8.hpp), on bytes written out by hand.

#include <catch2/catch.hpp>
#include <string>

#include "libcam/error.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/text/utf8.hpp"

using namespace libcam;
using namespace std::string_literals;

TEST_CASE("shown_value: a file's value printable, quoted and cut, its UTF-8 kept") {
    CHECK(shown_value("abc") == "'abc'");
    CHECK(shown_value("") == "''");
    CHECK(shown_value("x", '"') == "\"x\"");
    // Controls as escapes: a terminal shows them as they are written here.
    CHECK(shown_value("a\tb\nc\rd") == "'a\\tb\\nc\\rd'");
    CHECK(shown_value("\x1b[31mred"s) == "'\\x1B[31mred'");
    CHECK(shown_value("nul\0byte"s) == "'nul\\x00byte'");
    CHECK(shown_value("del\x7f"s) == "'del\\x7F'");
    // UTF-8 letters stay: e with an acute accent (C3 A9), the euro sign (E2 82 AC), an emoji (F0 9F 98 80).
    CHECK(shown_value("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80") == "'caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80'");
    // Bytes that are not UTF-8, each as \xNN: a lone continuation byte, a sequence cut
    // short, an overlong '/' (C0 AF), a UTF-16 surrogate (ED A0 80).
    CHECK(shown_value("\x80") == "'\\x80'");
    CHECK(shown_value("a\xE2\x82") == "'a\\xE2\\x82'");
    CHECK(shown_value("\xC0\xAF") == "'\\xC0\\xAF'");
    CHECK(shown_value("\xED\xA0\x80") == "'\\xED\\xA0\\x80'");
    // Invisible characters that break a line or turn the text after them around: U+0085
    // (C2 85), U+2028 (E2 80 A8), U+202E (E2 80 AE), U+FEFF (EF BB BF).
    CHECK(shown_value("\xC2\x85|\xE2\x80\xA8|\xE2\x80\xAE|\xEF\xBB\xBF") == "'\\u0085|\\u2028|\\u202E|\\uFEFF'");
    // Cut after 60 characters (kShownValueLength), saying how long the value was.
    const std::string long_value(100, 'x');
    CHECK(shown_value(long_value) == "'" + std::string(60, 'x') + "...' (100 bytes)");
    CHECK(shown_value(std::string(60, 'y')) == "'" + std::string(60, 'y') + "'");
    // Characters, not bytes: 61 two-byte letters are cut after the 60th.
    std::string accents;
    for (int i = 0; i < 61; ++i) accents += "\xC3\xA9";
    CHECK(shown_value(accents) == "'" + accents.substr(0, 120) + "...' (122 bytes)");
}

TEST_CASE("printable_text: a whole message made printable, cut only when asked") {
    CHECK(printable_text("file.json: line 3: \"K\": got 'a\x01'") == "file.json: line 3: \"K\": got 'a\\x01'");
    CHECK(printable_text(std::string(1000, 'z')) == std::string(1000, 'z'));
    CHECK(printable_text("abcdef", 3) == "abc...");
}

TEST_CASE("Every libcam error's message is one printable line, however it was built") {
    // A name from a file put into a message without shown_value: its line end, escape
    // character and the U+2028 line separator (E2 80 A8) are shown escaped.
    const FileError error("a.json: camera 'x\ny\x1b[2J\xE2\x80\xA8z' not found"s);
    CHECK(std::string(error.what()) == "a.json: camera 'x\\ny\\x1B[2J\\u2028z' not found");
    CHECK(std::string(InvalidArgument("tab\there").what()) == "tab\\there");
    // What is printable already stays as it was, escapes shown_value wrote among it.
    const std::string clean = "b.yml: line 4: the key " + shown_value("k\nl", '"') + " appears twice";
    CHECK(std::string(Error(clean).what()) == clean);
    // At most four times kShownMessageLength characters, then "...".
    const std::string huge(4 * kShownMessageLength + 500, 'w');
    CHECK(std::string(NotRepresentable(huge).what()) == std::string(4 * kShownMessageLength, 'w') + "...");
}

TEST_CASE("utf8_character_at: each character's code point and length, 0 where the bytes are not UTF-8") {
    const std::string text = "A\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80";
    CHECK(utf8_character_at(text, 0).code == 0x41);
    CHECK(utf8_character_at(text, 1).code == 0xE9);
    CHECK(utf8_character_at(text, 1).length == 2);
    CHECK(utf8_character_at(text, 3).code == 0x20AC);
    CHECK(utf8_character_at(text, 3).length == 3);
    CHECK(utf8_character_at(text, 6).code == 0x1F600);
    CHECK(utf8_character_at(text, 6).length == 4);
    CHECK(utf8_character_at(text, 2).length == 0);                   // a continuation byte
    CHECK(utf8_character_at("\xF4\x90\x80\x80", 0).length == 0);     // U+110000, past Unicode
    CHECK(utf8_character_at("\xE0\x80\xAF", 0).length == 0);         // an overlong '/'
}

TEST_CASE("wide_text_encoding: UTF-16 and UTF-32 text told from UTF-8 and from binary files") {
    // "{\"a\"" in each encoding, with and without its byte-order mark.
    CHECK(wide_text_encoding("\xFF\xFE{\0\"\0a\0\"\0"s) == "UTF-16");
    CHECK(wide_text_encoding("\xFE\xFF\0{\0\"\0a\0\""s) == "UTF-16");
    CHECK(wide_text_encoding("{\0\"\0a\0\"\0"s) == "UTF-16");
    CHECK(wide_text_encoding("\0{\0\"\0a\0\""s) == "UTF-16");
    CHECK(wide_text_encoding("\xFF\xFE\0\0{\0\0\0\"\0\0\0"s) == "UTF-32");
    CHECK(wide_text_encoding("\0\0\xFE\xFF\0\0\0{"s) == "UTF-32");
    CHECK(wide_text_encoding("1\0\0\0 \0\0\0P\0\0\0"s) == "UTF-32");
    // Non-ASCII text after a mark: U+00E9 then U+4E2D.
    CHECK(wide_text_encoding("\xFF\xFE\xE9\0\x2D\x4E"s) == "UTF-16");
    CHECK(wide_text_encoding("plain ASCII") == "");
    CHECK(wide_text_encoding("caf\xC3\xA9") == "");
    // COLMAP's cameras.bin: a count of 65279 cameras (FF FE 00 ... 00) then camera 1 (01 00 00 00), or
    // of 130815 (FF FE 01 00 ...) then camera 1: binary, not text.
    CHECK(wide_text_encoding("\xFF\xFE\0\0\0\0\0\0\x01\0\0\0"s) == "");
    CHECK(wide_text_encoding("\xFF\xFE\x01\0\0\0\0\0\x01\0\0\0"s) == "");
    // One camera, camera 1: small numbers, not characters.
    CHECK(wide_text_encoding("\x01\0\0\0\0\0\0\0\x01\0\0\0\x01\0\0\0"s) == "");
}
