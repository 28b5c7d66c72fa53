// libcam formats: every camera-file format, what libcam does with it and the lens models
// it holds, from the one table of formats (plain text, --json, or --markdown: the table of
// docs/file-formats.md; --limits: the table of the largest files read, docs/reliability.md).

#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_formats.hpp"

namespace libcam::cli {

namespace {

using Json = nlohmann::ordered_json;

std::string joined(const std::vector<std::string_view>& words, std::string_view separator) {
    std::string out;
    for (const std::string_view word : words) out += (out.empty() ? "" : std::string(separator)) + std::string(word);
    return out;
}

std::vector<std::string_view> lens_names(const CameraFormatInfo& format) {
    std::vector<std::string_view> names;
    for (const LensType lens : format.lenses) names.push_back(lens_info(lens).name);
    return names;
}

std::string access(const CameraFormatInfo& format) {
    std::string text = !format.writes ? "reads" : !format.reads ? "writes"
                       : format.writes_folder ? "reads, writes a folder" : "reads, writes";
    if (format.observations) text += "; observations";
    return text;
}

// The models a format holds, in words: "every model" where it holds them all.
std::string lens_models_text(const CameraFormatInfo& format) {
    if (format.lenses.size() == lens_models().size()) return "all";
    return joined(lens_names(format), ", ");
}

Json format_json(const CameraFormatInfo& format) {
    Json out;
    out["name"] = format.name;
    out["title"] = format.title;
    out["description"] = format.description;
    out["extensions"] = format.extensions;
    out["reads"] = format.reads;
    out["writes"] = format.writes;
    out["writes_folder"] = format.writes_folder;
    out["observations"] = format.observations;
    out["lens_models"] = lens_names(format);
    out["lens_names"] = format.lens_names;
    out["refuses"] = format.refuses;
    out["camera_names"] = format.camera_names;
    out["library"] = format.library;
    out["largest_file_bytes"] = format.largest_file;
    Json beside = Json::array();
    for (const FilesBesideInfo& files : format.files_beside) {
        beside.push_back({{"files", files.files}, {"largest_bytes", files.largest}});
    }
    out["files_beside"] = beside;
    out["available"] = format.available;
    return out;
}

// A table cell's text: a '|' in it would end the cell.
std::string cell(std::string_view text) {
    std::string out;
    for (const char c : text) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

std::string markdown(const std::vector<CameraFormatInfo>& formats) {
    std::ostringstream out;
    out << "| format | what | libcam | lens models it holds | the format's names | cannot hold | --camera takes |\n";
    out << "|---|---|---|---|---|---|---|\n";
    for (const CameraFormatInfo& format : formats) {
        out << "| `" << format.name << "` | " << cell(format.description) << " | " << access(format) << " | "
            << lens_models_text(format) << " | " << cell(format.lens_names) << " | " << cell(format.refuses) << " | "
            << cell(format.camera_names) << " |\n";
    }
    return out.str();
}

// "tracks.csv: 2 GiB", each file read beside the format's own.
std::string files_beside_text(const CameraFormatInfo& format) {
    std::string out;
    for (const FilesBesideInfo& files : format.files_beside) {
        out += (out.empty() ? "" : "; ") + std::string(files.files) + ": " + byte_size_text(files.largest);
    }
    return out;
}

// The table of docs/reliability.md: the most libcam reads of each format's files.
std::string limits_markdown(const std::vector<CameraFormatInfo>& formats) {
    std::ostringstream out;
    out << "| format | largest file read | files read beside it |\n";
    out << "|---|---|---|\n";
    for (const CameraFormatInfo& format : formats) {
        if (!format.reads) continue;
        out << "| `" << format.name << "` | " << byte_size_text(format.largest_file) << " | "
            << cell(files_beside_text(format)) << " |\n";
    }
    return out.str();
}

std::string plain(const std::vector<CameraFormatInfo>& formats) {
    std::ostringstream out;
    for (const CameraFormatInfo& format : formats) {
        out << format.name << ": " << format.title << " (" << access(format)
            << (format.available ? "" : "; needs " + std::string(format.library)) << ")\n";
        out << "  " << format.description << "\n";
        if (!format.extensions.empty()) out << "  files     " << joined(format.extensions, " ") << "\n";
        out << "  models    " << lens_models_text(format) << "\n";
        if (!format.lens_names.empty()) out << "  its names " << format.lens_names << "\n";
        if (!format.refuses.empty()) out << "  refuses   " << format.refuses << "\n";
        if (format.reads) out << "  --camera  " << format.camera_names << "\n";
        if (format.reads) {
            const std::string beside = files_beside_text(format);
            out << "  reads at most " << byte_size_text(format.largest_file)
                << (beside.empty() ? "" : " (" + beside + ")") << "\n";
        }
    }
    return out.str();
}

}  // namespace

Runner add_formats(CLI::App& app) {
    CLI::App* command = add_command(app, "formats");
    struct Flags {
        bool json = false;
        bool markdown = false;
        bool limits = false;
    };
    auto flags = std::make_shared<Flags>();
    CLI::Option* json = command->add_flag(
        "--json", flags->json,
        "Print a JSON array, one object per format: name, title, description, extensions, reads, writes, "
        "writes_folder, observations, lens_models, lens_names, refuses, camera_names (what --camera takes besides a "
        "position), library, largest_file_bytes, files_beside, available");
    CLI::Option* markdown_flag =
        command->add_flag("--markdown", flags->markdown, "Print the table of docs/file-formats.md");
    markdown_flag->excludes(json);
    command->add_flag("--limits", flags->limits,
                      "Print the table of docs/reliability.md: the largest file libcam reads of each format")
        ->excludes(json)
        ->excludes(markdown_flag);
    return [flags] {
        const std::vector<CameraFormatInfo> formats = camera_formats();
        if (flags->json) {
            Json list = Json::array();
            for (const CameraFormatInfo& format : formats) list.push_back(format_json(format));
            std::cout << list.dump(2) << "\n";
        } else {
            std::cout << (flags->limits     ? limits_markdown(formats)
                          : flags->markdown ? markdown(formats)
                                            : plain(formats));
        }
        return 0;
    };
}

}  // namespace libcam::cli
