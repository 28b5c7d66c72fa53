#pragma once
// libcam fit --observations SRC: the lens model a calibration's or reconstruction's own
// observations support, cross-validated by view (fit/observation_fit.hpp).

#include <string>
#include <vector>

#include "json_output.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/fit/observation_fit.hpp"

namespace libcam::cli {

struct ObservationFitFlags {
    std::string source;      // the observations
    std::string camera;      // which camera of a multi-camera file (name or position)
    std::vector<Candidate> candidates;
    int folds = 5;
    double margin = 0.05;
    bool json = false;
    std::string output;      // -o: the chosen camera
    std::string to;          // its format (empty: from the extension)
};

// --model's list of candidates, comma-separated (candidate_named); empty: none named.
// Throws UsageError naming a model libcam cannot fit.
std::vector<Candidate> candidates_from(const std::string& text);

// The format -o writes: --to's, else the output's extension's, else libcam JSON. Throws
// UsageError for a --to libcam does not write.
CameraFormat output_format_of(const std::string& to, const std::string& output);

// A lens model and its coefficients by name ("OPENCV5 k1 -0.27 k2 ..."), for reports.
std::string lens_text(const Camera& camera);

// Every candidate's parameters, RMS and held-out RMS (and the flags on it), one a line
// under a header; and the same as JSON (model, fitted, params, rms_px, heldout_rms_px,
// flags, or failure). `libcam calibrate` reports its fit with them too.
std::string candidates_table(const ObservationFitReport& report);
Json candidates_json(const ObservationFitReport& report);

// Runs it and prints the report; returns the exit code.
int run_fit_observations(const ObservationFitFlags& flags);

}  // namespace libcam::cli
