// libcam's chessboard corners beside mrgingham's (mrcal's own chessboard finder, Debian's
// mrgingham program) on the same images: 10x10-corner boards (the only grid mrgingham
// finds by default) rendered through a known lens, both sets of corners measured against
// the corners the lens puts there. Skipped, saying so, when mrgingham is not installed.
//
// mrgingham reports pixels with the top-left pixel's centre at (0, 0), as OpenCV and
// libcam do; a convention error between the two would show as a mean offset of half a
// pixel on each axis.

#include <catch2/catch.hpp>

#include <map>
#include <sstream>
#include <string>

#include "libcam/calibrate/detect.hpp"
#include "synthetic_sets.hpp"
#include "shell_output.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

bool mrgingham_installed() { return std::system("mrgingham --help > /dev/null 2>&1") == 0; }

// mrgingham's corners for each image it was given: its output is one line per corner,
// "image x y level", or "image - -" for an image without a board.
std::map<std::string, std::vector<Vec2>> mrgingham_corners(const std::vector<std::string>& images) {
    std::string command = "mrgingham --gridn 10 --jobs 1";
    for (const std::string& image : images) command += " '" + image + "'";
    std::map<std::string, std::vector<Vec2>> corners;
    std::istringstream lines(shell_output(command));
    for (std::string line; std::getline(lines, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string image, x, y;
        words >> image >> x >> y;
        if (x == "-") {
            corners[image];
            continue;
        }
        corners[image].emplace_back(std::stod(x), std::stod(y));
    }
    return corners;
}

// Each found corner against the nearest true corner (both finders may number the grid
// from any of its ends): the mean offset and the RMS about the truth.
struct Offset {
    Vec2 mean = Vec2::Zero();
    double sum_squared = 0.0;
    std::size_t count = 0;
    double rms() const { return std::sqrt(sum_squared / static_cast<double>(count)); }
};

void add_offsets(Offset& offset, const std::vector<Vec2>& found, const std::vector<Vec2>& truth) {
    for (const Vec2& corner : found) {
        double nearest = std::numeric_limits<double>::infinity();
        Vec2 difference = Vec2::Zero();
        for (const Vec2& true_corner : truth) {
            if ((corner - true_corner).norm() < nearest) {
                nearest = (corner - true_corner).norm();
                difference = corner - true_corner;
            }
        }
        REQUIRE(nearest < 2.0);  // a found corner is a corner of the board
        offset.mean += difference;
        offset.sum_squared += difference.squaredNorm();
        ++offset.count;
    }
}

}  // namespace

TEST_CASE("Chessboard corners: libcam's and mrgingham's on the same images, each against the truth",
          "[calibrate][detect][mrgingham]") {
    if (!mrgingham_installed()) {
        WARN("skipped: mrgingham is not installed (Debian's mrgingham package): nothing to compare with");
        return;
    }
    const BoardSpec board = parse_board_spec("chessboard:10x10:0.02");
    const Camera truth = opencv5_truth();
    // Facing the camera, and turned as a calibration's views are; near enough that the
    // squares are 20 to 40 pixels across, as in a real calibration at this size.
    const std::vector<PoseSpec> poses = {{{0.0, 0.0, 0.45}, {0.0, 0.0, 0.05}},
                                         {{-0.05, -0.03, 0.45}, {0.4, -0.3, 0.1}},
                                         {{0.05, 0.03, 0.45}, {-0.3, 0.4, -0.1}},
                                         {{0.0, 0.0, 0.4}, {0.5, 0.0, 0.0}}};
    const std::vector<SyntheticView> views = render_views(truth, board, chessboard_texture(board), poses);
    REQUIRE(views.size() == poses.size());

    TempDir folder;
    std::vector<std::string> paths;
    for (std::size_t v = 0; v < views.size(); ++v) {
        paths.push_back((folder.path() / ("view" + std::to_string(v) + ".png")).string());
        REQUIRE(cv::imwrite(paths.back(), views[v].image));
    }
    const std::map<std::string, std::vector<Vec2>> theirs = mrgingham_corners(paths);

    Offset libcam_offset, mrgingham_offset;
    std::size_t both_found = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
        Camera posed = truth;
        posed.pose = views[v].pose;
        const std::vector<Vec2> true_corners_here = true_corners(posed, board);
        const BoardDetection ours = detect_board(paths[v], board);
        const auto found = theirs.find(paths[v]);
        if (!ours.rejected.empty() || found == theirs.end() || found->second.size() != 100) continue;
        ++both_found;
        add_offsets(libcam_offset, ours.pixels, true_corners_here);
        add_offsets(mrgingham_offset, found->second, true_corners_here);
    }
    REQUIRE(both_found >= 3);
    libcam_offset.mean /= static_cast<double>(libcam_offset.count);
    mrgingham_offset.mean /= static_cast<double>(mrgingham_offset.count);
    INFO("libcam: mean offset " << libcam_offset.mean.transpose() << ", rms " << libcam_offset.rms());
    INFO("mrgingham: mean offset " << mrgingham_offset.mean.transpose() << ", rms " << mrgingham_offset.rms());
    // Both in one pixel convention: neither is half a pixel off the truth.
    CHECK(libcam_offset.mean.norm() < 0.05);
    CHECK(mrgingham_offset.mean.norm() < 0.1);
    // libcam's corners (findChessboardCornersSB, refined by cornerSubPix) at least as
    // close to the truth as mrgingham's.
    CHECK(libcam_offset.rms() <= mrgingham_offset.rms() * 1.05);
}
