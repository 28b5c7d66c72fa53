#include "libcam/lens/lens_model.hpp"

#include <array>

#include "libcam/error.hpp"

namespace libcam {

namespace {
constexpr std::array kLensModels = {
#define LIBCAM_LENS_INFO(id, name, n, behind, model) LensInfo{LensType::id, name, n, behind},
    LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_INFO)
#undef LIBCAM_LENS_INFO
};
}  // namespace

std::span<const LensInfo> lens_models() { return kLensModels; }

const LensInfo& lens_info(LensType type) { return kLensModels.at(static_cast<std::size_t>(type)); }

std::optional<LensType> lens_type_from_name(std::string_view name) {
    constexpr std::string_view mrcal_prefix = "LENSMODEL_";
    if (name.starts_with(mrcal_prefix)) name.remove_prefix(mrcal_prefix.size());
    for (const LensInfo& info : kLensModels) {
        if (info.name == name) return info.type;
    }
    return std::nullopt;
}

void Lens::validate(const char* field) const {
    const LensInfo& info = lens_info(type);
    if (static_cast<int>(coefficients.size()) != info.num_coefficients) {
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
}

}  // namespace libcam
