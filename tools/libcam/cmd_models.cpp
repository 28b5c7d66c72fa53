// libcam models: the lens-model table (libcam/lens/lens_model.hpp) as text, JSON or the
// markdown table of docs/lens-models.md. It only formats the table: everything it prints
// is a column of a row.

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam::cli {

namespace {

using Json = nlohmann::ordered_json;

const char* const kJsonKeys =
    "name, coefficients (names, in order), coefficient_count (null where the leading coefficients set it), "
    "sees_behind_camera, inverse (closed-form or solved), family (the name of its simplest model), "
    "family_rank, fit (always, wide-scenes, on-request or no), opencv (the function that projects it), mrcal, "
    "mrcal_in_name (the coefficients mrcal keeps in its name), colmap, kalibr, basalt, also_named (other "
    "programs' and papers' names, in words); an empty string where the library lacks the model";

std::string joined(std::span<const std::string_view> words) {
    std::string out;
    for (std::string_view word : words) out += (out.empty() ? "" : " ") + std::string(word);
    return out;
}

// The coefficients mrcal keeps in its name (leading, then trailing), by name.
std::vector<std::string_view> mrcal_in_name(const LensInfo& info) {
    const std::span<const std::string_view> names = info.coefficients.view();
    std::vector<std::string_view> out(names.begin(), names.begin() + info.mrcal_in_name.leading);
    out.insert(out.end(), names.end() - info.mrcal_in_name.trailing, names.end());
    return out;
}

// The columns: a title, then one cell per model.
constexpr std::size_t kColumns = 12;
using Cells = std::array<std::string, kColumns>;
const Cells kTitles = {"model",  "coefficients", "behind the camera", "inverse", "family, rank", "fit",
                       "OpenCV", "mrcal",        "COLMAP",            "Kalibr",  "basalt",       "also named"};
constexpr std::size_t kFirstPeer = 6;  // OpenCV: the columns from here on name the model elsewhere
constexpr std::size_t kAlsoNamed = 11;  // the last, in words

// One model's cells; `none` where a library lacks the model.
Cells cells_of(const LensInfo& info, const std::string& none) {
    const auto peer = [&](std::string_view name) { return name.empty() ? none : std::string(name); };
    std::string coefficients = info.coefficients.count == 0 ? "none" : joined(info.coefficients.view());
    // A count the leading coefficients set (SPLINED_STEREOGRAPHIC's control points).
    if (info.num_coefficients == kVariableCoefficientCount) coefficients += " ...";
    return {std::string(info.name),
            coefficients,
            info.sees_behind_camera ? "yes" : "no",
            std::string(to_string(info.inverse)),
            std::string(lens_family_base(info.type).name) + ", " + std::to_string(info.family_rank),
            std::string(to_string(info.fit)),
            peer(to_string(info.opencv)),
            peer(mrcal_model_name(info.type)),
            peer(info.colmap),
            peer(info.kalibr),
            peer(info.basalt),
            peer(info.also_named)};
}

std::string markdown_row(const Cells& cells) {
    std::string out = "|";
    for (const std::string& cell : cells) out += " " + cell + " |";
    return out + "\n";
}

std::string markdown_table() {
    std::string out = markdown_row(kTitles) + "|";
    for (std::size_t c = 0; c < kColumns; ++c) out += "---|";
    out += "\n";
    for (const LensInfo& info : lens_models()) {
        Cells cells = cells_of(info, "");
        // Other libraries' names as code (not the words of "also named").
        for (std::size_t c = kFirstPeer; c < kAlsoNamed; ++c) {
            if (!cells[c].empty()) cells[c] = "`" + cells[c] + "`";
        }
        out += markdown_row(cells);
    }
    return out;
}

// The columns `columns` of every model, aligned, under their titles.
std::string text_table(std::span<const std::size_t> columns) {
    std::vector<Cells> rows{kTitles};
    for (const LensInfo& info : lens_models()) rows.push_back(cells_of(info, "-"));
    std::ostringstream out;
    for (const Cells& row : rows) {
        std::string line;
        for (std::size_t c : columns) {
            std::size_t width = 0;
            for (const Cells& other : rows) width = std::max(width, other[c].size());
            line += row[c] + std::string(width + 2 - row[c].size(), ' ');
        }
        line.erase(line.find_last_not_of(' ') + 1);
        out << line << "\n";
    }
    return out.str();
}

Json models_json() {
    Json out = Json::array();
    for (const LensInfo& info : lens_models()) {
        const auto names = info.coefficients.view();
        out.push_back({{"name", info.name},
                       {"coefficients", std::vector<std::string_view>(names.begin(), names.end())},
                       {"coefficient_count", info.num_coefficients == kVariableCoefficientCount
                                                 ? Json(nullptr)
                                                 : Json(info.num_coefficients)},
                       {"sees_behind_camera", info.sees_behind_camera},
                       {"inverse", to_string(info.inverse)},
                       {"family", lens_family_base(info.type).name},
                       {"family_rank", info.family_rank},
                       {"fit", to_string(info.fit)},
                       {"opencv", to_string(info.opencv)},
                       {"mrcal", info.mrcal},
                       {"mrcal_in_name", mrcal_in_name(info)},
                       {"colmap", info.colmap},
                       {"kalibr", info.kalibr},
                       {"basalt", info.basalt},
                       {"also_named", info.also_named}});
    }
    return out;
}

}  // namespace

Runner add_models(CLI::App& app) {
    CLI::App* command = add_command(app, "models");
    struct Flags {
        bool json = false;
        bool markdown = false;
    };
    auto flags = std::make_shared<Flags>();
    CLI::Option* json =
        command->add_flag("--json", flags->json, std::string("Print a JSON array, one object per model: ") + kJsonKeys);
    command->add_flag("--markdown", flags->markdown, "Print the markdown table of docs/lens-models.md")->excludes(json);
    return [flags] {
        if (flags->json) {
            emit(models_json().dump(2) + "\n", "");
        } else if (flags->markdown) {
            emit(markdown_table(), "");
        } else {
            // Three tables a terminal can show: the model, the libraries (mrcal's long
            // configured names last), the other names.
            constexpr std::size_t abilities[] = {0, 1, 2, 3, 4, 5}, peers[] = {0, 6, 8, 9, 10, 7}, also[] = {0, 11};
            emit(text_table(abilities) + "\n" + text_table(peers) + "\n" + text_table(also), "");
        }
        return 0;
    };
}

}  // namespace libcam::cli
