#include "libcam/io/atomic_write.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "libcam/error.hpp"

namespace libcam {

namespace {

std::string reason() { return std::strerror(errno); }

// Writes all of `contents` to fd; false on any short or failed write.
bool write_all(int fd, std::string_view contents) {
    while (!contents.empty()) {
        const ssize_t written = ::write(fd, contents.data(), contents.size());
        if (written < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        contents.remove_prefix(static_cast<std::size_t>(written));
    }
    return true;
}

// Creates a new temporary file beside `path`, mode 0666 less the umask (as any new
// file); returns its descriptor and fills `temporary`.
constexpr std::string_view kTemporaryMark = ".tmp-";

int create_temporary(const std::filesystem::path& path, std::string& temporary) {
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    static thread_local std::mt19937_64 random{std::random_device{}()};
    for (int attempt = 0; attempt < 100; ++attempt) {
        temporary = (folder / ("." + path.filename().string() + std::string(kTemporaryMark) + std::to_string(random()))).string();
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    return -1;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
    std::string temporary;
    const int fd = create_temporary(path, temporary);
    if (fd < 0) throw FileError(path.string() + ": cannot create a temporary file beside it: " + reason());

    auto fail = [&](const std::string& what) {
        const std::string why = reason();
        ::close(fd);
        ::unlink(temporary.c_str());
        throw FileError(path.string() + ": " + what + ": " + why);
    };
    // Replacing a file keeps its permissions.
    struct stat existing {};
    if (::stat(path.c_str(), &existing) == 0 && ::fchmod(fd, existing.st_mode & 07777) != 0) {
        fail("cannot copy the permissions of the existing file");
    }
    if (!write_all(fd, contents)) fail("write failed");
    if (::fsync(fd) != 0) fail("flush to disk failed");
    if (::close(fd) != 0) {
        const std::string why = reason();
        ::unlink(temporary.c_str());
        throw FileError(path.string() + ": close failed: " + why);
    }
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        const std::string why = reason();
        ::unlink(temporary.c_str());
        throw FileError(path.string() + ": cannot replace the file: " + why);
    }
}

std::string read_text_file(const std::filesystem::path& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) throw FileError(path.string() + ": is a directory");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw FileError(path.string() + ": cannot open: " + reason());
    // One read of the size the file has (COLMAP's images.bin runs to hundreds of MB); a
    // file of no size known (a pipe, /proc's files, which say 0) is read as a stream.
    const std::streamoff size = in.tellg();
    if (size > 0 && in.seekg(0)) {
        std::string text(static_cast<std::size_t>(size), '\0');
        in.read(text.data(), size);
        if (in.bad()) throw FileError(path.string() + ": read failed");
        text.resize(static_cast<std::size_t>(in.gcount()));  // shorter if it shrank meanwhile
        return text;
    }
    in.clear();
    in.seekg(0);
    in.clear();  // a pipe cannot seek, and is read from where it is
    std::ostringstream stream;
    stream << in.rdbuf();
    if (in.bad()) throw FileError(path.string() + ": read failed");
    return stream.str();
}

namespace {

// ".<name>.tmp-<digits>", as create_temporary names them.
bool is_temporary_name(const std::string& name) {
    const std::size_t mark = name.rfind(kTemporaryMark);
    if (name.size() < 2 || name[0] != '.' || mark == std::string::npos || mark < 2) return false;
    const std::string_view number = std::string_view(name).substr(mark + kTemporaryMark.size());
    return !number.empty() && number.find_first_not_of("0123456789") == std::string_view::npos;
}

}  // namespace

std::size_t remove_stopped_writes(const std::filesystem::path& folder) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) return 0;
    std::vector<std::filesystem::path> stopped;
    for (auto it = std::filesystem::recursive_directory_iterator(folder, error);
         !error && it != std::filesystem::recursive_directory_iterator(); it.increment(error)) {
        if (it->is_regular_file(error) && is_temporary_name(it->path().filename().string())) stopped.push_back(it->path());
    }
    if (error) throw FileError(folder.string() + ": cannot list it: " + error.message());
    for (const std::filesystem::path& file : stopped) {
        if (!std::filesystem::remove(file, error) && error) {
            throw FileError(file.string() + ": cannot remove this file a stopped run left: " + error.message());
        }
    }
    return stopped.size();
}

}  // namespace libcam
