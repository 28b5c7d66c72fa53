// The table of the real files other projects wrote that libcam reads (the folder of real
// data beside the source tree, LIBCAM_REAL_DATA_DIR in tests/CMakeLists.txt; its
// SOURCES.md says where each comes from and what its tool stored or printed). Each file is
// named here with what SOURCES.md says it holds, and with the number that proves libcam
// reads it right, against a value found without libcam: the tool's own stored error
// recomputed from the file's observations, SOURCES.md's independent recomputation, the
// library that defines the camera's model, or published and computed vectors. Printed
// one row a file for docs/file-formats.md ("The real reconstructions and calibrations").

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "gs_reference.hpp"
#include "lens_cases.hpp"
#include "lensfun_reference.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/text/number_format.hpp"
#include "ocamcalib_reference.hpp"
#include "real_cameras.hpp"

using namespace libcam;
namespace fs = std::filesystem;

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// What proves a file read right.
enum class Proof {
    ColmapError,       // points3D's ERROR column: the mean of the recomputed point means
    OpenCvAverage,     // avg_reprojection_error: the RMS over every corner
    RecomputedMean,    // SOURCES.md's recomputation: the mean |residual| over the observations
    Library,           // every distinct camera against its model's library, over a grid
    OcamcalibVectors,  // ocamcalib-computed.json: world2cam by invpol and cam2world
    PyOcamcalib,       // py-OCamCalib's cam2world
    LensfunVectors,    // lensfun's regression vectors
    GsRasterizer,      // 3DGS's own projection, of a point before every camera
    NerfAngles,        // each frame's camera_angle_x and _y, from its fl_x and fl_y
    DsoCalibration,    // the 4Seasons data set's calib_N.txt, the same cameras in DSO's text
};

// One file and what SOURCES.md says of it.
struct RealFile {
    const char* path;  // in the real-data folder
    const char* models;
    std::size_t cameras;       // as libcam lists them: one per image of a reconstruction
    std::size_t posed;         // cameras whose pose is not the identity
    std::size_t observations;  // 0: none read
    Proof proof;
    double expected = kNone;   // what the recomputed number must be (where the proof has one)
    double tolerance = kNone;  // how far from it, or from the proof's reference
    double stored = kNone;     // the tool's own number, printed beside the recomputed one
    double point_tolerance = kNone;  // COLMAP: each point's recomputed mean against its ERROR
    const char* note = "";     // printed after the agreement: why the expected number is not the stored one
    const char* lens = "";     // lensfun: the regression vectors' case, whose lens is read
    ImageSize given_size = {0, 0};  // for a file that records none
    // SOURCES.md's focal length in pixels, for a file that stores it in other units
    // (OpenSfM's fraction of the image, AliceVision's millimetres), and to how many pixels.
    double fx = kNone;
    double fx_tolerance = kNone;
};

// COLMAP's text models store 6 significant digits: a point's mean moves by up to 0.0055 px
// (SOURCES.md); binary ones agree to 1e-12 px.
constexpr double kTextPoint = 0.006;
constexpr double kBinaryPoint = 1e-6;
constexpr const char* kNormalized = "quaternions normalized as COLMAP reads them";
// OpenCV's stored numbers are float32, or computed from float32 pixels: 1e-5 relative.
constexpr double kFloatStorage = 1e-5;
// libcam's projection against a library's, and against formulas worked out without it.
constexpr double kLibraryPx = 1e-9;

const RealFile kFiles[] = {
    // ---- COLMAP: the ERROR column of points3D, recomputed from cameras, images and points.
    // The text models write 6 significant digits, their quaternions among them; COLMAP
    // normalizes each on reading, and so does libcam. SOURCES.md's recomputation takes them
    // as written (0.953720, 0.973085, 0.342627); the same pure-Python recomputation with the
    // quaternions normalized, done for this table, gives the numbers here.
    {"colmap-jasminekhalil-ar", "OPENCV4", 7, 7, 9896, Proof::ColmapError, 0.953725029, 1e-6, 0.953712, kTextPoint,
     kNormalized},
    {"colmap-vijayvamsi7-table/final_try_1_workspace", "OPENCV4", 10, 10, 10461, Proof::ColmapError, 0.973081874, 1e-6,
     0.973087, kTextPoint, kNormalized},
    {"colmap-vijayvamsi7-table/final_try_1_workspace/sparse/0", "OPENCV4", 10, 10, 10461, Proof::ColmapError, 0.973087,
     1e-6, 0.973087, kBinaryPoint},
    {"colmap-bartoszek-test_colmap/sparse/0", "OPENCV4", 23, 23, 5931, Proof::ColmapError, 0.848027, 1e-6, 0.848027,
     kBinaryPoint},
    {"colmap-bartoszek-test_colmap/dense/0/sparse", "PINHOLE", 23, 23, 5931, Proof::ColmapError, 0.279490, 2e-6, 0.848027,
     kNone, "ERROR copied by image_undistorter, in the original pixels: against SOURCES.md's 0.27949"},
    {"colmap-halogenname-south-building/sparse/0", "OPENCV4", 5, 5, 6760, Proof::ColmapError, 0.399172, 1e-6, 0.399172,
     kBinaryPoint, "COLMAP 3.12's model, with rigs.bin and frames.bin"},
    {"colmap-myhan1023-mouse/sparse/0", "PINHOLE", 56, 56, 25656, Proof::ColmapError, 0.632516, 1e-6, 0.632516,
     kBinaryPoint},
    {"colmap-consideringname-ggbond-3dgs/distorted/sparse/0", "OPENCV4", 24, 24, 4426, Proof::ColmapError, 0.434863,
     1e-6, 0.434863, kBinaryPoint},
    {"colmap-consideringname-ggbond-3dgs/sparse/0", "PINHOLE", 24, 24, 4426, Proof::ColmapError, 0.437770, 2e-6,
     0.434863, kNone, "ERROR copied from distorted/: against SOURCES.md's 0.43777"},
    {"colmap-splatam-kinect/sparse/0", "OPENCV4", 50, 50, 55090, Proof::ColmapError, 1.239325, 2e-6, 1.239572, kNone,
     "ERROR stale, the cameras refined after it: against SOURCES.md's 1.239325"},
    {"kapture-samples/maupertuis/colmap/reconstruction", "PINHOLE", 4, 4, 3355, Proof::ColmapError, 0.342625167, 1e-6,
     0.342600, kTextPoint, kNormalized},
    // COLMAP cameras alone (their images.bin is not kept, or kapture wrote no points).
    {"colmap-nerf-multicam-sangminkim/colmap_text/cameras.txt", "OPENCV4", 2, 0, 0, Proof::Library},
    {"colmap-nerf-multicam-sangminkim/colmap_sparse/0/cameras.bin", "OPENCV4", 2, 0, 0, Proof::Library},
    {"kapture-samples/t265/colmap/cameras.txt", "FISHEYE", 2, 0, 0, Proof::Library},
    // ---- NeRF's transforms.json made from those two cameras.
    {"colmap-nerf-multicam-sangminkim/transforms.json", "OPENCV4", 42, 42, 0, Proof::NerfAngles, kNone, 1e-12},
    // ---- OpenCV's calibration sample: avg_reprojection_error.
    {"opencv-calib-outputs2/opencv-tutorial/out_camera_data.yml", "OPENCV5", 1, 0, 8 * 54, Proof::OpenCvAverage,
     0.38441346462381665, kFloatStorage},
    {"opencv-calib-outputs2/spaceview-opencv455-demo/out_camera_data.xml", "OPENCV5", 1, 0, 5 * 54,
     Proof::OpenCvAverage, 8.1388840849437472, kFloatStorage},
    {"opencv-calib-outputs2/arnoldad-rs435i/out_camera_data.xml", "OPENCV5", 1, 0, 5 * 48, Proof::OpenCvAverage,
     0.21650052128653835, kFloatStorage},
    {"opencv-calib-outputs2/scanvan/out_camera_data.xml", "OPENCV5", 1, 0, 9 * 54, Proof::OpenCvAverage,
     1.6316837814849146, kFloatStorage},
    {"opencv-calib-outputs2/shamisen00/out_camera_data.yml", "OPENCV5", 1, 0, 5 * 49, Proof::OpenCvAverage,
     2.9082761973083158, kFloatStorage},
    {"opencv-calib-outputs2/jrebort-mcc/out_camera_data.xml", "OPENCV5", 1, 0, 8 * 88, Proof::OpenCvAverage,
     0.075289322143560919, kFloatStorage},
    {"opencv-calib-outputs2/bryan-bai/out_camera_data.yml", "OPENCV5", 1, 0, 25 * 54, Proof::OpenCvAverage,
     0.72721969191026936, kFloatStorage},
    {"opencv-calib-outputs2/hpfily/out_camera_data.xml", "OPENCV5", 1, 0, 8 * 54, Proof::OpenCvAverage,
     0.85561914171043119, kFloatStorage},
    {"opencv-calib-outputs2/ntu-mecatron/out_camera_data.xml", "OPENCV5", 1, 0, 20 * 150, Proof::OpenCvAverage,
     0.55612728570502168, kFloatStorage},
    // ---- OpenSfM and OpenDroneMap.
    {"kapture-samples/berlin/opensfm/reconstruction.json", "OPENCV4", 3, 3, 3771, Proof::RecomputedMean, 1.77, 0.005,
     kNone, kNone, "with tracks.csv"},
    {"kapture-samples/berlin/opensfm/camera_models.json", "PINHOLE", 1, 0, 0, Proof::Library},
    {"opensfm-fuenwang-PBA/reconstruction.json", "OPENCV4", 3, 3, 0, Proof::Library},
    {.path = "opensfm-odm-JNotelddim/cameras.json", .models = "OPENCV5", .cameras = 1, .posed = 0, .observations = 0,
     .proof = Proof::Library, .fx = 4090.88, .fx_tolerance = 0.005},
    // ---- OpenMVG.
    {"kapture-samples/maupertuis_openMVG/ChateauMaupertuisTest/reconstruction_global/sfm_data.json", "OPENCV5", 4, 4,
     1228, Proof::RecomputedMean, 0.470, 0.0005},
    {"kapture-samples/maupertuis_openMVG/ChateauMaupertuisTest/matches/sfm_data.json", "PINHOLE", 4, 0, 0,
     Proof::Library},
    {"kapture-samples/t265/Everest_undistorted/sfm_data_small.json", "FISHEYE", 5, 5, 0, Proof::Library},
    // ---- AliceVision (Meshroom).
    {.path = "alicevision-meshroom-LoD2to3/data/meshroom/cameras.sfm", .models = "OPENCV5", .cameras = 51, .posed = 34,
     .observations = 0, .proof = Proof::Library, .fx = 2795.0, .fx_tolerance = 0.05},
    // ---- Metashape.
    {"metashape/hwiyoung-MappingLocalization/calibration/calib_lcam.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    {"metashape/hwiyoung-MappingLocalization/calibration/calib_lcam2.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    {"metashape/hwiyoung-MappingLocalization/calibration/calib_rcam.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    {"metashape/hwiyoung-MappingLocalization/calibration/calib_rcam2.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    {"metashape/hwiyoung-MappingLocalization/cameras.xml", "OPENCV5", 100, 0, 0, Proof::Library},
    {"metashape/lab336-4DGS-Preprocess/cameras.xml", "OPENCV4", 47, 47, 0, Proof::Library},
    {"metashape/bitbyt3r-metashape-automation/cameras.xml", "OPENCV4", 94, 94, 0, Proof::Library},
    {"metashape/amarburg-photoscan_outputs/demo/cameras.xml", "OPENCV5", 16, 16, 0, Proof::Library},
    // Metashape's export as OpenCV's XML, read as OpenCV's.
    {"metashape/3dom-fbk-deep-image-matching/camera_calib.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    {"metashape/3dom-fbk-deep-image-matching/staua-calib.xml", "OPENCV5", 1, 0, 0, Proof::Library},
    // ---- 3D Gaussian Splatting.
    {"3dgs-augustine-GSSample/cameras.json", "PINHOLE", 193, 193, 0, Proof::GsRasterizer, kNone, kLibraryPx},
    // ---- OCamCalib.
    {"ocamcalib/ches00-360-SL-Metasurface/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/renmengqisheng-calib_fisheye/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/vivekmudgal-fisheye-localization/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/AnjanaKN-imageconverter/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/AnjanaKN-imageconverter/Cam0.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/jingdongZhang-Improved_Feature_Descriptor/calib_results.txt", "OCAMCALIB", 1, 0, 0,
     Proof::OcamcalibVectors},
    {"ocamcalib/premnirmal-Homing-in-Scale-Space/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {"ocamcalib/urbste-ImprovedOcamCalib/calib_results.txt", "OCAMCALIB", 1, 0, 0, Proof::OcamcalibVectors},
    {.path = "ocamcalib/jakarto3d-py-OCamCalib/calibration_fisheye_1_18052022_154907.json", .models = "OCAMCALIB",
     .cameras = 1, .posed = 0, .observations = 0, .proof = Proof::PyOcamcalib, .tolerance = 1e-12,
     .given_size = {1088, 756}},
    // ---- lensfun: one lens of a database file a row.
    // lensfun's test asks 1e-3 px of its distortion cases and 0.1 px of the fisheye seen
    // rectilinear.
    {.path = "lensfun/data/db/slr-pentax.xml", .models = "OPENCV4", .cameras = 1, .posed = 0, .observations = 0,
     .proof = Proof::LensfunVectors, .tolerance = 1e-3, .lens = "verify_dist_poly3"},
    {.path = "lensfun/data/db/compact-canon.xml", .models = "OPENCV4", .cameras = 1, .posed = 0, .observations = 0,
     .proof = Proof::LensfunVectors, .tolerance = 1e-3, .lens = "verify_dist_poly5"},
    {.path = "lensfun/data/db/slr-pentax.xml", .models = "PTLENS", .cameras = 1, .posed = 0, .observations = 0,
     .proof = Proof::LensfunVectors, .tolerance = 1e-3, .lens = "verify_dist_ptlens"},
    {.path = "lensfun/data/db/mil-olympus.xml", .models = "EQUISOLID", .cameras = 1, .posed = 0, .observations = 0,
     .proof = Proof::LensfunVectors, .tolerance = 0.1, .lens = "verify_geom_fisheye_rectlinear"},
    // ---- Other data sets' calibrations among kapture's samples.
    {"kapture-samples/4seasons/TUM/calibration/camchain.yaml", "FISHEYE", 2, 2, 0, Proof::DsoCalibration},
    {"kapture-samples/utbm/bb2_left.yaml", "OPENCV5, PINHOLE", 2, 0, 0, Proof::Library},
    {"kapture-samples/utbm/bb2_right.yaml", "OPENCV5, PINHOLE", 2, 0, 0, Proof::Library},
};

// One row of the table: the columns after the file's, and whether the proof holds.
struct Row {
    std::string name;  // the file, and the lens of a lens database
    std::string format, cameras, posed, observations, models, agreement;
    bool holds = false;
};

// A recomputed or stored number, to the digits the tools print; an error, to two.
std::string number(double value) { return format_short(value, 6); }
std::string error(double value) { return format_short(value, 2); }

// The file's models, each once, in the file's order.
std::string models_of(const CameraSet& set) {
    std::vector<std::string> names;
    for (const NamedCamera& named : set.cameras) {
        const std::string name(lens_info(named.file.camera.lens.type).name);
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    std::string joined;
    for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
    return joined;
}

std::size_t posed_of(const CameraSet& set) {
    return static_cast<std::size_t>(std::count_if(set.cameras.begin(), set.cameras.end(), [](const NamedCamera& named) {
        const Pose& pose = named.file.camera.pose;
        return !(pose.R == Mat3::Identity() && pose.t == Vec3::Zero());
    }));
}

bool near(double value, double expected, double tolerance) { return std::abs(value - expected) <= tolerance; }

// ---- each proof: the sentence of the table's last column, and whether it holds ----------

Row colmap_error(const RealFile& file, const ObservationSet& set) {
    const Reprojection r = reproject(set);
    Row row;
    REQUIRE(r.summary.reported.size() == 1);
    const double recomputed = r.summary.reported[0].recomputed;
    row.holds = near(recomputed, file.expected, file.tolerance) && near(set.reported[0].value, file.stored, 5e-7);
    row.agreement = "mean of " + std::to_string(set.points.size()) + " point means " + number(recomputed) +
                    " px; ERROR column " + number(set.reported[0].value);
    if (!std::isnan(file.point_tolerance)) {
        REQUIRE(r.summary.per_point_reported);
        const double worst = r.summary.per_point_reported->max_abs_difference;
        row.holds = row.holds && worst <= file.point_tolerance;
        row.agreement += ", each point within " + error(worst) + " px";
    }
    if (*file.note != '\0') row.agreement += std::string(" (") + file.note + ")";
    return row;
}

Row opencv_average(const RealFile& file, const ObservationSet& set) {
    const Reprojection r = reproject(set);
    REQUIRE(r.summary.reported.size() == 1);
    const double recomputed = r.summary.reported[0].recomputed;
    Row row;
    row.holds = set.reported[0].value == file.expected && near(recomputed, file.expected, file.tolerance * file.expected) &&
                r.summary.all.stats.count == set.observations.size();
    row.agreement = "RMS " + number(recomputed) + " px over the corners; stored avg_reprojection_error " +
                    number(set.reported[0].value);
    return row;
}

Row recomputed_mean(const RealFile& file, const ObservationSet& set) {
    const Reprojection r = reproject(set);
    Row row;
    row.holds = near(r.summary.all.mean_px, file.expected, file.tolerance) && r.summary.all.stats.count == set.observations.size();
    row.agreement = "mean " + format_short(r.summary.all.mean_px, 4) + " px, max " +
                    format_short(r.summary.all.stats.max_px, 4) + "; SOURCES.md's recomputation " + number(file.expected);
    return row;
}

// Preparing a camera for projection takes 20 to 80 ms: of a file's many cameras (a
// Metashape project's sensors), the first, the last and two between them.
constexpr std::size_t kMostCamerasChecked = 4;

std::vector<const NamedCamera*> spread(const std::vector<const NamedCamera*>& cameras) {
    if (cameras.size() <= kMostCamerasChecked) return cameras;
    std::vector<const NamedCamera*> chosen;
    for (std::size_t i = 0; i < kMostCamerasChecked; ++i) {
        chosen.push_back(cameras[i * (cameras.size() - 1) / (kMostCamerasChecked - 1)]);
    }
    return chosen;
}

Row against_library(const CameraSet& set) {
    double worst = 0.0;
    std::size_t rays = 0;
    std::set<std::string> libraries;
    const std::vector<const NamedCamera*> distinct = test::distinct_cameras(set);
    const std::vector<const NamedCamera*> checked = spread(distinct);
    bool enough = true;
    for (const NamedCamera* named : checked) {
        const test::ReferenceAgreement agreement = test::against_reference(named->file.camera);
        worst = std::max(worst, agreement.worst_px);
        rays += agreement.rays;
        enough = enough && agreement.rays > agreement.pixels / 2;
        libraries.insert(test::reference_library(named->file.camera.lens.type));
    }
    std::string names;
    for (const std::string& name : libraries) names += (names.empty() ? "" : ", ") + name;
    Row row;
    row.holds = enough && worst <= kLibraryPx;
    const std::string of = checked.size() == distinct.size() ? "" : std::to_string(checked.size()) + " of ";
    row.agreement = names + ": worst " + error(worst) + " px over " + std::to_string(rays) + " pixels of " + of +
                    std::to_string(distinct.size()) + (distinct.size() == 1 ? " camera" : " distinct cameras");
    return row;
}

Row ocamcalib_vectors(const RealFile& file, const CameraSet& set) {
    const fs::path vectors = test::real_data_path("vectors/ocamcalib-computed.json");
    REQUIRE(test::real_data_present(vectors));
    const std::string key = file.path;
    const nlohmann::json expected = nlohmann::json::parse(std::ifstream(vectors))["files"][key];
    const Camera& camera = set.cameras.at(0).file.camera;
    const test::OcamcalibVectorsMiss miss =
        test::ocamcalib_vectors_miss(camera, read_ocamcalib_inverse(test::real_data_path(file.path)).value(), expected);
    Row row;
    row.holds = miss.world2cam_px < kLibraryPx && miss.cam2world < 1e-12 && miss.exact_px < kLibraryPx;
    row.agreement = "ocamcalib-computed.json, " + std::to_string(miss.pixels) + " pixels: world2cam (invpol) " +
                    error(miss.world2cam_px) + " px, cam2world " + error(miss.cam2world);
    return row;
}

Row py_ocamcalib(const RealFile& file, const CameraSet& set) {
    const nlohmann::json json = nlohmann::json::parse(std::ifstream(test::real_data_path(file.path)));
    const PreparedCamera prepared(set.cameras.at(0).file.camera);
    double worst = 0.0;
    const std::vector<Vec2> pixels = test::py_ocamcalib_pixels();
    for (const Vec2& pixel : pixels) {
        const Unprojection ray = prepared.unproject(pixel);
        worst = std::max(worst, ray.valid ? (ray.direction.normalized() - test::py_ocamcalib_ray(json, pixel)).norm()
                                          : std::numeric_limits<double>::infinity());
    }
    Row row;
    row.holds = worst <= file.tolerance;
    row.agreement = "py-OCamCalib's cam2world at " + std::to_string(pixels.size()) + " pixels: worst " + error(worst) +
                    " (unit rays; read with --image-size " + std::to_string(file.given_size.width) + "x" +
                    std::to_string(file.given_size.height) + ")";
    return row;
}

Row gs_rasterizer(const RealFile& file, const CameraSet& set) {
    const nlohmann::json json = nlohmann::json::parse(std::ifstream(test::real_data_path(file.path)));
    REQUIRE(json.size() == set.cameras.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        // A point before the camera, where 3DGS's rasterizer draws it.
        const Camera& camera = set.cameras[i].file.camera;
        const Vec3 world = camera.pose.R.transpose() * (Vec3(0.4, -0.3, 2.0) - camera.pose.t);
        const Projection projected = PreparedCamera(camera).project(world);
        const double miss = (projected.pixel - test::gs_rasterizer_pixel(json[i], world)).norm();
        worst = std::max(worst, projected.valid && !std::isnan(miss) ? miss : std::numeric_limits<double>::infinity());
    }
    Row row;
    row.holds = worst <= file.tolerance;
    row.agreement = "3DGS's projection (view matrix, getProjectionMatrix, ndc2Pix) of a point before each of the " +
                    std::to_string(set.cameras.size()) + " cameras: worst " + error(worst) + " px";
    return row;
}

Row nerf_angles(const RealFile& file, const CameraSet& set) {
    const nlohmann::json json = nlohmann::json::parse(std::ifstream(test::real_data_path(file.path)));
    REQUIRE(json["frames"].size() == set.cameras.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        // camera_angle_x = 2 atan(w / (2 fl_x)), as the writer stored it beside fl_x.
        const Camera& camera = set.cameras[i].file.camera;
        const nlohmann::json& frame = json["frames"][i];
        const double x = 2 * std::atan(static_cast<double>(camera.size.width) / (2 * camera.intrinsics.fx));
        const double y = 2 * std::atan(static_cast<double>(camera.size.height) / (2 * camera.intrinsics.fy));
        worst = std::max({worst, std::abs(x - frame["camera_angle_x"].get<double>()),
                          std::abs(y - frame["camera_angle_y"].get<double>())});
    }
    Row row;
    row.holds = worst <= file.tolerance;
    row.agreement = "each frame's stored camera_angle_x and _y from libcam's fx, fy: worst " + error(worst) + " rad";
    return row;
}

Row lensfun_vectors(const RealFile& file) {
    const nlohmann::json vectors = test::lensfun_vectors();
    REQUIRE(!vectors.is_null());
    const nlohmann::json* c = test::lensfun_vector_case(vectors, file.lens);
    REQUIRE(c != nullptr);
    const test::LensfunCaseMiss miss = test::lensfun_case_miss(*c);
    Row row;
    row.holds = miss.points == (*c)["x"].size() && miss.worst_px < file.tolerance;
    row.agreement = "lensfun's regression vectors (" + std::string(file.lens) + "): worst " + error(miss.worst_px) + " px over " + std::to_string(miss.points) + " points, to " +
                    number(file.tolerance);
    return row;
}

// DSO's calib.txt: "Equidistant fx fy cx cy k1 k2 k3 k4" on its first line, read as text.
std::vector<double> dso_numbers(const fs::path& path) {
    std::ifstream in(path);
    std::string model;
    in >> model;
    REQUIRE(model == "Equidistant");
    std::vector<double> numbers(8);
    for (double& value : numbers) in >> value;
    REQUIRE(in);
    return numbers;
}

Row dso_calibration(const RealFile& file, const CameraSet& set) {
    bool equal = set.cameras.size() == 2;
    for (std::size_t i = 0; i < 2 && equal; ++i) {
        const fs::path dso = test::real_data_path(file.path).parent_path() / ("calib_" + std::to_string(i) + ".txt");
        REQUIRE(test::real_data_present(dso));
        const std::vector<double> n = dso_numbers(dso);
        const Camera& camera = set.cameras[i].file.camera;
        equal = camera.intrinsics.fx == n[0] && camera.intrinsics.fy == n[1] && camera.intrinsics.cx == n[2] &&
                camera.intrinsics.cy == n[3] && camera.lens.coefficients == std::vector<double>(n.begin() + 4, n.end());
    }
    Row row;
    row.holds = equal && against_library(set).holds;
    row.agreement = "cam0, cam1 equal the data set's DSO calib_0.txt, calib_1.txt to the last digit; " +
                    against_library(set).agreement;
    return row;
}

// The options a file is read with: lensfun's lens, a size the file does not record.
ReadOptions options_of(const RealFile& file) {
    if (file.proof == Proof::LensfunVectors) {
        const nlohmann::json vectors = test::lensfun_vectors();
        const nlohmann::json* c = test::lensfun_vector_case(vectors, file.lens);
        REQUIRE(c != nullptr);
        return test::lensfun_case_options(*c);
    }
    ReadOptions options;
    if (file.given_size.width > 0) options.size = file.given_size;
    return options;
}

bool reads_observations(Proof proof) {
    return proof == Proof::ColmapError || proof == Proof::OpenCvAverage || proof == Proof::RecomputedMean;
}

Row row_of(const RealFile& file) {
    const fs::path path = test::real_data_path(file.path);
    const CameraSet cameras = read_camera_set(path, std::nullopt, options_of(file));
    std::optional<ObservationSet> observed;
    if (reads_observations(file.proof)) observed = read_observations(path);
    Row row;
    switch (file.proof) {
        case Proof::ColmapError: row = colmap_error(file, *observed); break;
        case Proof::OpenCvAverage: row = opencv_average(file, *observed); break;
        case Proof::RecomputedMean: row = recomputed_mean(file, *observed); break;
        case Proof::Library: row = against_library(cameras); break;
        case Proof::OcamcalibVectors: row = ocamcalib_vectors(file, cameras); break;
        case Proof::PyOcamcalib: row = py_ocamcalib(file, cameras); break;
        case Proof::LensfunVectors: row = lensfun_vectors(file); break;
        case Proof::GsRasterizer: row = gs_rasterizer(file, cameras); break;
        case Proof::NerfAngles: row = nerf_angles(file, cameras); break;
        case Proof::DsoCalibration: row = dso_calibration(file, cameras); break;
    }
    if (!std::isnan(file.fx)) {
        const double fx = cameras.cameras.at(0).file.camera.intrinsics.fx;
        row.holds = row.holds && near(fx, file.fx, file.fx_tolerance);
        row.agreement += "; fx " + number(fx) + " px, SOURCES.md's " + number(file.fx);
    }
    row.name = file.path;
    if (file.proof == Proof::LensfunVectors) row.name += " (" + cameras.cameras.at(0).name + ")";
    row.format = std::string(to_string(cameras.format));
    row.cameras = std::to_string(cameras.cameras.size());
    row.posed = std::to_string(posed_of(cameras));
    row.models = models_of(cameras);
    row.observations = observed ? std::to_string(observed->observations.size()) + " in " +
                                      std::to_string(observed->views.size()) + " views"
                                : "-";
    // Each count as SOURCES.md gives it.
    CHECK(cameras.cameras.size() == file.cameras);
    CHECK(posed_of(cameras) == file.posed);
    CHECK(row.models == file.models);
    CHECK((observed ? observed->observations.size() : 0) == file.observations);
    return row;
}

}  // namespace

TEST_CASE("Every real reconstruction and calibration libcam reads, with the number that proves it read right",
          "[sweep][files][real-data]") {
    if (!test::real_data_present(test::real_data_path())) return;
    for (const RealFile& file : kFiles) {
        if (!test::real_data_present(test::real_data_path(file.path))) continue;
        Row row;
        {
            CAPTURE(file.path, file.lens);
            row = row_of(file);
        }
        WARN(row.name << " | " << row.format << " | " << row.cameras << " | " << row.posed << " | " << row.observations
                  << " | " << row.models << " | " << row.agreement);
        CAPTURE(file.path, file.lens);
        CHECK(row.holds);
    }
}
