#include "libcam/io/detail/npz_archive.hpp"

#include <zip.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam::detail {

std::size_t NpyArray::size() const {
    std::size_t count = 1;
    for (const std::size_t n : shape) count *= n;
    return count;
}

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw FileError(where + ": " + what); }

// The value of the little-endian integer in `bytes`.
std::uint64_t little_endian(std::string_view bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = bytes.size(); i-- > 0;) value = (value << 8) | static_cast<unsigned char>(bytes[i]);
    return value;
}

// ---- the header: a Python dict literal of three keys ------------------------------------

struct HeaderReader {
    std::string_view text;
    const std::string& where;
    std::size_t at = 0;

    void skip_spaces() {
        while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    }
    bool take(char c) {
        skip_spaces();
        if (at < text.size() && text[at] == c) return ++at, true;
        return false;
    }
    void expect(char c) {
        if (!take(c)) fail(where, "npy header: expected '" + std::string(1, c) + "' at " + std::to_string(at) +
                                      " in " + shown_value(text));
    }
    std::string quoted() {
        skip_spaces();
        if (at >= text.size() || (text[at] != '\'' && text[at] != '"')) expect('\'');
        const char quote = text[at++];
        const std::size_t end = text.find(quote, at);
        if (end == std::string_view::npos) fail(where, "npy header: unterminated string in " + shown_value(text));
        std::string value(text.substr(at, end - at));
        at = end + 1;
        return value;
    }
    std::string word() {
        skip_spaces();
        const std::size_t start = at;
        while (at < text.size() && std::isalnum(static_cast<unsigned char>(text[at]))) ++at;
        return std::string(text.substr(start, at - start));
    }
    std::vector<std::size_t> shape() {
        expect('(');
        std::vector<std::size_t> dimensions;
        while (!take(')')) {
            const std::string digits = word();
            if (digits.empty() || digits.size() > 12 ||
                digits.find_first_not_of("0123456789") != std::string::npos) {
                fail(where, "npy header: shape holds \"" + digits + "\", not a count");
            }
            dimensions.push_back(std::stoull(digits));
            if (!take(',')) {
                expect(')');
                break;
            }
        }
        return dimensions;
    }
};

struct Header {
    std::string descr;
    bool fortran_order = false;
    std::vector<std::size_t> shape;
};

Header parse_header(std::string_view text, const std::string& where) {
    HeaderReader reader{text, where};
    Header header;
    bool has_descr = false, has_order = false, has_shape = false;
    reader.expect('{');
    while (!reader.take('}')) {
        const std::string key = reader.quoted();
        reader.expect(':');
        if (key == "descr") {
            header.descr = reader.quoted(), has_descr = true;
        } else if (key == "fortran_order") {
            const std::string value = reader.word();
            if (value != "True" && value != "False") fail(where, "npy header: fortran_order is \"" + value + "\"");
            header.fortran_order = value == "True", has_order = true;
        } else if (key == "shape") {
            header.shape = reader.shape(), has_shape = true;
        } else {
            fail(where, "npy header: unknown key " + shown_value(key));
        }
        if (!reader.take(',')) {
            reader.expect('}');
            break;
        }
    }
    if (!has_descr || !has_order || !has_shape) fail(where, "npy header lacks descr, fortran_order or shape");
    return header;
}

// ---- the elements -----------------------------------------------------------------------

// The bytes of one element of `descr`, or 0 for a dtype this reader refuses.
std::size_t item_size(const std::string& descr) {
    if (descr == "<f8" || descr == "<i8") return 8;
    if (descr == "<i4") return 4;
    if (descr == "|b1") return 1;
    if (descr.size() > 2 && descr.size() <= 8 && descr.starts_with("<U") &&
        descr.find_first_not_of("0123456789", 2) == std::string::npos) {
        return 4 * std::stoul(descr.substr(2));
    }
    return 0;
}

double element(std::string_view bytes, const std::string& descr) {
    const std::uint64_t bits = little_endian(bytes);
    if (descr == "<f8") return std::bit_cast<double>(bits);
    if (descr == "<i8") return static_cast<double>(static_cast<std::int64_t>(bits));
    if (descr == "<i4") return static_cast<double>(static_cast<std::int32_t>(static_cast<std::uint32_t>(bits)));
    return bits != 0 ? 1.0 : 0.0;  // |b1
}

// A numpy unicode string: UTF-32LE code points, padded with NULs, as UTF-8.
std::string utf8_of_utf32(std::string_view bytes, const std::string& where) {
    std::string text;
    for (std::size_t i = 0; i + 4 <= bytes.size(); i += 4) {
        const auto c = static_cast<std::uint32_t>(little_endian(bytes.substr(i, 4)));
        if (c == 0) break;
        if (c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) fail(where, "string holds code point " + std::to_string(c));
        if (c < 0x80) {
            text += static_cast<char>(c);
        } else if (c < 0x800) {
            text += static_cast<char>(0xC0 | (c >> 6)), text += static_cast<char>(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            text += static_cast<char>(0xE0 | (c >> 12)), text += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
            text += static_cast<char>(0x80 | (c & 0x3F));
        } else {
            text += static_cast<char>(0xF0 | (c >> 18)), text += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
            text += static_cast<char>(0x80 | ((c >> 6) & 0x3F)), text += static_cast<char>(0x80 | (c & 0x3F));
        }
    }
    return text;
}

// ---- the archive ------------------------------------------------------------------------

struct ZipCloser {
    void operator()(zip_t* archive) const { zip_discard(archive); }
};
struct ZipFileCloser {
    void operator()(zip_file_t* file) const { zip_fclose(file); }
};

// The zip's error as words, for messages.
std::string zip_message(zip_error_t* error) {
    std::string message = zip_error_strerror(error);
    zip_error_fini(error);
    return message;
}

std::unique_ptr<zip_t, ZipCloser> open_zip(std::string_view bytes, const std::string& where) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
    if (source == nullptr) fail(where, "not a zip archive: " + zip_message(&error));
    zip_t* archive = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (archive == nullptr) {
        zip_source_free(source);
        fail(where, "not a zip archive (" + std::to_string(bytes.size()) + " bytes): " + zip_message(&error));
    }
    zip_error_fini(&error);
    return std::unique_ptr<zip_t, ZipCloser>(archive);
}

// A member's bytes. Its stated size is checked against deflate's largest ratio (1032:1)
// before anything is allocated, so a forged size cannot ask for gigabytes.
std::string read_member(zip_t* archive, zip_uint64_t index, const std::string& where) {
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(archive, index, 0, &stat) != 0 || (stat.valid & ZIP_STAT_SIZE) == 0 ||
        (stat.valid & ZIP_STAT_COMP_SIZE) == 0) {
        fail(where, "member " + std::to_string(index) + ": no size: " + zip_strerror(archive));
    }
    constexpr zip_uint64_t kLargest = zip_uint64_t{1} << 30;
    if (stat.size > kLargest || stat.size > 1032 * stat.comp_size + 1024) {
        fail(where, "member " + std::to_string(index) + ": size " + std::to_string(stat.size) + " from " +
                        std::to_string(stat.comp_size) + " compressed bytes");
    }
    const std::unique_ptr<zip_file_t, ZipFileCloser> file(zip_fopen_index(archive, index, 0));
    if (!file) fail(where, "member " + std::to_string(index) + ": " + zip_strerror(archive));
    std::string bytes(stat.size, '\0');
    const zip_int64_t read = zip_fread(file.get(), bytes.data(), stat.size);
    char extra = 0;
    // Reading past the end makes libzip check the member's CRC.
    if (read < 0 || static_cast<zip_uint64_t>(read) != stat.size || zip_fread(file.get(), &extra, 1) != 0) {
        fail(where, "member " + std::to_string(index) + ": " + zip_file_strerror(file.get()));
    }
    return bytes;
}

}  // namespace

NpyArray parse_npy(std::string_view bytes, const std::string& where) {
    constexpr std::string_view kMagic("\x93NUMPY", 6);
    if (!bytes.starts_with(kMagic) || bytes.size() < 10) fail(where, "not an .npy array (no \\x93NUMPY magic)");
    const int major = static_cast<unsigned char>(bytes[6]);
    if (major < 1 || major > 3) fail(where, "npy version " + std::to_string(major) + " (libcam reads 1 to 3)");
    const std::size_t length_bytes = major == 1 ? 2 : 4;
    if (bytes.size() < 8 + length_bytes) fail(where, "npy header truncated");
    const std::uint64_t header_length = little_endian(bytes.substr(8, length_bytes));
    const std::size_t data_start = 8 + length_bytes + header_length;
    if (header_length > bytes.size() || data_start > bytes.size()) {
        fail(where, "npy header length " + std::to_string(header_length) + " past the array's " +
                        std::to_string(bytes.size()) + " bytes");
    }
    const Header header = parse_header(bytes.substr(8 + length_bytes, header_length), where);
    const std::size_t item = item_size(header.descr);
    if (item == 0) fail(where, "dtype " + shown_value(header.descr) + " (libcam reads <f8, <i4, <i8, |b1 and <U)");
    if (header.fortran_order) fail(where, "fortran_order True (libcam reads C order)");
    NpyArray array{header.descr, header.shape, {}, {}};
    std::size_t count = 1;
    for (const std::size_t n : header.shape) {
        if (n != 0 && count > std::numeric_limits<std::size_t>::max() / item / n) fail(where, "shape too large");
        count *= n;
    }
    const std::string_view data = bytes.substr(data_start);
    if (data.size() != count * item) {
        fail(where, "shape " + std::to_string(count) + " elements of " + header.descr + " needs " +
                        std::to_string(count * item) + " bytes, the array holds " + std::to_string(data.size()));
    }
    if (array.is_text()) {
        if (!header.shape.empty()) fail(where, "an array of strings (libcam reads a single string)");
        array.text = utf8_of_utf32(data, where);
        return array;
    }
    array.numbers.reserve(count);
    for (std::size_t i = 0; i < count; ++i) array.numbers.push_back(element(data.substr(i * item, item), header.descr));
    return array;
}

std::map<std::string, NpyArray> read_npz(std::string_view bytes, const std::string& where) {
    const auto archive = open_zip(bytes, where);
    const zip_int64_t members = zip_get_num_entries(archive.get(), 0);
    std::map<std::string, NpyArray> arrays;
    for (zip_int64_t i = 0; i < members; ++i) {
        const auto index = static_cast<zip_uint64_t>(i);
        const char* name = zip_get_name(archive.get(), index, 0);
        const std::string member = name != nullptr ? name : "";
        if (!member.ends_with(".npy") || member.size() == 4) fail(where, "member " + shown_value(member, '"') + " is not an .npy");
        const std::string key = member.substr(0, member.size() - 4);
        const std::string array_where = where + ": " + printable_text(key, kShownValueLength);
        if (arrays.contains(key)) fail(array_where, "stored twice");
        arrays.emplace(key, parse_npy(read_member(archive.get(), index, array_where), array_where));
    }
    return arrays;
}

namespace {

void append_little_endian(std::string& out, std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xFF);
}

// The header's shape as Python writes a tuple: "()", "(3,)", "(2, 6)".
std::string python_shape(const std::vector<std::size_t>& shape) {
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
    return text + (shape.size() == 1 ? ",)" : ")");
}

// UTF-8 text as numpy's UTF-32LE code points.
std::string utf32_of_utf8(const std::string& text) {
    std::string out;
    for (std::size_t at = 0; at < text.size();) {
        const auto lead = static_cast<unsigned char>(text[at]);
        const int length = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
        if (at + static_cast<std::size_t>(length) > text.size()) throw InvalidArgument("npy: text that is not UTF-8");
        std::uint32_t code = length == 1 ? lead : lead & (0xFF >> (length + 1));
        for (int i = 1; i < length; ++i) code = (code << 6) | (static_cast<unsigned char>(text[at + i]) & 0x3F);
        append_little_endian(out, code, 4);
        at += static_cast<std::size_t>(length);
    }
    return out;
}

struct ZipWriteCloser {
    void operator()(zip_t* archive) const { zip_discard(archive); }
};
struct SourceFreer {
    void operator()(zip_source_t* source) const { zip_source_free(source); }
};

[[noreturn]] void zip_failed(const std::string& what, zip_error_t* error) {
    throw Error("npz: " + what + ": " + zip_message(error));
}

}  // namespace

std::string format_npy(const NpyArray& array) {
    std::string data;
    std::string descr = array.descr;
    if (array.is_text()) {
        if (!array.shape.empty()) throw InvalidArgument("npy: a string array of shape " + python_shape(array.shape));
        data = utf32_of_utf8(array.text);
        descr = "<U" + std::to_string(std::max<std::size_t>(data.size() / 4, 1));
        if (data.empty()) data.assign(4, '\0');  // numpy's '' is one NUL code point
    } else {
        if (array.numbers.size() != array.size()) {
            throw InvalidArgument("npy: " + std::to_string(array.numbers.size()) + " numbers for shape " +
                                  python_shape(array.shape));
        }
        for (const double value : array.numbers) {
            if (descr == "<f8") {
                append_little_endian(data, std::bit_cast<std::uint64_t>(value), 8);
            } else if (descr == "<i4") {
                if (!(value >= std::numeric_limits<std::int32_t>::min() && value <= std::numeric_limits<std::int32_t>::max()) ||
                    value != std::floor(value)) {
                    throw InvalidArgument("npy: " + format_number(value) + " is no 32-bit integer");
                }
                append_little_endian(data, static_cast<std::uint32_t>(static_cast<std::int32_t>(value)), 4);
            } else if (descr == "|b1") {
                data += static_cast<char>(value != 0.0 ? 1 : 0);
            } else {
                throw InvalidArgument("npy: dtype " + shown_value(descr) + " (libcam writes <f8, <i4, |b1 and <U)");
            }
        }
    }
    std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + python_shape(array.shape) + ", }";
    // numpy pads with spaces so that the data starts on a 64-byte boundary, then a line end.
    const std::size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    append_little_endian(out, header.size(), 2);
    return out + header + data;
}

std::string write_npz(const std::vector<std::pair<std::string, NpyArray>>& arrays) {
    std::vector<std::string> members;  // alive until the archive is closed: libzip reads them then
    members.reserve(arrays.size());
    for (const auto& [name, array] : arrays) members.push_back(format_npy(array));
    zip_error_t error;
    zip_error_init(&error);
    const std::unique_ptr<zip_source_t, SourceFreer> buffer(zip_source_buffer_create(nullptr, 0, 0, &error));
    if (!buffer) zip_failed("no buffer", &error);
    zip_t* opened = zip_open_from_source(buffer.get(), ZIP_TRUNCATE, &error);
    if (opened == nullptr) zip_failed("cannot open an archive in memory", &error);
    zip_source_keep(buffer.get());  // the archive's close would free it; its bytes are read after
    std::unique_ptr<zip_t, ZipWriteCloser> archive(opened);
    for (std::size_t i = 0; i < arrays.size(); ++i) {
        zip_source_t* member = zip_source_buffer(archive.get(), members[i].data(), members[i].size(), 0);
        const zip_int64_t index =
            member == nullptr ? -1 : zip_file_add(archive.get(), (arrays[i].first + ".npy").c_str(), member, ZIP_FL_ENC_UTF_8);
        if (index < 0) {
            if (member != nullptr) zip_source_free(member);
            throw Error("npz: cannot add " + arrays[i].first + ": " + zip_strerror(archive.get()));
        }
        zip_set_file_compression(archive.get(), static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 0);
    }
    if (zip_close(archive.get()) != 0) throw Error(std::string("npz: cannot write the archive: ") + zip_strerror(archive.get()));
    (void)archive.release();  // closed
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_source_stat(buffer.get(), &stat) != 0 || (stat.valid & ZIP_STAT_SIZE) == 0) {
        throw Error("npz: the archive's size is unknown");
    }
    std::string bytes(stat.size, '\0');
    if (zip_source_open(buffer.get()) != 0) throw Error("npz: cannot read the archive back");
    const zip_int64_t read = zip_source_read(buffer.get(), bytes.data(), stat.size);
    zip_source_close(buffer.get());
    if (read < 0 || static_cast<zip_uint64_t>(read) != stat.size) throw Error("npz: the archive read back short");
    return bytes;
}

}  // namespace libcam::detail
