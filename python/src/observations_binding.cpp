#include "observations_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "camera_binding.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"

namespace libcam::python {

namespace {

// An (n, columns) float64 array filled by fill(row, out_row).
template <class Fill>
py::array_t<double> rows(std::size_t n, std::size_t columns, Fill&& fill) {
    py::array_t<double> out({n, columns});
    auto view = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < n; ++i) fill(i, &view(static_cast<py::ssize_t>(i), 0));
    return out;
}

template <class T, class Get>
py::array_t<T> column(std::size_t n, Get&& get) {
    py::array_t<T> out(n);
    auto view = out.template mutable_unchecked<1>();
    for (std::size_t i = 0; i < n; ++i) view(static_cast<py::ssize_t>(i)) = get(i);
    return out;
}

py::dict stats_dict(const ResidualStats& r) {
    py::dict out;
    out["count"] = r.stats.count;
    const bool measured = r.stats.count > 0;
    const auto value = [&](double v) { return measured ? py::cast(v) : py::object(py::none()); };
    out["rms_px"] = value(r.stats.rms_px);
    out["mean_px"] = value(r.mean_px);
    out["median_px"] = value(r.stats.median_px);
    out["p99_px"] = value(r.stats.p99_px);
    out["max_px"] = value(r.stats.max_px);
    out["bias_px"] = py::make_tuple(r.bias.x(), r.bias.y());
    out["weighted_rms_px"] = r.weighted_rms_px ? py::cast(*r.weighted_rms_px) : py::object(py::none());
    return out;
}

py::list groups(const std::vector<GroupResiduals>& list) {
    py::list out;
    for (const GroupResiduals& g : list) {
        py::dict entry = stats_dict(g.residuals);
        entry["name"] = g.name;
        out.append(entry);
    }
    return out;
}

py::object comparison(const std::optional<PerItemComparison>& c) {
    if (!c) return py::none();
    py::dict out;
    out["compared"] = c->compared;
    out["max_abs_difference_px"] = c->max_abs_difference;
    out["worst"] = c->worst_item;
    return out;
}

// The residuals as arrays in the file's own pixels, and the summary as dicts.
py::dict reprojection_dict(const ObservationSet& set, const Reprojection& r) {
    const std::size_t n = set.observations.size();
    const Vec2 offset = set.pixel_offset;
    py::dict out;
    out["observed"] = rows(n, 2, [&](std::size_t i, double* row) {
        row[0] = set.observations[i].pixel.x() + offset.x();
        row[1] = set.observations[i].pixel.y() + offset.y();
    });
    out["projected"] = rows(n, 2, [&](std::size_t i, double* row) {
        row[0] = r.residuals[i].projected.x() + offset.x();
        row[1] = r.residuals[i].projected.y() + offset.y();
    });
    out["residual"] = rows(n, 2, [&](std::size_t i, double* row) {
        row[0] = r.residuals[i].residual.x();
        row[1] = r.residuals[i].residual.y();
    });
    out["error_px"] = column<double>(n, [&](std::size_t i) { return r.residuals[i].error_px; });
    out["counted"] = column<bool>(n, [&](std::size_t i) { return r.residuals[i].status == ResidualStatus::Counted; });
    py::list status;
    for (const ObservationResidual& residual : r.residuals) status.append(std::string(to_string(residual.status)));
    out["status"] = status;
    out["view"] = column<std::int64_t>(n, [&](std::size_t i) { return set.observations[i].view; });
    out["point_id"] = column<std::int64_t>(n, [&](std::size_t i) {
        return set.point_ids[static_cast<std::size_t>(set.observations[i].point)];
    });
    const ReprojectionSummary& s = r.summary;
    out["summary"] = stats_dict(s.all);
    out["not_counted"] = py::dict(py::arg("outliers") = s.outliers, py::arg("behind_camera") = s.behind_camera,
                                  py::arg("outside_domain") = s.outside_domain,
                                  py::arg("outside_image") = s.outside_image);
    out["per_view"] = groups(s.per_view);
    out["per_camera"] = groups(s.per_camera);
    py::dict reported, recomputed, definitions;
    for (const ReportedComparison& c : s.reported) {
        reported[py::str(c.reported.key)] = c.reported.value;
        recomputed[py::str(c.reported.key)] = c.recomputed;
        definitions[py::str(c.reported.key)] = std::string(definition_of(c.reported.measure));
    }
    out["reported"] = reported;
    out["recomputed"] = recomputed;
    out["definitions"] = definitions;
    out["recomputed_past_domain"] = s.reported_past_domain;
    out["per_view_reported"] = comparison(s.per_view_reported);
    out["per_point_reported"] = comparison(s.per_point_reported);
    out["convention_check"] =
        py::dict(py::arg("best_shift_px") = py::make_tuple(s.convention.best_shift_px.x(), s.convention.best_shift_px.y()),
                 py::arg("rms_px") = s.convention.rms_px, py::arg("rms_half_shift_px") = s.convention.rms_half_shift_px,
                 py::arg("suspect") = s.convention.suspect);
    return out;
}

ObservationSet read(const std::string& path, const std::string& camera_file, const py::object& size) {
    ObservationReadOptions options{.camera_file = camera_file};
    if (!size.is_none()) options.size = size_from(size);
    py::gil_scoped_release release;
    return read_observations(path, options);
}

py::dict reproject_set(const ObservationSet& set, int threads) {
    Reprojection r;
    {
        py::gil_scoped_release release;
        r = reproject(set, threads);
    }
    return reprojection_dict(set, r);
}

py::dict projection_uncertainty_of(const ObservationSet& set, const std::vector<std::array<double, 2>>& pixels,
                                   double distance, std::optional<int> chosen) {
    // By default the camera the file is (each camera's .cameramodel of an mrcal solve of
    // several holds the whole solve), else the first.
    const int camera = chosen ? *chosen : std::max(set.own_camera, 0);
    if (camera < 0 || static_cast<std::size_t>(camera) >= set.cameras.size()) {
        throw InvalidArgument("camera: " + std::to_string(camera) + ": the observations hold " +
                              std::to_string(set.cameras.size()) + " cameras");
    }
    const ProjectionUncertainty uncertainty(solved_calibration(set, camera));
    std::vector<Vec2> at;
    for (const auto& p : pixels) at.emplace_back(p[0], p[1]);
    const std::vector<Mat2> covariances = uncertainty.covariances(at, distance);
    py::array_t<double> covariance({static_cast<py::ssize_t>(at.size()), py::ssize_t{2}, py::ssize_t{2}});
    py::array_t<double> sigma(static_cast<py::ssize_t>(at.size()));
    for (std::size_t i = 0; i < at.size(); ++i) {
        for (int r = 0; r < 2; ++r) {
            for (int c = 0; c < 2; ++c) covariance.mutable_at(static_cast<py::ssize_t>(i), r, c) = covariances[i](r, c);
        }
        sigma.mutable_at(static_cast<py::ssize_t>(i)) = worst_direction_stdev(covariances[i]);
    }
    py::list parameters;
    for (const ParameterSpread& p : uncertainty.parameters()) {
        py::dict entry;
        entry["name"] = p.name;
        entry["value"] = p.value;
        entry["stdev"] = p.stdev;
        parameters.append(entry);
    }
    py::dict out;
    out["observed_pixel_uncertainty_px"] = uncertainty.observed_pixel_uncertainty_px();
    out["sigma_px"] = sigma;
    out["covariance"] = covariance;
    out["parameters"] = parameters;
    return out;
}

}  // namespace

void bind_observations(py::module_& m) {
    py::class_<ObservationSet>(m, "Observations", R"doc(
The observations a calibration or reconstruction file holds (libcam.read_observations):
its cameras, views with their poses, points, and each observed pixel, in the file's own
pixels (pixel_offset says how they sit against OpenCV's: (0.5, 0.5) for COLMAP).)doc")
        .def_property_readonly("tool", [](const ObservationSet& s) { return std::string(to_string(s.tool)); })
        .def_property_readonly("source", [](const ObservationSet& s) { return s.source; })
        .def_property_readonly("pixel_offset", [](const ObservationSet& s) {
            return py::make_tuple(s.pixel_offset.x(), s.pixel_offset.y());
        })
        .def_property_readonly("cameras", [](const ObservationSet& s) {
            py::list out;
            for (const ObservedCamera& c : s.cameras) out.append(py::make_tuple(c.name, PythonCamera(c.camera)));
            return out;
        }, "[(name, Camera)]: each camera's intrinsics and lens (its pose is the identity: each view has one)")
        .def_property_readonly("views", [](const ObservationSet& s) {
            py::list out;
            for (const ObservedView& v : s.views) {
                py::dict view;
                view["name"] = v.name;
                view["camera"] = v.camera;
                view["R"] = rows(3, 3, [&](std::size_t i, double* row) {
                    for (int j = 0; j < 3; ++j) row[j] = v.pose.R(static_cast<int>(i), j);
                });
                view["t"] = column<double>(3, [&](std::size_t i) { return v.pose.t(static_cast<int>(i)); });
                out.append(view);
            }
            return out;
        }, "[{'name', 'camera' (index), 'R', 't'}]: world (or board) to camera")
        .def_property_readonly("points", [](const ObservationSet& s) {
            return rows(s.points.size(), 3, [&](std::size_t i, double* row) {
                for (int j = 0; j < 3; ++j) row[j] = s.points[i](j);
            });
        })
        .def_property_readonly("point_ids", [](const ObservationSet& s) {
            return column<std::int64_t>(s.point_ids.size(), [&](std::size_t i) { return s.point_ids[i]; });
        })
        .def_property_readonly("view", [](const ObservationSet& s) {
            return column<std::int64_t>(s.observations.size(), [&](std::size_t i) { return s.observations[i].view; });
        }, "each observation's view (index into views)")
        .def_property_readonly("point", [](const ObservationSet& s) {
            return column<std::int64_t>(s.observations.size(), [&](std::size_t i) { return s.observations[i].point; });
        }, "each observation's point (index into points)")
        .def_property_readonly("pixel", [](const ObservationSet& s) {
            return rows(s.observations.size(), 2, [&](std::size_t i, double* row) {
                row[0] = s.observations[i].pixel.x() + s.pixel_offset.x();
                row[1] = s.observations[i].pixel.y() + s.pixel_offset.y();
            });
        }, "each observed pixel, in the file's own pixels")
        .def_property_readonly("weight", [](const ObservationSet& s) {
            return column<double>(s.observations.size(), [&](std::size_t i) { return s.observations[i].weight; });
        })
        .def_property_readonly("inlier", [](const ObservationSet& s) {
            return column<bool>(s.observations.size(), [&](std::size_t i) { return s.observations[i].inlier; });
        })
        .def_property_readonly("reported", [](const ObservationSet& s) {
            py::dict out;
            for (const ReportedNumber& r : s.reported) out[py::str(r.key)] = r.value;
            return out;
        }, "the numbers the file stored about its fit, by the file's own keys")
        .def("__len__", [](const ObservationSet& s) { return s.observations.size(); })
        .def("__repr__", [](const ObservationSet& s) {
            return "<libcam.Observations of " + std::string(to_string(s.tool)) + ": " +
                   std::to_string(s.cameras.size()) + " cameras, " + std::to_string(s.views.size()) + " views, " +
                   std::to_string(s.observations.size()) + " observations>";
        });

    m.def("read_observations", &read, py::arg("path"), py::arg("camera_file") = "", py::arg("size") = py::none(), R"doc(
The observations a file or folder holds: OpenCV's calibration output, a .cameramodel with
mrcal's optimization_inputs, a COLMAP model folder, OpenSfM's reconstruction.json,
OpenMVG's sfm_data.json, AliceVision's cameras.sfm, VisualSfM's .nvm or Bundler's
bundle.out (size=(width, height): their files store none), or a .csv/.json table with
camera_file. Returns libcam.Observations.)doc");
    m.def("projection_uncertainty", &projection_uncertainty_of, py::arg("observations"), py::arg("pixels"),
          py::arg("distance") = kAtInfinity, py::arg("camera") = py::none(), R"doc(
mrcal's projection uncertainty (mrcal 2.2's projection_uncertainty, what =
'worstdirection-stdev') of a calibration's observations (libcam.read_observations of a
.cameramodel with optimization_inputs, OpenCV's calibration output, ...): the point at
`distance` (the board's unit; infinity: the direction) along each pixel's ray (OpenCV's
pixels, (n, 2)); camera: its index (default: the camera the file is, for a solve of
several cameras, else the first; the whole solve counts). Returns
{'observed_pixel_uncertainty_px' (the noise the residuals
imply), 'sigma_px' (n,) (NaN where a pixel has no ray), 'covariance' (n, 2, 2),
'parameters': [{'name', 'value', 'stdev'}]}, as the libcam program's uncertainty command.)doc");
    m.def("reproject", &reproject_set, py::arg("observations"), py::arg("threads") = 0, R"doc(
Every observation reprojected through libcam's projection of its camera and pose (as the
libcam program's reproject command): {'observed', 'projected', 'residual' (n, 2) in the
file's pixels, residual = projected - observed; 'error_px', 'counted' (n,); 'status';
'view', 'point_id'; 'summary': {'count', 'rms_px', 'mean_px', 'median_px', 'p99_px',
'max_px', 'bias_px', 'weighted_rms_px'}; 'per_view', 'per_camera'; 'reported' and
'recomputed' (the file's own numbers and libcam's value of each by its tool's rule, which
counts 'recomputed_past_domain' observations past the lens's valid domain that libcam's
own statistics set apart), 'definitions';
'convention_check': {'best_shift_px', 'suspect', ...}}.)doc");
}

}  // namespace libcam::python
