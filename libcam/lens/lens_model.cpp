#include "libcam/lens/lens_model.hpp"

#include <algorithm>
#include <cmath>

#include "libcam/error.hpp"
#include "libcam/lens/lens_models.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

std::optional<LensType> opencv_model_with(std::size_t count) {
    for (const LensInfo& info : lens_models()) {
        if (info.opencv == OpenCvFunction::ProjectPoints && info.num_coefficients > 0 &&
            static_cast<std::size_t>(info.num_coefficients) == count) {
            return info.type;
        }
    }
    return std::nullopt;
}

std::optional<LensType> lens_type_from_name(std::string_view name) {
    constexpr std::string_view mrcal_prefix = "LENSMODEL_";
    if (name.starts_with(mrcal_prefix)) name.remove_prefix(mrcal_prefix.size());
    for (const LensInfo& info : kLensTable) {
        if (info.name == name) return info.type;
    }
    return std::nullopt;
}

std::string mrcal_model_name(LensType type, std::span<const double> coefficients) {
    const LensInfo& info = lens_info(type);
    std::string name(info.mrcal);
    if (name.empty()) return name;
    const auto leading = static_cast<std::size_t>(info.mrcal_in_name.leading);
    const auto trailing = static_cast<std::size_t>(info.mrcal_in_name.trailing);
    const bool configured = !coefficients.empty() && coefficients.size() >= leading + trailing;
    // The shortest text of each value: the splined model's whole numbers (at most 65535)
    // print as integers, as mrcal reads them.
    const auto append = [&](std::size_t name_index, std::size_t value_index) {
        name += "_" + std::string(info.coefficients.names[name_index]) + "=" +
                (configured ? format_number(coefficients[value_index]) : std::string("..."));
    };
    for (std::size_t i = 0; i < leading; ++i) append(i, i);
    const auto named = static_cast<std::size_t>(info.coefficients.count);
    for (std::size_t i = 0; i < trailing; ++i) append(named - trailing + i, coefficients.size() - trailing + i);
    return name;
}

std::string_view to_string(Inverse inverse) {
    switch (inverse) {
        case Inverse::ClosedForm: return "closed-form";
        case Inverse::Solved: return "solved";
    }
    throw InvalidArgument("inverse: unknown value #" + std::to_string(static_cast<int>(inverse)));
}

std::string_view to_string(FitCandidate fit) {
    switch (fit) {
        case FitCandidate::No: return "no";
        case FitCandidate::Always: return "always";
        case FitCandidate::WideScenes: return "wide-scenes";
        case FitCandidate::OnRequest: return "on-request";
    }
    throw InvalidArgument("fit: unknown value #" + std::to_string(static_cast<int>(fit)));
}

std::string_view to_string(OpenCvFunction function) {
    switch (function) {
        case OpenCvFunction::None: return "";
        case OpenCvFunction::ProjectPoints: return "cv::projectPoints";
        case OpenCvFunction::Fisheye: return "cv::fisheye::projectPoints";
        case OpenCvFunction::Omnidir: return "cv::omnidir::projectPoints";
    }
    throw InvalidArgument("opencv: unknown value #" + std::to_string(static_cast<int>(function)));
}

Lens simplest_equal_lens(const Lens& lens) {
    const LensInfo& info = lens_info(lens.type);
    if (info.num_coefficients == kVariableCoefficientCount) return lens;
    // BROWN_K4 is OPENCV5 followed by k4, but its family is its own: OPENCV8's k4 divides.
    if (lens.type == LensType::BrownK4 && lens.coefficients.size() == 6 && lens.coefficients[5] == 0.0) {
        return simplest_equal_lens({LensType::OpenCv5, std::vector<double>(lens.coefficients.begin(),
                                                                           lens.coefficients.begin() + 5)});
    }
    // EQUIDISTANT_RADIAL without its odd terms is FISHEYE: theta (1 + b theta^2 + k2 theta^4),
    // the equidistant lens under the name OpenCV's users know (its family is PanoTools').
    if (lens.type == LensType::EquidistantRadial && lens.coefficients.size() == 4 && lens.coefficients[0] == 0.0 &&
        lens.coefficients[2] == 0.0) {
        return {LensType::Fisheye, {lens.coefficients[1], lens.coefficients[3], 0.0, 0.0}};
    }
    for (const LensInfo& smaller : kLensTable) {
        if (smaller.family != info.family || smaller.family_rank >= info.family_rank) continue;
        const std::span<const std::string_view> names = smaller.coefficients.view();
        const std::span<const std::string_view> ours = info.coefficients.view();
        if (!std::equal(names.begin(), names.end(), ours.begin())) continue;
        const auto dropped = lens.coefficients.begin() + static_cast<long>(names.size());
        if (std::all_of(dropped, lens.coefficients.end(), [](double c) { return c == 0.0; })) {
            return {smaller.type, std::vector<double>(lens.coefficients.begin(), dropped)};
        }
    }
    return lens;
}

void Lens::validate(const char* field) const {
    const LensInfo& info = lens_info(type);
    // A model with a variable count checks it itself (check_coefficients, below).
    if (info.num_coefficients != kVariableCoefficientCount &&
        static_cast<int>(coefficients.size()) != info.num_coefficients) {
        throw InvalidArgument(std::string(field) + ": model " + std::string(info.name) + " takes " +
                              std::to_string(info.num_coefficients) + " coefficients, got " +
                              std::to_string(coefficients.size()));
    }
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
        if (!std::isfinite(coefficients[i])) {
            throw InvalidArgument(std::string(field) + "[" + std::to_string(i) + "]: must be finite, got " +
                                  format_number(coefficients[i]));
        }
    }
    // A model whose coefficients are bounded says so with check_coefficients.
    visit_lens_model<double>(type, [&]<class Model>() {
        if constexpr (requires { Model::check_coefficients(std::span<const double>(coefficients), field); }) {
            Model::check_coefficients(coefficients, field);
        }
    });
}

}  // namespace libcam
