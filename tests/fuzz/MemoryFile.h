#pragma once
// What the fuzz targets that read a path share. One in-memory file (memfd_create) that a fuzz
// target refills with each input and hands to a reader that takes a path, through /proc/self/fd: no
// disk traffic per run.

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace sierra::fuzz {

struct MemoryFile {
    explicit MemoryFile(const char* name) : fd(::memfd_create(name, MFD_CLOEXEC)) {}
    ~MemoryFile() { ::close(fd); }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;

    // The file's contents become `data`; a failure is a finding (trap).
    void fill(const uint8_t* data, size_t size) {
        if (fd < 0 || ::ftruncate(fd, 0) != 0) __builtin_trap();
        for (size_t done = 0; done < size;) {
            const ssize_t n = ::pwrite(fd, data + done, size - done, off_t(done));
            if (n <= 0) __builtin_trap();
            done += size_t(n);
        }
    }

    int fd;
    std::string path = "/proc/self/fd/" + std::to_string(fd);
};

// WGS 84 as WKT: the reference system of the georeferenced grid the drape
// and vector targets place their inputs on (10 E, 47 N, 0.01 degrees a sample,
// where their seeds lie).
inline constexpr const char* kWgs84 =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
    "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433],AUTHORITY[\"EPSG\",\"4326\"]]";

}  // namespace sierra::fuzz
