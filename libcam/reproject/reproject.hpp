#pragma once
// Reprojection of a tool's own observations (io/observations.hpp) through libcam's
// projection of the cameras and poses the tool solved: every observation's residual, the
// statistics `libcam reproject` prints, each number the file stored beside libcam's
// recomputation of it, and a check of the pixel-centre convention.
//
//   const ObservationSet set = read_observations("out_camera_data.yml");
//   const Reprojection r = reproject(set);
//   r.summary.stats.rms_px  // == the file's avg_reprojection_error, to its storage
//
// A residual is projected minus observed, in pixels. Observations are counted in the
// statistics only when they are inliers whose point projects (in front of the camera,
// inside the lens's valid domain) and whose observed pixel lies on the image; the others
// are counted apart by reason.
//
// The numbers a file stored are recomputed by its tool's rule, not libcam's: a tool
// evaluates its model's formula without a bound on the valid domain (OpenCV's
// projectPoints counts every corner), so a point past the domain counts there with the
// pixel the formula gives all the same.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "libcam/io/observations.hpp"
#include "libcam/stats/error_stats.hpp"

namespace libcam {

enum class ResidualStatus {
    Counted,        // in the statistics
    Outlier,        // the tool marked it so (mrcal's negative weight)
    BehindCamera,   // the point is behind the camera (z <= 0) and the lens does not see it
    OutsideDomain,  // past the lens's valid domain (where its distortion folds over)
    OutsideImage,   // the observed pixel is off the image
};
std::string_view to_string(ResidualStatus status);

struct ObservationResidual {
    Vec2 projected = Vec2::Zero();  // OpenCV pixels; NaN where the point does not project
    Vec2 residual = Vec2::Zero();   // projected - observed
    double error_px = 0.0;          // |residual|; +inf where the point does not project
    ResidualStatus status = ResidualStatus::Counted;
    // Past the lens's valid domain (OutsideDomain): the pixel the model's formula gives
    // there all the same, what a tool that evaluates it without that bound computed; NaN
    // otherwise, and where even the formula gives no finite pixel.
    Vec2 past_domain_projected = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
};

// The statistics of some counted residuals.
struct ResidualStats {
    ErrorStats stats;      // count, median, p99, max, rms of |d|
    double mean_px = 0.0;  // mean |d|
    Vec2 bias = Vec2::Zero();  // mean d: a constant shift of every projection
    // sqrt(mean |w d|^2), where the tool weights observations; nullopt where it does not
    std::optional<double> weighted_rms_px;
};

struct GroupResiduals {
    std::string name;  // the view's or camera's name
    ResidualStats residuals;
};

// A number the file stored, and libcam's value of it from the residuals.
struct ReportedComparison {
    ReportedNumber reported;
    double recomputed = 0.0;
};

// Per view or per point: the file's numbers against libcam's, where the file stores them.
struct PerItemComparison {
    std::size_t compared = 0;       // items with both a stored and a recomputed number
    double max_abs_difference = 0.0;
    std::string worst_item;         // the view's name or the point's id where it is largest
};

// Whether the observations were written in the other pixel-centre convention: the shift
// that, added to every projection, minimises the RMS (minus the mean residual), and
// whether the data fit a half-pixel shift markedly better than none.
struct ConventionCheck {
    Vec2 best_shift_px = Vec2::Zero();
    double rms_px = 0.0;           // as the file is
    double rms_half_shift_px = 0.0;  // with the half-pixel shift nearest best_shift_px
    bool suspect = false;
};

struct ReprojectionSummary {
    ResidualStats all;                  // every counted observation
    std::vector<GroupResiduals> per_view;    // in the file's order of views
    std::vector<GroupResiduals> per_camera;  // in the file's order of cameras
    std::size_t outliers = 0;
    std::size_t behind_camera = 0;
    std::size_t outside_domain = 0;
    std::size_t outside_image = 0;
    // The stored numbers against libcam's recomputation by the tool's rule (above), and how
    // many observations past the valid domain that rule counts which libcam's own
    // statistics set apart.
    std::vector<ReportedComparison> reported;
    std::optional<PerItemComparison> per_view_reported;   // OpenCV's per-view errors
    std::optional<PerItemComparison> per_point_reported;  // COLMAP's ERROR column
    std::size_t reported_past_domain = 0;
    ConventionCheck convention;
};

struct Reprojection {
    std::vector<ObservationResidual> residuals;  // one per observation, in the set's order
    ReprojectionSummary summary;
};

// Every observation's residual through libcam's projection, and their summary.
// `threads`: how many threads project (1: this one).
Reprojection reproject(const ObservationSet& set, int threads = 1);

// The statistics of the counted residuals among `indices` (all when empty) of `set`.
ResidualStats residual_stats(const ObservationSet& set, const std::vector<ObservationResidual>& residuals,
                             const std::vector<std::size_t>& indices);

// The indices of the n observations with the largest counted error, largest first.
std::vector<std::size_t> worst_observations(const std::vector<ObservationResidual>& residuals, std::size_t n);

}  // namespace libcam
