#include "libcam/lens/lens_model.hpp"

#include <algorithm>
#include <cmath>

#include "libcam/error.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam {

std::optional<LensType> lens_type_from_name(std::string_view name) {
    constexpr std::string_view mrcal_prefix = "LENSMODEL_";
    if (name.starts_with(mrcal_prefix)) name.remove_prefix(mrcal_prefix.size());
    for (const LensInfo& info : kLensTable) {
        if (info.name == name) return info.type;
    }
    return std::nullopt;
}

Lens simplest_equal_lens(const Lens& lens) {
    const LensInfo& info = lens_info(lens.type);
    if (info.num_coefficients == kVariableCoefficientCount) return lens;
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
