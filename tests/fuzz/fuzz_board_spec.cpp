// libFuzzer target for `--board SPEC` (calibrate/board.cpp): every input is either a
// board whose corners can be laid out (counts and lengths in range, the dictionary large
// enough) or refused with one line of InvalidArgument; nothing else.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "libcam/calibrate/board.hpp"
#include "libcam/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const libcam::BoardSpec board = libcam::parse_board_spec(text);
        if (board.columns < 3 || board.rows < 3 || !(board.square > 0) || !std::isfinite(board.square)) std::abort();
        if (board.kind == libcam::BoardKind::Charuco && !(board.marker > 0 && board.marker < board.square)) std::abort();
        if (board.corner_points().size() != board.corner_count()) std::abort();
        if (libcam::parse_board_spec(board.text()).text() != board.text()) std::abort();  // what it prints reads back
    } catch (const libcam::InvalidArgument& error) {
        if (std::string(error.what()).find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
