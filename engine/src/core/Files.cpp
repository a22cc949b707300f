#include <sierra/core/Files.h>

#include <sierra/core/Error.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sierra {
namespace {

// Eight hex digits unique within the process and very likely across processes,
// so two writers of the same path never share a temporary name.
std::string tempSuffix() {
    static std::atomic<uint64_t> counter{0};
    static const uint64_t base = [] {
        std::random_device device;
        return (uint64_t(device()) << 32) ^ uint64_t(device()) ^
               uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    }();
    uint64_t x = base + 0x9e3779b97f4a7c15ull * ++counter;
    x ^= x >> 31;
    char text[9];
    std::snprintf(text, sizeof text, "%08x", unsigned(x & 0xffffffffu));
    return text;
}

const char* fileKind(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "not a regular file";
}

// Closes a POSIX file descriptor on scope exit.
struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

std::string parentDirectory(const std::string& path) {
    std::string dir = std::filesystem::path(path).parent_path().string();
    return dir.empty() ? std::string(".") : dir;
}

// Refuses an existing target that is not a regular file (lstat: a symlink to a
// regular file is refused too, since rename would replace the link itself).
void checkTarget(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw Error(msg("cannot write ", path, ": it exists and is ", fileKind(st.st_mode),
                        ", not a regular file; remove it or choose another output path"));
}

}  // namespace

uint64_t regularFileSize(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
    if (!S_ISREG(st.st_mode))
        throw Error(msg("cannot open ", path, ": it is ", fileKind(st.st_mode),
                        "; expected a regular file"));
    return uint64_t(st.st_size);
}

std::vector<uint8_t> readFileBytes(const std::string& path, uint64_t maxBytes,
                                   std::string_view limitReason) {
    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever;
    // fstat then refuses it. Regular files ignore the flag.
    Fd file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0)
        throw Error(msg("cannot read ", path, ": ", std::strerror(errno)));
    if (!S_ISREG(st.st_mode))
        throw Error(msg("cannot open ", path, ": it is ", fileKind(st.st_mode),
                        "; expected a regular file"));
    const uint64_t size = uint64_t(st.st_size);
    if (size > maxBytes)
        throw Error(msg(path, " has ", size, " bytes, more than the ", maxBytes, " bytes allowed",
                        limitReason.empty() ? "" : "; ", limitReason));
    std::vector<uint8_t> bytes(size);
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(file.fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Error(msg("cannot read ", path, ": ", std::strerror(errno)));
        if (n == 0) break;  // shrank while reading: keep what is there
        done += size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

void writeFileAtomic(const std::string& path, const std::function<void(std::FILE*)>& write) {
    checkTarget(path);
    const std::string temp = path + ".tmp-" + tempSuffix();
    auto fail = [&](const char* what, int err) {
        std::remove(temp.c_str());
        throw Error(msg("cannot write ", path, ": ", what, " failed (", std::strerror(err),
                        "); check that the directory exists and is writable"));
    };
    // O_EXCL: never write through something another process put at the name.
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int err = errno;
        throw Error(msg("cannot write ", path, ": creating the temporary file failed (",
                        std::strerror(err), "); check that the directory exists and is writable"));
    }
    std::FILE* file = ::fdopen(fd, "wb");
    if (!file) {
        const int err = errno;
        ::close(fd);
        fail("opening the temporary file", err);
    }
    try {
        write(file);
    } catch (...) {
        std::fclose(file);
        std::remove(temp.c_str());
        throw;
    }
    bool writeOk = std::fflush(file) == 0 && std::ferror(file) == 0;
    int writeErr = errno;
    // The data must be on disk before the rename makes it visible, or a crash
    // could leave the new name pointing at an empty file.
    bool syncOk = writeOk && ::fsync(::fileno(file)) == 0;
    int syncErr = errno;
    bool closedOk = std::fclose(file) == 0;
    if (!writeOk) fail("writing", writeErr);
    if (!syncOk) fail("flushing to disk (fsync)", syncErr);
    if (!closedOk) fail("closing", errno);
    // Checked again right before the rename: the target may have appeared meanwhile.
    try {
        checkTarget(path);
    } catch (...) {
        std::remove(temp.c_str());
        throw;
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) fail("renaming the temporary file", errno);
    // The rename itself lives in the directory: sync it so it survives a crash.
    // A directory that cannot be opened or synced (some network file systems)
    // leaves the file complete, so this is best effort.
    Fd dir{::open(parentDirectory(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
    if (dir.fd >= 0) ::fsync(dir.fd);
}

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes) {
    writeFileAtomic(path, [&](std::FILE* file) {
        if (!bytes.empty()) std::fwrite(bytes.data(), 1, bytes.size(), file);
    });
}

void writeFileAtomic(const std::string& path, std::string_view text) {
    writeFileAtomic(path, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

void ensureWritableLocation(const std::string& path) {
    SIERRA_CHECK(!path.empty(), "ensureWritableLocation: empty output path");
    const std::string dir = parentDirectory(path);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
        throw Error(msg("cannot write ", path, ": cannot create the directory ", dir, " (",
                        ec.message(), ")"));
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        throw Error(msg("cannot write ", path, ": ", dir, ": ", std::strerror(errno)));
    if (!S_ISDIR(st.st_mode))
        throw Error(msg("cannot write ", path, ": ", dir, " is ", fileKind(st.st_mode),
                        ", not a directory"));
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw Error(msg("cannot write ", path, ": the directory ", dir, " is not writable (",
                        std::strerror(errno), ")"));
    checkTarget(path);
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace sierra
