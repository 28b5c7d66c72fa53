#include "libcam/interop/mrcal.hpp"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include "libcam/error.hpp"
#include "libcam/interop/detail/mrcal_c.hpp"
#include "libcam/interop/mrcal_diagnostic.hpp"
#include "libcam/io/detail/cameramodel_text.hpp"

namespace libcam {

namespace {

// SPLINED_STEREOGRAPHIC's configuration as mrcal parsed it from the name (empty for
// every other model), and as the lens holds it.
std::vector<double> mrcal_configuration(const mrcal_lensmodel_t& model) {
    if (model.type != MRCAL_LENSMODEL_SPLINED_STEREOGRAPHIC) return {};
    const auto& config = model.LENSMODEL_SPLINED_STEREOGRAPHIC__config;
    return {double(config.order), double(config.Nx), double(config.Ny), double(config.fov_x_deg)};
}
std::vector<double> configuration_of(const Lens& lens) {
    const int leading = lens_info(lens.type).mrcal_in_name.leading;
    return {lens.coefficients.begin(), lens.coefficients.begin() + leading};
}

// The lens's mrcal model, by the name the table gives it.
mrcal_lensmodel_t mrcal_lensmodel(const Lens& lens) {
    mrcal_lensmodel_t model{};
    // The configuration in the name: the table's mrcal_in_name (CAHVORE's linearity,
    // SPLINED_STEREOGRAPHIC's order, Nx, Ny and fov_x_deg).
    const std::string name = mrcal_model_name(lens.type, lens.coefficients);
    if (name.empty() || !mrcal_lensmodel_from_name(&model, name.c_str()) || model.type < 0) {
        std::string has;
        for (const LensInfo& info : lens_models()) {
            if (!info.mrcal.empty()) has += (has.empty() ? "" : ", ") + std::string(info.name);
        }
        throw NotRepresentable("lens: model " + std::string(lens_info(lens.type).name) +
                               " has no mrcal equivalent (mrcal models " + has + " among those libcam supports)");
    }
    return model;
}

LensType lens_type_from_mrcal(const mrcal_lensmodel_t& model, const std::string& source) {
    const char* name = mrcal_lensmodel_name_unconfigured(&model);
    // (Appending, not "#" + std::to_string(...): GCC 12 at -O3 raises a false -Wrestrict on that.)
    const std::string mrcal_name =
        name != nullptr ? std::string(name) : std::string("#").append(std::to_string(static_cast<int>(model.type)));
    // A configured model's unconfigured name holds "..." for each value: "LENSMODEL_CAHVORE_linearity=...".
    for (const LensInfo& info : lens_models()) {
        if (!info.mrcal.empty() && mrcal_model_name(info.type) == mrcal_name) return info.type;
    }
    throw NotRepresentable(source + ": \"lensmodel\": " + mrcal_name + " is not a lens model libcam supports");
}

// The camera's mrcal intrinsics vector: fx, fy, cx, cy, then the distortion.
std::vector<double> mrcal_intrinsics(const Camera& camera) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("K: skew " + format_number(camera.intrinsics.skew) +
                               " cannot be stored in mrcal's model (fx, fy, cx, cy only)");
    }
    const Intrinsics& k = camera.intrinsics;
    std::vector<double> values{k.fx, k.fy, k.cx, k.cy};
    const auto& coefficients = camera.lens.coefficients;
    const InMrcalName in_name = lens_info(camera.lens.type).mrcal_in_name;
    values.insert(values.end(), coefficients.begin() + in_name.leading, coefficients.end() - in_name.trailing);
    return values;
}

struct CameramodelDeleter {
    void operator()(mrcal_cameramodel_t* model) const { mrcal_free_cameramodel(&model); }
};
using CameramodelPtr = std::unique_ptr<mrcal_cameramodel_t, CameramodelDeleter>;

// Runs `parse` with stderr sent to a temporary file, and returns what it printed:
// libmrcal's parser reports why it failed only on stderr.
template <class F>
std::string capturing_stderr(F&& parse) {
    static std::mutex mutex;  // fd 2 is process-wide
    const std::lock_guard lock(mutex);
    std::fflush(stderr);
    std::FILE* capture = std::tmpfile();
    const int saved = ::dup(STDERR_FILENO);
    if (capture == nullptr || saved < 0 || ::dup2(::fileno(capture), STDERR_FILENO) < 0) {
        if (capture != nullptr) std::fclose(capture);
        if (saved >= 0) ::close(saved);
        parse();
        return {};
    }
    parse();
    std::fflush(stderr);
    ::dup2(saved, STDERR_FILENO);
    ::close(saved);
    std::string captured;
    std::rewind(capture);
    char buffer[512];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, capture)) > 0) captured.append(buffer, n);
    std::fclose(capture);
    while (!captured.empty() && (captured.back() == '\n' || captured.back() == '\r')) captured.pop_back();
    return captured;
}

CameramodelPtr parse_with_mrcal(std::string_view text, const std::string& source) {
    detail::check_cameramodel_lexically(text, source);
    // libmrcal reads up to a 0 byte when given length 0; the newline ends a final
    // comment, which its lexer would otherwise scan past the end.
    const std::string terminated = std::string(text) + "\n";
    mrcal_cameramodel_t* raw = nullptr;
    const std::string diagnostic = capturing_stderr([&] { raw = mrcal_read_cameramodel_string(terminated.c_str(), 0); });
    if (raw == nullptr) {
        if (text.find("'lens_model'") != std::string_view::npos || text.find("\"lens_model\"") != std::string_view::npos) {
            throw FileError(source + ": it has the legacy key 'lens_model', which libmrcal's C parser rejects: rename it "
                                     "'lensmodel'");
        }
        throw FileError(source + ": " + mrcal_parse_failure(diagnostic, text));
    }
    return CameramodelPtr(raw);
}

std::string number_list(const double* values, int count) {
    std::string out = "[";
    // + 0.0 prints a zero as 0, not -0.
    for (int i = 0; i < count; ++i) out += (i ? ", " : " ") + format_number(values[i] + 0.0);
    return out + " ]";
}

}  // namespace

bool mrcal_unprojects(const Lens& lens) {
    if (lens_info(lens.type).mrcal.empty()) return false;
    const mrcal_lensmodel_t model = mrcal_lensmodel(lens);
    return mrcal_lensmodel_metadata(&model).has_gradients;
}

std::string mrcal_lensmodel_name(const Lens& lens) {
    mrcal_lensmodel(lens);  // throws for a lens mrcal lacks
    return mrcal_model_name(lens.type, lens.coefficients);
}

std::string format_cameramodel(const Camera& camera) { return format_cameramodel(camera, "", -1); }

std::string format_cameramodel(const Camera& camera, const std::string& optimization_inputs, int icam_intrinsics) {
    camera.validate();
    mrcal_lensmodel(camera.lens);  // throws for a lens mrcal lacks
    const std::vector<double> intrinsics = mrcal_intrinsics(camera);
    const Vec3 rvec = camera.pose.rvec();
    const double extrinsics[6] = {rvec.x(), rvec.y(), rvec.z(), camera.pose.t.x(), camera.pose.t.y(), camera.pose.t.z()};

    std::ostringstream out;
    out << "# generated by libcam\n{\n"
        << "    'lensmodel':  '" << mrcal_lensmodel_name(camera.lens) << "',\n"
        << "    # intrinsics are fx,fy,cx,cy,distortion0,distortion1,....\n"
        << "    'intrinsics': " << number_list(intrinsics.data(), static_cast<int>(intrinsics.size())) << ",\n"
        << "    'imagersize': [ " << camera.size.width << ", " << camera.size.height << " ],\n"
        << "    # extrinsics are rt_cam_ref: Rodrigues rotation, then translation (world to camera)\n"
        << "    'extrinsics': " << number_list(extrinsics, 6);
    if (!optimization_inputs.empty()) {
        out << ",\n    'optimization_inputs': " << optimization_inputs << ",\n    'icam_intrinsics': " << icam_intrinsics;
    }
    out << "\n}\n";
    const std::string text = out.str();

    // The text must read back through libmrcal exactly.
    const CameramodelPtr check = parse_with_mrcal(text, "libcam's .cameramodel output");
    bool same = check->imagersize[0] == camera.size.width && check->imagersize[1] == camera.size.height;
    for (std::size_t i = 0; i < intrinsics.size(); ++i) same = same && check->intrinsics[i] == intrinsics[i];
    for (int i = 0; i < 6; ++i) same = same && check->rt_cam_ref[i] == extrinsics[i];
    if (camera.lens.type == LensType::Cahvore) {
        same = same && check->lensmodel.LENSMODEL_CAHVORE__config.linearity == camera.lens.coefficients.back();
    }
    same = same && mrcal_configuration(check->lensmodel) == configuration_of(camera.lens);
    if (!same) throw Error("internal: .cameramodel text does not read back through libmrcal bit for bit");
    return text;
}

Camera parse_cameramodel(std::string_view text, const std::string& source) {
    const CameramodelPtr model = parse_with_mrcal(text, source);
    Camera camera;
    camera.lens.type = lens_type_from_mrcal(model->lensmodel, source);
    const int num_intrinsics = mrcal_lensmodel_num_params(&model->lensmodel);
    const double* values = model->intrinsics;
    camera.intrinsics = Intrinsics{values[0], values[1], values[2], values[3], 0.0};
    camera.lens.coefficients = mrcal_configuration(model->lensmodel);
    camera.lens.coefficients.insert(camera.lens.coefficients.end(), values + 4, values + num_intrinsics);
    if (camera.lens.type == LensType::Cahvore) {
        camera.lens.coefficients.push_back(model->lensmodel.LENSMODEL_CAHVORE__config.linearity);
    }
    camera.size = {static_cast<long>(model->imagersize[0]), static_cast<long>(model->imagersize[1])};
    const double* rt = model->rt_cam_ref;
    camera.pose = Pose::from_rvec(Vec3(rt[0], rt[1], rt[2]), Vec3(rt[3], rt[4], rt[5]));
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        throw FileError(source + ": " + error.what());
    }
    return camera;
}

namespace {

// Throws InvalidArgument unless `in` holds whole points of in_width numbers and `out`
// has room for as many of out_width; returns the count.
int packed_count(const char* function, std::span<const double> in, std::size_t in_width, std::span<double> out,
                 std::size_t out_width) {
    const std::size_t n = in.size() / in_width;
    if (in.size() % in_width != 0 || out.size() != n * out_width || n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw InvalidArgument(std::string(function) + ": expected " + std::to_string(in_width) + " numbers per input and " +
                              std::to_string(out_width) + " per output, got " + std::to_string(in.size()) + " and " +
                              std::to_string(out.size()));
    }
    return static_cast<int>(n);
}

}  // namespace

void mrcal_project_packed(const Camera& camera, std::span<const double> points_xyz, std::span<double> pixels_xy) {
    camera.validate();
    const int n = packed_count("mrcal_project_packed", points_xyz, 3, pixels_xy, 2);
    const mrcal_lensmodel_t model = mrcal_lensmodel(camera.lens);
    const std::vector<double> intrinsics = mrcal_intrinsics(camera);
    // mrcal_point3_t and mrcal_point2_t are unions of x, y[, z] with double[3] / double[2].
    if (!mrcal_project(reinterpret_cast<mrcal_point2_t*>(pixels_xy.data()), nullptr, nullptr,
                       reinterpret_cast<const mrcal_point3_t*>(points_xyz.data()), n, &model, intrinsics.data())) {
        throw Error("mrcal_project failed");
    }
}

void mrcal_unproject_packed(const Camera& camera, std::span<const double> pixels_xy, std::span<double> directions_xyz) {
    camera.validate();
    const int n = packed_count("mrcal_unproject_packed", pixels_xy, 2, directions_xyz, 3);
    const mrcal_lensmodel_t model = mrcal_lensmodel(camera.lens);
    const std::vector<double> intrinsics = mrcal_intrinsics(camera);
    if (!mrcal_unproject(reinterpret_cast<mrcal_point3_t*>(directions_xyz.data()),
                         reinterpret_cast<const mrcal_point2_t*>(pixels_xy.data()), n, &model, intrinsics.data())) {
        throw Error("mrcal_unproject failed");
    }
}

std::vector<Vec2> mrcal_project_points(const Camera& camera, const std::vector<Vec3>& camera_points) {
    std::vector<double> in;
    in.reserve(3 * camera_points.size());
    for (const Vec3& p : camera_points) in.insert(in.end(), {p.x(), p.y(), p.z()});
    std::vector<double> out(2 * camera_points.size());
    camera.validate();  // so that what the catches below see is mrcal's refusal alone
    // mrcal refuses a whole call when one point is outside what it can project (CAHVORE
    // past |L| theta = 90 degrees, saying so on stderr): then one point at a time, NaN
    // for those, with mrcal's messages kept off stderr.
    const auto project_each = [&] {
        for (std::size_t i = 0; i < camera_points.size(); ++i) {
            try {
                mrcal_project_packed(camera, std::span<const double>(in).subspan(3 * i, 3),
                                     std::span<double>(out).subspan(2 * i, 2));
            } catch (const NotRepresentable&) {
                throw;
            } catch (const Error&) {
                out[2 * i] = out[2 * i + 1] = std::numeric_limits<double>::quiet_NaN();
            }
        }
    };
    std::exception_ptr failure;  // nothing may leave capturing_stderr by an exception
    const auto project = [&] {
        try {
            try {
                mrcal_project_packed(camera, in, out);
            } catch (const NotRepresentable&) {
                throw;
            } catch (const Error&) {
                project_each();
            }
        } catch (...) {
            failure = std::current_exception();
        }
    };
    if (camera.lens.type == LensType::Cahvore) {
        (void)capturing_stderr(project);
    } else {
        project();
    }
    if (failure) std::rethrow_exception(failure);
    std::vector<Vec2> pixels(camera_points.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = {out[2 * i], out[2 * i + 1]};
    return pixels;
}

std::vector<Vec3> mrcal_unproject_pixels(const Camera& camera, const std::vector<Vec2>& pixels) {
    std::vector<double> in;
    in.reserve(2 * pixels.size());
    for (const Vec2& q : pixels) in.insert(in.end(), {q.x(), q.y()});
    std::vector<double> out(3 * pixels.size());
    mrcal_unproject_packed(camera, in, out);
    std::vector<Vec3> directions(pixels.size());
    for (std::size_t i = 0; i < directions.size(); ++i) directions[i] = {out[3 * i], out[3 * i + 1], out[3 * i + 2]};
    return directions;
}

}  // namespace libcam
