#pragma once
// The calibration board a user names on the command line (`--board SPEC`):
//
//   chessboard:CxR:SQUARE                 C x R inner corners, squares SQUARE metres wide
//   charuco:CxR:SQUARE:MARKER:DICT        C x R squares, markers MARKER metres wide, from
//                                         OpenCV's dictionary DICT (DICT_5X5_100, ...)
//
// A ChArUco board is laid out as OpenCV 4.6's cv::aruco::CharucoBoard::create lays it out:
// its (C-1) x inner corners numbered row by row. The board's frame: corner (i, j)
// of a chessboard (column i, row j; index j * C + i) at (i s, j s, 0); ChArUco corner k
// at OpenCV's chessboardCorners[k], ((k mod (C-1)) + 1, (k div (C-1)) + 1, 0) s.
// Parsing needs no OpenCV (the spec's parser is fuzzed on its own).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/geometry/vector_math.hpp"

namespace libcam {

enum class BoardKind { Chessboard, Charuco };

struct BoardSpec {
    BoardKind kind = BoardKind::Chessboard;
    int columns = 0;  // inner corners (chessboard) or squares (ChArUco) across
    int rows = 0;
    double square = 0.0;  // metres
    double marker = 0.0;  // ChArUco only
    std::string dictionary;  // ChArUco only: OpenCV's name, e.g. DICT_5X5_100
    int dictionary_id = 0;   // cv::aruco::PREDEFINED_DICTIONARY_NAME's value

    // Corners the whole board has (C x R, or (C-1) x for ChArUco).
    std::size_t corner_count() const;
    // Each corner's position on the board, by its index (see above).
    std::vector<Vec3> corner_points() const;
    // The spec as the user writes it.
    std::string text() const;
};

// Throws InvalidArgument "board 'SPEC': PART: what is wrong" for a spec that does not
// parse, naming the part (the kind, the size, the square, the marker, the dictionary).
BoardSpec parse_board_spec(std::string_view spec);

// OpenCV's predefined ArUco dictionaries by name, with cv::aruco's enumeration value.
struct ArucoDictionaryName {
    std::string_view name;
    int id;
    int markers;  // how many markers it holds
};
const std::vector<ArucoDictionaryName>& aruco_dictionaries();

}  // namespace libcam
