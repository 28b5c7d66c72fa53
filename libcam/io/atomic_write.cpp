#include "libcam/io/atomic_write.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <random>
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
    sync_folder(path.has_parent_path() ? path.parent_path() : ".");
}

void sync_folder(const std::filesystem::path& folder) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throw FileError(folder.string() + ": cannot open the folder to flush it: " + reason());
    // Some file systems (and /proc-like ones) cannot flush a folder: the file is in place
    // all the same, only its survival of a power cut is not promised there.
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
        const std::string why = reason();
        ::close(fd);
        throw FileError(folder.string() + ": cannot flush the folder to disk: " + why);
    }
    ::close(fd);
}

std::string byte_size_text(std::uint64_t bytes) {
    if (bytes != 0 && bytes % kGiB == 0) return std::to_string(bytes / kGiB) + " GiB";
    if (bytes != 0 && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
    if (bytes != 0 && bytes % 1024 == 0) return std::to_string(bytes / 1024) + " KiB";
    return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
}

namespace {

// Closes the descriptor it holds when it goes.
struct OpenFile {
    int fd = -1;
    ~OpenFile() {
        if (fd >= 0) ::close(fd);
    }
};

// What a path that is no regular file or FIFO is, in words, with where it leads.
std::string not_a_file(const std::filesystem::path& path, const struct stat& status) {
    const std::string kind = S_ISCHR(status.st_mode) || S_ISBLK(status.st_mode) ? "a device" : "a socket";
    std::error_code error;
    const std::filesystem::path target = std::filesystem::canonical(path, error);
    const std::string where = !error && target != path ? " (" + target.string() + ")" : "";
    return path.string() + ": " + kind + where + ", not a file: libcam reads camera files from files and pipes";
}

}  // namespace

bool regular_file_exists(const std::filesystem::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0) return S_ISREG(status.st_mode);
    if (errno == ENOENT || errno == ENOTDIR) return false;
    throw FileError(path.string() + ": " + reason());
}

void throw_larger_than(const std::filesystem::path& path, const ReadLimit& limit) {
    throw FileError(path.string() + ": larger than " + byte_size_text(limit.max_bytes) +
                    ", more than libcam reads of any " + std::string(limit.kind) + " file");
}

std::string read_text_file(const std::filesystem::path& path, const ReadLimit& limit) {
    const std::string name = path.string();
    // Not blocking on open: a FIFO no process writes to reads as empty, not as a hang.
    OpenFile file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
    if (file.fd < 0) throw FileError(name + ": cannot open: " + reason());
    struct stat status {};
    if (::fstat(file.fd, &status) != 0) throw FileError(name + ": cannot read: " + reason());
    if (S_ISDIR(status.st_mode)) throw FileError(name + ": is a directory");
    if (!S_ISREG(status.st_mode) && !S_ISFIFO(status.st_mode)) throw FileError(not_a_file(path, status));
    // A file's size refuses it before any read; /proc's files say 0 and a FIFO has
    // none, so the reads stop one byte past the limit whatever the size said.
    if (S_ISREG(status.st_mode) && static_cast<std::uint64_t>(status.st_size) > limit.max_bytes) {
        throw_larger_than(path, limit);
    }
    const int flags = ::fcntl(file.fd, F_GETFL);
    if (flags < 0 || ::fcntl(file.fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        throw FileError(name + ": cannot read: " + reason());
    }
    std::string text;
    // Room for the file and the one byte more whose read says it ended (or that it is
    // past the limit), so that a file read whole is never copied to grow the string.
    const auto size = static_cast<std::uint64_t>(status.st_size);
    text.reserve(static_cast<std::size_t>(std::min(size, limit.max_bytes) + 1));
    constexpr std::size_t kChunk = 1 << 20;
    while (true) {
        const std::size_t at = text.size();
        std::uint64_t want = std::min<std::uint64_t>(kChunk, limit.max_bytes + 1 - at);
        if (text.capacity() > at) want = std::min<std::uint64_t>(want, text.capacity() - at);
        text.resize(at + static_cast<std::size_t>(want));
        const ssize_t got = ::read(file.fd, text.data() + at, static_cast<std::size_t>(want));
        if (got < 0 && errno == EINTR) {
            text.resize(at);
            continue;
        }
        if (got < 0) throw FileError(name + ": read failed: " + reason());
        text.resize(at + static_cast<std::size_t>(got));
        if (got == 0) return text;
        if (text.size() > limit.max_bytes) throw_larger_than(path, limit);
    }
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
