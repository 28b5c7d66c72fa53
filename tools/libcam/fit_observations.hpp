#pragma once
// libcam fit --observations SRC: the lens model a calibration's or reconstruction's own
// observations support, cross-validated by view (fit/observation_fit.hpp).

#include <string>
#include <vector>

#include "libcam/fit/fit.hpp"

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

// Runs it and prints the report; returns the exit code.
int run_fit_observations(const ObservationFitFlags& flags);

}  // namespace libcam::cli
