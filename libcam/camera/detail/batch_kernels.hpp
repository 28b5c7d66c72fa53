#pragma once
// What the batch paths (projector.cpp, unprojector.cpp) share; internal to libcam.
//
// The loops run in blocks of kBlock points. Within a block every step is its own
// simple loop over arrays, with the model evaluated in Lane<Scalar> (lens/lane.hpp) and
// the per-point validity kept as a Scalar 0 or 1 in the loop (a byte written from a
// double comparison does not vectorise with SSE2), narrowed to bytes at the end.
//
// A loop reads the camera's constants (lens parameters, K, the table's geometry) from
// local copies made just before it: the compiler cannot tell that a store to an output
// array does not change a constant read through a reference (or even a by-value
// parameter, which the ABI passes in memory), so it would reload them on every point,
// under the point's branch, and a load under a branch is what stops the vectoriser.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam::batch {

// Points per block: a block's scratch arrays (a few kB) stay in the L1 cache. Chunks
// given to threads are multiples of it.
inline constexpr std::size_t kBlock = 128;

// The model's parameters in its scalar type, from the camera's coefficients and the
// valid radius worked out once per camera.
template <class Model>
typename Model::Parameters model_parameters(const Lens& lens, double valid_radius) {
    using Scalar = typename Model::Vec2T::Scalar;
    if constexpr (requires { Model::parameters(std::span<const double>(lens.coefficients), valid_radius); }) {
        return Model::parameters(lens.coefficients, valid_radius);  // a model with more per camera
    } else {
        return lens_parameters<Scalar, Model::num_coefficients>(lens.coefficients, valid_radius);
    }
}

// A camera's lens in Model's scalar (Lane<T>, for the vectorised loops) and in a plain
// scalar, for the points those loops leave to a one-by-one pass: the Unprojector's full
// solver (double) and the Projector's second pass (T).
template <class Model, class PlainScalar>
struct BatchLens {
    using Plain = LensInScalar<Model, PlainScalar>;
    typename Model::Parameters lanes;
    typename Plain::Parameters plain;

    BatchLens(const Lens& lens, double valid_radius)
        : lanes(model_parameters<Model>(lens, valid_radius)), plain(model_parameters<Plain>(lens, valid_radius)) {}
};

// Throws InvalidArgument unless every coordinate array of a batch has n entries.
inline void require_same_sizes(const char* field, std::size_t n, std::initializer_list<std::size_t> others) {
    for (std::size_t size : others) {
        if (size != n) {
            throw InvalidArgument(std::string(field) + ": coordinate arrays of different lengths (" + std::to_string(n) +
                                  " and " + std::to_string(size) + ")");
        }
    }
}

// Whether two ranges of memory share a byte (compared as addresses: they may belong to
// different arrays). The kernels read and write their arrays as restrict pointers, so
// the batch calls refuse outputs that overlap inputs or each other.
template <class A, class B>
bool overlap(std::span<A> a, std::span<B> b) {
    const auto begin_a = reinterpret_cast<std::uintptr_t>(a.data()), end_a = begin_a + a.size_bytes();
    const auto begin_b = reinterpret_cast<std::uintptr_t>(b.data()), end_b = begin_b + b.size_bytes();
    return begin_a < end_b && begin_b < end_a;
}

// Asks for the cache lines of `count` values from `first` on, which the next block copies
// in one burst: asked while this block computes, they are there when it starts, where
// the burst would otherwise wait on memory for a batch larger than the cache.
template <class Scalar>
void prefetch_for_reading(const Scalar* first, std::size_t count) {
    constexpr std::size_t kLine = 64;
    const char* bytes = reinterpret_cast<const char*>(first);
    for (std::size_t byte = 0; byte < count * sizeof(Scalar); byte += kLine) __builtin_prefetch(bytes + byte, 0);
}

// Throws InvalidArgument unless a batch on numpy's layouts fits its n flags (`values`
// holds `in_width` coordinates per entry, `results` `out_width`) and unless the results
// and the flags overlap nothing: the kernel copies a block's inputs before it writes the
// block's results, but results written over a later block's inputs would change them.
// `in_name` and `out_name` name one coordinate ("pixel"); an s makes them plural.
template <class Scalar>
void require_interleaved_batch(const char* call, std::span<const Scalar> values, std::size_t in_width,
                               const char* in_name, std::span<Scalar> results, std::size_t out_width,
                               const char* out_name, std::span<std::uint8_t> flags) {
    const std::size_t n = flags.size();
    const std::string name(call), in(in_name), out(out_name);
    if (values.size() != in_width * n || results.size() != out_width * n) {
        throw InvalidArgument(name + ": " + std::to_string(n) + " flags need " + std::to_string(in_width * n) + " " + in +
                              " coordinates and " + std::to_string(out_width * n) + " " + out + " coordinates, got " +
                              std::to_string(values.size()) + " and " + std::to_string(results.size()));
    }
    if (overlap(results, values) || overlap(results, flags) || overlap(values, flags)) {
        throw InvalidArgument(name + ": the " + out + "s and the flags must not overlap the " + in + "s or each other");
    }
}

template <class Scalar>
constexpr Scalar flag(bool value) {
    return value ? Scalar(1) : Scalar(0);
}

// Bytes 1 where the flag is positive (1 valid; 0 and -1 are the ways of being invalid).
// Through int: a byte from a double comparison does not vectorise with SSE2, a byte
// from an int does.
template <class Scalar>
void store_flags(std::span<const Scalar> flags, std::uint8_t* out) {
    for (std::size_t i = 0; i < flags.size(); ++i) {
        const int flag = static_cast<int>(flags[i]);
        out[i] = static_cast<std::uint8_t>(flag > 0 ? flag : 0);
    }
}

}  // namespace libcam::batch
