#pragma once
// Frames to a video file through FFmpeg's libraries (libavcodec, libavformat,
// libswscale): H.264, HEVC, AV1 and VP9 in yuv420p, or GIF with a palette.
//
//   render::VideoEncoder video({.path = "fly.mp4", .width = 1920, .height = 1080});
//   for (...) video.write(frame);  // gpu::Image, RGBA8, top row first
//   video.finish();                // flushes, writes the trailer, renames
//
// The file is written to "PATH.tmp-XXXXXX" beside PATH and renamed by
// finish(), so a reader never sees half a video; on an error, or a destructor
// without finish(), the temporary file is removed. finish() after fewer frames
// than planned (a run that was stopped) gives a complete, playable file.
// Frames run from pts 0 whatever their index in a longer sequence, so the
// segments of a sequence's slices join with `ffmpeg -f concat -c copy`.

#include <sierra/gpu/ReadBack.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sierra::render {

struct VideoDesc {
    std::string path;  // .mp4, .mov, .mkv, .webm or .gif (the container follows the extension)
    int width = 0;     // frame size in pixels; yuv420p codecs need both even
    int height = 0;
    int fps = 30;  // frames per second, 1..1000 (GIF: delays are whole centiseconds)
    // "" = by container: H.264 for mp4/mov/mkv, VP9 for webm, GIF for gif.
    // h264, hevc, av1, vp9, gif, or an encoder by name: libx264, libx265,
    // libsvtav1, libaom-av1, libvpx-vp9, h264_nvenc, hevc_nvenc, av1_nvenc,
    // or libopenh264, libkvazaar, librav1e where libavcodec has them.
    std::string codec;
    // Constant quality; -1 = the codec's default (libx264 23, libx265 28,
    // libvpx-vp9 31, libsvtav1 35, libaom-av1 30, NVENC cq 23). Lower is better.
    int crf = -1;
    int64_t bitrate = 0;  // bits per second, average; 0 = none (constant quality). Not with crf.
    // The encoder's speed preset; "" = Sierra's default: "veryfast" for
    // libx264/libx265, 8 for libsvtav1, "p4" for NVENC, the library's for the rest.
    std::string preset;
    // The EGL device is NVIDIA's: h264, hevc and av1, asked for by family name or
    // by container default, use NVENC when libavcodec offers it and it opens,
    // else the software encoder (without a message).
    bool preferNvenc = false;
};

// The encoders of VideoDesc::codec's names that this libavcodec has, e.g.
// "libx264, libvpx-vp9, gif" (for error messages).
std::string availableVideoEncoders();

// Checks what VideoEncoder(desc) checks before it opens anything (the
// container, codec, encoder, rate, quality and size), with the same errors:
// a program calls it with its options, before any work.
void checkVideo(const VideoDesc& desc);

class VideoEncoder {
  public:
    // Opens the encoder and the temporary file. Throws sierra::Error for an
    // unknown codec, a codec this libavcodec lacks ("libavcodec here has no
    // encoder libx265; available: ..."), a codec the container cannot hold,
    // fps out of range, crf with bitrate, or an odd size for yuv420p (naming
    // the nearest even size).
    explicit VideoEncoder(const VideoDesc& desc);
    ~VideoEncoder();  // finishes nothing: removes the temporary file unless finish() ran
    VideoEncoder(VideoEncoder&&) noexcept;
    VideoEncoder& operator=(VideoEncoder&&) noexcept;
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    // Encodes the next frame (RGBA8 of the desc's size, top row first; alpha
    // is ignored). Throws sierra::Error on a wrong size or an encoder error.
    void write(const gpu::Image& rgba);
    // Drains the encoder, writes the trailer and renames the file into place.
    // Throws sierra::Error on failure (the temporary file is then removed).
    // At most once; write() after it throws.
    void finish();

    const std::string& encoderName() const;  // "libx264", "h264_nvenc", ...
    int framesWritten() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace sierra::render
