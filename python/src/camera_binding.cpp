#include "camera_binding.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "arrays.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/convert/opengl.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam::python {

PythonCamera::PythonCamera(const Camera& camera, PixelOrigin origin, std::optional<LookAtCamera> look_at_camera) {
    PreparedCamera prepared(camera);
    state_ = std::make_shared<State>(prepared, origin, std::move(look_at_camera));
}

template <>
const Projector<double>& PythonCamera::projector<double>() const {
    return state_->projector_double;
}
template <>
const Projector<float>& PythonCamera::projector<float>() const {
    return state_->projector_float;
}
template <>
const Unprojector<double>& PythonCamera::unprojector<double>() const {
    return state_->prepared.unprojector();
}
template <>
const Unprojector<float>& PythonCamera::unprojector<float>() const {
    State& state = *state_;
    std::call_once(state.float_unprojector_built,
                   [&state] { state.float_unprojector = std::make_unique<const Unprojector<float>>(state.prepared); });
    return *state.float_unprojector;
}

namespace {

// Points per step of a thread: gathered from the caller's array into structure-of-arrays
// buffers that stay in the core's second-level cache (80 KiB for 2048 points), run through
// the batch engine, and scattered into the output. A multiple of the engine's block.
// Not 512, the first-level cache's worth: each engine call has a fixed cost (its lens
// and table set up), which at 512 points added 0.7 ns to the exact unprojection's 15 ns
// per point.
constexpr std::size_t kChunk = 2048;
// Points per engine call when it reads and writes the caller's arrays in place: larger,
// as there is no copy to keep in the cache, only the pixels the NaN pass reads back
// (4096 points: 64 kB).
constexpr std::size_t kInPlaceChunk = 4096;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Structure-of-arrays to and from numpy's interleaved (..., K) layout. In double, two
// points per SSE2 instruction: the compiler does not vectorise these shuffles itself.
template <class T>
void interleave2(const T* x, const T* y, T* out, std::size_t n) {
    std::size_t i = 0;
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, double>) {
        for (; i + 2 <= n; i += 2) {
            const __m128d a = _mm_loadu_pd(x + i), b = _mm_loadu_pd(y + i);
            _mm_storeu_pd(out + 2 * i, _mm_unpacklo_pd(a, b));
            _mm_storeu_pd(out + 2 * i + 2, _mm_unpackhi_pd(a, b));
        }
    }
#endif
    for (; i < n; ++i) out[2 * i] = x[i], out[2 * i + 1] = y[i];
}

template <class T>
void interleave3(const T* x, const T* y, const T* z, T* out, std::size_t n) {
    std::size_t i = 0;
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, double>) {
        for (; i + 2 <= n; i += 2) {
            const __m128d a = _mm_loadu_pd(x + i), b = _mm_loadu_pd(y + i), c = _mm_loadu_pd(z + i);
            _mm_storeu_pd(out + 3 * i, _mm_unpacklo_pd(a, b));      // x0 y0
            _mm_storeu_pd(out + 3 * i + 2, _mm_shuffle_pd(c, a, 2));  // z0 x1
            _mm_storeu_pd(out + 3 * i + 4, _mm_unpackhi_pd(b, c));  // y1 z1
        }
    }
#endif
    for (; i < n; ++i) out[3 * i] = x[i], out[3 * i + 1] = y[i], out[3 * i + 2] = z[i];
}

template <class T>
void deinterleave2(const T* in, T* x, T* y, std::size_t n) {
    std::size_t i = 0;
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, double>) {
        for (; i + 2 <= n; i += 2) {
            const __m128d p0 = _mm_loadu_pd(in + 2 * i), p1 = _mm_loadu_pd(in + 2 * i + 2);
            _mm_storeu_pd(x + i, _mm_unpacklo_pd(p0, p1));
            _mm_storeu_pd(y + i, _mm_unpackhi_pd(p0, p1));
        }
    }
#endif
    for (; i < n; ++i) x[i] = in[2 * i], y[i] = in[2 * i + 1];
}

template <class T>
void deinterleave3(const T* in, T* x, T* y, T* z, std::size_t n) {
    std::size_t i = 0;
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, double>) {
        for (; i + 2 <= n; i += 2) {
            const __m128d p0 = _mm_loadu_pd(in + 3 * i), p1 = _mm_loadu_pd(in + 3 * i + 2),
                          p2 = _mm_loadu_pd(in + 3 * i + 4);  // x0 y0 | z0 x1 | y1 z1
            _mm_storeu_pd(x + i, _mm_shuffle_pd(p0, p1, 2));
            _mm_storeu_pd(y + i, _mm_shuffle_pd(p0, p2, 1));
            _mm_storeu_pd(z + i, _mm_shuffle_pd(p1, p2, 2));
        }
    }
#endif
    for (; i < n; ++i) x[i] = in[3 * i], y[i] = in[3 * i + 1], z[i] = in[3 * i + 2];
}

// NaN in the K values of every entry whose flag is 0, value c of entry i at
// out[i * entry_step + c * value_step] (numpy's own layout by default). The first invalid
// entry is found by memchr (libc's, vectorised: a byte loop here, which GCC leaves scalar
// at -O2, cost a quarter of the projection's time), and the pass that writes runs from
// there only.
template <class T, int K>
void nan_where_invalid(const std::uint8_t* flags, T* out, std::size_t n, std::size_t entry_step = K,
                       std::size_t value_step = 1) {
    const void* first_invalid = n > 0 ? std::memchr(flags, 0, n) : nullptr;
    if (first_invalid == nullptr) return;
    for (std::size_t i = static_cast<std::size_t>(static_cast<const std::uint8_t*>(first_invalid) - flags); i < n; ++i) {
        if (flags[i] == 0) {
            for (int c = 0; c < K; ++c) out[i * entry_step + c * value_step] = T(kNaN);
        }
    }
}

// The mask from the engine's flags (1 or 0, as bool's bytes), and NaN in every
// coordinate of an invalid entry (which the engine leaves at 0).
template <class T, int K>
void mask_and_nan(const std::uint8_t* flags, bool* mask, T* out, std::size_t n) {
    std::memcpy(mask, flags, n);
    nan_where_invalid<T, K>(flags, out, n);
}

enum class Frame { Camera, World };

Frame frame_from(const std::string& name) {
    if (name == "camera") return Frame::Camera;
    if (name == "world") return Frame::World;
    throw InvalidArgument("frame: expected 'camera' or 'world', got '" + name + "'");
}

UnprojectMethod method_from(const std::string& name) {
    const std::optional<UnprojectMethod> method = method_from_name(name);
    if (!method) throw InvalidArgument("method: expected 'exact', 'fast' or 'lut', got '" + name + "'");
    return *method;
}

// An identity pose is skipped: R X + t would give X (but for the sign of a zero).
bool is_identity(const Pose& pose) { return pose.R == Mat3::Identity() && pose.t == Vec3::Zero(); }

// Reads point i of an array of K coordinates. The common layout, C-ordered (..., K), is
// a compile-time stride, which the compiler turns into vector shuffles; any other is
// read through the array's own strides.
template <class T, int K, bool kPacked>
struct Reader {
    static constexpr bool kIsPacked = kPacked;
    const T* data;
    std::ptrdiff_t point_stride, coordinate_stride;

    T operator()(std::size_t i, int coordinate) const {
        if constexpr (kPacked) return data[static_cast<std::ptrdiff_t>(i) * K + coordinate];
        return data[static_cast<std::ptrdiff_t>(i) * point_stride + coordinate * coordinate_stride];
    }

    // Asks for points [first, first + count) to be brought into the cache while the engine
    // computes the current chunk, so that reading memory and computing overlap.
    void prefetch(std::size_t first, std::size_t count) const {
        if constexpr (kPacked) {
            const char* begin = reinterpret_cast<const char*>(data + first * K);
            const char* end = reinterpret_cast<const char*>(data + (first + count) * K);
            for (const char* line = begin; line < end; line += 64) __builtin_prefetch(line);
        }
    }
};

// Whether an array of K coordinates per point is C-ordered (..., K): numpy's own layout.
template <int K>
bool packed(const PointArray& points) {
    return points.coordinate_stride == 1 && (points.point_stride == K || points.count <= 1);
}

// Whether each coordinate's values lie together (point_stride 1): a (K, N) array's
// numpy.moveaxis, or a Fortran-ordered (N, K) array, as the C++ batch engine takes them.
bool in_columns(const PointArray& points) { return points.count > 1 && points.point_stride == 1; }

// Calls body(reader) with the reader for the array's layout.
template <class T, int K, class Body>
void with_reader(const PointArray& points, Body&& body) {
    const T* data = points.data<T>();
    if (packed<K>(points)) {
        body(Reader<T, K, true>{data, K, 1});
    } else {
        body(Reader<T, K, false>{data, points.point_stride, points.coordinate_stride});
    }
}

// Where a projection writes its pixels: numpy's (..., 2) layout, or two columns of
// `count` values (Outputs::columns).
template <class T>
struct PixelsOut {
    T* data;
    bool columns;
    std::size_t count;

    T* x(std::size_t first) const { return columns ? data + first : data + 2 * first; }
    T* y(std::size_t first) const { return columns ? data + count + first : data + 2 * first + 1; }
    std::size_t step() const { return columns ? 1 : 2; }  // from one pixel's x (or y) to the next's
};

// Pixels [first, first + n): the rows flipped for a bottom-left pixel origin, and NaN
// where a flag is 0.
template <class T>
void finish_pixels(const std::uint8_t* flags, const PixelsOut<T>& out, std::size_t first, std::size_t n, bool flip,
                   const ImageSize& size) {
    const std::size_t step = out.step();
    if (flip) {
        T* y = out.y(first);
        for (std::size_t i = 0; i < n; ++i) y[i * step] = flip_row<T>(y[i * step], size);
    }
    nan_where_invalid<T, 2>(flags, out.x(first), n, step, out.columns ? out.count : 1);
}

template <class T>
void project_into(const PythonCamera& camera, const PointArray& points, Frame frame, const PixelsOut<T>& pixels_out,
                  bool* mask_out, int threads) {
    const Projector<T>& projector = camera.projector<T>();
    const Pose& pose = camera.camera().pose;
    const bool transform = frame == Frame::World && !is_identity(pose);
    const bool flip = camera.pixel_origin() != PixelOrigin::TopLeft;
    const ImageSize size = camera.camera().size;
    // Camera points in the layout the engine reads, pixels in the one it writes: the engine
    // works on the caller's arrays in place, chunk by chunk (a chunk's pixels are still in
    // the cache for the NaNs). bool and std::uint8_t are one byte each; the engine writes
    // 0 or 1.
    const auto in_place = [&](const auto& project_chunk) {
        parallel_chunks(points.count, threads, kChunk, [&](std::size_t begin, std::size_t end) {
            for (std::size_t first = begin; first < end; first += kInPlaceChunk) {
                const std::size_t count = std::min(kInPlaceChunk, end - first);
                std::uint8_t* mask = reinterpret_cast<std::uint8_t*>(mask_out + first);
                project_chunk(first, count, mask);
                finish_pixels<T>(mask, pixels_out, first, count, flip, size);
            }
        });
    };
    const T* in = points.data<T>();
    if (!transform && in_columns(points) && pixels_out.columns) {
        const std::ptrdiff_t column = points.coordinate_stride;
        in_place([&](std::size_t first, std::size_t count, std::uint8_t* mask) {
            projector.project({in + first, count}, {in + column + first, count}, {in + 2 * column + first, count},
                              {pixels_out.x(first), count}, {pixels_out.y(first), count}, {mask, count}, 1);
        });
        return;
    }
    if (!transform && packed<3>(points) && !pixels_out.columns) {
        in_place([&](std::size_t first, std::size_t count, std::uint8_t* mask) {
            projector.project_interleaved({in + 3 * first, 3 * count}, {pixels_out.x(first), 2 * count}, {mask, count}, 1);
        });
        return;
    }
    with_reader<T, 3>(points, [&](const auto read) {
        parallel_chunks(points.count, threads, kChunk, [&](std::size_t begin, std::size_t end) {
            Points3<T> camera_points;
            Points2<T> pixels;
            ValidFlags valid;
            for (std::size_t first = begin; first < end; first += kChunk) {
                const std::size_t count = std::min(kChunk, end - first);
                camera_points.resize(count);
                T* x = camera_points.x.data();
                T* y = camera_points.y.data();
                T* z = camera_points.z.data();
                if (transform) {
                    for (std::size_t i = 0; i < count; ++i) {
                        // In double, as PreparedCamera::project: R X + t.
                        const std::size_t k = first + i;
                        const Vec3 c = pose.camera_from_world(Vec3(double(read(k, 0)), double(read(k, 1)), double(read(k, 2))));
                        x[i] = T(c.x()), y[i] = T(c.y()), z[i] = T(c.z());
                    }
                } else if constexpr (decltype(read)::kIsPacked) {
                    deinterleave3(read.data + 3 * first, x, y, z, count);
                } else {
                    for (std::size_t i = 0; i < count; ++i) {
                        x[i] = read(first + i, 0), y[i] = read(first + i, 1), z[i] = read(first + i, 2);
                    }
                }
                read.prefetch(first + count, std::min(kChunk, end - std::min(end, first + count)));
                projector.project(camera_points, pixels, valid, 1);
                if (pixels_out.columns) {
                    std::copy_n(pixels.x.data(), count, pixels_out.x(first));
                    std::copy_n(pixels.y.data(), count, pixels_out.y(first));
                } else {
                    interleave2(pixels.x.data(), pixels.y.data(), pixels_out.x(first), count);
                }
                std::memcpy(mask_out + first, valid.data(), count);
                finish_pixels<T>(valid.data(), pixels_out, first, count, flip, size);
            }
        });
    });
}

// Where the pixels of an unprojection come from: the caller's array, or every pixel of
// the image.
struct PixelSource {
    const PointArray* points = nullptr;  // null: the whole image, row by row
    long width = 0;
};

// Fills pixels [first, first + count) of the chunk from the source, in OpenCV's rows.
template <class T, class Read>
void fill_pixels(const Read& read, std::size_t first, std::size_t count, Points2<T>& pixels) {
    T* x = pixels.x.data();
    T* y = pixels.y.data();
    if constexpr (Read::kIsPacked) {
        deinterleave2(read.data + 2 * first, x, y, count);
    } else {
        for (std::size_t i = 0; i < count; ++i) x[i] = read(first + i, 0), y[i] = read(first + i, 1);
    }
}

template <class T>
void fill_image_pixels(std::size_t width, std::size_t first, std::size_t count, Points2<T>& pixels) {
    // Entry k of the image is pixel (k % width, k / width).
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t k = first + i;
        pixels.x[i] = T(static_cast<double>(k % width));
        pixels.y[i] = T(static_cast<double>(k / width));
    }
}

template <class T>
void unproject_into(const PythonCamera& camera, const PixelSource& source, std::size_t count_all,
                    UnprojectMethod method, Frame frame, bool normalize, T* directions_out, bool* mask_out, int threads) {
    const Unprojector<T>& unprojector = camera.unprojector<T>();
    const Pose& pose = camera.camera().pose;
    const ImageSize size = camera.camera().size;
    const bool flip = camera.pixel_origin() != PixelOrigin::TopLeft;
    // Pixels as numpy's C-ordered (N, 2) array and the rays as the engine gives them: one
    // engine call reads and writes the caller's arrays in place, on the engine's threads
    // (each call has a fixed cost: a table view, the lens's constants), then NaN where the
    // flags say (memchr skips the valid runs). bool and std::uint8_t are one byte each;
    // the engine writes 0 or 1.
    if (source.points && packed<2>(*source.points) && frame == Frame::Camera && !normalize && !flip) {
        std::uint8_t* mask = reinterpret_cast<std::uint8_t*>(mask_out);
        unprojector.unproject_interleaved({source.points->data<T>(), 2 * count_all}, method,
                                          {directions_out, 3 * count_all}, {mask, count_all}, threads);
        nan_where_invalid<T, 3>(mask, directions_out, count_all);
        return;
    }
    const auto run = [&](const auto& fill, const auto& prefetch) {
        parallel_chunks(count_all, threads, kChunk, [&](std::size_t begin, std::size_t end) {
            Points2<T> pixels;
            Points3<T> directions;
            ValidFlags valid;
            for (std::size_t first = begin; first < end; first += kChunk) {
                const std::size_t count = std::min(kChunk, end - first);
                pixels.resize(count);
                fill(first, count, pixels);
                if (flip) {
                    for (std::size_t i = 0; i < count; ++i) pixels.y[i] = flip_row<T>(pixels.y[i], size);
                }
                prefetch(first + count, std::min(kChunk, end - std::min(end, first + count)));
                unprojector.unproject(pixels, method, directions, valid, 1);
                T* out = directions_out + 3 * first;
                bool* mask = mask_out + first;
                const T* dx = directions.x.data();
                const T* dy = directions.y.data();
                const T* dz = directions.z.data();
                const std::uint8_t* ok = valid.data();
                if (frame == Frame::World || normalize) {
                    for (std::size_t i = 0; i < count; ++i) {
                        mask[i] = ok[i] != 0;
                        if (!mask[i]) {
                            out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = T(kNaN);
                            continue;
                        }
                        // In double, as PreparedCamera::ray: R^T d, normalised.
                        Vec3 d(static_cast<double>(dx[i]), static_cast<double>(dy[i]), static_cast<double>(dz[i]));
                        if (frame == Frame::World) d = pose.world_direction_from_camera(d);
                        d.normalize();
                        out[3 * i] = T(d.x()), out[3 * i + 1] = T(d.y()), out[3 * i + 2] = T(d.z());
                    }
                } else {
                    interleave3(dx, dy, dz, out, count);
                    mask_and_nan<T, 3>(ok, mask, out, count);
                }
            }
        });
    };
    if (source.points) {
        with_reader<T, 2>(*source.points, [&](const auto read) {
            run([&](std::size_t first, std::size_t count, Points2<T>& pixels) { fill_pixels<T>(read, first, count, pixels); },
                [&](std::size_t first, std::size_t count) { read.prefetch(first, count); });
        });
    } else {
        // The image's rows in the camera's pixel origin: a bottom-left camera's row 0 is
        // OpenCV's last, which the flip above makes of it.
        const std::size_t width = static_cast<std::size_t>(source.width);
        run([&](std::size_t first, std::size_t count, Points2<T>& pixels) { fill_image_pixels<T>(width, first, count, pixels); },
            [](std::size_t, std::size_t) {});
    }
}

// The arrays a call writes: new ones, or those the caller gave as out=(values, mask),
// which must have the result's shape and type, be writeable, and not overlap the input
// (a chunk's results would overwrite the next chunk's input). The values are C-ordered,
// or, where the call writes that layout (Columns::Allowed), each coordinate's values
// together (new_column_array): the layout of a (2, N) array's numpy.moveaxis, or of a
// Fortran-ordered (N, 2) array.
enum class Columns { No, Allowed, Default };

template <class T>
struct Outputs {
    py::array_t<T> values;
    py::array_t<bool> mask;
    bool columns = false;  // values[c * count + i] rather than values[i * k + c]

    Outputs(const py::object& out, const std::vector<py::ssize_t>& leading_shape, int k, const py::array* input,
            Columns layout) {
        if (out.is_none()) {
            columns = layout == Columns::Default;
            values = columns ? new_column_array<T>(leading_shape, k) : new_array<T>(leading_shape, k);
            mask = new_array<bool>(leading_shape, 0);
            return;
        }
        const std::string type = sizeof(T) == 4 ? "float32" : "float64";
        const std::string expected_values = "a writeable " + type + " array of shape " + shape_text(leading_shape, k) +
                                            (layout == Columns::No ? ", C-ordered"
                                                                   : ", C-ordered or each coordinate's values together");
        const std::string expected_mask = "a C-ordered, writeable bool array of shape " + shape_text(leading_shape, 0);
        if (!py::isinstance<py::tuple>(out) || py::len(out) != 2) {
            throw py::type_error("out: expected (" + expected_values + ", " + expected_mask + ")");
        }
        std::size_t count = 1;
        for (const py::ssize_t extent : leading_shape) count *= static_cast<std::size_t>(extent);
        values = checked<T>(py::tuple(out)[0], leading_shape, k, "out[0]", expected_values, [&](const py::array& a) {
            columns = layout != Columns::No && count > 1 && !(a.flags() & py::array::c_style) && column_layout(a, count);
            return columns || (a.flags() & py::array::c_style);
        });
        mask = checked<bool>(py::tuple(out)[1], leading_shape, 0, "out[1]", expected_mask,
                             [](const py::array& a) { return (a.flags() & py::array::c_style) != 0; });
        static const py::object may_share_memory = py::module_::import("numpy").attr("may_share_memory");
        if (input && (py::cast<bool>(may_share_memory(values, *input)) || py::cast<bool>(may_share_memory(mask, *input)))) {
            throw py::type_error("out: must not share memory with the input");
        }
    }

    template <class U, class LayoutOk>
    static py::array_t<U> checked(const py::handle& given, const std::vector<py::ssize_t>& leading_shape, int k,
                                  const char* name, const std::string& expected, LayoutOk&& layout_ok) {
        if (!py::isinstance<py::array>(given)) throw py::type_error(std::string(name) + ": expected " + expected);
        const auto array = py::reinterpret_borrow<py::array>(given);
        std::vector<py::ssize_t> shape = leading_shape;
        if (k > 0) shape.push_back(k);
        const bool same_shape = array.ndim() == static_cast<py::ssize_t>(shape.size()) &&
                                std::equal(shape.begin(), shape.end(), array.shape());
        if (!array.dtype().is(py::dtype::of<U>()) || !same_shape || !layout_ok(array) || !array.writeable()) {
            throw py::type_error(std::string(name) + ": expected " + expected + ", got " +
                                 array.dtype().attr("name").cast<std::string>() + " array of shape " +
                                 std::string(py::str(array.attr("shape"))));
        }
        return py::reinterpret_borrow<py::array_t<U>>(given);
    }
};

template <class T>
py::tuple project_typed(const PythonCamera& camera, const PointArray& points, Frame frame, int threads,
                        const py::object& out) {
    // The pixels lie as the points do when the caller leaves the choice to the call (as
    // numpy's functions keep their input's layout): columns in, columns out.
    Outputs<T> outputs(out, points.leading_shape, 2, &points.array, in_columns(points) ? Columns::Default : Columns::Allowed);
    const PixelsOut<T> pixels{outputs.values.mutable_data(), outputs.columns, points.count};
    bool* mask_data = outputs.mask.mutable_data();
    {
        py::gil_scoped_release release;
        project_into<T>(camera, points, frame, pixels, mask_data, threads);
    }
    return py::make_tuple(std::move(outputs.values), std::move(outputs.mask));
}

py::tuple project(const PythonCamera& camera, const py::handle& points_in, const std::string& frame, int threads,
                  const py::object& out) {
    const PointArray points = point_array(points_in, "points", 3);
    const Frame f = frame_from(frame);
    const int n = thread_count(threads);
    if (points.type == FloatType::Float32) return project_typed<float>(camera, points, f, n, out);
    return project_typed<double>(camera, points, f, n, out);
}

template <class T>
py::tuple unproject_typed(const PythonCamera& camera, const PixelSource& source, std::size_t count,
                          const std::vector<py::ssize_t>& leading_shape, UnprojectMethod method, Frame frame,
                          bool normalize, int threads, const py::object& out) {
    Outputs<T> outputs(out, leading_shape, 3, source.points ? &source.points->array : nullptr, Columns::No);
    T* directions_data = outputs.values.mutable_data();
    bool* mask_data = outputs.mask.mutable_data();
    {
        py::gil_scoped_release release;
        unproject_into<T>(camera, source, count, method, frame, normalize, directions_data, mask_data, threads);
    }
    return py::make_tuple(std::move(outputs.values), std::move(outputs.mask));
}

py::tuple unproject(const PythonCamera& camera, const py::handle& pixels_in, const std::string& method,
                    const std::string& frame, bool normalize, int threads, const py::object& out) {
    const PointArray pixels = point_array(pixels_in, "pixels", 2);
    const UnprojectMethod m = method_from(method);
    const Frame f = frame_from(frame);
    const int n = thread_count(threads);
    const PixelSource source{&pixels, 0};
    if (pixels.type == FloatType::Float32) {
        return unproject_typed<float>(camera, source, pixels.count, pixels.leading_shape, m, f, normalize, n, out);
    }
    return unproject_typed<double>(camera, source, pixels.count, pixels.leading_shape, m, f, normalize, n, out);
}

py::tuple ray_image(const PythonCamera& camera, const std::string& method, const std::string& frame, bool normalize,
                    const py::object& dtype, int threads) {
    const ImageSize size = camera.camera().size;
    const std::vector<py::ssize_t> shape{size.height, size.width};
    const PixelSource source{nullptr, size.width};
    const std::size_t count = static_cast<std::size_t>(size.width) * static_cast<std::size_t>(size.height);
    const py::dtype type = py::dtype::from_args(dtype);
    const UnprojectMethod m = method_from(method);
    const Frame f = frame_from(frame);
    const int n = thread_count(threads);
    if (type.is(py::dtype::of<float>())) return unproject_typed<float>(camera, source, count, shape, m, f, normalize, n, py::none());
    if (type.is(py::dtype::of<double>())) return unproject_typed<double>(camera, source, count, shape, m, f, normalize, n, py::none());
    throw py::type_error("dtype: expected numpy.float32 or numpy.float64, got " + type.attr("name").cast<std::string>());
}

py::dict fov_angles(const Camera& camera) {
    const FovDescription description = describe_fov(camera);
    py::dict out;
    out["horizontal"] = description.fov_deg.horizontal;
    out["vertical"] = description.fov_deg.vertical;
    out["diagonal"] = description.fov_deg.diagonal;
    return out;
}

py::dict to_gl(const PythonCamera& python_camera, double near, double far, const std::string& depth_range) {
    DepthRange range = DepthRange::MinusOneToOne;
    if (depth_range == "0..1") {
        range = DepthRange::ZeroToOne;
    } else if (depth_range != "-1..1") {
        throw InvalidArgument("depth_range: expected '-1..1' (OpenGL) or '0..1' (Direct3D, Vulkan), got '" +
                              depth_range + "'");
    }
    const GlCamera gl = to_opengl(python_camera.camera(), near, far, range);
    py::dict out;
    out["projection"] = to_numpy(gl.projection);
    out["view"] = to_numpy(gl.view);
    out["viewport"] = py::make_tuple(gl.viewport[0], gl.viewport[1], gl.viewport[2], gl.viewport[3]);
    out["near"] = gl.near;
    out["far"] = gl.far;
    out["depth_range"] = depth_range;
    return out;
}

WriteOptions write_options(const PythonCamera& camera) {
    WriteOptions options;
    options.look_at_camera = camera.look_at_camera();
    return options;
}

std::optional<CameraFormat> format_from(const std::optional<std::string>& name) {
    if (!name) return std::nullopt;
    return camera_format_from_string(*name);
}

void write(const PythonCamera& camera, const std::string& path, const std::optional<std::string>& format) {
    std::optional<CameraFormat> chosen = format_from(format);
    if (!chosen) chosen = camera_format_from_path(path);
    if (!chosen) {
        throw FileError(path + ": no format given and none known for its extension (formats: " + camera_format_names() +
                        ")");
    }
    write_camera_file(path, camera.camera(), *chosen, write_options(camera));
}

std::string format_text(const PythonCamera& camera, const std::string& format) {
    return format_camera(camera.camera(), camera_format_from_string(format), write_options(camera));
}

py::object to_blender(const PythonCamera& camera) {
    const std::string text = format_camera(camera.camera(), CameraFormat::BlenderJson);
    return py::module_::import("json").attr("loads")(text);
}

std::string describe(const PythonCamera& camera) {
    const Camera& c = camera.camera();
    const auto number = [](double value) { return format_number(value); };
    std::ostringstream out;
    out << "libcam.Camera(" << lens_info(c.lens.type).name << ", " << c.size.width << "x" << c.size.height
        << ", fx=" << number(c.intrinsics.fx) << ", fy=" << number(c.intrinsics.fy) << ", cx=" << number(c.intrinsics.cx)
        << ", cy=" << number(c.intrinsics.cy);
    if (c.intrinsics.skew != 0) out << ", skew=" << number(c.intrinsics.skew);
    if (!c.lens.coefficients.empty()) {
        out << ", dist=[";
        for (std::size_t i = 0; i < c.lens.coefficients.size(); ++i) out << (i ? ", " : "") << number(c.lens.coefficients[i]);
        out << "]";
    }
    if (!is_identity(c.pose)) {
        const Vec3 centre = c.pose.centre();
        out << ", center=(" << number(centre.x()) << ", " << number(centre.y()) << ", " << number(centre.z()) << ")";
    }
    if (camera.pixel_origin() != PixelOrigin::TopLeft) out << ", pixel_origin='" << to_string(camera.pixel_origin()) << "'";
    out << ")";
    return out.str();
}

}  // namespace

Lens lens_from(const std::string& model, const std::vector<double>& dist) {
    const std::optional<LensType> type = lens_type_from_name(model);
    if (!type) throw InvalidArgument("model: unknown lens model '" + model + "' (see libcam.models)");
    Lens lens{*type, dist};
    lens.validate("dist");
    return lens;
}

Pose pose_from(const py::object& R, const py::object& t, const py::object& rvec) {
    Pose pose;
    if (!R.is_none() && !rvec.is_none()) throw InvalidArgument("R, rvec: give one of them, not both");
    if (!R.is_none()) pose.R = matrix3(R, "R");
    if (!rvec.is_none()) pose.R = rotation_from_rvec(vector3(rvec, "rvec"));
    if (!t.is_none()) pose.t = vector3(t, "t");
    return pose;
}

ImageSize size_from(const py::object& size) {
    const std::vector<double> wh = vector_any(size, "size");
    if (wh.size() != 2 || wh[0] != std::floor(wh[0]) || wh[1] != std::floor(wh[1])) {
        throw py::type_error("size: expected (width, height) in whole pixels");
    }
    ImageSize out{static_cast<long>(wh[0]), static_cast<long>(wh[1])};
    out.validate("size");
    return out;
}

void bind_camera(py::module_& m) {
    py::class_<PythonCamera>(m, "Camera", R"doc(
A calibrated camera: image size, intrinsic matrix K, lens model with its distortion
coefficients, and the pose R, t taking world points into the camera (X_cam = R X + t),
all in OpenCV's conventions: x right, y down, z forward; pixel (0, 0) is the centre of
the top-left pixel.

Cameras are immutable. Make one with libcam.read, libcam.from_opencv, libcam.from_fov,
or Camera(K, size, model, dist, R=..., t=...).)doc")
        .def(py::init([](const py::object& K, const py::object& size, const std::string& model, const py::object& dist,
                         const py::object& R, const py::object& t, const py::object& rvec) {
                 Camera camera;
                 camera.size = size_from(size);
                 camera.intrinsics = Intrinsics::from_K(matrix3(K, "K"), "K");
                 camera.lens = lens_from(model, dist.is_none() ? std::vector<double>{} : vector_any(dist, "dist"));
                 camera.pose = pose_from(R, t, rvec);
                 return PythonCamera(camera);
             }),
             py::arg("K"), py::arg("size"), py::arg("model") = "PINHOLE", py::arg("dist") = py::none(),
             py::arg("R") = py::none(), py::arg("t") = py::none(), py::arg("rvec") = py::none(),
             "A camera from K (3x3), size (width, height), a lens model's name (libcam.models) with its\n"
             "coefficients, and the pose as R (3x3) or rvec (Rodrigues) with t. Raises libcam.Error naming\n"
             "the field for a value out of range.")
        .def("project", &project, py::arg("points"), py::arg("frame") = "world", py::arg("threads") = 1,
             py::arg("out") = py::none(), R"doc(
The pixels of points, and which of them the lens images.

points: array of shape (..., 3), float32 or float64 (other real arrays become float64),
        world points (frame="world", through R, t) or camera-frame points (frame="camera").
Returns (pixels, valid): pixels of shape (..., 2) in the points' float type, valid a bool
array of shape (...). A point is invalid, its pixel NaN, where the lens model does not
image it: behind the camera for a perspective lens, outside the model's valid domain (past
the radius where its distortion folds over), or where the pixel is not finite.
threads: how many threads share the work (0: every core); the result is the same.
out: optional (pixels, valid) arrays to write into instead of new ones: pixels C-ordered,
     or with each coordinate's values together (numpy.moveaxis of a (2, ...) array).
Layout: points whose coordinates each lie together (a (3, N) array's .T, or
numpy.asfortranarray) are read in place, and the new pixels are laid out the same way
(their .T is a C-ordered (2, N) array); the fastest layout for large batches.)doc")
        .def("unproject", &unproject, py::arg("pixels"), py::arg("method") = "exact", py::arg("frame") = "camera",
             py::arg("normalize") = false, py::arg("threads") = 1, py::arg("out") = py::none(), R"doc(
The directions of the rays through pixels, and which pixels have one.

pixels: array of shape (..., 2), float32 or float64, in the camera's pixel convention
        (OpenCV's unless the camera was made with pixel_origin="bottom-left").
method: "exact" (Newton's method to rounding level, certified: within 1e-9 px),
        "fast" (within about 0.01 px) or "lut" (table interpolation, within about 0.01 px).
frame:  "camera" (OpenCV axes; not normalised unless normalize=True: z = 1 for PINHOLE and
        OpenCV's models, unit length for the others) or "world" (unit length, R^T d).
Returns (directions, valid): directions of shape (..., 3), valid of shape (...). A pixel
is invalid, its direction NaN, where it has no ray under the lens: outside the image
circle of a fisheye, past the radius where the distortion folds over, or where no ray
reprojects to it to rounding accuracy. The validity is the same for every method.
out: optional (directions, valid) arrays to write into instead of new ones.)doc")
        .def(
            "rays",
            [](const PythonCamera& camera, const py::handle& pixels, const std::string& method, int threads) {
                return unproject(camera, pixels, method, "world", true, threads, py::none());
            },
            py::arg("pixels"), py::arg("method") = "exact", py::arg("threads") = 1, R"doc(
The world-frame rays through pixels: unit directions of shape (..., 3) and the valid mask
of shape (...), as unproject(pixels, frame="world"). Every ray starts at camera.center.
Invalid pixels (no ray) get NaN.)doc")
        .def("ray_image", &ray_image, py::arg("method") = "exact", py::arg("frame") = "camera",
             py::arg("normalize") = false, py::arg("dtype") = py::dtype::of<double>(), py::arg("threads") = 1, R"doc(
The ray of every pixel: directions of shape (height, width, 3) and the valid mask of shape
(height, width); entry [y, x] is pixel (x, y) in the camera's pixel convention. Invalid
pixels (no ray) get NaN. method, frame and normalize as in unproject.)doc")
        .def_property_readonly("K", [](const PythonCamera& c) { return to_numpy(c.camera().intrinsics.K()); },
                               "The intrinsic matrix, 3x3 (a copy).")
        .def_property_readonly(
            "dist",
            [](const PythonCamera& c) {
                const std::vector<double>& k = c.camera().lens.coefficients;
                return to_numpy_vector(Eigen::Map<const Eigen::VectorXd>(k.data(), static_cast<Eigen::Index>(k.size())));
            },
            "The lens's coefficients in the model's order (OpenCV's for OpenCV's models).")
        .def_property_readonly(
            "model", [](const PythonCamera& c) { return std::string(lens_info(c.camera().lens.type).name); },
            "The lens model's name, a key of libcam.models.")
        .def_property_readonly(
            "size", [](const PythonCamera& c) { return py::make_tuple(c.camera().size.width, c.camera().size.height); },
            "(width, height) in pixels.")
        .def_property_readonly("R", [](const PythonCamera& c) { return to_numpy(c.camera().pose.R); },
                               "World to camera rotation, 3x3: X_cam = R X + t.")
        .def_property_readonly("t", [](const PythonCamera& c) { return to_numpy_vector(c.camera().pose.t); },
                               "World to camera translation: X_cam = R X + t.")
        .def_property_readonly("rvec", [](const PythonCamera& c) { return to_numpy_vector(c.camera().pose.rvec()); },
                               "R as a Rodrigues vector (cv2.Rodrigues).")
        .def_property_readonly("center", [](const PythonCamera& c) { return to_numpy_vector(c.camera().pose.centre()); },
                               "The camera centre in the world: -R^T t.")
        .def_property_readonly("P", [](const PythonCamera& c) { return to_numpy(c.camera().P()); },
                               "K [R | t], 3x4 (the pinhole part: distortion is not linear).")
        .def_property_readonly(
            "pixel_origin", [](const PythonCamera& c) { return std::string(to_string(c.pixel_origin())); },
            "'top-left' (OpenCV's pixels) or 'bottom-left' (rows counted upward, as the look-at formula).")
        .def_property_readonly(
            "fov", [](const PythonCamera& c) { return fov_angles(c.camera()); },
            "Full fields of view in degrees across the image through the principal point:\n"
            "{'horizontal', 'vertical', 'diagonal'} (the pinhole part of the camera).")
        .def_property_readonly(
            "valid_angle", [](const PythonCamera& c) { return c.prepared().valid_angle() * 180.0 / M_PI; },
            "The largest angle from the optical axis the lens images, in degrees.")
        .def("to_gl", &to_gl, py::arg("near"), py::arg("far"), py::arg("depth_range") = "-1..1", R"doc(
OpenGL's camera for a PINHOLE camera: {'projection': 4x4, 'view': 4x4, 'viewport': (0, 0, W, H),
'near', 'far', 'depth_range'}. Matrices are row-major (pass GL_TRUE to glUniformMatrix4fv).
depth_range: '-1..1' (OpenGL) or '0..1' (Direct3D, Vulkan).)doc")
        .def("to_blender", &to_blender,
             "Blender's camera settings (type, lens, sensor, shift, resolution, pose) as a dict; raises\n"
             "libcam.NotRepresentable for a lens Blender cannot draw (see `libcam render-plan`).")
        .def("write", &write, py::arg("path"), py::arg("format") = py::none(),
             "Writes the camera file (atomically); format by name or by the path's extension.")
        .def("format", &format_text, py::arg("format"), "The camera file's text in a format (e.g. 'opencv-yaml').")
        .def(
            "resized",
            [](const PythonCamera& c, const py::object& size) {
                return PythonCamera(resized(c.camera(), size_from(size)), c.pixel_origin());
            },
            py::arg("size"), "The camera of the image resized to (width, height), as cv2.resize does.")
        .def(
            "binned", [](const PythonCamera& c, int factor) { return PythonCamera(binned(c.camera(), factor), c.pixel_origin()); },
            py::arg("factor"), "The camera of the image binned by factor x factor pixel blocks.")
        .def(
            "__eq__",
            [](const PythonCamera& a, const PythonCamera& b) {
                const Camera &x = a.camera(), &y = b.camera();
                return x.size == y.size && x.intrinsics.K() == y.intrinsics.K() && x.lens == y.lens &&
                       x.pose.R == y.pose.R && x.pose.t == y.pose.t && a.pixel_origin() == b.pixel_origin();
            },
            py::is_operator())
        .def("__repr__", &describe);
}

}  // namespace libcam::python
