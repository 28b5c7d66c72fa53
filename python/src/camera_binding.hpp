#pragma once
// libcam.Camera: a calibrated camera, validated once, with the batch engine it projects
// and unprojects through. Immutable: every change makes a new camera.

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/graphics/look_at_camera.hpp"
#include "libcam/geometry/pixel_origin.hpp"

namespace libcam::python {

namespace py = pybind11;

class PythonCamera {
public:
    // Validates the camera (libcam.Error naming the field otherwise).
    explicit PythonCamera(const Camera& camera, PixelOrigin origin = PixelOrigin::TopLeft,
                          std::optional<LookAtCamera> look_at_camera = std::nullopt);

    const Camera& camera() const { return state_->prepared.camera(); }
    const PreparedCamera& prepared() const { return state_->prepared; }
    PixelOrigin pixel_origin() const { return state_->origin; }
    const std::optional<LookAtCamera>& look_at_camera() const { return state_->look_at_camera; }

    template <class T>
    const Projector<T>& projector() const;
    // Built on first use (the table of the models solved iteratively), once.
    template <class T>
    const Unprojector<T>& unprojector() const;

private:
    struct State {
        State(const PreparedCamera& camera, PixelOrigin pixel_origin, std::optional<LookAtCamera> fov)
            : prepared(camera), origin(pixel_origin), look_at_camera(std::move(fov)), projector_double(camera),
              projector_float(camera) {}
        PreparedCamera prepared;
        PixelOrigin origin;
        std::optional<LookAtCamera> look_at_camera;
        Projector<double> projector_double;
        Projector<float> projector_float;
        std::once_flag float_unprojector_built;
        std::unique_ptr<const Unprojector<float>> float_unprojector;
    };
    std::shared_ptr<State> state_;
};

void bind_camera(py::module_& m);

// The camera's parts from Python arguments, checked (TypeError for a wrong shape,
// libcam.Error naming the field for a value out of range): a lens model's name and its
// coefficients; the pose from R or rvec, and t; the image size (width, height).
Lens lens_from(const std::string& model, const std::vector<double>& dist);
Pose pose_from(const py::object& R, const py::object& t, const py::object& rvec);
ImageSize size_from(const py::object& size);

}  // namespace libcam::python
