#include "libcam/calibrate/board.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// Far past any printed board, small enough that C x R corners cannot overflow anything.
constexpr int kMaxSide = 1000;

[[noreturn]] void fail(std::string_view spec, std::string_view part, const std::string& what) {
    throw InvalidArgument("board " + shown_value(spec) + ": " + std::string(part) + ": " + what);
}

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    std::size_t begin = 0;
    while (true) {
        const std::size_t end = text.find(separator, begin);
        parts.push_back(text.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin));
        if (end == std::string_view::npos) return parts;
        begin = end + 1;
    }
}

int parse_count(std::string_view spec, std::string_view part, std::string_view text, int least) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size() || value < least || value > kMaxSide) {
        fail(spec, part, "expected a whole number from " + std::to_string(least) + " to " + std::to_string(kMaxSide) +
                             ", got " + shown_value(text));
    }
    return value;
}

double parse_length(std::string_view spec, std::string_view part, std::string_view text) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value) || !(value > 0.0)) {
        fail(spec, part, "expected a length in metres above 0, got " + shown_value(text));
    }
    return value;
}

// "CxR", each at least `least`.
void parse_size(std::string_view spec, std::string_view text, int least, BoardSpec& board) {
    const std::size_t x = text.find('x');
    if (x == std::string_view::npos) fail(spec, "size", "expected COLUMNSxROWS (9x6), got " + shown_value(text));
    board.columns = parse_count(spec, "size", text.substr(0, x), least);
    board.rows = parse_count(spec, "size", text.substr(x + 1), least);
}

const ArucoDictionaryName& dictionary_named(std::string_view spec, std::string_view name) {
    for (const ArucoDictionaryName& entry : aruco_dictionaries()) {
        if (entry.name == name) return entry;
    }
    std::string names;
    for (const ArucoDictionaryName& entry : aruco_dictionaries()) names += (names.empty() ? "" : ", ") + std::string(entry.name);
    fail(spec, "dictionary", shown_value(name) + " is not one of OpenCV's: " + names);
}

}  // namespace

const std::vector<ArucoDictionaryName>& aruco_dictionaries() {
    // cv::aruco::PREDEFINED_DICTIONARY_NAME (OpenCV 4.6), in its order.
    static const std::vector<ArucoDictionaryName> kDictionaries = {
        {"DICT_4X4_50", 0, 50},           {"DICT_4X4_100", 1, 100},         {"DICT_4X4_250", 2, 250},
        {"DICT_4X4_1000", 3, 1000},       {"DICT_5X5_50", 4, 50},           {"DICT_5X5_100", 5, 100},
        {"DICT_5X5_250", 6, 250},         {"DICT_5X5_1000", 7, 1000},       {"DICT_6X6_50", 8, 50},
        {"DICT_6X6_100", 9, 100},         {"DICT_6X6_250", 10, 250},        {"DICT_6X6_1000", 11, 1000},
        {"DICT_7X7_50", 12, 50},          {"DICT_7X7_100", 13, 100},        {"DICT_7X7_250", 14, 250},
        {"DICT_7X7_1000", 15, 1000},      {"DICT_ARUCO_ORIGINAL", 16, 1024}, {"DICT_APRILTAG_16h5", 17, 30},
        {"DICT_APRILTAG_25h9", 18, 35},   {"DICT_APRILTAG_36h10", 19, 2320}, {"DICT_APRILTAG_36h11", 20, 587},
    };
    return kDictionaries;
}

BoardSpec parse_board_spec(std::string_view spec) {
    const std::vector<std::string_view> parts = split(spec, ':');
    BoardSpec board;
    if (parts[0] == "chessboard") {
        if (parts.size() != 3) {
            fail(spec, "form", "expected chessboard:CxR:SQUARE (inner corners, square side in metres), got " +
                                   std::to_string(parts.size()) + " parts");
        }
        board.kind = BoardKind::Chessboard;
        parse_size(spec, parts[1], 3, board);
        board.square = parse_length(spec, "square", parts[2]);
        return board;
    }
    if (parts[0] == "charuco") {
        if (parts.size() != 5) {
            fail(spec, "form", "expected charuco:CxR:SQUARE:MARKER:DICT (squares, their side and the markers' in "
                               "metres, OpenCV's dictionary name), got " + std::to_string(parts.size()) + " parts");
        }
        board.kind = BoardKind::Charuco;
        parse_size(spec, parts[1], 3, board);
        board.square = parse_length(spec, "square", parts[2]);
        board.marker = parse_length(spec, "marker", parts[3]);
        if (!(board.marker < board.square)) {
            fail(spec, "marker", "a marker (" + format_number(board.marker) + " m) must be smaller than its square (" +
                                     format_number(board.square) + " m)");
        }
        const ArucoDictionaryName& dictionary = dictionary_named(spec, parts[4]);
        const int markers = board.columns * board.rows / 2;
        if (markers > dictionary.markers) {
            fail(spec, "dictionary", std::string(dictionary.name) + " holds " + std::to_string(dictionary.markers) +
                                         " markers, a " + std::to_string(board.columns) + "x" +
                                         std::to_string(board.rows) + " board needs " + std::to_string(markers));
        }
        board.dictionary = std::string(dictionary.name);
        board.dictionary_id = dictionary.id;
        return board;
    }
    fail(spec, "kind", "expected chessboard or charuco, got " + shown_value(parts[0]));
}

std::size_t BoardSpec::corner_count() const {
    const int inset = kind == BoardKind::Charuco ? 1 : 0;
    return static_cast<std::size_t>(columns - inset) * static_cast<std::size_t>(rows - inset);
}

std::vector<Vec3> BoardSpec::corner_points() const {
    // A ChArUco board's corners are the inner corners of its squares: one square in.
    const int inset = kind == BoardKind::Charuco ? 1 : 0;
    const int across = columns - inset, down = rows - inset;
    std::vector<Vec3> points;
    points.reserve(corner_count());
    for (int j = 0; j < down; ++j) {
        for (int i = 0; i < across; ++i) points.emplace_back((i + inset) * square, (j + inset) * square, 0.0);
    }
    return points;
}

std::string BoardSpec::text() const {
    std::string out = (kind == BoardKind::Charuco ? "charuco:" : "chessboard:") + std::to_string(columns) + "x" +
                      std::to_string(rows) + ":" + format_number(square);
    if (kind == BoardKind::Charuco) out += ":" + format_number(marker) + ":" + dictionary;
    return out;
}

}  // namespace libcam
