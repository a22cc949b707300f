#include <sierra/core/Files.h>

#include <sierra/core/Error.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>

namespace sierra {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

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

}  // namespace

std::vector<uint8_t> readFileBytes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(msg("cannot open ", path, ": Is a directory; expected a file"));
    FilePtr file(std::fopen(path.c_str(), "rb"));
    if (!file) throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
    std::vector<uint8_t> bytes;
    std::array<uint8_t, 1 << 16> buffer;
    for (;;) {
        size_t n = std::fread(buffer.data(), 1, buffer.size(), file.get());
        bytes.insert(bytes.end(), buffer.data(), buffer.data() + n);
        if (n < buffer.size()) break;
    }
    if (std::ferror(file.get())) throw Error(msg("cannot read ", path, ": ", std::strerror(errno)));
    return bytes;
}

void writeFileAtomic(const std::string& path, const std::function<void(std::FILE*)>& write) {
    const std::string temp = path + ".tmp-" + tempSuffix();
    auto fail = [&](const char* what, int err) {
        std::remove(temp.c_str());
        throw Error(msg("cannot write ", path, ": ", what, " failed (", std::strerror(err),
                        "); check that the directory exists and is writable"));
    };
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) fail("creating the temporary file", errno);
    try {
        write(file);
    } catch (...) {
        std::fclose(file);
        std::remove(temp.c_str());
        throw;
    }
    bool writeOk = std::ferror(file) == 0;
    int writeErr = errno;
    bool closedOk = std::fclose(file) == 0;
    if (!writeOk) fail("writing", writeErr);
    if (!closedOk) fail("closing", errno);
    if (std::rename(temp.c_str(), path.c_str()) != 0) fail("renaming the temporary file", errno);
}

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes) {
    writeFileAtomic(path, [&](std::FILE* file) {
        if (!bytes.empty()) std::fwrite(bytes.data(), 1, bytes.size(), file);
    });
}

void writeFileAtomic(const std::string& path, std::string_view text) {
    writeFileAtomic(path, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace sierra
