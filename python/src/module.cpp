// The compiled part of the libcam Python package (libcam/_libcam): cameras, files, the
// lens-model table and libcam's errors. The package's __init__.py re-exports it.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "calibrate_binding.hpp"
#include "camera_binding.hpp"
#include "dataset_binding.hpp"
#include "libcam/camera/simd.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/version.hpp"
#include "observations_binding.hpp"
#include "tools_binding.hpp"

namespace libcam::python {


namespace {

std::string_view inverse_name(Inverse inverse) { return inverse == Inverse::ClosedForm ? "closed-form" : "solved"; }

std::string_view opencv_name(OpenCvFunction function) {
    switch (function) {
        case OpenCvFunction::None: return "";
        case OpenCvFunction::ProjectPoints: return "cv2.projectPoints";
        case OpenCvFunction::Fisheye: return "cv2.fisheye.projectPoints";
        case OpenCvFunction::Omnidir: return "cv2.omnidir.projectPoints";
    }
    return "";
}

// The lens-model table, one dict per model, keyed by name.
py::dict model_table() {
    py::dict models;
    for (const LensInfo& info : lens_models()) {
        py::list coefficients;
        for (std::string_view name : info.coefficients.view()) coefficients.append(std::string(name));
        py::dict row;
        row["name"] = std::string(info.name);
        row["coefficients"] = py::tuple(coefficients);
        row["coefficient_count"] = info.num_coefficients == kVariableCoefficientCount ? py::object(py::none())
                                                                                       : py::object(py::int_(info.num_coefficients));
        row["sees_behind_camera"] = info.sees_behind_camera;
        row["inverse"] = std::string(inverse_name(info.inverse));
        row["opencv"] = std::string(opencv_name(info.opencv));
        row["mrcal"] = std::string(info.mrcal);
        row["colmap"] = std::string(info.colmap);
        row["kalibr"] = std::string(info.kalibr);
        row["basalt"] = std::string(info.basalt);
        models[py::str(std::string(info.name))] = row;
    }
    return models;
}

// The lens model cv2 uses for a distortion vector of this many coefficients.
LensType opencv_model_for(std::size_t count) {
    switch (count) {
        case 0: return LensType::Pinhole;
        case 4: return LensType::OpenCv4;
        case 5: return LensType::OpenCv5;
        case 8: return LensType::OpenCv8;
        case 12: return LensType::OpenCv12;
        case 14: return LensType::OpenCv14;
        default: break;
    }
    throw InvalidArgument("dist: OpenCV takes 4, 5, 8, 12 or 14 coefficients, got " + std::to_string(count) +
                          " (for cv2.fisheye give model='FISHEYE')");
}

PythonCamera from_opencv(const py::object& K, const py::object& dist, const py::object& size, const py::object& rvec,
                         const py::object& tvec, const std::optional<std::string>& model) {
    Camera camera;
    camera.size = size_from(size);
    camera.intrinsics = Intrinsics::from_K(matrix3(K, "K"), "K");
    const std::vector<double> coefficients = dist.is_none() ? std::vector<double>{} : vector_any(dist, "dist");
    camera.lens = model ? lens_from(*model, coefficients) : Lens{opencv_model_for(coefficients.size()), coefficients};
    camera.lens.validate("dist");
    camera.pose = pose_from(py::none(), tvec, rvec);
    return PythonCamera(camera);
}

PythonCamera from_fov(double fov_deg, const py::object& size, const std::string& axis, const py::object& eye,
                      const py::object& target, const py::object& gaze, const py::object& up,
                      const std::string& pixel_origin) {
    if (!target.is_none() && !gaze.is_none()) throw InvalidArgument("target, gaze: give one of them, not both");
    LookAtCamera fov;
    fov.size = size_from(size);
    fov.fov_deg = fov_deg;
    fov.fov_axis = fov_axis_from_string(axis);
    fov.eye = vector3(eye, "eye");
    fov.up = vector3(up, "up");
    if (!target.is_none()) fov.gaze = vector3(target, "target") - fov.eye;
    if (!gaze.is_none()) fov.gaze = vector3(gaze, "gaze");
    fov.validate();
    return PythonCamera(to_camera(fov), pixel_origin_from_string(pixel_origin), fov);
}

ReadOptions read_options(const py::object& size) {
    ReadOptions options;
    if (!size.is_none()) options.size = size_from(size);
    return options;
}

std::optional<CameraFormat> format_from(const std::optional<std::string>& name) {
    if (!name) return std::nullopt;
    return camera_format_from_string(*name);
}

PythonCamera camera_of(const CameraFile& file) { return PythonCamera(file.camera, PixelOrigin::TopLeft, file.look_at_camera); }

}  // namespace

}  // namespace libcam::python

namespace py = pybind11;
using namespace libcam;
using namespace libcam::python;

PYBIND11_MODULE(_libcam, m) {
    m.doc() = "libcam: graphics cameras and calibrated cameras, exact both ways.";
    m.attr("__version__") = LIBCAM_VERSION;
    // .cameramodel files go through libmrcal's own parser.
    register_interop_formats();

    // libcam's errors: ValueError subclasses whose message names the field and the value
    // (made printable: a message that quotes a file's bytes is still a valid str).
    static py::exception<Error> error(m, "Error", PyExc_ValueError);
    static py::exception<FileError> file_error(m, "FileError", error.ptr());
    static py::exception<NotRepresentable> not_representable(m, "NotRepresentable", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const FileError& e) {
            file_error(printable_text(e.what()).c_str());
        } catch (const NotRepresentable& e) {
            not_representable(printable_text(e.what()).c_str());
        } catch (const Error& e) {
            error(printable_text(e.what()).c_str());
        }
    });

    m.attr("models") = model_table();
    m.attr("formats") = [] {
        py::list names;
        for (std::size_t i = 0; i < kCameraFormatCount; ++i) {
            names.append(std::string(to_string(static_cast<CameraFormat>(i))));
        }
        return py::tuple(names);
    }();

    bind_camera(m);
    bind_tools(m);
    bind_observations(m);
    bind_dataset(m);
    bind_calibrate(m);

    m.def(
        "simd_target", [] { return std::string(simd_target_name(simd_target())); },
        R"doc(
The instruction set the batch calls run on: 'sse2', 'avx2' or 'avx512', the best this CPU
has unless set_simd_target() or the environment variable LIBCAM_SIMD chose another. Every
set gives the same bits.)doc");
    m.def(
        "supported_simd_targets",
        [] {
            py::list names;
            for (SimdTarget target : supported_simd_targets()) names.append(std::string(simd_target_name(target)));
            return names;
        },
        "The instruction sets this build has and this CPU runs, the baseline ('sse2') first.");
    m.def(
        "set_simd_target",
        [](const std::optional<std::string>& name) {
            if (!name) return set_simd_target(std::nullopt);
            const std::optional<SimdTarget> target = simd_target_from_name(*name);
            if (!target) throw InvalidArgument("set_simd_target: expected 'sse2', 'avx2' or 'avx512', got '" + *name + "'");
            set_simd_target(*target);
        },
        py::arg("name"), R"doc(
Forces the instruction set of every later batch call ('sse2', 'avx2', 'avx512'), to time
one against another; None goes back to the default. Raises libcam.Error for a name it
does not know or a set this CPU does not run.)doc");

    m.def(
        "read",
        [](const std::string& path, const std::optional<std::string>& camera, const std::optional<std::string>& format,
           const py::object& size) {
            return camera_of(read_camera_file(path, camera.value_or(""), format_from(format), read_options(size)));
        },
        py::arg("path"), py::arg("camera") = py::none(), py::arg("format") = py::none(), py::arg("size") = py::none(),
        R"doc(
Reads one camera of a camera file (OpenCV YAML/XML, mrcal .cameramodel, Kalibr, ROS,
COLMAP, basalt, NeRF transforms.json, libcam JSON, ...; libcam.formats lists them).
camera: the file's name for it, its image's file name alone where that name is a path
        and no other camera's image shares it, or its position counting from 0 (default:
        the first).
format: the format's name, when the extension and contents do not tell.
size: (width, height), for files that do not record it (NeRF's synthetic scenes).
Raises libcam.FileError naming the file and the field for a file it cannot read.)doc");
    m.def(
        "read_all",
        [](const std::string& path, const std::optional<std::string>& format, const py::object& size) {
            const CameraSet set = read_camera_set(path, format_from(format), read_options(size));
            py::dict cameras;
            for (std::size_t i = 0; i < set.cameras.size(); ++i) {
                const NamedCamera& named = set.cameras[i];
                const std::string name = named.name.empty() ? std::to_string(i) : named.name;
                cameras[py::str(name)] = camera_of(named.file);
            }
            return cameras;
        },
        py::arg("path"), py::arg("format") = py::none(), py::arg("size") = py::none(),
        "Every camera of a file (a stereo pair, a rig, COLMAP's images) as {name: Camera}, in the file's order.");
    m.def("from_opencv", &from_opencv, py::arg("K"), py::arg("dist"), py::arg("size"), py::arg("rvec") = py::none(),
          py::arg("tvec") = py::none(), py::arg("model") = py::none(), R"doc(
The camera cv2.calibrateCamera describes: K (3x3), dist (4, 5, 8, 12 or 14 coefficients
in OpenCV's order, any shape cv2 gives), size (width, height), and optionally the pose
rvec, tvec (world to camera). model: the lens model when the count does not say it
(model='FISHEYE' for cv2.fisheye's k1..k4, 'MEI' for cv2.omnidir's xi, k1, k2, p1, p2).)doc");
    m.def("from_fov", &from_fov, py::arg("fov_deg"), py::arg("size"), py::arg("axis") = "both",
          py::arg("eye") = py::make_tuple(0, 0, 0), py::arg("target") = py::none(), py::arg("gaze") = py::none(),
          py::arg("up") = py::make_tuple(0, 1, 0), py::arg("pixel_origin") = "top-left", R"doc(
The graphics (look-at) camera: an eye, a target (or a gaze direction; default: looking
down -z), an up vector and a field of view, as a PINHOLE camera whose rays are the
look-at formula's d = alpha u + beta v + w.
axis: which span the angle measures: 'horizontal', 'vertical', 'diagonal', or 'both' (the
      look-at formula's own: the same angle across the width and the height, so pixels are
      square only for a square image).
pixel_origin: 'top-left' (OpenCV's pixels) or 'bottom-left' (rows counted upward, as the
      look-at formula counts them): the convention of every pixel this camera takes and gives.)doc");
}
