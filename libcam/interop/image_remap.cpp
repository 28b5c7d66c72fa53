#include "libcam/interop/image_remap.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"

namespace libcam {

namespace {

// The map's coordinates as float32 pairs, `none` where there is no source; with
// `clamp`, on-image coordinates in the outer half pixel moved onto the edge pixel.
cv::Mat float_map(const RemapMap& map, float none, bool clamp) {
    cv::Mat out(static_cast<int>(map.size.height), static_cast<int>(map.size.width), CV_32FC2);
    const double right = static_cast<double>(map.source_size.width - 1);
    const double bottom = static_cast<double>(map.source_size.height - 1);
    auto* xy = out.ptr<float>();
    for (std::size_t i = 0; i < map.x.size(); ++i) {
        if (!map.has_source(i)) {
            xy[2 * i] = xy[2 * i + 1] = none;
            continue;
        }
        const double x = clamp ? std::clamp(map.x[i], 0.0, right) : map.x[i];
        const double y = clamp ? std::clamp(map.y[i], 0.0, bottom) : map.y[i];
        xy[2 * i] = static_cast<float>(x);
        xy[2 * i + 1] = static_cast<float>(y);
    }
    return out;
}

// One float channel of an OpenEXR image: its name, its first value, and the floats from
// one pixel's value to the next (2 for a channel of interleaved x, y pairs).
struct ExrChannel {
    const char* name;
    const float* data;
    std::size_t stride = 1;
};

// An OpenEXR image of float channels, each `width` x `height` row by row.
std::string exr_of_channels(int width, int height, const std::vector<ExrChannel>& channels) {
    Imf::Header header(width, height);
    for (const ExrChannel& channel : channels) header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
    Imf::StdOSStream stream;
    {
        Imf::OutputFile file(stream, header);
        Imf::FrameBuffer frame;
        for (const ExrChannel& channel : channels) {
            char* base = const_cast<char*>(reinterpret_cast<const char*>(channel.data));
            const std::size_t pixel = channel.stride * sizeof(float);
            frame.insert(channel.name, Imf::Slice(Imf::FLOAT, base, pixel, pixel * static_cast<std::size_t>(width)));
        }
        file.setFrameBuffer(frame);
        file.writePixels(height);
    }
    return stream.str();
}

std::string exr_bytes(const RemapMap& map) {
    const cv::Mat xy = float_map(map, std::numeric_limits<float>::quiet_NaN(), false);
    return exr_of_channels(static_cast<int>(map.size.width), static_cast<int>(map.size.height),
                           {{"R", xy.ptr<float>(), 2}, {"G", xy.ptr<float>() + 1, 2}});
}

std::string stmap_bytes(const RemapMap& map, const StmapFormat& format) {
    const std::size_t n = map.x.size();
    std::vector<float> u(n), v(n), blue(n, 0.0f), alpha(n);
    const double width = static_cast<double>(format.size.width), height = static_cast<double>(format.size.height);
    for (std::size_t i = 0; i < n; ++i) {
        const bool has = map.has_source(i);
        u[i] = has ? static_cast<float>((map.x[i] + 0.5 - static_cast<double>(format.left)) / width) : -1.0f;
        v[i] = has ? static_cast<float>(1.0 - (map.y[i] + 0.5 - static_cast<double>(format.top)) / height) : -1.0f;
        alpha[i] = has ? 1.0f : 0.0f;
    }
    return exr_of_channels(static_cast<int>(map.size.width), static_cast<int>(map.size.height),
                           {{"R", u.data()}, {"G", v.data()}, {"B", blue.data()}, {"A", alpha.data()}});
}

// NumPy's .npy, version 1.0: magic, header length, a Python dict padded to 64 bytes.
std::string npy_bytes(const RemapMap& map) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(map.size.height) +
                         ", " + std::to_string(map.size.width) + ", 2), }";
    const std::size_t preamble = 10;
    header.append(63 - (preamble + header.size()) % 64, ' ');
    header += '\n';
    std::string out = "\x93NUMPY";
    out += '\x01';
    out += '\x00';
    out += static_cast<char>(header.size() & 0xff);
    out += static_cast<char>(header.size() >> 8);
    out += header;
    const cv::Mat xy = float_map(map, std::numeric_limits<float>::quiet_NaN(), false);
    static_assert(std::endian::native == std::endian::little, "the .npy writer assumes a little-endian machine");
    out.append(reinterpret_cast<const char*>(xy.ptr<float>()), xy.total() * 2 * sizeof(float));
    return out;
}

}  // namespace

Interpolation interpolation_from_string(std::string_view name) {
    if (name == "nearest") return Interpolation::Nearest;
    if (name == "linear") return Interpolation::Linear;
    if (name == "cubic") return Interpolation::Cubic;
    if (name == "lanczos") return Interpolation::Lanczos;
    throw InvalidArgument("interpolation: must be nearest, linear, cubic or lanczos, got '" + std::string(name) + "'");
}

std::string_view to_string(Interpolation interpolation) {
    switch (interpolation) {
        case Interpolation::Nearest: return "nearest";
        case Interpolation::Linear: return "linear";
        case Interpolation::Cubic: return "cubic";
        case Interpolation::Lanczos: return "lanczos";
    }
    return "cubic";
}

cv::Mat opencv_map(const RemapMap& map) { return float_map(map, kNoSourceCoordinate, false); }

std::pair<cv::Mat, cv::Mat> opencv_fixed_point_map(const RemapMap& map) {
    std::pair<cv::Mat, cv::Mat> fixed;
    cv::convertMaps(opencv_map(map), cv::Mat(), fixed.first, fixed.second, CV_16SC2);
    return fixed;
}

PreparedRemap prepare_remap(const RemapMap& map, Interpolation interpolation) {
    PreparedRemap prepared;
    prepared.source_size = map.source_size;
    prepared.interpolation = interpolation;
    const bool nearest = interpolation == Interpolation::Nearest;
    cv::convertMaps(float_map(map, kNoSourceCoordinate, true), cv::Mat(), prepared.xy, prepared.fraction, CV_16SC2,
                    nearest);
    return prepared;
}

cv::Mat remap_image(const cv::Mat& source_image, const PreparedRemap& map) {
    if (source_image.cols != map.source_size.width || source_image.rows != map.source_size.height) {
        throw InvalidArgument("image: " + std::to_string(source_image.cols) + "x" + std::to_string(source_image.rows) +
                              " pixels, but the source camera's image is " + std::to_string(map.source_size.width) +
                              "x" + std::to_string(map.source_size.height));
    }
    const int flags[] = {cv::INTER_NEAREST, cv::INTER_LINEAR, cv::INTER_CUBIC, cv::INTER_LANCZOS4};
    cv::Mat target;
    cv::remap(source_image, target, map.xy, map.fraction, flags[static_cast<int>(map.interpolation)],
              cv::BORDER_CONSTANT, cv::Scalar::all(0));
    return target;
}

cv::Mat remap_image(const cv::Mat& source_image, const RemapMap& map, Interpolation interpolation) {
    return remap_image(source_image, prepare_remap(map, interpolation));
}

void check_map_file_name(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (extension != ".npy" && extension != ".exr") {
        throw FileError(path.string() + ": a map is written as .exr or .npy, not '" + extension + "'");
    }
}

void check_stmap_file_name(const std::filesystem::path& path) {
    if (path.extension() != ".exr") {
        throw FileError(path.string() + ": an STMap is written as .exr, not '" + path.extension().string() + "'");
    }
}

std::string encoded_map(const std::filesystem::path& path, const RemapMap& map) {
    check_map_file_name(path);
    if (path.extension() == ".npy") return npy_bytes(map);
    try {
        return exr_bytes(map);
    } catch (const std::exception& error) {
        throw FileError(path.string() + ": OpenEXR could not write the map: " + error.what());
    }
}

void write_map_file(const std::filesystem::path& path, const RemapMap& map) {
    write_file_atomically(path, encoded_map(path, map));
}

void write_stmap_file(const std::filesystem::path& path, const RemapMap& map, const StmapFormat& format) {
    if (format.size.width < 1 || format.size.height < 1) {
        throw InvalidArgument("STMap format: must be at least 1x1, got " + std::to_string(format.size.width) + "x" +
                              std::to_string(format.size.height));
    }
    check_stmap_file_name(path);
    std::string bytes;
    try {
        bytes = stmap_bytes(map, format);
    } catch (const std::exception& error) {
        throw FileError(path.string() + ": OpenEXR could not write the STMap: " + error.what());
    }
    write_file_atomically(path, bytes);
}

cv::Mat read_image(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw FileError(path.string() + ": no such image file");
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (image.empty()) throw FileError(path.string() + ": not an image OpenCV can read");
    return image;
}

void write_image(const std::filesystem::path& path, const cv::Mat& image, int jpeg_quality) {
    std::vector<unsigned char> bytes;
    bool encoded = false;
    try {
        encoded = cv::imencode(path.extension().string(), image, bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
    } catch (const cv::Exception&) {
        encoded = false;
    }
    if (!encoded) throw FileError(path.string() + ": OpenCV cannot write an image of this type as " + path.extension().string());
    write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace libcam
