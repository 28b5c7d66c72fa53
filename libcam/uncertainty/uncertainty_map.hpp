#pragma once
// The projection uncertainty over the whole image, and where it can be trusted: what
// `libcam uncertainty` and `libcam calibrate` report and `--heatmap` draws.
//
//   const SolvedCalibration solved = solved_calibration(read_observations(path), 0);
//   const ProjectionUncertainty uncertainty(solved);
//   const UncertaintyMap map = uncertainty_map(uncertainty, 60, kAtInfinity);
//   const UncertaintySummary summary = summarize(map, observed_region(solved));

#include <cstddef>
#include <vector>

#include "libcam/io/observations.hpp"
#include "libcam/uncertainty/projection_uncertainty.hpp"

namespace libcam {

// The calibration a file's observations describe, for one of its cameras: that camera,
// each of its views' solved pose, and the observations the tool counted (its inliers,
// with their weights). A board's corners only: a reconstruction's points are solved with
// the cameras, which this uncertainty (the boards' corners known) does not describe.
// Where the file holds a solve of several cameras sharing the boards' poses (mrcal's), the
// others and the shared poses come too (SolvedCalibration::others, frames). Throws
// FileError naming the file when it holds no board, or no counted observation of a camera.
SolvedCalibration solved_calibration(const ObservationSet& set, int camera);

// sigma_px at the centres of columns x rows equal tiles of the image, row by row
// (tile_centres); NaN where a pixel has no ray.
struct UncertaintyMap {
    ImageSize image;
    long columns = 0;
    long rows = 0;
    double distance = kAtInfinity;
    std::vector<Vec2> pixels;
    std::vector<double> sigma_px;
};

// `columns` tiles across (mrcal's default is 60), as many down as keeps them square.
// Throws InvalidArgument for columns below 2.
UncertaintyMap uncertainty_map(const ProjectionUncertainty& uncertainty, long columns, double distance);

// The region the observations covered: the convex hull of every observed pixel, in order
// around it.
std::vector<Vec2> observed_region(const SolvedCalibration& solved);
bool inside_region(const std::vector<Vec2>& region, const Vec2& pixel);

struct UncertaintySummary {
    double worst_observed_px = 0.0;  // the largest sigma at a tile centre inside the observed region
    std::size_t observed_tiles = 0;  // how many tile centres lie inside it
    double share_below_0_1 = 0.0;    // of every tile centre: sigma under 0.1 px
    double share_below_1 = 0.0;      // sigma under 1 px
};
UncertaintySummary summarize(const UncertaintyMap& map, const std::vector<Vec2>& region);

}  // namespace libcam
