#pragma once
// A COLMAP model (cameras, images and points3D, .bin or .txt) read and checked once, for
// every command that reads one: its cameras (`libcam info`, colmap_format.hpp), its
// observations (`libcam reproject`, colmap_observations.hpp) and the whole model
// (`libcam dataset`, dataset/colmap_dataset.hpp). The three agree on what a model is: one
// these checks refuse, each refuses with the same line.
//
// The checks, in this order, the first that fails naming the file, the record and the value:
//   - each file parses (colmap_format.hpp: the numbers, the counts against the file's size,
//     every camera valid, every pose a rotation);
//   - CAMERA_ID, IMAGE_ID and POINT3D_ID are each unique in their file;
//   - every image's CAMERA_ID is a camera of the cameras file;
//   - every POINTS2D's POINT3D_ID is -1 or a point of points3D;
//   - every element of a point's track names an image of the images file, a POINT2D_IDX
//     inside that image's POINTS2D, and a 2-D point that is this point's or no point's
//     (-1, which COLMAP then links to this point, and so does this reader); no 2-D point
//     is named twice;
//   - every POINTS2D that names a point is in that point's track.
// COLMAP's own invariant: a 2-D point and its 3-D point's track name each other. COLMAP
// 4.x checks the track elements when it loads a model (Reconstruction::AddPoint3D:
// Image(image_id) and Point2D(point2D_idx) throw on an absent image or index, and a 2-D
// point of another point fails THROW_CHECK_EQ); 3.8 checked nothing and failed at the
// first use. Its writers never write a model that breaks it.
//
// Memory and time: the records as the files hold them, each image's POINTS2D included;
// the ids are indexed by ColmapIdIndex, a table where they are compact (as COLMAP numbers
// them) and a sorted list otherwise. The tracks are checked against the POINTS2D by a sum
// over each in file order (colmap_model.cpp), and only where the sums differ element by
// element, with a bit per POINTS2D, to say where.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "libcam/io/detail/colmap_format.hpp"

namespace libcam {

// A file's ids to their positions.
class ColmapIdIndex {
public:
    ColmapIdIndex() = default;
    explicit ColmapIdIndex(const std::vector<std::uint64_t>& ids);

    // The position of `id`, or -1.
    int find(std::uint64_t id) const {
        if (sorted_.empty()) return id < table_.size() ? table_[static_cast<std::size_t>(id)] : -1;
        return find_sorted(id);
    }

    // An id that appears more than once, if any.
    std::optional<std::uint64_t> duplicate() const { return duplicate_; }

private:
    int find_sorted(std::uint64_t id) const;

    std::vector<int> table_;
    std::vector<std::pair<std::uint64_t, int>> sorted_;
    std::optional<std::uint64_t> duplicate_;
};

// The files of a model, of one kind.
struct ColmapModelPaths {
    std::filesystem::path cameras;
    std::filesystem::path images;    // empty: none beside the cameras file
    std::filesystem::path points3d;  // empty: none (or no images)
    bool binary = false;
};

// The model's records, checked (above), with their ids indexed.
struct ColmapModelRecords {
    std::vector<ColmapCameraRecord> cameras;
    std::vector<ColmapImage> images;  // each with its POINTS2D when the model has points3D
    ColmapPoints3D points;
    ColmapIdIndex camera_index, image_index, point_index;
};

// The model whose cameras file is `cameras` (its bytes `cameras_bytes`: binary when they
// hold a NUL byte, which COLMAP's text never has): the images and points3D files of the
// same kind beside it, where they are. With no images file it is the cameras alone, and
// with no points3D file the images' POINT3D_IDs are not checked.
ColmapModelPaths colmap_model_beside(const std::filesystem::path& cameras, std::string_view cameras_bytes);

// Every file of the model read and checked (above). `cameras_bytes`: the cameras file's,
// already read. Throws FileError.
ColmapModelRecords read_colmap_model_records(const ColmapModelPaths& paths, std::string_view cameras_bytes);

// The whole model, all three files required (FileError naming the one missing): for the
// commands that use its points. `cameras_bytes` as above.
ColmapModelRecords read_whole_colmap_model(const std::filesystem::path& cameras, std::string_view cameras_bytes);

// The same from a model folder or any of its files, found as `libcam info` finds it.
ColmapModelRecords read_whole_colmap_model(const std::filesystem::path& folder_or_file);

// Every camera of a cameras.txt or cameras.bin (told apart by a NUL byte, which text
// never has), with the images file of the same kind beside it when context.folder has one,
// the model read and checked as every command reads it (above: with points3D
// where it is there too).
std::vector<NamedCamera> read_colmap_model(std::string_view cameras, const ReadContext& context);

}  // namespace libcam
