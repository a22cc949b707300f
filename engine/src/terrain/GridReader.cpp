// Window readers of GridReader.h: memory-mapped raw and .npy files, a
// heightfield in memory, and (GridReaderGdal.cpp) anything GDAL reads.
#include <sierra/terrain/GridReader.h>
#include <sierra/terrain/HeightfieldIO.h>

#include "HeightfieldLoaders.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace sierra::terrain {
namespace detail {
#ifdef SIERRA_WITH_GDAL
std::unique_ptr<GridReader> openGdalGridReader(std::span<const std::string> paths);
#endif
}  // namespace detail

namespace {

// A read-only map of a whole file. Pages are read in as the reader touches
// them and are the kernel's to drop: a build streams through a file many times
// its memory.
class MappedFile {
  public:
    explicit MappedFile(const std::string& path) : path_(path) {
        size_ = regularFileSize(path);
        if (size_ == 0) throw Error(msg(path, ": the file is empty"));
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) throw Error(msg("cannot open ", path, ": ", std::strerror(errno)));
        void* p = ::mmap(nullptr, size_, PROT_READ, MAP_SHARED, fd, 0);
        const int err = errno;
        ::close(fd);
        if (p == MAP_FAILED) throw Error(msg("cannot map ", path, ": ", std::strerror(err)));
        data_ = static_cast<const uint8_t*>(p);
        ::madvise(p, size_, MADV_SEQUENTIAL);
    }
    ~MappedFile() { ::munmap(const_cast<uint8_t*>(data_), size_); }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    const uint8_t* data() const { return data_; }
    uint64_t size() const { return size_; }
    // Drops the pages of bytes [0, end) from this process (they stay in the
    // page cache, readable again at a fault's cost).
    void release(uint64_t end) const {
        const uint64_t page = uint64_t(::sysconf(_SC_PAGESIZE));
        end = std::min(end, size_) / page * page;
        if (end > 0) ::madvise(const_cast<uint8_t*>(data_), end, MADV_DONTNEED);
    }
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    const uint8_t* data_ = nullptr;
    uint64_t size_ = 0;
};

// Row-major values of one numeric type in a mapped file.
class MappedGridReader : public GridReader {
  public:
    MappedGridReader(std::unique_ptr<MappedFile> file, uint64_t dataStart, std::string descr,
                     int64_t width, int64_t height)
        : file_(std::move(file)), start_(dataStart), descr_(std::move(descr)) {
        info_.width = width;
        info_.height = height;
        if (descr_ == "<u2") info_.int16Offset = 32768.0;
        if (descr_ == "<i2" || (descr_[1] == 'u' && descr_[2] == '1')) info_.int16Offset = 0.0;
        const uint64_t need = uint64_t(width) * uint64_t(height) * valueBytes();
        if (file_->size() < start_ || file_->size() - start_ < need)
            throw Error(msg(file_->path(), ": truncated: ", width, "x", height, " ", descr_,
                            " samples need ", need, " bytes, the file has ",
                            file_->size() - std::min(file_->size(), start_)));
    }

    void read(int64_t x0, int64_t y0, int w, int h, float* heights, uint8_t* valid) const override {
        const uint8_t* base = file_->data() + start_;
        const bool isFloat = descr_[1] == 'f';
        for (int y = 0; y < h; ++y) {
            const size_t row = size_t(y0 + y) * size_t(info_.width) + size_t(x0);
            float* out = heights + size_t(y) * w;
            if (descr_ == "<u2") {  // the common raw DEM: one conversion a sample
                const uint8_t* p = base + 2 * row;
                for (int x = 0; x < w; ++x)
                    out[x] = float(uint16_t(p[2 * x] | (p[2 * x + 1] << 8)));
                if (valid) std::memset(valid + size_t(y) * w, 1, size_t(w));
                continue;
            }
            for (int x = 0; x < w; ++x) {
                const float v = float(detail::npyNumber(descr_, base, row + size_t(x)));
                if (isFloat && !std::isfinite(v))
                    throw Error(msg(file_->path(), ": sample (", x0 + x, ", ", y0 + y, ") is ", v,
                                    "; heights must be finite"));
                out[x] = v;
            }
            if (valid) std::memset(valid + size_t(y) * w, 1, size_t(w));
        }
    }

    void releaseRowsBefore(int64_t row) const override {
        if (row > 0) file_->release(start_ + uint64_t(row) * uint64_t(info_.width) * valueBytes());
    }

  private:
    uint64_t valueBytes() const { return uint64_t(descr_[2] - '0'); }
    std::unique_ptr<MappedFile> file_;
    uint64_t start_;
    std::string descr_;
};

class MemoryGridReader : public GridReader {
  public:
    // Reads `field`, kept by reference, or `owned` when given (then field is it).
    explicit MemoryGridReader(const Heightfield& field, std::unique_ptr<Heightfield> owned = {})
        : owned_(std::move(owned)), field_(owned_ ? *owned_ : field) {
        info_.width = field.width();
        info_.height = field.height();
        info_.spacingX = field.spacingX();
        info_.spacingZ = field.spacingZ();
        info_.metres = field.metres();
        info_.hasNoData = field.hasMask();
        info_.geoCentre = field.geoCentre();
        info_.georeference = field.georeference();
    }
    void read(int64_t x0, int64_t y0, int w, int h, float* heights, uint8_t* valid) const override {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                heights[size_t(y) * w + x] = field_.at(int(x0 + x), int(y0 + y));
                if (valid) valid[size_t(y) * w + x] = field_.valid(int(x0 + x), int(y0 + y));
            }
    }

  private:
    std::unique_ptr<Heightfield> owned_;
    const Heightfield& field_;
};

std::unique_ptr<GridReader> openRaw(const std::string& path, const std::string& ext,
                                    const GridReaderOptions& options) {
    auto file = std::make_unique<MappedFile>(path);
    const uint64_t bytes = ext == ".r16" ? 2 : 4;
    int64_t width = options.rawWidth, height = options.rawHeight;
    if ((width == 0) != (height == 0))
        throw Error(msg(path, ": give both the raw width and height, or neither"));
    if (width == 0) {
        if (file->size() % bytes != 0)
            throw Error(msg(path, ": ", file->size(), " bytes is not a whole number of ", bytes,
                            "-byte samples"));
        const uint64_t samples = file->size() / bytes;
        const int64_t side = int64_t(std::llround(std::sqrt(double(samples))));
        if (uint64_t(side) * uint64_t(side) != samples)
            throw Error(msg(path, ": ", samples,
                            " samples is not a square; give the raw size (--raw-size WxH)"));
        width = height = side;
    }
    if (width < 2 || height < 2)
        throw Error(msg(path, ": a ", width, "x", height, " grid is too small (at least 2x2)"));
    if (uint64_t(width) * uint64_t(height) * bytes != file->size())
        throw Error(msg(path, ": ", width, "x", height, " samples of ", bytes, " bytes need ",
                        uint64_t(width) * uint64_t(height) * bytes, " bytes, the file has ",
                        file->size()));
    return std::make_unique<MappedGridReader>(std::move(file), 0, ext == ".r16" ? "<u2" : "<f4",
                                              width, height);
}

std::unique_ptr<GridReader> openNpy(const std::string& path) {
    auto file = std::make_unique<MappedFile>(path);
    const detail::NpyHeader h =
        detail::parseNpyHeader(path, std::span(file->data(), file->size()),
                               {"<f4", "<f8", "<i2", "<u2", "<i4", "<u4", "|u1", "<u1"});
    if (h.shape.size() != 2)
        throw Error(msg(path, ": .npy array has shape (", h.dims,
                        "); expected a 2-D array (rows, columns)"));
    const int64_t height = int64_t(h.shape[0]), width = int64_t(h.shape[1]);
    if (width < 2 || height < 2)
        throw Error(msg(path, ": a ", width, "x", height, " grid is too small (at least 2x2)"));
    return std::make_unique<MappedGridReader>(std::move(file), h.dataStart, h.descr, width, height);
}

}  // namespace

std::unique_ptr<GridReader> openGridReader(std::span<const std::string> paths,
                                           const GridReaderOptions& options) {
    if (paths.empty()) throw Error("no input: give a heightmap file (or several to mosaic)");
    const std::string ext = lowerExtension(paths[0]);
    const bool mapped = ext == ".r16" || ext == ".r32" || ext == ".npy";
    // Formats that are small by nature (images, .npz archives) are loaded
    // whole by the heightfield loaders, georeference and mask included.
    if (ext == ".npz" || ext == ".png" || ext == ".pgm") {
        if (paths.size() != 1)
            throw Error(
                msg("only GDAL inputs mosaic; ", paths[0], " is a ", ext, " file: give it alone"));
        auto field =
            std::make_unique<Heightfield>(loadHeightfield(paths[0], {.maxPaddedSide = kMaxSide}));
        const Heightfield& ref = *field;
        return std::make_unique<MemoryGridReader>(ref, std::move(field));
    }
    if (mapped) {
        if (paths.size() != 1)
            throw Error(
                msg("only GDAL inputs mosaic; ", paths[0], " is a ", ext, " file: give it alone"));
        return ext == ".npy" ? openNpy(paths[0]) : openRaw(paths[0], ext, options);
    }
#ifdef SIERRA_WITH_GDAL
    return detail::openGdalGridReader(paths);
#else
    throw Error(msg(paths[0], ": this build has no GDAL; give a .r16, .r32 or .npy file"));
#endif
}

std::unique_ptr<GridReader> memoryGridReader(const Heightfield& field) {
    return std::make_unique<MemoryGridReader>(field);
}

}  // namespace sierra::terrain
