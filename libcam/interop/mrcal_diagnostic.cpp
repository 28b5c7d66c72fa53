#include "libcam/interop/mrcal_diagnostic.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <regex>

#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

using Match = std::smatch;

// The line of the file at byte `position` (libmrcal counts from the file's first byte).
std::string line_at(const std::string& position, std::string_view text) {
    const std::size_t at = std::min<std::size_t>(std::stoull(position), text.size());
    return "line " + std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// A key's value in the file, where it is written 'key': 'value' (or with ""), or empty.
std::string value_of(std::string_view text, const std::string& key) {
    const std::regex pattern("['\"]" + key + "['\"]\\s*:\\s*['\"]([^'\"]*)['\"]");
    std::match_results<std::string_view::const_iterator> found;
    if (!std::regex_search(text.begin(), text.end(), found, pattern)) return {};
    return found[1].str();
}

bool has_key(std::string_view text, std::string_view key) {
    for (const char quote : {'\'', '"'}) {
        const std::string quoted = std::string(1, quote) + std::string(key) + quote;
        if (text.find(quoted) != std::string_view::npos) return true;
    }
    return false;
}

// libmrcal could not allocate the intrinsics: only a splined model's grid asks for that many.
std::string too_many_intrinsics(std::string_view text) {
    const std::string lensmodel = value_of(text, "lensmodel");
    std::smatch grid;
    const std::regex nx_ny("Nx=(\\d{1,9})_Ny=(\\d{1,9})");
    if (std::regex_search(lensmodel, grid, nx_ny)) {
        const unsigned long long count = 4 + 2 * std::stoull(grid[1].str()) * std::stoull(grid[2].str());
        return "\"lensmodel\": its spline of Nx=" + grid[1].str() + " by Ny=" + grid[2].str() +
               " asks for 4 + 2 Nx Ny = " + std::to_string(count) + " intrinsics, more than libmrcal could allocate";
    }
    return "\"lensmodel\": " + shown_value(lensmodel) + ": libmrcal could not allocate its intrinsics";
}

std::string missing_keys(std::string_view text) {
    std::string missing;
    for (const char* key : {"lensmodel", "intrinsics", "extrinsics", "imagersize"}) {
        if (!has_key(text, key)) missing += (missing.empty() ? "\"" : ", \"") + std::string(key) + "\"";
    }
    return "missing " + (missing.empty() ? std::string("a key") : missing) +
           " (a .cameramodel needs lensmodel, intrinsics, extrinsics and imagersize)";
}

// What a list of numbers should hold, for the message of one that holds more.
std::string expected_count(const std::string& field, const std::string& count, std::string_view text) {
    if (field != "intrinsics") return "the " + count + " expected";
    return "the " + count + " of its lensmodel " + shown_value(value_of(text, "lensmodel"));
}

// ", got 'x'": the value libmrcal stopped at, from its message or else from the file (it
// quotes '' for a word that does not start as a number).
std::string got(const std::ssub_match& given, const std::string& position, std::string_view text) {
    if (given.matched && given.length() > 0) return ", got " + shown_value(given.str());
    std::size_t at = std::min<std::size_t>(std::stoull(position), text.size());
    at = std::min(text.find_first_not_of(" \t\r\n", at), text.size());
    const std::size_t end = std::min(text.find_first_of(",])} \t\r\n", at), text.size());
    return end > at ? ", got " + shown_value(text.substr(at, end - at)) : "";
}

struct Translation {
    const char* pattern;  // libmrcal's words, after its "file(line): "
    std::function<std::string(const Match&, std::string_view text)> say;
};

// libmrcal 2.2's cameramodel-parser.re, each message it prints.
const std::array<Translation, 20>& translations() {
    static const std::array<Translation, 20> table = {{
        {"malloc\\(\\) failed", [](const Match&, std::string_view text) { return too_many_intrinsics(text); }},
        {"Incomplete cameramodel.*", [](const Match&, std::string_view text) { return missing_keys(text); }},
        {"Didn't see expected ',' at (\\d+) while parsing (\\w+)",
         [](const Match& m, std::string_view text) {
             return line_at(m[1], text) + ": \"" + m[2].str() + "\": expected ',' between its values";
         }},
        {"Didn't see the closing \\)/\\] for the (\\w+) at position (\\d+)\\. Expected (\\d+) values.*",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": \"" + m[1].str() + "\": more values than " +
                    expected_count(m[1].str(), m[3].str(), text);
         }},
        {"Didn't see the opening \\[/\\( for the (\\w+) at position (\\d+).*",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": \"" + m[1].str() + "\": expected a list [ ... ]";
         }},
        {"Could not parse lensmodel '(.*)'",
         [](const Match& m, std::string_view) {
             return "\"lensmodel\": " + shown_value(m[1].str()) + " is not a lens model mrcal knows (LENSMODEL_...)";
         }},
        {"Couldn't get valid Nparams from lensmodel string '(.*)'",
         [](const Match& m, std::string_view) {
             return "\"lensmodel\": " + shown_value(m[1].str()) + " is not a lens model mrcal knows (LENSMODEL_...)";
         }},
        {"Error parsing double-precision value for (\\w+) at (\\d+)(?:\\. String: '(.*)')?",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": \"" + m[1].str() + "\": expected a finite number" + got(m[3], m[2], text);
         }},
        {"Error parsing unsigned (?:integer|int) for (\\w+) at (\\d+)(?:\\. String: '(.*)')?",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": \"" + m[1].str() + "\": expected whole numbers >= 0" +
                    got(m[3], m[2], text);
         }},
        {"Didn't see leading '\\{'.*",
         [](const Match&, std::string_view) {
             return std::string("expected '{' first: a .cameramodel is a Python dict");
         }},
        {"Didn't see trailing , at (\\d+)",
         [](const Match& m, std::string_view text) { return line_at(m[1], text) + ": expected ',' after the value"; }},
        {"Didn't see expected ':' at (\\d+).*",
         [](const Match& m, std::string_view text) { return line_at(m[1], text) + ": expected ':' after the key"; }},
        {"Didn't see the (\\w+) string at position (\\d+).*",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": expected a quoted " + m[1].str() + " ('...')";
         }},
        {"Saw 'intrinsics' key, before a 'lensmodel' key.*",
         [](const Match&, std::string_view) {
             return std::string("\"intrinsics\" comes before any \"lensmodel\": libmrcal needs \"lensmodel\" first");
         }},
        {"(\\w+) defined more than once",
         [](const Match& m, std::string_view) { return "\"" + m[1].str() + "\" given twice"; }},
        {"Error reading a balanced list at (\\d+).*",
         [](const Match& m, std::string_view text) {
             return line_at(m[1], text) + ": a value libmrcal cannot read (it reads numbers, quoted strings, and lists "
                                          "of them)";
         }},
        {"Error parsing value for key '(.*)' at (\\d+)",
         [](const Match& m, std::string_view text) {
             return line_at(m[2], text) + ": \"" + m[1].str() + "\": a value libmrcal cannot read";
         }},
        {"Garbage after trailing \\} at (\\d+).*",
         [](const Match& m, std::string_view text) { return line_at(m[1], text) + ": text after the closing '}'"; }},
        {"(Cubic|Quadratic) splines: absolute minimum Nx, Ny is (\\d+)\\. Got Nx=(\\d+) Ny=(\\d+).*",
         [](const Match& m, std::string_view) {
             return "\"lensmodel\": a " + std::string(m[1].str() == "Cubic" ? "cubic" : "quadratic") +
                    " spline needs Nx and Ny of at least " + m[2].str() + ", got Nx=" + m[3].str() +
                    " Ny=" + m[4].str();
         }},
        {"I only support spline order.*",
         [](const Match&, std::string_view) { return std::string("\"lensmodel\": a spline's order must be 2 or 3"); }},
    }};
    return table;
}

}  // namespace

std::string mrcal_parse_failure(std::string_view diagnostic, std::string_view text) {
    // "cameramodel-parser.re(254): Didn't see ...": the words after libmrcal's own place, on
    // the first line that has one. Other lines written meanwhile are not libmrcal's (a
    // sanitizer's warning, in a checked build, before libmrcal's "malloc() failed").
    static const std::regex place("^[^ ]*\\(\\d+\\): ");
    std::string words(diagnostic.substr(0, diagnostic.find('\n')));
    for (std::size_t at = 0; at < diagnostic.size();) {
        const std::size_t end = std::min(diagnostic.find('\n', at), diagnostic.size());
        const std::string line(diagnostic.substr(at, end - at));
        if (std::regex_search(line, place)) {
            words = line;
            break;
        }
        at = end + 1;
    }
    words = std::regex_replace(words, place, "", std::regex_constants::format_first_only);
    for (const Translation& translation : translations()) {
        Match match;
        if (std::regex_match(words, match, std::regex(translation.pattern))) return translation.say(match, text);
    }
    if (words.empty()) return "libmrcal could not read it, and did not say why";
    return "libmrcal could not read it: " + printable_text(words, 200);
}

}  // namespace libcam
