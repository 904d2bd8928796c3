// Bounded reads of regular files (see InputFile.h).
#include "io/InputFile.h"

#include <preskin/Error.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace preskin::io {

namespace {

[[noreturn]] void fail(const std::string& label, const std::string& problem) {
    throw Error(label + ": file: " + problem);
}

// Refuses anything but a regular file of at most maxBytes; returns its size.
uint64_t checkStat(const struct stat& st, const std::string& label, uint64_t maxBytes) {
    if (S_ISDIR(st.st_mode)) fail(label, "is a folder, not a file");
    if (S_ISFIFO(st.st_mode)) fail(label, "is a FIFO (named pipe), not a regular file");
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) fail(label, "is a device, not a regular file");
    if (S_ISSOCK(st.st_mode)) fail(label, "is a socket, not a regular file");
    if (!S_ISREG(st.st_mode)) fail(label, "is not a regular file");
    const auto size = static_cast<uint64_t>(st.st_size);
    if (size > maxBytes) {
        fail(label, std::to_string(size) + " bytes exceeds the limit of " + std::to_string(maxBytes) + " bytes");
    }
    return size;
}

uint64_t statPath(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == ENOENT || errno == ENOTDIR) {
            std::error_code ec;
            const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
            fail(label,
                 path.is_relative() && !ec ? "not found (looked for " + absolute.lexically_normal().string() + ")"
                                           : std::string("not found"));
        }
        fail(label, std::string("cannot read: ") + std::strerror(errno));
    }
    return checkStat(st, label, maxBytes);
}

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

}  // namespace

uint64_t checkInputFile(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes) {
    return statPath(path, label, maxBytes);
}

std::vector<uint8_t> readInputFile(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes) {
    return readInputFileStart(path, label, maxBytes, UINT64_MAX);
}

std::vector<uint8_t> readInputFileStart(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes,
                                        uint64_t count) {
    // stat first, so that nothing but a regular file is ever opened (opening a device can act);
    // O_NONBLOCK keeps a FIFO swapped in meanwhile from blocking the open; fstat checks again.
    statPath(path, label, maxBytes);
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) fail(label, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0) fail(label, std::string("cannot read: ") + std::strerror(errno));
    const uint64_t size = checkStat(st, label, maxBytes);
    const bool whole = count >= size;

    std::vector<uint8_t> bytes(static_cast<size_t>(whole ? size : count));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd.get(), bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(label, std::string("cannot read: ") + std::strerror(errno));
        if (n == 0) fail(label, "shrank while it was read");
        done += static_cast<size_t>(n);
    }
    if (!whole) return bytes;
    uint8_t extra = 0;
    ssize_t n = 0;
    do {
        n = ::read(fd.get(), &extra, 1);
    } while (n < 0 && errno == EINTR);
    if (n > 0) fail(label, "grew while it was read");
    return bytes;
}

}  // namespace preskin::io
