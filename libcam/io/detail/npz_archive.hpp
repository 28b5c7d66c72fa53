#pragma once
// numpy's .npz archives (np.savez, np.savez_compressed): a zip of .npy arrays, opened
// with libzip; each .npy's header (magic, version, the dict of descr, fortran_order and
// shape) is read here. Only what mrcal stores is handled: little-endian float64, int32,
// int64, bool, and unicode strings, in C order; anything else is refused by name.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace libcam::detail {

struct NpyArray {
    std::string descr;                // numpy's dtype string: "<f8", "<i4", "|b1", "<U17"
    std::vector<std::size_t> shape;   // empty for a scalar
    std::vector<double> numbers;      // the elements in C order, for a numeric dtype
    std::string text;                 // the string, for a scalar "<U..." (trailing NULs dropped)

    bool is_text() const { return descr.starts_with("<U"); }
    std::size_t size() const;  // the number of elements
};

// One .npy file's bytes; `where` names it in messages ("x.cameramodel: optimization_inputs:
// intrinsics"). Throws FileError "<where>: <what>" for what it does not handle.
NpyArray parse_npy(std::string_view bytes, const std::string& where);

// Every array of an .npz archive by name (the zip's member name without ".npy"). Throws
// FileError "<where>: <what>" for a corrupt archive or array.
std::map<std::string, NpyArray> read_npz(std::string_view bytes, const std::string& where);

// The .npy bytes of an array as numpy's np.save writes them (format 1.0, C order, the
// header padded to a multiple of 64 bytes and ending in a line end): its numbers as
// "<f8", "<i4" (whole numbers that fit) or "|b1", or its text as a scalar "<U" string.
// Throws InvalidArgument for a dtype it does not write or a number its dtype cannot hold.
std::string format_npy(const NpyArray& array);

// An .npz archive as np.savez_compressed writes one: each array a deflated member
// "<name>.npy", in the order given.
std::string write_npz(const std::vector<std::pair<std::string, NpyArray>>& arrays);

}  // namespace libcam::detail
