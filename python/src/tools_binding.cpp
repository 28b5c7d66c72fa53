#include "tools_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "arrays.hpp"
#include "camera_binding.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
#include "libcam/fit/scene.hpp"
#include "libcam/check/verify.hpp"
#include "libcam/remap/new_camera.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/stereo/rectify.hpp"

namespace libcam::python {


namespace {

// The statistics under the names every report gives them (error_stats_fields).
py::dict stats_dict(const ErrorStats& stats) {
    py::dict out;
    for (const ErrorStatsField& field : error_stats_fields(stats)) {
        if (field.name == "count") {
            out["count"] = stats.count;
        } else {
            out[py::str(std::string(field.name))] = field.value;
        }
    }
    return out;
}

template <class T>
py::object optional_value(const std::optional<T>& value) {
    return value ? py::cast(*value) : py::object(py::none());
}

// ---------------------------------------------------------------------------- verify

py::dict verify(const PythonCamera& camera, const py::object& grid, const std::vector<double>& depths, int threads) {
    VerifyOptions options;
    const std::vector<double> columns_rows = vector_any(grid, "grid");
    if (columns_rows.size() != 2) throw py::type_error("grid: expected (columns, rows)");
    options.grid_columns = static_cast<long>(columns_rows[0]);
    options.grid_rows = static_cast<long>(columns_rows[1]);
    options.depths = depths;
    options.threads = threads;
    VerifyReport report;
    {
        py::gil_scoped_release release;
        report = verify_camera(camera.camera(), options);
    }
    py::list checks;
    for (const VerifyCheck& check : report.checks) {
        py::dict row;
        row["name"] = check.name;
        row["library"] = check.library;
        row["tolerance_px"] = optional_value(check.tolerance_px);
        row["skipped_because"] = optional_value(check.skipped_because);
        row["note"] = check.note;
        row["stats"] = stats_dict(check.stats);
        row["pass"] = check.pass();
        checks.append(row);
    }
    py::dict out;
    out["pass"] = report.pass();
    out["model"] = std::string(lens_info(report.lens_type).name);
    out["grid"] = py::make_tuple(options.grid_columns, options.grid_rows);
    out["invalid_fraction"] = report.invalid_fraction;
    out["checks"] = checks;
    if (report.opencv_default) {
        const OpenCvDefaultSummary& s = *report.opencv_default;
        py::dict summary;
        summary["function"] = s.function;
        summary["median_px"] = s.median_px;
        summary["max_px"] = s.max_px;
        summary["worst_pixel"] = py::make_tuple(s.worst_pixel.x(), s.worst_pixel.y());
        summary["fraction_over_0_1px"] = s.fraction_over_0_1px;
        summary["fraction_over_1px"] = s.fraction_over_1px;
        out["opencv_default"] = summary;
    } else {
        out["opencv_default"] = py::none();
    }
    return out;
}

// ------------------------------------------------------------------------------- fit

CameraMotion motion_from(const std::string& name) {
    if (name == "none") return CameraMotion::None;
    if (name == "rotation") return CameraMotion::Rotation;
    if (name == "rotation+shift") return CameraMotion::RotationAndShift;
    throw InvalidArgument("motion: expected 'none', 'rotation' or 'rotation+shift', got '" + name + "'");
}

Scene scene_from(const py::object& radius, const py::object& center, const py::object& roi, const py::object& max_angle,
                 const ImageSize& size) {
    const int given = int(!radius.is_none()) + int(!roi.is_none()) + int(!max_angle.is_none());
    if (given > 1) throw InvalidArgument("radius, roi, max_angle: give one scene, not several");
    if (!center.is_none() && radius.is_none()) throw InvalidArgument("center: goes with radius");
    if (!radius.is_none()) {
        Vec2 c(size.centre_x(), size.centre_y());
        if (!center.is_none()) {
            const std::vector<double> xy = vector_any(center, "center");
            if (xy.size() != 2) throw py::type_error("center: expected (x, y)");
            c = Vec2(xy[0], xy[1]);
        }
        return Scene::circle(radius.cast<double>(), c);
    }
    if (!roi.is_none()) {
        const std::vector<double> box = vector_any(roi, "roi");
        if (box.size() != 4) throw py::type_error("roi: expected (x0, y0, x1, y1)");
        return Scene::rectangle({box[0], box[1]}, {box[2], box[3]});
    }
    if (!max_angle.is_none()) return Scene::field_angle(max_angle.cast<double>());
    return Scene::whole_image();
}

py::dict fit(const PythonCamera& source, double tolerance, const py::object& radius, const py::object& center,
             const py::object& roi, const py::object& max_angle, const std::optional<std::vector<std::string>>& models,
             const std::vector<double>& depths, const std::string& motion) {
    const Camera& camera = source.camera();
    const Scene scene = scene_from(radius, center, roi, max_angle, camera.size);
    FitOptions options;
    options.tolerance_px = tolerance;
    options.depths = depths;
    options.motion = motion_from(motion);
    if (models) {
        for (const std::string& name : *models) options.candidates.push_back(candidate_named(name));
    }
    FitReport report;
    {
        py::gil_scoped_release release;
        report = fit_scene(camera, scene, options);
    }
    py::list candidates;
    for (const CandidateReport& candidate : report.candidates) {
        py::dict row;
        row["model"] = std::string(candidate.fit.candidate.name);
        row["camera"] = PythonCamera(camera_in_world(candidate.fit, camera));
        row["rms_px"] = candidate.rms_px;
        row["max_px"] = candidate.max_px;
        row["covers_scene"] = candidate.covers_scene;
        row["pass"] = candidate.pass;
        candidates.append(row);
    }
    py::dict out;
    out["scene"] = scene.describe(camera.size);
    out["tolerance_px"] = tolerance;
    out["largest_angle_deg"] = report.largest_angle_deg;
    out["fit_samples"] = report.fit_observations;
    out["check_samples"] = report.check_observations;
    out["candidates"] = candidates;
    out["chosen"] = report.chosen ? candidates[*report.chosen] : py::object(py::none());
    return out;
}

// ------------------------------------------------------------------- new camera, map

Keep keep_from(const std::string& name) {
    if (name == "valid") return Keep::Valid;
    if (name == "all") return Keep::All;
    throw InvalidArgument("keep: expected 'valid' or 'all', got '" + name + "'");
}

py::tuple new_camera(const PythonCamera& source, const std::string& model, const std::optional<std::string>& keep,
                     const std::optional<double>& fov, const std::string& fov_axis, const py::object& size,
                     const py::object& rotation, int threads) {
    NewCameraRequest request;
    const std::optional<LensType> type = lens_type_from_name(model);
    if (!type) throw InvalidArgument("model: expected PINHOLE, LONLAT or CYLINDRICAL, got '" + model + "'");
    request.model = *type;
    if (fov && keep) throw InvalidArgument("keep, fov: give one of them, not both");
    request.keep = fov ? std::nullopt : std::optional<Keep>(keep_from(keep.value_or("valid")));
    request.fov_deg = fov.value_or(0.0);
    request.fov_axis = fov_axis_from_string(fov_axis);
    if (!size.is_none()) request.size = size_from(size);
    if (!rotation.is_none()) request.rotation = matrix3(rotation, "rotation");
    request.threads = thread_count(threads);
    NewCamera chosen;
    {
        py::gil_scoped_release release;
        chosen = choose_new_camera(source.prepared(), request);
    }
    return py::make_tuple(PythonCamera(chosen.camera), chosen.why);
}

template <class T>
py::tuple map_arrays(const BasicRemapMap<T>& map) {
    const std::vector<py::ssize_t> shape{map.size.height, map.size.width};
    py::array_t<T> coordinates = new_array<T>(shape, 2);
    py::array_t<bool> mask = new_array<bool>(shape, 0);
    T* out = coordinates.mutable_data();
    bool* valid = mask.mutable_data();
    const std::size_t n = map.x.size();
    {
        py::gil_scoped_release release;
        for (std::size_t i = 0; i < n; ++i) {
            out[2 * i] = map.x[i];
            out[2 * i + 1] = map.y[i];
            valid[i] = map.has_source(i);
        }
    }
    return py::make_tuple(std::move(coordinates), std::move(mask));
}

py::tuple remap_map(const PythonCamera& target, const PythonCamera& source, const std::string& method,
                    const py::object& rotation, const py::object& dtype, int threads) {
    RemapOptions options;
    const std::optional<UnprojectMethod> m = method_from_name(method);
    if (!m) throw InvalidArgument("method: expected 'exact', 'fast' or 'lut', got '" + method + "'");
    options.method = *m;
    options.rotation = rotation.is_none() ? rotation_between(target.camera(), source.camera()) : matrix3(rotation, "rotation");
    options.threads = thread_count(threads);
    const py::dtype type = py::dtype::from_args(dtype);
    if (!type.is(py::dtype::of<float>()) && !type.is(py::dtype::of<double>())) {
        throw py::type_error("dtype: expected numpy.float32 or numpy.float64, got " + type.attr("name").cast<std::string>());
    }
    // A float map is built in float (the double map rounded once): half the memory.
    const auto built = [&]<class T>() {
        BasicRemapMap<T> map;
        {
            py::gil_scoped_release release;
            map = build_remap_map<T>(target.prepared(), source.prepared(), options);
        }
        return map_arrays<T>(map);
    };
    return type.is(py::dtype::of<float>()) ? built.template operator()<float>() : built.template operator()<double>();
}

// ------------------------------------------------------------------------- stereo

// A rectified pair with the two source cameras its maps come from.
struct PythonStereoPair {
    RectifiedPair pair;
    PythonCamera first, second;
};

PythonStereoPair rectify(const PythonCamera& first, const PythonCamera& second, const std::string& to,
                         const std::string& keep, const py::object& size, int threads) {
    RectifyRequest request;
    if (to == "pinhole") {
        request.model = LensType::Pinhole;
    } else if (to == "latlon") {
        request.model = LensType::Latlon;
    } else if (to != "auto") {
        throw InvalidArgument("to: expected 'pinhole', 'latlon' or 'auto', got '" + to + "'");
    }
    request.keep = keep_from(keep);
    if (!size.is_none()) request.size = size_from(size);
    request.threads = thread_count(threads);
    RectifiedPair pair;
    {
        py::gil_scoped_release release;
        pair = rectify_pair(first.camera(), second.camera(), request);
    }
    return {std::move(pair), first, second};
}

// (N, 2) left pixels and N disparities, as float64 arrays.
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <class Each>
void for_each_disparity(const Doubles& pixels, const Doubles& disparity, Each&& each) {
    if (pixels.ndim() != 2 || pixels.shape(1) != 2) throw py::type_error("pixels: expected shape (N, 2)");
    if (disparity.ndim() != 1 || disparity.shape(0) != pixels.shape(0)) {
        throw py::type_error("disparity: expected shape (N,), one per pixel");
    }
    const double* p = pixels.data();
    const double* d = disparity.data();
    for (py::ssize_t i = 0; i < pixels.shape(0); ++i) each(i, Vec2(p[2 * i], p[2 * i + 1]), d[i]);
}

py::array_t<double> disparity_to_range(const PythonStereoPair& stereo, const Doubles& pixels, const Doubles& disparity) {
    py::array_t<double> out(pixels.ndim() == 2 ? pixels.shape(0) : 0);
    double* r = out.mutable_data();
    for_each_disparity(pixels, disparity, [&](py::ssize_t i, const Vec2& q, double d) {
        r[i] = range_from_disparity(stereo.pair, q, d);
    });
    return out;
}

py::array_t<double> disparity_to_points(const PythonStereoPair& stereo, const Doubles& pixels, const Doubles& disparity) {
    py::array_t<double> out(std::vector<py::ssize_t>{pixels.ndim() == 2 ? pixels.shape(0) : 0, 3});
    double* x = out.mutable_data();
    for_each_disparity(pixels, disparity, [&](py::ssize_t i, const Vec2& q, double d) {
        const Vec3 point = point_from_disparity(stereo.pair, q, d);
        for (int c = 0; c < 3; ++c) x[3 * i + c] = point[c];
    });
    return out;
}

py::tuple stereo_maps(const PythonStereoPair& stereo, const py::object& dtype, int threads) {
    py::list maps;
    for (std::size_t k = 0; k < 2; ++k) {
        const PythonCamera rectified(stereo.pair.cameras[k].camera);
        maps.append(remap_map(rectified, k == 0 ? stereo.first : stereo.second, "exact",
                              to_numpy(stereo.pair.cameras[k].rotation), dtype, threads));
    }
    return py::tuple(maps);
}

}  // namespace

void bind_tools(py::module_& m) {
    py::class_<PythonStereoPair>(m, "RectifiedPair", "A rectified stereo pair (libcam.rectify).")
        .def_property_readonly("model", [](const PythonStereoPair& s) { return std::string(lens_info(s.pair.model).name); },
                               "'PINHOLE' or 'LATLON'.")
        .def_property_readonly("baseline", [](const PythonStereoPair& s) { return s.pair.baseline; },
                               "The distance between the two centres, in the poses' units.")
        .def_property_readonly("cameras", [](const PythonStereoPair& s) {
            return py::make_tuple(PythonCamera(s.pair.cameras[0].camera), PythonCamera(s.pair.cameras[1].camera));
        }, "The two rectified cameras (in the sources' world).")
        .def_property_readonly("rotations", [](const PythonStereoPair& s) {
            return py::make_tuple(to_numpy(s.pair.cameras[0].rotation), to_numpy(s.pair.cameras[1].rotation));
        }, "Each source camera's frame into the rectified frame (OpenCV's R1, R2).")
        .def_property_readonly("kept", [](const PythonStereoPair& s) {
            return py::make_tuple(s.pair.cameras[0].kept, s.pair.cameras[1].kept);
        }, "The share of each source image's pixels looking in front of it that land on its rectified image.")
        .def_property_readonly("Q", [](const PythonStereoPair& s) -> py::object {
            if (s.pair.model != LensType::Pinhole) return py::none();
            return to_numpy(s.pair.Q);
        }, "PINHOLE: OpenCV's disparity-to-depth matrix; None for LATLON.")
        .def_property_readonly("why", [](const PythonStereoPair& s) { return s.pair.why; })
        .def("maps", &stereo_maps, py::arg("dtype") = py::dtype::of<float>(), py::arg("threads") = 1,
             "((map, valid), (map, valid)): each source image's map into its rectified image, as remap_map gives it.")
        .def("__repr__", [](const PythonStereoPair& s) {
            return "<libcam.RectifiedPair " + std::string(lens_info(s.pair.model).name) + ", baseline " +
                   std::to_string(s.pair.baseline) + ">";
        });
    m.def("rectify", &rectify, py::arg("first"), py::arg("second"), py::arg("to") = "auto", py::arg("keep") = "valid",
          py::arg("size") = py::none(), py::arg("threads") = 1, R"doc(
The two cameras rectified (as the libcam program's rectify command): to 'pinhole' (OpenCV's
stereoRectify), 'latlon' (mrcal's rectified_system) or 'auto'; keep 'valid' (no black border)
or 'all' (pinhole). The cameras' poses place them in one world. Returns a RectifiedPair.)doc");
    m.def("disparity_to_range", &disparity_to_range, py::arg("pair"), py::arg("pixels"), py::arg("disparity"), R"doc(
The distance from the first camera's centre of each point seen at `pixels` (N, 2) of the
first rectified image with `disparity` (N,) = u_left - u_right: PINHOLE through Q, LATLON
as mrcal.stereo_range. NaN where the disparity is not positive.)doc");
    m.def("disparity_to_points", &disparity_to_points, py::arg("pair"), py::arg("pixels"), py::arg("disparity"),
          "The points (N, 3) in the first rectified camera's frame (see disparity_to_range).");
    m.def("verify", &verify, py::arg("camera"), py::arg("grid") = py::make_tuple(200, 150),
          py::arg("depths") = std::vector<double>{0.5, 2.0, 10.0, 1000.0}, py::arg("threads") = 0, R"doc(
Checks the camera's projection and unprojection against OpenCV and mrcal on a grid of
pixels (as the libcam program's verify command): {'pass', 'model', 'grid',
'invalid_fraction', 'checks': [{'name', 'library', 'tolerance_px', 'skipped_because',
'note', 'stats': {'count', 'median_px', 'p99_px', 'max_px', 'rms_px'}, 'pass'}],
'opencv_default': where cv2.undistortPoints' default iterations go wrong}.)doc");
    m.def("fit", &fit, py::arg("camera"), py::arg("tolerance") = 1.0, py::arg("radius") = py::none(),
          py::arg("center") = py::none(), py::arg("roi") = py::none(), py::arg("max_angle") = py::none(),
          py::arg("models") = py::none(), py::arg("depths") = std::vector<double>{}, py::arg("motion") = "none", R"doc(
The simplest lens model that reproduces the camera within `tolerance` pixels over a
scene (as the libcam program's fit command): the whole image, or a circle (radius,
center), a rectangle (roi = (x0, y0, x1, y1)) or the rays within max_angle degrees of the
optical axis. models: the candidates to try (default: simplest first, by the scene's
width). Returns {'scene', 'tolerance_px', 'largest_angle_deg', 'fit_samples',
'check_samples', 'candidates': [{'model', 'camera', 'rms_px', 'max_px', 'covers_scene',
'pass'}], 'chosen': the first candidate that passes, or None}.)doc");
    m.def("new_camera", &new_camera, py::arg("source"), py::arg("model") = "PINHOLE", py::arg("keep") = py::none(),
          py::arg("fov") = py::none(), py::arg("fov_axis") = "horizontal", py::arg("size") = py::none(),
          py::arg("rotation") = py::none(), py::arg("threads") = 1, R"doc(
The camera to turn the source's images into (undistortion), chosen for you: a PINHOLE,
LONLAT or CYLINDRICAL camera that keeps 'valid' (every pixel has a source: no black
borders; the default) or 'all' (every source pixel lands on the image), or has the field
of view `fov` degrees on fov_axis. Returns (camera, why).)doc");
    m.def("remap_map", &remap_map, py::arg("target"), py::arg("source"), py::arg("method") = "exact",
          py::arg("rotation") = py::none(), py::arg("dtype") = py::dtype::of<float>(), py::arg("threads") = 1, R"doc(
The map that turns an image of `source` into an image of `target`: for each target pixel
the source pixel seeing the same ray. Returns (map, valid): map of shape (height, width, 2)
holding (x, y) source coordinates, which cv2.remap(image, map, None, cv2.INTER_LINEAR)
takes as it is, and valid of shape (height, width), both in OpenCV's pixels (row 0 at the
top, as images are stored) whatever the cameras' pixel_origin. Target pixels without a
source get NaN (cv2.remap gives them its border value). rotation: the target's axes relative to the
source's (default: from the two cameras' poses).)doc");
}

}  // namespace libcam::python
