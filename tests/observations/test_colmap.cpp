// COLMAP models' observations (io/detail/colmap_observations.hpp): the real models of
// ../shared/real-data (SOURCES.md section 1 gives their counts and the numbers COLMAP
// stored and model_analyzer printed), and small models written here whose numbers are
// worked by hand.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "libcam/check/reproject.hpp"
#include "libcam/error.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

namespace {

using namespace libcam;
using libcam::test::real_data_path;
using libcam::test::real_data_present;

// What SOURCES.md says of one model.
struct RealModel {
    const char* path;             // in the real-data folder
    std::size_t images;
    std::size_t points;
    std::size_t observations;
    double stored_mean;           // the mean of ERROR, as model_analyzer prints it (6 digits)
    double recomputed_mean;       // SOURCES.md's independent recomputation
    double mean_tolerance;        // of libcam's recomputation against it
    double per_point_tolerance;   // of libcam's per-point means against ERROR
};

// Text models store 6 significant digits: SOURCES.md gives the largest per-point
// difference that rounding makes (0.0055 px); binary ones agree to 1e-12 px.
constexpr double kText = 0.006;
constexpr double kBinary = 1e-6;

const RealModel kModels[] = {
    {"colmap-jasminekhalil-ar", 7, 2707, 9896, 0.953712, 0.953720, 2e-6, kText},
    {"colmap-vijayvamsi7-table/final_try_1_workspace", 10, 2167, 10461, 0.973087, 0.973085, 2e-6, kText},
    {"colmap-vijayvamsi7-table/final_try_1_workspace/sparse/0", 10, 2167, 10461, 0.973087, 0.973087, 1e-6, kBinary},
    {"colmap-bartoszek-test_colmap/sparse/0", 23, 1443, 5931, 0.848027, 0.848027, 1e-6, kBinary},
    {"colmap-halogenname-south-building/sparse/0", 5, 2013, 6760, 0.399172, 0.399172, 1e-6, kBinary},
    {"colmap-myhan1023-mouse/sparse/0", 56, 4443, 25656, 0.632516, 0.632516, 1e-6, kBinary},
    {"colmap-consideringname-ggbond-3dgs/distorted/sparse/0", 24, 1038, 4426, 0.434863, 0.434863, 1e-6, kBinary},
    {"kapture-samples/maupertuis/colmap/reconstruction", 4, 1039, 3355, 0.342600, 0.342627, 2e-6, kText},
};

}  // namespace

TEST_CASE("COLMAP observations: every real model reads, and reprojects to the ERROR COLMAP stored") {
    for (const RealModel& model : kModels) {
        const auto folder = real_data_path(model.path);
        if (!real_data_present(folder)) continue;
        INFO(model.path);
        const ObservationSet set = read_observations(folder);
        CHECK(set.tool == ObservationTool::Colmap);
        CHECK(set.pixel_offset == Vec2(0.5, 0.5));
        CHECK(set.views.size() == model.images);
        CHECK(set.points.size() == model.points);
        CHECK(set.observations.size() == model.observations);
        REQUIRE(set.reported.size() == 1);
        CHECK(set.reported[0].key == "mean_point_error_px");
        CHECK(set.reported[0].measure == ReportedMeasure::MeanOfPointMeans);
        CHECK(set.reported[0].value == Approx(model.stored_mean).margin(5e-7));
        const Reprojection r = reproject(set);
        CHECK(r.summary.all.stats.count == model.observations);
        REQUIRE(r.summary.reported.size() == 1);
        CHECK(r.summary.reported[0].recomputed == Approx(model.recomputed_mean).margin(model.mean_tolerance));
        REQUIRE(r.summary.per_point_reported);
        CHECK(r.summary.per_point_reported->compared == model.points);
        CHECK(r.summary.per_point_reported->max_abs_difference <= model.per_point_tolerance);
    }
}
