#pragma once
// mrcal's optimization_inputs in a .cameramodel: the solve mrcal-calibrate-cameras ran,
// kept in the file as a Python bytes literal holding base85 text of an .npz archive
// (mrcal's cameramodel.py, _serialize_optimization_inputs). Read here without mrcal:
// every camera of the solve, one view per board observation (and per camera seeing
// discrete points), the board's corners with mrcal's calobject_warp applied, and each
// observation's weight (negative or zero: mrcal's outlier). A solve whose inputs hold no
// observation is refused: there is nothing to reproject.

#include <filesystem>
#include <string>
#include <string_view>

#include "libcam/io/observations.hpp"

namespace libcam::detail {

// The cameramodel row's read_observations: the file's own camera first, read and checked
// as `libcam info` reads it (the row's reader, libmrcal's parser: libcam::interop must be
// registered), so that the two refuse a file alike; then parse_mrcal_observations.
ObservationSet read_mrcal_observations(const std::filesystem::path& file, std::string_view text,
                                       const ObservationReadOptions& options);

// The observations of a .cameramodel's text; `source` names it in messages.
ObservationSet parse_mrcal_observations(std::string_view text, const std::string& source);

// Bytes as Python's base64.b85encode writes them, as mrcal stores its optimization_inputs
// (mrcal_optimization_inputs, mrcal_inputs_writer.cpp).
std::string base85_encode(std::string_view bytes);

}  // namespace libcam::detail
