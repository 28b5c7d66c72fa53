#include "libcam/geometry/pixel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "libcam/error.hpp"

namespace libcam {

namespace {

// (side - 1) index / (count - 1): the product is an exact integer, so the one rounding
// is the division's and the last index lands exactly on side - 1.
double grid_coordinate(long index, long count, long side) {
    return static_cast<double>(side - 1) * static_cast<double>(index) / static_cast<double>(count - 1);
}

// The indices in [0, count) whose coordinates fall in [low - slack, high + slack].
std::pair<long, long> index_range(double low, double high, double step, long count, double slack) {
    if (step == 0.0) return {0, 0};  // a side of one pixel: the one coordinate is 0
    return {std::max(0L, static_cast<long>(std::ceil(low / step - slack))),
            std::min(count - 1, static_cast<long>(std::floor(high / step + slack)))};
}

}  // namespace

void PixelGrid::validate(const char* field) const {
    if (columns < 2 || rows < 2) {
        throw InvalidArgument(std::string(field) + ": needs at least 2x2 points (both ends of each side), got " +
                              std::to_string(columns) + "x" + std::to_string(rows));
    }
}

double PixelGrid::x(long column, const ImageSize& size) const { return grid_coordinate(column, columns, size.width); }
double PixelGrid::y(long row, const ImageSize& size) const { return grid_coordinate(row, rows, size.height); }

double PixelGrid::step_x(const ImageSize& size) const {
    return static_cast<double>(size.width - 1) / static_cast<double>(columns - 1);
}
double PixelGrid::step_y(const ImageSize& size) const {
    return static_cast<double>(size.height - 1) / static_cast<double>(rows - 1);
}

std::vector<Vec2> PixelGrid::pixels(const ImageSize& size) const {
    std::vector<Vec2> out;
    out.reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
    for (long row = 0; row < rows; ++row) {
        for (long column = 0; column < columns; ++column) out.emplace_back(x(column, size), y(row, size));
    }
    return out;
}

std::vector<Vec2> PixelGrid::pixels_in(const ImageSize& size, const Vec2& low, const Vec2& high, double slack) const {
    const auto [column0, column1] = index_range(low.x(), high.x(), step_x(size), columns, slack);
    const auto [row0, row1] = index_range(low.y(), high.y(), step_y(size), rows, slack);
    std::vector<Vec2> out;
    for (long row = row0; row <= row1; ++row) {
        for (long column = column0; column <= column1; ++column) out.emplace_back(x(column, size), y(row, size));
    }
    return out;
}

std::vector<Vec2> tile_centres(const ImageSize& size, long columns, long rows) {
    const double tile_width = static_cast<double>(size.width) / static_cast<double>(columns);
    const double tile_height = static_cast<double>(size.height) / static_cast<double>(rows);
    std::vector<Vec2> out;
    out.reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
    for (long v = 0; v < rows; ++v) {
        for (long u = 0; u < columns; ++u) {
            out.emplace_back((static_cast<double>(u) + 0.5) * tile_width - 0.5,
                             (static_cast<double>(v) + 0.5) * tile_height - 0.5);
        }
    }
    return out;
}

}  // namespace libcam
