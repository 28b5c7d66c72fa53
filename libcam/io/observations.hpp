#pragma once
// Observations: the pixels where a tool saw known points (a calibration's board corners,
// a reconstruction's tracks), with the cameras and poses the tool solved from them, and
// the numbers the tool stored about its own fit. read_observations reads them from the
// files calibration and reconstruction tools write; libcam/reproject/reproject.hpp checks
// them; docs/reprojection.md defines each tool's number.
//
//   const ObservationSet set = read_observations("sparse/0");
//   for (const Observation& o : set.observations)
//       ... set.views[o.view], set.points[o.point], o.pixel ...
//
// Everything is in libcam's conventions whatever the file's: pixels are OpenCV's (centre
// of the top-left pixel at (0, 0)), poses world-to-camera (x_cam = R X + t). What the
// file's own pixels were is kept (pixel_offset), so residuals can be written back in them.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

// Which tool wrote the file: it decides what the file's stored numbers mean.
enum class ObservationTool {
    OpenCvCalibration,  // OpenCV's calibration sample (out_camera_data.yml/.xml)
    Mrcal,              // mrcal's optimization_inputs in a .cameramodel
    Colmap,             // a COLMAP model's images and points3D
    OpenSfm,            // OpenSfM's reconstruction.json with tracks.csv
    OpenMvg,            // OpenMVG's sfm_data.json with its structure
    AliceVision,        // AliceVision's (Meshroom's) SfMData JSON with its structure
    VisualSfm,          // VisualSfM's .nvm
    Bundler,            // Bundler's bundle.out
    Table,              // a CSV or JSON table of observations, with a camera file
};

// One set of intrinsics (a COLMAP camera, an mrcal camera). Its `camera.pose` is the
// identity: each view has its own.
struct ObservedCamera {
    std::string name;  // the file's name or id for it ("1", "cam0")
    Camera camera;
};

// One image: which camera took it, and where that camera was.
struct ObservedView {
    std::string name;  // the image's name, or "view 3" where the file names none
    int camera = 0;    // index into ObservationSet::cameras
    Pose pose;         // world (for a board: the board's frame) to camera
    // A board view of a solve of several cameras (mrcal's): the board pose (index into
    // ObservationSet::frames) it shares with the other cameras' views of it, and whether
    // its camera's pose from the reference camera was solved (the reference's is not).
    // -1 and false elsewhere.
    int frame = -1;
    bool camera_pose_solved = false;
};

// One observed pixel of one point in one view.
struct Observation {
    int view = 0;             // index into ObservationSet::views
    int point = 0;            // index into ObservationSet::points
    Vec2 pixel = Vec2::Zero();  // where the tool saw it, in OpenCV's pixels
    double weight = 1.0;      // the tool's weight (mrcal's); 1 where the tool has none
    bool inlier = true;       // false where the tool marked it an outlier
};

// What a tool's number is: each tool averages something different and calls it "the
// reprojection error" (docs/reprojection.md). `d` is an observation's residual vector,
// projected minus observed, in pixels.
enum class ReportedMeasure {
    RmsOverObservations,  // sqrt(sum |d|^2 / N) over every observation (OpenCV's avg_reprojection_error)
    MeanOfPointMeans,     // the mean over 3D points of each point's mean |d| over its track (COLMAP)
    // mrcal stores no number; the one mrcal-calibrate-cameras prints (mrcal_optimize's
    // rms_reproj_error__pixels) also counts each outlier as two zeros, a point's range
    // penalty and the regularization terms, which no file keeps (docs/reprojection.md).
};
// The definition in words, for reports.
std::string_view definition_of(ReportedMeasure measure);

// A number the tool stored (or printed) about its fit, by the file's own key.
struct ReportedNumber {
    std::string key;  // "avg_reprojection_error", "mean_point_error_px"
    double value = 0.0;
    ReportedMeasure measure = ReportedMeasure::RmsOverObservations;
};

// The board whose corners a calibration observed.
struct ObservedBoard {
    int width = 0;   // corners per row
    int height = 0;  // rows of corners
    double spacing = 0.0;  // between neighbouring corners, in the file's unit
    // mrcal's calobject_warp (the board's bow, in its unit), zero where the tool has none;
    // ObservationSet::points already hold the corners it moves.
    Vec2 warp = Vec2::Zero();
    // Whether the tool's solve freed the warp (mrcal's do_optimize_calobject_warp): its
    // uncertainty then counts the warp's freedom too.
    bool warp_solved = false;
};

struct ObservationSet {
    ObservationTool tool = ObservationTool::Table;
    std::string source;  // the file or folder read, for messages
    // The file's pixels minus OpenCV's: (0.5, 0.5) for COLMAP and OpenSfM, whose top-left
    // pixel's centre is (0.5, 0.5); zero for OpenCV, mrcal, OpenMVG and AliceVision. NVM
    // and Bundler measure from the image centre, Bundler with y up: their readers give
    // OpenCV's pixels, and this is zero.
    Vec2 pixel_offset = Vec2::Zero();
    std::vector<ObservedCamera> cameras;
    std::vector<ObservedView> views;
    // The observed points, world frame; for a board, its corners in the board's frame
    // (corner i * width + j at (j, i, 0) * spacing, warp applied), shared by every view.
    std::vector<Vec3> points;
    // The file's own id of each point (COLMAP's POINT3D_ID, OpenSfM's track id, the
    // board's corner index), for the rows a user can find in the file again.
    std::vector<std::int64_t> point_ids;
    std::vector<Observation> observations;
    std::optional<ObservedBoard> board;
    // mrcal's frames: each board pose, board to the reference camera (views' `frame`).
    std::vector<Pose> frames;
    // The camera the file is, where it holds a solve of several (mrcal's icam_intrinsics:
    // each camera's .cameramodel carries the whole solve); -1 where it names none.
    int own_camera = -1;
    // What the tool stored about its fit: whole-file numbers; one per view, the RMS over
    // the view's observations (OpenCV's per_view_reprojection_errors), empty where the file
    // stores none; one per point, the mean |d| over its track (COLMAP's ERROR column, NaN
    // for a point without one), empty where the file stores none.
    std::vector<ReportedNumber> reported;
    std::vector<double> reported_per_view;
    std::vector<double> reported_per_point;
};

struct ObservationReadOptions {
    // For a table of observations (CSV or JSON): the camera file whose cameras (by name or
    // position) the table's first column names. Unused by the other formats.
    std::filesystem::path camera_file;
    // The image size, for the formats that store none (VisualSfM's .nvm, Bundler's
    // bundle.out); every image of the file has it. Unused by the other formats.
    std::optional<ImageSize> size = std::nullopt;
};

// Reads the observations a file or folder holds: OpenCV's calibration output (YAML or XML),
// a .cameramodel with mrcal's optimization_inputs, a COLMAP model folder (text, binary,
// COLMAP 3.12's rigs and frames), OpenSfM's reconstruction.json (tracks.csv beside it),
// OpenMVG's sfm_data.json, AliceVision's SfMData JSON (cameras.sfm) with its structure,
// VisualSfM's .nvm, Bundler's bundle.out (with the image sizes in list.txt beside it), or
// a table (.csv or .json) with options.camera_file.
// Throws FileError naming the file, the field and the value for a malformed file, and for
// a camera file that holds no observations.
ObservationSet read_observations(const std::filesystem::path& path, const ObservationReadOptions& options = {});

// The index of the camera `selector` names: its name in the file, or its position counting
// from 0. Throws InvalidArgument naming the file and listing its cameras.
int observed_camera_index(const ObservationSet& set, std::string_view selector);

// A board calibration's observations as mrcal keeps its solve in a .cameramodel: the value
// of its 'optimization_inputs' (a Python bytes literal, b'...', of base85 text of an .npz
// archive, as mrcal's cameramodel.py writes it), which mrcal's tools (mrcal.cameramodel(),
// mrcal-show-projection-uncertainty, mrcal-show-residuals) and read_observations read
// back. The solve as libcam's: intrinsics, camera poses and board poses free, a flat
// board unless set.board holds a bow, no regularization, the outliers weighed -1 (every
// corner a view did not see too). One camera's views each have their board pose; several
// cameras share set.frames (each view's `frame`), the first camera the reference.
// `observed_pixel_uncertainty` is stored as mrcal stores its own (the noise, in pixels).
// Throws NotRepresentable, saying why, for what mrcal cannot hold: no board, cameras of
// different lens models, a lens mrcal lacks, skew.
std::string mrcal_optimization_inputs(const ObservationSet& set, double observed_pixel_uncertainty);

// The name of the tool ("OpenCV's calibration sample", "COLMAP") for messages and reports.
std::string_view to_string(ObservationTool tool);

// Throws FileError "<source>: <what>" unless every index is in range, every camera
// valid, every pixel and weight finite, and point_ids as long as points: what every
// reader promises, checked once here.
void check_observations(const ObservationSet& set);

}  // namespace libcam
