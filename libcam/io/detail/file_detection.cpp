// Which format a camera file is, from its name and contents, and what it was read as in
// the messages of its errors (format_row.hpp: locate_camera_file, rethrow_read_as).

#include <algorithm>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/ocamcalib_format.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/text/utf8.hpp"

namespace libcam::detail {

namespace {

using Rows = std::vector<const FormatRow*>;

// The first line that is not blank and not a # comment (mrcal and COLMAP write comments
// first), without its leading blanks.
std::string_view first_content_line(std::string_view text) {
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        std::string_view line = text.substr(at, end - at);
        const auto start = line.find_first_not_of(" \t\r");
        if (start != std::string_view::npos && line[start] != '#') return line.substr(start);
        at = end + 1;
    }
    return {};
}

// What a file starts with, as a message shows it: its first characters, printable.
std::string shown_start(std::string_view text) {
    const std::size_t start = std::min(text.find_first_not_of(" \t\r\n"), text.size());
    const std::string_view rest = text.substr(start);
    return "'" + printable_text(rest.substr(0, rest.find('\n')), 24) + "'";
}

bool starts_with_word_then(std::string_view line, char separator) {
    const auto end = line.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.");
    if (end == 0 || end == std::string_view::npos) return false;
    const auto next = line.find_first_not_of(" \t", end);
    return next != std::string_view::npos && line[next] == separator && (separator != ':' || next == end);
}

// What files of each kind of content are, in words: "by its contents (JSON)".
std::string_view content_name(Content content) {
    switch (content) {
        case Content::Json: return "JSON";
        case Content::Yaml: return "YAML";
        case Content::Xml: return "XML";
        case Content::PythonDict: return "a Python dict, as mrcal writes";
        case Content::KeyValue: return "key = value lines";
        case Content::Table: return "lines of numbers and words";
        case Content::Binary: return "binary";
        case Content::Python: return "Python";
        case Content::OcamText: return "OCamCalib's text";
    }
    return "?";
}

// The files of each kind of content, in words: "the default for JSON files".
std::string content_files(Content content) {
    switch (content) {
        case Content::Binary: return "binary files";
        case Content::OcamText: return "OCamCalib's files";
        case Content::PythonDict: return "mrcal's Python dicts";
        case Content::Table: return "tables of numbers and words";
        default: return std::string(content_name(content)) + " files";
    }
}

// What a file without a known extension holds, by its first characters: JSON starts
// with '{' or '[' and quotes its keys, OpenCV's YAML starts with %YAML and its XML with
// <?xml; mrcal's text is a Python dict, commented first; other YAML starts with a key and
// a colon (Kalibr's camchains: "cam0:"); JPL's cahvor with "key = value"; COLMAP's
// cameras.txt with a camera id and a model name, and its cameras.bin is binary.
Content sniff_content(std::string_view text, const std::string& source) {
    if (text.find('\0') != std::string_view::npos) return Content::Binary;
    const std::string_view body = first_content_line(text);
    if (body.empty()) return Content::PythonDict;  // only comments: mrcal's parser says what is missing
    // Before COLMAP's table: the toolbox's numbers follow its own comments.
    if (looks_like_ocamcalib(text)) return Content::OcamText;
    if (body.starts_with("%YAML") || body.starts_with("---")) return Content::Yaml;
    if (body.starts_with("<")) return Content::Xml;
    if (body.starts_with("[")) return Content::Json;
    if (body.starts_with("{")) {
        // JSON has no comments and quotes its keys with '"'; mrcal writes comments and ''.
        const bool commented = body.data() != text.data() + text.find_first_not_of(" \t\r\n");
        const std::string_view rest = text.substr(static_cast<std::size_t>(body.data() - text.data()));
        const auto quote = rest.find_first_of("\"'");
        const bool double_quoted = quote != std::string_view::npos && rest[quote] == '"';
        return !commented && double_quoted ? Content::Json : Content::PythonDict;
    }
    if (starts_with_word_then(body, '=')) return Content::KeyValue;
    if (starts_with_word_then(body, ':')) return Content::Yaml;
    if (body.front() >= '0' && body.front() <= '9') return Content::Table;
    throw FileError(source + ": unknown camera file format: it starts with " + shown_start(body) +
                    " (not JSON, YAML, XML, mrcal's .cameramodel or .cahvor, or COLMAP's cameras.txt; --from-format "
                    "names it: " + camera_format_names() + ")");
}

bool has_extension(const FormatRow& row, std::string_view extension) {
    return !extension.empty() &&
           std::find(row.extensions.begin(), row.extensions.end(), extension) != row.extensions.end();
}

Rows rows_with_extension(std::string_view extension) {
    Rows rows;
    for (const FormatRow& row : format_rows()) {
        if (has_extension(row, extension)) rows.push_back(&row);
    }
    return rows;
}

Rows rows_of_content(Content content) {
    Rows rows;
    for (const FormatRow& row : format_rows()) {
        if (row.content & static_cast<unsigned>(content)) rows.push_back(&row);
    }
    return rows;
}

// "a, b or c" of the rows' names or titles.
template <class Part>
std::string listed(const Rows& rows, Part&& part, std::string_view last = " or ") {
    std::string out;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        out += (i == 0 ? "" : i + 1 == rows.size() ? std::string(last) : ", ") + std::string(part(*rows[i]));
    }
    return out;
}

std::string_view name_of(const FormatRow& row) { return row.name; }
std::string_view title_of(const FormatRow& row) { return row.title; }

// "libcam reads .xml files as OpenCV XML, Agisoft Metashape XML or lensfun database XML".
std::string read_as(const Rows& rows, std::string_view extension) {
    return "libcam reads " + std::string(extension) + " files as " + listed(rows, title_of);
}

// Files of an extension that only XML (or only JSON) formats have must be that: random
// bytes named .xml are refused as not XML, not parsed as something else.
void require_content(const Rows& rows, std::string_view text, std::string_view extension, const std::string& source) {
    unsigned kinds = 0;
    for (const FormatRow* row : rows) kinds |= row->content;
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    const char start = first == std::string_view::npos ? '\0' : text[first];
    const bool xml = kinds == static_cast<unsigned>(Content::Xml);
    const bool json = kinds == static_cast<unsigned>(Content::Json);
    if ((xml && start != '<') || (json && start != '{' && start != '[')) {
        throw FileError(source + ": not " + (xml ? "XML" : "JSON") + ": it starts with " + shown_start(text) +
                        ", not " + (xml ? "'<'" : "'{' or '['") + " (" + read_as(rows, extension) + ")");
    }
}

// UTF-8 text, for rows without a binary form: the message says what the file would be.
void require_text(const Rows& rows, std::string_view text, std::string_view extension, const std::string& source) {
    try {
        check_text(text, source);
    } catch (const FileError& error) {
        throw FileError(std::string(error.what()) + " (" + read_as(rows, extension) + ", which is text)");
    }
}

// The file parsed once as the structure its candidates share, for their claims; nullopt
// when it is not JSON, YAML or XML, or does not parse (`failure` then says where). The
// text is UTF-8: every row of these contents is text.
std::optional<DocumentNode> parsed_for_claims(std::string_view text, unsigned content, const std::string& source,
                                              std::string& failure) {
    try {
        if (content & static_cast<unsigned>(Content::Json)) return parse_json_tree(text, source);
        if (content & static_cast<unsigned>(Content::Yaml)) return parse_yaml_document(text, source);
        if (content & static_cast<unsigned>(Content::Xml)) return parse_xml_outline(text, source);
    } catch (const FileError& error) {
        failure = error.what();
    }
    return std::nullopt;
}

// The tree parsed for the claims, handed to the reader's parse of the same text: one
// parse, not two (a JSON or YAML reader parses as parsed_for_claims did).
void keep_for_reader(std::string_view text, unsigned content, const std::string& source, DocumentNode root) {
    const bool json = (content & static_cast<unsigned>(Content::Json)) != 0;
    if (json || (content & static_cast<unsigned>(Content::Yaml)) != 0) {
        keep_parsed_document(json ? DocumentSyntax::Json : DocumentSyntax::Yaml, text, source, std::move(root));
    }
}

// The keys of a parsed file a row's telling_keys are looked for among: the top map's,
// and those of the first entry of the top list or map.
std::vector<std::string_view> file_keys(const DocumentNode& root) {
    std::vector<std::string_view> keys(root.keys.begin(), root.keys.end());
    const bool has_first = (root.kind == DocumentNode::Kind::Sequence || root.kind == DocumentNode::Kind::Map) &&
                           !root.items.empty();
    if (has_first) keys.insert(keys.end(), root.items.front().keys.begin(), root.items.front().keys.end());
    return keys;
}

// The row among `rows` whose telling_keys the file has most of, with those keys in
// words ("\"img_name\""); nullptr where it has none of any.
const FormatRow* told_by_keys(const DocumentNode& root, const Rows& rows, std::string& keys_found) {
    const std::vector<std::string_view> keys = file_keys(root);
    const FormatRow* best = nullptr;
    std::size_t most = 0;
    for (const FormatRow* row : rows) {
        std::string found;
        std::size_t count = 0;
        for (const std::string_view key : row->telling_keys) {
            if (key.empty() || std::find(keys.begin(), keys.end(), key) == keys.end()) continue;
            found += (count++ == 0 ? "\"" : ", \"") + std::string(key) + "\"";
        }
        if (count > most) {
            most = count;
            best = row;
            keys_found = (count == 1 ? "its key " : "its keys ") + found;
        }
    }
    return best;
}

struct Detection {
    const FormatRow* row;
    std::string how;
    bool text_checked = false;  // checked to be UTF-8 (check_text) on the way
};

// What named a file's candidate formats, for messages: "its extension .json" and ".json
// files", or "its contents (JSON)" and "files of JSON".
struct Named {
    std::string by;
    std::string what;
    bool extension = false;
};

// The format of a file among `candidates` (the rows its extension or its contents name):
// the only one; the first whose claims accept the file's keys; the one whose telling
// keys it has most of; else the one that claims nothing (the default for that ending or
// content), the message saying which others it could have been. A file whose extension
// names one format was evidently read as that, and its messages need not say so.
Detection choose(const Rows& candidates, std::string_view text, const Named& named, const std::string& source) {
    const std::string& by = named.by;
    if (candidates.size() == 1) return {candidates.front(), named.extension ? "" : "by " + by};
    unsigned shared = ~0u;
    for (const FormatRow* row : candidates) shared &= row->content;
    std::string failure;
    if (std::optional<DocumentNode> root = parsed_for_claims(text, shared, source, failure)) {
        std::optional<Detection> found;
        for (const FormatRow* row : candidates) {
            if (row->claims != nullptr && row->claims(*root)) {
                found = Detection{row, "by " + by + " and its keys"};
                break;
            }
        }
        std::string keys;
        if (!found) {
            if (const FormatRow* told = told_by_keys(*root, candidates, keys)) found = Detection{told, "by " + by + " and " + keys};
        }
        keep_for_reader(text, shared, source, std::move(*root));
        if (found) return *found;
    }
    const auto claims_nothing = [](const FormatRow* row) { return row->claims == nullptr; };
    const auto fallback = std::find_if(candidates.begin(), candidates.end(), claims_nothing);
    const FormatRow* chosen = fallback != candidates.end() ? *fallback : candidates.front();
    Rows others;
    std::copy_if(candidates.begin(), candidates.end(), std::back_inserter(others),
                 [](const FormatRow* row) { return row->claims != nullptr; });
    const std::string how = "the default for " + named.what;
    if (others.empty()) return {chosen, how + " (--from-format names another)"};
    // JSON or XML that does not parse is broken for every format it could be: the parser
    // says where. (An OpenCV YAML reader also takes XML, which YAML's parser refuses.)
    const bool json_or_xml =
        shared == static_cast<unsigned>(Content::Json) || shared == static_cast<unsigned>(Content::Xml);
    if (!failure.empty() && json_or_xml) {
        throw FileError(failure + " (its keys, which tell the formats of " + named.what + " apart, cannot be read)");
    }
    if (!failure.empty()) return {chosen, how + ": it does not parse, so its keys could not tell which format it is"};
    return {chosen, how + ": its keys are those of none of " + listed(others, name_of)};
}

// The format of a file by its extension, else its contents; the text checked to be UTF-8
// first where every candidate is text, so that no parser sees bytes that are not.
Detection detect_format(std::string_view text, const std::filesystem::path& path, const std::string& source) {
    const std::string extension = path.extension().string();
    Rows candidates = rows_with_extension(extension);
    Named named{"its extension " + extension, extension + " files", true};
    if (candidates.empty()) {
        const Content content = sniff_content(text, source);
        const std::string kind(content_name(content));
        candidates = rows_of_content(content);
        named = {"its contents (" + kind + ")", content_files(content), false};
    }
    const auto binary = [](const FormatRow* row) { return row->binary; };
    const bool all_text = std::none_of(candidates.begin(), candidates.end(), binary);
    if (all_text && named.extension) {
        require_content(candidates, text, extension, source);
        require_text(candidates, text, extension, source);
    } else if (all_text) {
        check_text(text, source);
    }
    Detection detection = choose(candidates, text, named, source);
    detection.text_checked = all_text;
    return detection;
}

// The most `rows` read of a file, and the kind of file that is, for the message.
ReadLimit limit_of(const Rows& rows, std::string_view kind) {
    ReadLimit limit{0, kind};
    for (const FormatRow* row : rows) limit.max_bytes = std::max(limit.max_bytes, row->largest_file);
    return limit;
}

Rows all_rows() {
    Rows rows;
    for (const FormatRow& row : format_rows()) rows.push_back(&row);
    return rows;
}

const FormatRow& row_of(CameraFormat format) { return format_rows()[static_cast<std::size_t>(format)]; }

// The file a path names: itself, the cameras file of the folder it names (COLMAP's
// sparse/0), or the file its format reads for the part of a model it names (images.bin:
// the cameras.bin beside it), with that format.
std::filesystem::path file_named(const std::filesystem::path& path, std::optional<CameraFormat>& format) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        for (const FormatRow& row : format_rows()) {
            if (row.file_in_folder == nullptr || (format && *format != row.format)) continue;
            const std::filesystem::path inside = row.file_in_folder(path);
            if (!inside.empty()) {
                format = row.format;
                return inside;
            }
        }
        throw FileError(path.string() + ": a folder, and " + std::string(kNoColmapModel));
    }
    for (const FormatRow& row : format_rows()) {
        if (row.file_for_part == nullptr || (format && *format != row.format)) continue;
        const std::filesystem::path model_file = row.file_for_part(path);
        if (!model_file.empty()) {
            format = row.format;
            return model_file;
        }
    }
    return path;
}

}  // namespace

void refuse_wide_text(std::string_view text, const std::string& source) {
    const std::string_view encoding = wide_text_encoding(text);
    if (!encoding.empty()) {
        throw FileError(source + ": " + std::string(encoding) +
                        " text: libcam reads camera files as UTF-8; save it as UTF-8");
    }
}

LocatedFile locate_camera_file(const std::filesystem::path& path, std::optional<CameraFormat> format) {
    const std::filesystem::path file = file_named(path, format);
    const std::string source = file.string();
    // The most it reads: the format's, or the most of any format it may be.
    Rows rows = format ? Rows{&row_of(*format)} : rows_with_extension(file.extension().string());
    const bool named = !rows.empty();
    if (rows.empty()) rows = all_rows();
    const std::string kind = rows.size() == 1 ? std::string(rows.front()->title)
                             : named ? file.extension().string() + " camera" : std::string("camera");
    LocatedFile located{file, format.value_or(CameraFormat::Json), read_text_file(file, limit_of(rows, kind)), {}};
    std::string& text = located.text;
    refuse_wide_text(text, source);
    // Some editors start UTF-8 text with a byte-order mark, which no parser here expects.
    if (text.starts_with(kUtf8ByteOrderMark) && text.find('\0') == std::string::npos) {
        text.erase(0, kUtf8ByteOrderMark.size());
    }
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw FileError(source + ": file is empty");
    bool checked = false;
    if (!format) {
        const Detection detection = detect_format(text, file, source);
        located.format = detection.row->format;
        located.how = detection.how;
        checked = detection.text_checked;
    }
    const FormatRow& row = row_of(located.format);
    if (text.size() > row.largest_file) throw_larger_than(file, {row.largest_file, row.title});
    if (!row.binary && !checked) reading_as(located, [&] { check_text(text, source); });
    return located;
}

void rethrow_read_as(const LocatedFile& located) {
    // What the file was read as: for errors about the file, not about the options given
    // with it (InvalidArgument: "name one lens with --lens").
    const auto message = [&](const Error& error, bool about_the_file) {
        const std::string what = printable_text(error.what(), kShownMessageLength);
        if (located.how.empty() || !about_the_file) return what;
        return what + " (read as " + std::string(row_of(located.format).title) + ", " + located.how + ")";
    };
    try {
        throw;
    } catch (const FileError& error) {
        throw FileError(message(error, true));
    } catch (const NotRepresentable& error) {
        throw NotRepresentable(message(error, true));
    } catch (const InvalidArgument& error) {
        throw InvalidArgument(message(error, false));
    } catch (const Error& error) {
        throw Error(message(error, false));
    }
}

}  // namespace libcam::detail
