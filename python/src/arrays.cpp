#include "arrays.hpp"

#include <sstream>

#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"

namespace libcam::python {

namespace {

std::string shape_text(const py::array& array) {
    std::ostringstream out;
    out << "(";
    for (py::ssize_t i = 0; i < array.ndim(); ++i) out << (i ? ", " : "") << array.shape(i);
    if (array.ndim() == 1) out << ",";
    out << ")";
    return out.str();
}

std::string dtype_text(const py::array& array) { return py::str(array.dtype()).cast<std::string>(); }

[[noreturn]] void wrong(const char* name, const std::string& expected, const std::string& got) {
    throw py::type_error(std::string(name) + ": expected " + expected + ", got " + got);
}

// Whether the leading axes of `array` walk memory with one stride per point, and the
// strides are whole elements (a view of a packed structure may not be).
bool strides_collapse(const py::array& array) {
    const py::ssize_t item = array.itemsize();
    for (py::ssize_t i = 0; i < array.ndim(); ++i) {
        if (array.strides(i) % item != 0) return false;
    }
    for (py::ssize_t i = 0; i + 2 < array.ndim(); ++i) {
        if (array.shape(i) > 1 && array.strides(i) != array.strides(i + 1) * array.shape(i + 1)) return false;
    }
    return true;
}

}  // namespace

std::string shape_text(const std::vector<py::ssize_t>& leading_shape, int k) {
    std::vector<py::ssize_t> shape = leading_shape;
    if (k > 0) shape.push_back(k);
    std::ostringstream out;
    out << "(";
    for (std::size_t i = 0; i < shape.size(); ++i) out << (i ? ", " : "") << shape[i];
    if (shape.size() == 1) out << ",";
    out << ")";
    return out.str();
}

bool column_layout(const py::array& array, std::size_t count) {
    const py::ssize_t ndim = array.ndim(), item = array.itemsize();
    if (ndim < 1 || array.strides(ndim - 1) != item * static_cast<py::ssize_t>(count)) return false;
    py::ssize_t step = item;
    for (py::ssize_t d = ndim - 2; d >= 0; --d) {
        if (array.shape(d) > 1 && array.strides(d) != step) return false;  // an axis of one has any stride
        step *= array.shape(d);
    }
    return true;
}

PointArray point_array(const py::handle& value, const char* name, int k) {
    const std::string expected_shape = "shape (..., " + std::to_string(k) + ")";
    py::array array;
    if (py::isinstance<py::array>(value)) {
        array = py::reinterpret_borrow<py::array>(value);
        const char kind = array.dtype().kind();
        if (kind == 'i' || kind == 'u') {
            array = py::array_t<double, py::array::forcecast>::ensure(array);
        } else if (!array.dtype().is(py::dtype::of<double>()) && !array.dtype().is(py::dtype::of<float>())) {
            wrong(name, "a float32 or float64 array of " + expected_shape, dtype_text(array) + " array of shape " + shape_text(array));
        }
    } else {
        array = py::array_t<double, py::array::forcecast>::ensure(value);
        if (!array) {
            PyErr_Clear();
            wrong(name, "an array of " + expected_shape, std::string(py::str(py::type::of(value).attr("__name__"))));
        }
        if (array.dtype().kind() != 'f') wrong(name, "numbers", dtype_text(array));
    }
    if (array.ndim() < 1 || array.shape(array.ndim() - 1) != k) {
        wrong(name, "an array of " + expected_shape, "shape " + shape_text(array));
    }
    if (!strides_collapse(array)) {
        array = py::array::ensure(array, py::array::c_style);
    }
    PointArray points;
    points.type = array.dtype().is(py::dtype::of<float>()) ? FloatType::Float32 : FloatType::Float64;
    const py::ssize_t ndim = array.ndim();
    points.count = 1;
    for (py::ssize_t i = 0; i + 1 < ndim; ++i) {
        points.leading_shape.push_back(array.shape(i));
        points.count *= static_cast<std::size_t>(array.shape(i));
    }
    const py::ssize_t item = array.itemsize();
    points.coordinate_stride = array.strides(ndim - 1) / item;
    // The stride of the innermost leading axis of more than one point (any, when none has).
    points.point_stride = 0;
    for (py::ssize_t i = ndim - 2; i >= 0; --i) {
        if (array.shape(i) > 1) {
            points.point_stride = array.strides(i) / item;
            break;
        }
    }
    points.array = std::move(array);
    return points;
}

Mat3 matrix3(const py::handle& value, const char* name) {
    const auto array = py::array_t<double, py::array::forcecast>::ensure(value);
    if (!array || array.ndim() != 2 || array.shape(0) != 3 || array.shape(1) != 3) {
        PyErr_Clear();
        throw py::type_error(std::string(name) + ": expected a 3x3 array of numbers");
    }
    const auto a = array.unchecked<2>();
    Mat3 out;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) out(r, c) = a(r, c);
    }
    return out;
}

std::vector<double> vector_any(const py::handle& value, const char* name) {
    const auto array = py::array_t<double, py::array::forcecast>::ensure(value);
    if (!array) {
        PyErr_Clear();
        throw py::type_error(std::string(name) + ": expected a sequence of numbers");
    }
    // cv2 gives distortion as (1, n) or (n, 1): any shape with one axis longer than 1.
    py::ssize_t longer = 0;
    for (py::ssize_t i = 0; i < array.ndim(); ++i) longer += array.shape(i) > 1 ? 1 : 0;
    if (longer > 1) throw py::type_error(std::string(name) + ": expected a vector, got shape " + shape_text(array));
    const auto flat = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    return std::vector<double>(flat.data(), flat.data() + flat.size());
}

Vec3 vector3(const py::handle& value, const char* name) {
    const std::vector<double> v = vector_any(value, name);
    if (v.size() != 3) {
        throw py::type_error(std::string(name) + ": expected 3 numbers, got " + std::to_string(v.size()));
    }
    return {v[0], v[1], v[2]};
}

py::array_t<double> to_numpy(const Eigen::MatrixXd& matrix) {
    py::array_t<double> out({matrix.rows(), matrix.cols()});
    auto o = out.mutable_unchecked<2>();
    for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
        for (Eigen::Index c = 0; c < matrix.cols(); ++c) o(r, c) = matrix(r, c);
    }
    return out;
}

py::array_t<double> to_numpy_vector(const Eigen::VectorXd& vector) {
    py::array_t<double> out(vector.size());
    for (Eigen::Index i = 0; i < vector.size(); ++i) out.mutable_data()[i] = vector(i);
    return out;
}

int thread_count(int threads) {
    if (threads < 0) throw InvalidArgument("threads: must be 0 (every core) or more, got " + std::to_string(threads));
    return worker_count(threads);
}

}  // namespace libcam::python
