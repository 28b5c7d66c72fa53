#include "libcam/convert/colmap_models.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "libcam/error.hpp"

namespace libcam {

namespace {

// The rows: the libcam model each COLMAP model is, and which of its coefficients
// COLMAP's extra parameters are (COLMAP's src/colmap/sensor/models.h).
constexpr ColmapModel kColmapModels[] = {
    {"SIMPLE_PINHOLE", 0, "f, cx, cy", LensType::Pinhole, true, {}, 0},
    {"PINHOLE", 1, "fx, fy, cx, cy", LensType::Pinhole, false, {}, 0},
    {"SIMPLE_RADIAL", 2, "f, cx, cy, k", LensType::OpenCv4, true, {0}, 1},
    {"RADIAL", 3, "f, cx, cy, k1, k2", LensType::OpenCv4, true, {0, 1}, 2},
    {"OPENCV", 4, "fx, fy, cx, cy, k1, k2, p1, p2", LensType::OpenCv4, false, {0, 1, 2, 3}, 4},
    {"OPENCV_FISHEYE", 5, "fx, fy, cx, cy, k1, k2, k3, k4", LensType::Fisheye, false, {0, 1, 2, 3}, 4},
    {"FULL_OPENCV", 6, "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6", LensType::OpenCv8, false,
     {0, 1, 2, 3, 4, 5, 6, 7}, 8},
    {"FOV", 7, "fx, fy, cx, cy, omega", LensType::Fov, false, {0}, 1},
    {"SIMPLE_RADIAL_FISHEYE", 8, "f, cx, cy, k", LensType::Fisheye, true, {0}, 1},
    {"RADIAL_FISHEYE", 9, "f, cx, cy, k1, k2", LensType::Fisheye, true, {0, 1}, 2},
    {"THIN_PRISM_FISHEYE", 10, "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1", LensType::ThinPrismFisheye, false,
     {0, 1, 2, 3, 4, 5, 6, 7}, 8},
    {"RAD_TAN_THIN_PRISM_FISHEYE", 11, "fx, fy, cx, cy, k0, k1, k2, k3, k4, k5, p0, p1, s0, s1, s2, s3",
     LensType::RadTanThinPrismFisheye, false, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, 12},
    // Fitzgibbon's division model (COLMAP 3.12).
    {"SIMPLE_DIVISION", 12, "f, cx, cy, k", LensType::Division, true, {0}, 1},
    {"DIVISION", 13, "fx, fy, cx, cy, k", LensType::Division, false, {0}, 1},
    // COLMAP's plain equidistant fisheyes (added after 3.8): KB4 with no distortion.
    {"SIMPLE_FISHEYE", 14, "f, cx, cy", LensType::Fisheye, true, {}, 0},
    {"FISHEYE", 15, "fx, fy, cx, cy", LensType::Fisheye, false, {}, 0},
    {"EUCM", 16, "fx, fy, cx, cy, alpha, beta", LensType::Eucm, false, {0, 1}, 2},
    // COLMAP's equirectangular camera (added in 4.1): LONLAT over the whole sphere.
    {"EQUIRECTANGULAR", 17, "w, h", LensType::Lonlat, false, {}, 0, true},
};

// Every libcam model the lens table names a COLMAP model for is that row, with all its
// coefficients in order: the two tables agree.
constexpr bool tables_agree() {
    for (const LensInfo& info : lens_models()) {
        if (info.colmap.empty()) continue;
        const ColmapModel* row = nullptr;
        for (const ColmapModel& model : kColmapModels) {
            if (model.name == info.colmap) row = &model;
        }
        if (row == nullptr || row->lens != info.type || row->coefficient_count != info.num_coefficients) return false;
        for (int i = 0; i < row->coefficient_count; ++i) {
            if (row->coefficient[static_cast<std::size_t>(i)] != i) return false;
        }
    }
    return true;
}
static_assert(tables_agree(), "the lens table's colmap names and the COLMAP table disagree");

const ColmapModel& require_model(std::string_view name) {
    const ColmapModel* model = colmap_model(name);
    if (model == nullptr) {
        throw InvalidArgument("COLMAP model \"" + std::string(name) + "\": libcam knows " + colmap_model_names());
    }
    return *model;
}

// The COLMAP model COLMAP users know for a lens model: the one the lens table names, else
// the first two-focal model whose lens contains it.
const ColmapModel* default_model(LensType lens) {
    if (const ColmapModel* named = colmap_model(lens_info(lens).colmap)) return named;
    for (const ColmapModel& model : kColmapModels) {
        if (!model.one_focal && lens_contains(model.lens, lens)) return &model;
    }
    return nullptr;
}

// EQUIRECTANGULAR's K from its parameters, the image's width and height.
Intrinsics equirectangular_intrinsics(double width, double height) {
    const double pi = std::numbers::pi;
    return {width / (2 * pi), height / pi, width / 2 - kColmapPixelShift, height / 2 - kColmapPixelShift, 0.0};
}

Camera camera_from_equirectangular(const ColmapModel& model, std::span<const double> params, const ImageSize& size) {
    for (std::size_t i = 0; i < params.size(); ++i) {
        if (!(params[i] > 0.0) || !std::isfinite(params[i])) {
            throw InvalidArgument("COLMAP " + std::string(model.name) + " parameter " + std::to_string(i + 1) +
                                  " (of " + std::string(model.parameters) + "): must be a positive size, got " +
                                  format_number(params[i]));
        }
    }
    Camera camera;
    camera.size = size;
    camera.intrinsics = equirectangular_intrinsics(params[0], params[1]);
    camera.lens = {LensType::Lonlat, {}};
    camera.validate();
    return camera;
}

// w and h from the principal point (exact: halving and doubling), then fx and fy checked
// against them to within rounding (a camera read from EQUIRECTANGULAR has them to the bit;
// one written by another tool may differ in the last digits).
ColmapCamera equirectangular_from_camera(const ColmapModel& model, const Camera& camera) {
    const std::string target = "COLMAP " + std::string(model.name);
    if (camera.lens.type != LensType::Lonlat) {
        throw NotRepresentable(target + " cannot express the camera's " + std::string(lens_info(camera.lens.type).name) +
                               " lens (it is LONLAT over the whole sphere)");
    }
    const Intrinsics& k = camera.intrinsics;
    if (k.skew != 0.0) throw NotRepresentable(target + ": COLMAP has no skew, the camera's is " + format_number(k.skew));
    const double width = 2 * (k.cx + kColmapPixelShift), height = 2 * (k.cy + kColmapPixelShift);
    const Intrinsics expected = equirectangular_intrinsics(width, height);
    constexpr double kRelativeTolerance = 1e-12;
    const auto near = [](double a, double b) { return std::abs(a - b) <= kRelativeTolerance * std::abs(b); };
    if (!(width > 0.0) || !(height > 0.0) || !near(k.fx, expected.fx) || !near(k.fy, expected.fy)) {
        throw NotRepresentable(target + " spans the whole sphere: fx = w / (2 pi) and fy = h / pi for the w, h its "
                               "principal point gives (" + format_number(width) + ", " + format_number(height) +
                               "), which would be fx " + format_number(expected.fx) + " and fy " +
                               format_number(expected.fy) + "; the camera's are " + format_number(k.fx) + " and " +
                               format_number(k.fy));
    }
    return {model.name, {width, height}};
}

bool all_zero_from(const std::vector<double>& values, std::size_t first) {
    return std::all_of(values.begin() + static_cast<long>(std::min(first, values.size())), values.end(),
                       [](double value) { return value == 0.0; });
}

}  // namespace

const ColmapModel* colmap_model_by_id(int id) {
    for (const ColmapModel& model : kColmapModels) {
        if (model.id == id) return &model;
    }
    return nullptr;
}

std::string colmap_model_names() {
    std::string names;
    for (const ColmapModel& model : kColmapModels) names += (names.empty() ? "" : ", ") + std::string(model.name);
    return names;
}

// Runs of consecutive ids, "0 to 11, 14 to 16".
std::string colmap_model_ids() {
    std::string ids;
    const std::span<const ColmapModel> models = kColmapModels;
    for (std::size_t i = 0; i < models.size();) {
        std::size_t last = i;
        while (last + 1 < models.size() && models[last + 1].id == models[last].id + 1) ++last;
        ids += (ids.empty() ? "" : ", ") + std::to_string(models[i].id);
        if (last > i) ids += " to " + std::to_string(models[last].id);
        i = last + 1;
    }
    return ids;
}

const ColmapModel& colmap_model_for(const Lens& lens) {
    LensType type = lens.type;
    // FULL_OPENCV holds the first eight of OpenCV's coefficients; the richer models'
    // others must be 0.
    const auto eight = static_cast<std::size_t>(lens_info(LensType::OpenCv8).num_coefficients);
    if (lens_contains(type, LensType::OpenCv8) && type != LensType::OpenCv8 && all_zero_from(lens.coefficients, eight)) {
        type = LensType::OpenCv8;
    }
    if (const ColmapModel* model = default_model(type)) return *model;
    throw NotRepresentable("COLMAP has no model for a " + std::string(lens_info(lens.type).name) + " lens (its models: " +
                           colmap_model_names() + ")");
}

std::span<const ColmapModel> colmap_models() { return kColmapModels; }

const ColmapModel* colmap_model(std::string_view name) {
    for (const ColmapModel& model : kColmapModels) {
        if (model.name == name) return &model;
    }
    return nullptr;
}

Camera camera_from_colmap(std::string_view name, std::span<const double> params, const ImageSize& size) {
    const ColmapModel& model = require_model(name);
    if (params.size() != static_cast<std::size_t>(model.num_params())) {
        throw InvalidArgument("COLMAP " + std::string(model.name) + " takes " + std::to_string(model.num_params()) +
                              " parameters (" + std::string(model.parameters) + "), got " +
                              std::to_string(params.size()));
    }
    if (model.size_parameters) return camera_from_equirectangular(model, params, size);
    for (std::size_t i = 0; i < params.size(); ++i) {
        if (!std::isfinite(params[i])) {
            throw InvalidArgument("COLMAP " + std::string(model.name) + " parameter " + std::to_string(i + 1) +
                                  " (of " + std::string(model.parameters) + "): must be finite, got " +
                                  format_number(params[i]));
        }
    }
    const std::size_t focals = model.one_focal ? 1 : 2;
    Camera camera;
    camera.size = size;
    camera.intrinsics = {params[0], params[focals - 1], params[focals] - kColmapPixelShift,
                         params[focals + 1] - kColmapPixelShift, 0.0};
    camera.lens.type = model.lens;
    camera.lens.coefficients.assign(static_cast<std::size_t>(lens_info(model.lens).num_coefficients), 0.0);
    for (int i = 0; i < model.coefficient_count; ++i) {
        camera.lens.coefficients[static_cast<std::size_t>(model.coefficient[static_cast<std::size_t>(i)])] =
            params[focals + 2 + static_cast<std::size_t>(i)];
    }
    camera.validate();
    return camera;
}

ColmapCamera colmap_from_camera(const Camera& camera, std::optional<std::string_view> name) {
    camera.validate();
    const ColmapModel& model = name ? require_model(*name) : colmap_model_for(camera.lens);
    if (model.size_parameters) return equirectangular_from_camera(model, camera);
    const std::string target = "COLMAP " + std::string(model.name);
    const std::string lens_name(lens_info(camera.lens.type).name);
    // A richer model of the same family fits when its further coefficients are all 0
    // (an OPENCV12 whose thin-prism terms are 0 is an OPENCV8).
    const auto held = static_cast<std::size_t>(lens_info(model.lens).num_coefficients);
    const bool fits_as_smaller = lens_contains(camera.lens.type, model.lens) && all_zero_from(camera.lens.coefficients, held);
    if (!lens_contains(model.lens, camera.lens.type) && !fits_as_smaller) {
        throw NotRepresentable(target + " cannot express the camera's " + lens_name + " lens (it is " +
                               std::string(lens_info(model.lens).name) + ")");
    }
    const Intrinsics& k = camera.intrinsics;
    if (k.skew != 0.0) throw NotRepresentable(target + ": COLMAP has no skew, the camera's is " + format_number(k.skew));
    if (model.one_focal && k.fx != k.fy) {
        throw NotRepresentable(target + " has one focal length; the camera's fx " + format_number(k.fx) + " and fy " +
                               format_number(k.fy) + " differ");
    }
    // The camera's coefficients as the COLMAP model's lens (a family's richer model has
    // the same coefficients followed by more).
    std::vector<double> coefficients = camera.lens.coefficients;
    coefficients.resize(static_cast<std::size_t>(lens_info(model.lens).num_coefficients), 0.0);
    ColmapCamera out{model.name, {}};
    out.params.push_back(k.fx);
    if (!model.one_focal) out.params.push_back(k.fy);
    out.params.push_back(k.cx + kColmapPixelShift);
    out.params.push_back(k.cy + kColmapPixelShift);
    std::vector<bool> carried(coefficients.size(), false);
    for (int i = 0; i < model.coefficient_count; ++i) {
        const auto index = static_cast<std::size_t>(model.coefficient[static_cast<std::size_t>(i)]);
        out.params.push_back(coefficients[index]);
        carried[index] = true;
    }
    const auto names = lens_info(model.lens).coefficients.view();
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
        if (!carried[i] && coefficients[i] != 0.0) {
            throw NotRepresentable(target + " holds " + std::string(names[i]) + " at 0; the camera's is " +
                                   format_number(coefficients[i]));
        }
    }
    return out;
}

}  // namespace libcam
