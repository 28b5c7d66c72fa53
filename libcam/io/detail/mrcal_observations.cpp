#include "libcam/io/detail/mrcal_observations.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/cameramodel_text.hpp"
#include "libcam/io/detail/npz_archive.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam::detail {

// Python's base64 b85 alphabet (RFC 1924's), for mrcal's optimization_inputs both ways.
constexpr std::string_view kBase85Alphabet =
    "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz!#$%&()*+-;<=>?@^_`{|}~";

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw FileError(where + ": " + what); }

std::string line_of(std::string_view text, std::size_t offset) {
    return "line " + std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// ---- the Python dict, scanned only as far as its optimization_inputs ---------------------

struct PyToken {
    enum Kind { End, String, Punct, Word } kind = End;
    std::string_view prefix;  // a string's letters before its quote: "b", "rb"
    std::string_view body;    // a string's text between its quotes, escapes undecoded
    char punct = 0;
    std::size_t offset = 0;
};

class PyScanner {
public:
    PyScanner(std::string_view text, const std::string& source) : text_(text), source_(source) {}

    PyToken next() {
        skip_space_and_comments();
        PyToken token;
        token.offset = at_;
        if (at_ >= text_.size()) return token;
        const char c = text_[at_];
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            const std::size_t start = at_;
            while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) {
                ++at_;
            }
            token.prefix = text_.substr(start, at_ - start);
            if (at_ < text_.size() && (text_[at_] == '\'' || text_[at_] == '"') && token.prefix.size() <= 2) {
                return string_token(token);
            }
            token.kind = PyToken::Word;
            return token;
        }
        if (c == '\'' || c == '"') return string_token(token);
        token.kind = PyToken::Punct;
        token.punct = c;
        ++at_;
        return token;
    }

private:
    void skip_space_and_comments() {
        while (at_ < text_.size()) {
            const char c = text_[at_];
            if (c == '#') {
                const std::size_t end = text_.find('\n', at_);
                at_ = end == std::string_view::npos ? text_.size() : end;
            } else if (std::isspace(static_cast<unsigned char>(c)) || (c == '\\' && next_is('\n'))) {
                ++at_;
            } else {
                return;
            }
        }
    }
    bool next_is(char c) const { return at_ + 1 < text_.size() && text_[at_ + 1] == c; }

    // A string literal from its opening quote: a backslash keeps the next character in the
    // string, raw or not, as Python's tokenizer does.
    PyToken string_token(PyToken token) {
        const char quote = text_[at_];
        const std::string_view triple(text_.data() + at_, std::min<std::size_t>(3, text_.size() - at_));
        const bool is_triple = triple.size() == 3 && triple[1] == quote && triple[2] == quote;
        const std::size_t quotes = is_triple ? 3 : 1;
        const std::size_t start = at_ + quotes;
        for (std::size_t i = start; i < text_.size(); ++i) {
            if (text_[i] == '\\') {
                ++i;
            } else if (text_[i] == '\n' && !is_triple) {
                break;
            } else if (text_[i] == quote && (!is_triple || text_.substr(i, 3) == std::string(3, quote))) {
                token.kind = PyToken::String;
                token.body = text_.substr(start, i - start);
                at_ = i + quotes;
                return token;
            }
        }
        fail(source_, line_of(text_, token.offset) + ": string literal not closed");
    }

    std::string_view text_;
    const std::string& source_;
    std::size_t at_ = 0;
};

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// A bytes literal's value from its body: Python's escapes (\\ \' \" \n \xhh \ooo,
// backslash-newline, and an unknown escape kept as written); a raw literal as written.
std::string decode_bytes_literal(const PyToken& token, const std::string& where) {
    const bool raw = token.prefix.find_first_of("rR") != std::string_view::npos;
    std::string bytes;
    const std::string_view body = token.body;
    for (std::size_t i = 0; i < body.size(); ++i) {
        const auto c = static_cast<unsigned char>(body[i]);
        if (c >= 0x80) fail(where, "byte " + std::to_string(i) + " of the bytes literal is not ASCII");
        if (c != '\\' || raw) {
            bytes += static_cast<char>(c);
            continue;
        }
        if (++i >= body.size()) fail(where, "the bytes literal ends in a lone backslash");
        const char e = body[i];
        static constexpr std::string_view kSimple = "\\'\"abfnrtv", kValues = "\\'\"\a\b\f\n\r\t\v";
        if (const std::size_t simple = kSimple.find(e); simple != std::string_view::npos) {
            bytes += kValues[simple];
        } else if (e == '\n') {
            // a line continuation: nothing
        } else if (e == 'x') {
            const int high = i + 1 < body.size() ? hex_value(body[i + 1]) : -1;
            const int low = i + 2 < body.size() ? hex_value(body[i + 2]) : -1;
            if (high < 0 || low < 0) fail(where, "\\x at byte " + std::to_string(i) + " lacks two hex digits");
            bytes += static_cast<char>(high * 16 + low);
            i += 2;
        } else if (e >= '0' && e <= '7') {
            int value = 0;
            std::size_t digits = 0;
            for (; digits < 3 && i + digits < body.size() && body[i + digits] >= '0' && body[i + digits] <= '7';
                 ++digits) {
                value = value * 8 + (body[i + digits] - '0');
            }
            if (value > 0xFF) fail(where, "octal escape \\" + std::string(body.substr(i, digits)) + " past 0o377");
            bytes += static_cast<char>(value);
            i += digits - 1;
        } else {
            bytes += '\\';
            bytes += e;
        }
    }
    return bytes;
}

// The value of the dict's 'optimization_inputs': its bytes literal, decoded (adjacent
// literals joined, as Python joins them).
// Moves the scanner past the ':' of the model's top-level key `key`; false where the model
// has no such key.
bool skip_to_top_level_value(PyScanner& scanner, std::string_view text, std::string_view key, const std::string& where) {
    int depth = 0;
    char before = 0;  // the punctuation before the current token
    for (PyToken token = scanner.next(); token.kind != PyToken::End; token = scanner.next()) {
        if (token.kind == PyToken::Punct) {
            if (token.punct == '{' || token.punct == '[' || token.punct == '(') ++depth;
            if (token.punct == '}' || token.punct == ']' || token.punct == ')') --depth;
            before = token.punct;
            continue;
        }
        const bool is_key =
            token.kind == PyToken::String && depth == 1 && (before == '{' || before == ',') && token.body == key;
        before = 0;
        if (!is_key) continue;
        const PyToken colon = scanner.next();
        if (colon.kind != PyToken::Punct || colon.punct != ':') fail(where, line_of(text, colon.offset) + ": no ':'");
        return true;
    }
    return false;
}

std::string optimization_inputs_literal(std::string_view text, const std::string& source) {
    PyScanner scanner(text, source);
    const std::string where = source + ": optimization_inputs";
    if (!skip_to_top_level_value(scanner, text, "optimization_inputs", where)) {
        fail(source, "no 'optimization_inputs' (the solve's observations), so no observations to read");
    }
    std::string bytes;
    PyToken value = scanner.next();
    for (; value.kind == PyToken::String; value = scanner.next()) {
        if (value.prefix.find_first_of("bB") == std::string_view::npos) {
            fail(where, line_of(text, value.offset) + ": not a bytes literal (b'...')");
        }
        bytes += decode_bytes_literal(value, where);
    }
    if (value.kind != PyToken::Punct || (value.punct != ',' && value.punct != '}')) {
        fail(where, line_of(text, value.offset) + ": not a bytes literal (b'...') followed by ',' or '}'");
    }
    return bytes;
}

// The camera of the solve the model is (its 'icam_intrinsics'), -1 where it names none.
int own_camera_of(std::string_view text, const std::string& source, std::size_t cameras) {
    PyScanner scanner(text, source);
    const std::string where = source + ": icam_intrinsics";
    if (!skip_to_top_level_value(scanner, text, "icam_intrinsics", where)) return -1;
    // The scanner has no numbers: the value's text up to the next ',' or '}'.
    const PyToken value = scanner.next();
    const std::size_t stop = std::min(text.find_first_of(",}", value.offset), text.size());
    std::string_view digits = text.substr(value.offset, stop - value.offset);
    while (!digits.empty() && std::isspace(static_cast<unsigned char>(digits.back()))) digits.remove_suffix(1);
    int camera = -1;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), camera);
    if (error != std::errc() || end != digits.data() + digits.size() || camera < 0 ||
        static_cast<std::size_t>(camera) >= cameras) {
        fail(where, line_of(text, value.offset) + ": expected the index of one of the solve's " +
                        std::to_string(cameras) + " cameras, got " + shown_value(digits));
    }
    return camera;
}

// Python's base64.b85decode (the RFC 1924 alphabet): each 5 characters are 4 bytes, big
// endian; a short last group is padded with '~' and its padding bytes dropped.
std::string base85_decode(std::string_view text, const std::string& where) {
    constexpr std::string_view kAlphabet = kBase85Alphabet;
    const std::size_t padding = (5 - text.size() % 5) % 5;
    std::string bytes;
    bytes.reserve((text.size() + padding) / 5 * 4);
    for (std::size_t group = 0; group < text.size(); group += 5) {
        std::uint64_t value = 0;
        for (std::size_t i = group; i < group + 5; ++i) {
            const std::size_t digit = i < text.size() ? kAlphabet.find(text[i]) : 84;
            if (digit == std::string_view::npos) {
                fail(where, "byte " + std::to_string(i) + " ('" + std::string(1, text[i]) + "') is not base85");
            }
            value = value * 85 + digit;
        }
        if (value > 0xFFFFFFFFu) fail(where, "base85 group at byte " + std::to_string(group) + " overflows 32 bits");
        for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((value >> shift) & 0xFF);
    }
    bytes.resize(bytes.size() - padding);
    return bytes;
}

// ---- the arrays ---------------------------------------------------------------------------

constexpr std::size_t kAny = static_cast<std::size_t>(-1);

std::string shape_text(const std::vector<std::size_t>& shape) {
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) {
        text += (i ? ", " : "") + (shape[i] == kAny ? std::string("N") : std::to_string(shape[i]));
    }
    return text + (shape.size() == 1 ? ",)" : ")");
}

struct Inputs {
    std::map<std::string, NpyArray> arrays;
    std::string where;  // "<file>: optimization_inputs"

    std::string at(std::string_view key) const { return where + ": " + std::string(key); }

    // The array, or nullptr where it is absent or None (mrcal stores None as '').
    const NpyArray* find(std::string_view key) const {
        const auto found = arrays.find(std::string(key));
        if (found == arrays.end() || (found->second.is_text() && found->second.text.empty())) return nullptr;
        return &found->second;
    }
    const NpyArray& required(std::string_view key) const {
        const NpyArray* array = find(key);
        if (array == nullptr) fail(at(key), "missing");
        return *array;
    }
    // A numeric array of the shape (kAny: any count there).
    const NpyArray* numeric(std::string_view key, const std::vector<std::size_t>& shape, bool needed) const {
        const NpyArray* array = needed ? &required(key) : find(key);
        if (array == nullptr) return nullptr;
        bool fits = !array->is_text() && array->shape.size() == shape.size();
        for (std::size_t i = 0; fits && i < shape.size(); ++i) fits = shape[i] == kAny || shape[i] == array->shape[i];
        if (!fits) {
            fail(at(key), "shape " + shape_text(array->shape) + " of " + array->descr + ", expected " +
                              shape_text(shape) + " of numbers");
        }
        return array;
    }
    std::string text(std::string_view key) const {
        const NpyArray& array = required(key);
        if (!array.is_text()) fail(at(key), "dtype '" + array.descr + "', expected a string");
        return array.text;
    }
};

// An index the file gives, checked to be a whole number in [lowest, count).
int index_in(double value, int lowest, std::size_t count, const std::string& where, const std::string& what) {
    if (!(value >= lowest && value < static_cast<double>(count)) || value != std::floor(value)) {
        fail(where, what + " " + format_number(value) + " is not one of the " + std::to_string(count));
    }
    return static_cast<int>(value);
}

// ---- the cameras --------------------------------------------------------------------------

// The lens model of mrcal's name, and the values its name holds (the splined model's
// order, Nx, Ny, fov_x_deg; CAHVORE's linearity): matched against each model's unconfigured
// name in the lens table, whose "..." stand for the values.
std::optional<std::pair<LensType, std::vector<double>>> lens_of_mrcal_name(std::string_view name) {
    for (const LensInfo& info : lens_models()) {
        if (info.mrcal.empty()) continue;
        const std::string pattern = mrcal_model_name(info.type);
        std::vector<double> values;
        std::size_t at = 0, from = 0;
        bool matches = true;
        while (matches) {
            const std::size_t dots = pattern.find("...", from);
            const std::string_view literal = std::string_view(pattern).substr(from, dots - from);
            matches = name.substr(at).starts_with(literal);
            at += literal.size();
            if (!matches || dots == std::string::npos) break;
            from = dots + 3;
            const std::size_t next = pattern.find("...", from);
            const std::string_view after = std::string_view(pattern).substr(from, next - from);
            const std::size_t end = after.empty() ? name.size() : name.find(after, at);
            double value = 0.0;
            const auto parsed = std::from_chars(name.data() + at, name.data() + std::min(end, name.size()), value);
            matches = end != std::string_view::npos && end > at && parsed.ptr == name.data() + end &&
                      parsed.ec == std::errc();
            values.push_back(value);
            at = end;
        }
        if (matches && at == name.size()) return std::make_pair(info.type, values);
    }
    return std::nullopt;
}

// An image side, checked to be a whole number that fits a long before it becomes one (the
// camera's validation checks its range).
long side_of(double value, const Inputs& inputs, std::size_t camera) {
    if (!(std::abs(value) < 1e15) || value != std::floor(value)) {
        fail(inputs.at("imagersizes"), "camera " + std::to_string(camera) + ": size " + format_number(value));
    }
    return static_cast<long>(value);
}

std::vector<ObservedCamera> cameras_of(const Inputs& inputs) {
    const std::string lensmodel = inputs.text("lensmodel");
    const auto lens = lens_of_mrcal_name(lensmodel);
    if (!lens) fail(inputs.at("lensmodel"), shown_value(lensmodel, '"') + " is not an mrcal model libcam reads");
    const NpyArray& intrinsics = *inputs.numeric("intrinsics", {kAny, kAny}, true);
    const std::size_t count = intrinsics.shape[0], per_camera = intrinsics.shape[1];
    const NpyArray& sizes = *inputs.numeric("imagersizes", {count, 2}, true);
    if (per_camera < 4) fail(inputs.at("intrinsics"), std::to_string(per_camera) + " values per camera, not fx fy cx cy...");
    const int leading = lens_info(lens->first).mrcal_in_name.leading;
    std::vector<ObservedCamera> cameras;
    for (std::size_t c = 0; c < count; ++c) {
        const double* k = intrinsics.numbers.data() + c * per_camera;
        Camera camera;
        camera.size = {side_of(sizes.numbers[2 * c], inputs, c), side_of(sizes.numbers[2 * c + 1], inputs, c)};
        camera.intrinsics = {.fx = k[0], .fy = k[1], .cx = k[2], .cy = k[3]};
        camera.lens.type = lens->first;
        const std::vector<double>& named = lens->second;
        camera.lens.coefficients.assign(named.begin(), named.begin() + leading);
        camera.lens.coefficients.insert(camera.lens.coefficients.end(), k + 4, k + per_camera);
        camera.lens.coefficients.insert(camera.lens.coefficients.end(), named.begin() + leading, named.end());
        cameras.push_back({std::to_string(c), std::move(camera)});
    }
    return cameras;
}

// The poses of an (N, 6) array of mrcal's rt (Rodrigues rotation, then translation).
std::vector<Pose> poses_of(const NpyArray* rt) {
    std::vector<Pose> poses;
    if (rt == nullptr) return poses;
    for (std::size_t i = 0; i < rt->shape[0]; ++i) {
        const double* v = rt->numbers.data() + 6 * i;
        poses.push_back(Pose::from_rvec(Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])));
    }
    return poses;
}

// A camera's pose from the reference frame: its extrinsics, or the identity for the
// reference camera (index -1).
Pose camera_from_reference(const std::vector<Pose>& extrinsics, int index) {
    return index < 0 ? Pose{} : extrinsics[static_cast<std::size_t>(index)];
}

// ---- the board and the points -------------------------------------------------------------

// The board's corners as mrcal's project() places them: corner (row i, column j) at
// (j, i) * spacing, lifted by the warp's two parabolas, 4 k r (1 - r) across each axis.
void add_board(const Inputs& inputs, const NpyArray& observed, ObservationSet& set) {
    ObservedBoard board;
    board.height = static_cast<int>(observed.shape[1]);
    board.width = static_cast<int>(observed.shape[2]);
    const NpyArray& spacing = *inputs.numeric("calibration_object_spacing", {}, true);
    board.spacing = spacing.numbers[0];
    if (const NpyArray* warp = inputs.numeric("calobject_warp", {2}, false)) {
        board.warp = Vec2(warp->numbers[0], warp->numbers[1]);
        if (board.width < 2 || board.height < 2) {
            fail(inputs.at("calobject_warp"), "a warp on a board of " + std::to_string(board.width) + " x " +
                                                  std::to_string(board.height) + " corners (mrcal needs 2 x 2)");
        }
        const NpyArray* solved = inputs.numeric("do_optimize_calobject_warp", {}, false);
        board.warp_solved = solved != nullptr && solved->numbers[0] != 0.0;
    }
    for (int i = 0; i < board.height; ++i) {
        for (int j = 0; j < board.width; ++j) {
            Vec3 corner(j * board.spacing, i * board.spacing, 0.0);
            if (board.warp != Vec2::Zero()) {
                const double xr = double(j) / (board.width - 1), yr = double(i) / (board.height - 1);
                corner.z() += board.warp.x() * 4.0 * xr * (1.0 - xr);
                corner.z() += board.warp.y() * 4.0 * yr * (1.0 - yr);
            }
            set.points.push_back(corner);
            set.point_ids.push_back(i * board.width + j);
        }
    }
    set.board = board;
}

// One observation per (x, y, weight) triple; mrcal's outliers have weight <= 0
// (mrcal.c's markOutliers, mrcal.residuals_chessboard).
Observation observation_of(const double* xyw, int view, int point) {
    return {.view = view, .point = point, .pixel = Vec2(xyw[0], xyw[1]), .weight = xyw[2], .inlier = xyw[2] > 0.0};
}

void add_board_observations(const Inputs& inputs, const std::vector<Pose>& frames,
                            const std::vector<Pose>& extrinsics, ObservationSet& set) {
    const NpyArray* observed = inputs.numeric("observations_board", {kAny, kAny, kAny, 3}, false);
    if (observed == nullptr || observed->shape[0] == 0) return;
    const std::size_t count = observed->shape[0];
    const std::string indices_key = "indices_frame_camintrinsics_camextrinsics";
    const NpyArray& indices = *inputs.numeric(indices_key, {count, 3}, true);
    add_board(inputs, *observed, set);
    const std::size_t corners = set.points.size();
    for (std::size_t n = 0; n < count; ++n) {
        const std::string row = inputs.at(indices_key) + ": row " + std::to_string(n);
        const int frame = index_in(indices.numbers[3 * n], 0, frames.size(), row, "frame");
        const int camera = index_in(indices.numbers[3 * n + 1], 0, set.cameras.size(), row, "camera intrinsics");
        const int extrinsic = index_in(indices.numbers[3 * n + 2], -1, extrinsics.size(), row, "camera extrinsics");
        const Pose pose = camera_from_reference(extrinsics, extrinsic).after(frames[static_cast<std::size_t>(frame)]);
        // Named as mrcal indexes board observations: by frame, and camera where there are several.
        std::string name = "frame " + std::to_string(frame);
        if (set.cameras.size() > 1) name += " camera " + std::to_string(camera);
        set.views.push_back({std::move(name), camera, pose, frame, extrinsic >= 0});
        for (std::size_t corner = 0; corner < corners; ++corner) {
            const double* xyw = observed->numbers.data() + 3 * (n * corners + corner);
            set.observations.push_back(observation_of(xyw, static_cast<int>(set.views.size() - 1), int(corner)));
        }
    }
}

// Discrete points: one view per camera (intrinsics and extrinsics) that sees them, in the
// reference frame.
void add_point_observations(const Inputs& inputs, const std::vector<Pose>& extrinsics, ObservationSet& set) {
    const NpyArray* observed = inputs.numeric("observations_point", {kAny, 3}, false);
    if (observed == nullptr || observed->shape[0] == 0) return;
    const std::size_t count = observed->shape[0];
    const std::string indices_key = "indices_point_camintrinsics_camextrinsics";
    const NpyArray& indices = *inputs.numeric(indices_key, {count, 3}, true);
    const NpyArray& points = *inputs.numeric("points", {kAny, 3}, true);
    const auto first_point = static_cast<int>(set.points.size());
    for (std::size_t p = 0; p < points.shape[0]; ++p) {
        set.points.emplace_back(points.numbers[3 * p], points.numbers[3 * p + 1], points.numbers[3 * p + 2]);
        set.point_ids.push_back(static_cast<std::int64_t>(p));
    }
    std::map<std::pair<int, int>, int> view_of_camera;
    for (std::size_t n = 0; n < count; ++n) {
        const std::string row = inputs.at(indices_key) + ": row " + std::to_string(n);
        const int point = index_in(indices.numbers[3 * n], 0, points.shape[0], row, "point");
        const int camera = index_in(indices.numbers[3 * n + 1], 0, set.cameras.size(), row, "camera intrinsics");
        const int extrinsic = index_in(indices.numbers[3 * n + 2], -1, extrinsics.size(), row, "camera extrinsics");
        const auto [found, added] = view_of_camera.try_emplace({camera, extrinsic}, int(set.views.size()));
        if (added) {
            set.views.push_back({"camera " + std::to_string(camera) + " extrinsics " + std::to_string(extrinsic) +
                                     " (points)",
                                 camera, camera_from_reference(extrinsics, extrinsic)});
        }
        set.observations.push_back(observation_of(observed->numbers.data() + 3 * n, found->second, first_point + point));
    }
}

}  // namespace

ObservationSet parse_mrcal_observations(std::string_view text, const std::string& source) {
    check_cameramodel_lexically(text, source);  // as the camera's reader does: one idea of a .cameramodel
    Inputs inputs;
    inputs.where = source + ": optimization_inputs";
    const std::string encoded = optimization_inputs_literal(text, source);
    inputs.arrays = read_npz(base85_decode(encoded, inputs.where), inputs.where);
    ObservationSet set;
    set.tool = ObservationTool::Mrcal;
    set.source = source;
    set.cameras = cameras_of(inputs);
    const std::vector<Pose> frames = poses_of(inputs.numeric("frames_rt_toref", {kAny, 6}, false));
    const std::vector<Pose> extrinsics = poses_of(inputs.numeric("extrinsics_rt_fromref", {kAny, 6}, false));
    add_board_observations(inputs, frames, extrinsics, set);
    if (set.cameras.size() > 1) {
        set.frames = frames;
        set.own_camera = own_camera_of(text, source, set.cameras.size());
    }
    add_point_observations(inputs, extrinsics, set);
    if (set.observations.empty()) {
        fail(inputs.where, "observations_board and observations_point hold no observation (the solve's inputs "
                           "were saved without them): nothing to reproject");
    }
    return set;
}

ObservationSet read_mrcal_observations(const std::filesystem::path& file, std::string_view text,
                                       const ObservationReadOptions&) {
    // The file's own camera first, read and checked as `libcam info` reads it (libmrcal's
    // parser, libcam::interop): a file that reader refuses is refused here with its line.
    (void)parse_camera_set(text, CameraFormat::Cameramodel, file.string());
    return parse_mrcal_observations(text, file.string());
}

// Python's base64.b85encode (RFC 1924's alphabet): each 4 bytes, big endian, as 5
// characters; the last group padded with zero bytes and cut to its length plus one.
std::string base85_encode(std::string_view bytes) {
    constexpr std::string_view kAlphabet = kBase85Alphabet;
    std::string out;
    out.reserve((bytes.size() + 3) / 4 * 5);
    for (std::size_t group = 0; group < bytes.size(); group += 4) {
        std::uint32_t value = 0;
        for (std::size_t i = group; i < group + 4; ++i) {
            value = (value << 8) | (i < bytes.size() ? static_cast<unsigned char>(bytes[i]) : 0u);
        }
        char digits[5];
        for (int d = 4; d >= 0; --d, value /= 85) digits[d] = kAlphabet[value % 85];
        const std::size_t kept = std::min<std::size_t>(bytes.size() - group, 4) + 1;
        out.append(digits, kept);
    }
    return out;
}

}  // namespace libcam::detail
