#include <sierra/render/Exr.h>

#include <sierra/core/Error.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <exception>

namespace sierra::render {

namespace {

// An EXR file built in memory, so writeFileAtomic puts it on disk whole.
class MemoryStream final : public Imf::OStream {
  public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        const size_t end = position_ + size_t(n);
        if (bytes_.size() < end) bytes_.resize(end);
        std::memcpy(bytes_.data() + position_, c, size_t(n));
        position_ = end;
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t pos) override { position_ = size_t(pos); }
    std::vector<uint8_t> take() { return std::move(bytes_); }

  private:
    std::vector<uint8_t> bytes_;
    size_t position_ = 0;
};

}  // namespace

std::vector<uint8_t> encodeExr(const ExrImage& image) {
    const size_t channels = image.channels.size();
    SIERRA_CHECK(image.width > 0 && image.height > 0 && channels > 0 &&
                     image.values.size() == size_t(image.width) * size_t(image.height) * channels,
                 "an EXR image of ", image.width, "x", image.height, " with ", channels,
                 " channels needs that many values, got ", image.values.size());
    const Imf::PixelType type = image.precision == ExrPrecision::Half ? Imf::HALF : Imf::FLOAT;
    // Half channels are converted from the floats first (OpenEXR reads each
    // channel in its own type from the frame buffer).
    std::vector<Imath::half> halves;
    if (type == Imf::HALF) {
        halves.resize(image.values.size());
        std::transform(image.values.begin(), image.values.end(), halves.begin(),
                       [](float v) { return Imath::half(v); });
    }
    try {
        Imf::Header header(image.width, image.height, 1.0f, Imath::V2f(0.0f, 0.0f), 1.0f,
                           Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
        Imf::FrameBuffer frame;
        const size_t pixelStride =
            channels * (type == Imf::HALF ? sizeof(Imath::half) : sizeof(float));
        for (size_t c = 0; c < channels; ++c) {
            header.channels().insert(image.channels[c], Imf::Channel(type));
            char* base =
                type == Imf::HALF
                    ? reinterpret_cast<char*>(halves.data() + c)
                    : const_cast<char*>(reinterpret_cast<const char*>(image.values.data() + c));
            frame.insert(image.channels[c],
                         Imf::Slice(type, base, pixelStride, pixelStride * size_t(image.width)));
        }
        MemoryStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        }
        return stream.take();
    } catch (const std::exception& e) {
        throw Error(
            msg("OpenEXR cannot encode a ", image.width, "x", image.height, " image: ", e.what()));
    }
}

ExrImage readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        ExrImage image;
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        const Imf::ChannelList& list = file.header().channels();
        for (auto it = list.begin(); it != list.end(); ++it) {
            if (image.channels.empty())
                image.precision =
                    it.channel().type == Imf::HALF ? ExrPrecision::Half : ExrPrecision::Float;
            image.channels.emplace_back(it.name());
        }
        const size_t channels = image.channels.size();
        image.values.resize(size_t(image.width) * size_t(image.height) * channels);
        Imf::FrameBuffer frame;
        const size_t pixelStride = channels * sizeof(float);
        // Slices address the data window's origin.
        char* origin = reinterpret_cast<char*>(image.values.data()) -
                       (ptrdiff_t(window.min.x) + ptrdiff_t(window.min.y) * image.width) *
                           ptrdiff_t(pixelStride);
        for (size_t c = 0; c < channels; ++c)
            frame.insert(image.channels[c],
                         Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), pixelStride,
                                    pixelStride * size_t(image.width)));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const std::exception& e) {
        throw Error(msg(path, ": OpenEXR cannot read it: ", e.what()));
    }
}

}  // namespace sierra::render
