#pragma once
// numpy arrays in and out of the module: points of shape (..., k) in float32 or float64,
// read where they lie (any strides that collapse to one stride per point) and written
// into new C-ordered arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <vector>

#include "libcam/geometry/vector_math.hpp"

namespace libcam::python {

namespace py = pybind11;

enum class FloatType { Float32, Float64 };

// n points of k coordinates: coordinate j of point i at data[i * point_stride + j * coordinate_stride]
// (strides in elements). `array` keeps the memory alive.
struct PointArray {
    py::array array;
    FloatType type = FloatType::Float64;
    std::size_t count = 0;
    std::ptrdiff_t point_stride = 0;
    std::ptrdiff_t coordinate_stride = 1;
    std::vector<py::ssize_t> leading_shape;  // the shape without its last axis

    template <class T>
    const T* data() const {
        return static_cast<const T*>(array.data());
    }
};

// `value` as points of `k` coordinates. float32 and float64 arrays are read in place;
// other real arrays (integers) and sequences become float64. Throws TypeError naming
// `name`, the expected shape and what was given, for anything else.
PointArray point_array(const py::handle& value, const char* name, int k);

// A new array of shape leading_shape + (k,) whose coordinates each lie together, as the
// rows of a C-ordered (k,) + leading_shape array (numpy.moveaxis of one to the end):
// coordinate c of entry i at data()[c * count + i].
template <class T>
py::array_t<T> new_column_array(const std::vector<py::ssize_t>& leading_shape, int k) {
    std::vector<py::ssize_t> shape = leading_shape, strides(leading_shape.size() + 1);
    py::ssize_t step = sizeof(T);
    for (std::size_t d = leading_shape.size(); d-- > 0;) {
        strides[d] = step;
        step *= leading_shape[d];
    }
    shape.push_back(k);
    strides.back() = step;
    return py::array_t<T>(shape, strides);
}

// Whether an array of shape leading_shape + (k,) lies as new_column_array's does.
bool column_layout(const py::array& array, std::size_t count);

// "(a, b, k)" for an array of shape leading_shape + (k,) (no last axis when k == 0).
std::string shape_text(const std::vector<py::ssize_t>& leading_shape, int k);

// A new C-ordered array of shape leading_shape + (k,) (no last axis when k == 0).
template <class T>
py::array_t<T> new_array(const std::vector<py::ssize_t>& leading_shape, int k) {
    std::vector<py::ssize_t> shape = leading_shape;
    if (k > 0) shape.push_back(k);
    return py::array_t<T>(shape);
}

// A fixed-size matrix from an array-like of that shape (float64); TypeError naming
// `name` and the shape otherwise.
Mat3 matrix3(const py::handle& value, const char* name);
Vec3 vector3(const py::handle& value, const char* name);
std::vector<double> vector_any(const py::handle& value, const char* name);

// numpy arrays (copies) of Eigen matrices.
py::array_t<double> to_numpy(const Eigen::MatrixXd& matrix);
py::array_t<double> to_numpy_vector(const Eigen::VectorXd& vector);

// The number of threads a call asked for: 0 means every core.
int thread_count(int threads);

}  // namespace libcam::python
