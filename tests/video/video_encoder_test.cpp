// render::VideoEncoder: synthetic frames encoded to mp4, webm and gif, then
// decoded again with libavformat and libavcodec: the codec, size, frame count
// and rate are those asked for, and the pictures are the frames given.
// No GL context is needed.

#include <sierra/render/Capture.h>
#include <sierra/render/Video.h>

#include "../unit/temp_dir_test_util.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace sierra::render {
namespace {

using VideoEncoderTest = test::TempDirTest;

// Frame k of a smooth moving scene: gradients and a soft disc travelling
// right, the kind of picture a terrain render is (no noise).
gpu::Image syntheticFrame(int width, int height, int k) {
    gpu::Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
    const double cx = width * (0.2 + 0.02 * k), cy = height * 0.5, r = height * 0.3;
    const double edge = height / 8.0;  // a soft edge: chroma is sampled at half resolution
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double d = std::hypot(x - cx, y - cy);
            const double disc = std::clamp((r - d) / edge, 0.0, 1.0);
            uint8_t* p = &image.rgba[(size_t(y) * width + x) * 4];
            p[0] = uint8_t(std::lround(40 + 150.0 * x / width * (1 - disc) + 200 * disc));
            p[1] = uint8_t(std::lround(90 + 120.0 * y / height * (1 - disc) + 120 * disc));
            p[2] = uint8_t(std::lround(200 - 100.0 * y / height * (1 - disc) + 30 * disc));
            p[3] = 255;
        }
    return image;
}

// What a decoder finds in a video file.
struct Decoded {
    std::string codec;
    int width = 0, height = 0;
    double fps = 0.0;                // the stream's average frame rate
    double seconds = 0.0;            // the last frame's end
    std::vector<gpu::Image> frames;  // RGBA, BT.709 limited range taken back to RGB
};

Decoded decode(const std::string& path) {
    Decoded out;
    AVFormatContext* format = nullptr;
    if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0)
        throw Error("cannot open " + path);
    avformat_find_stream_info(format, nullptr);
    const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    EXPECT_GE(index, 0);
    const AVStream* stream = format->streams[index];
    const AVCodec* codec = avcodec_find_decoder(stream->codecpar->codec_id);
    AVCodecContext* context = avcodec_alloc_context3(codec);
    avcodec_parameters_to_context(context, stream->codecpar);
    avcodec_open2(context, codec, nullptr);
    out.codec = avcodec_get_name(stream->codecpar->codec_id);
    out.width = stream->codecpar->width;
    out.height = stream->codecpar->height;
    out.fps = av_q2d(stream->avg_frame_rate);
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    SwsContext* scale = nullptr;
    int64_t end = 0;
    auto receive = [&] {
        while (avcodec_receive_frame(context, frame) == 0) {
            if (!scale) {
                scale = sws_getContext(frame->width, frame->height, AVPixelFormat(frame->format),
                                       frame->width, frame->height, AV_PIX_FMT_RGBA,
                                       SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
                if (frame->format == AV_PIX_FMT_YUV420P)
                    sws_setColorspaceDetails(scale, sws_getCoefficients(SWS_CS_ITU709), 0,
                                             sws_getCoefficients(SWS_CS_DEFAULT), 1, 0, 1 << 16,
                                             1 << 16);
            }
            gpu::Image image{frame->width, frame->height,
                             std::vector<uint8_t>(size_t(frame->width) * frame->height * 4)};
            uint8_t* dst[1] = {image.rgba.data()};
            const int stride[1] = {image.width * 4};
            sws_scale(scale, frame->data, frame->linesize, 0, frame->height, dst, stride);
            out.frames.push_back(std::move(image));
        }
    };
    while (av_read_frame(format, packet) >= 0) {
        if (packet->stream_index == index) {
            end = std::max(end, packet->pts + packet->duration);
            avcodec_send_packet(context, packet);
            receive();
        }
        av_packet_unref(packet);
    }
    avcodec_send_packet(context, nullptr);
    receive();
    out.seconds = double(end) * av_q2d(stream->time_base);
    sws_freeContext(scale);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&context);
    avformat_close_input(&format);
    return out;
}

// Encodes `count` synthetic frames; returns the encoder's name.
std::string encode(const VideoDesc& desc, int count) {
    VideoEncoder video(desc);
    for (int k = 0; k < count; ++k) video.write(syntheticFrame(desc.width, desc.height, k));
    EXPECT_EQ(video.framesWritten(), count);
    video.finish();
    return video.encoderName();
}

// No "NAME.tmp-*" beside the output.
bool noTemporaryFiles(const std::filesystem::path& dir) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return false;
    return true;
}

struct Case {
    const char* name;
    const char* codec;     // as the decoder names it
    double minPsnr;        // dB, decoded against the frames given
    const char* ask = "";  // VideoDesc::codec; "" = the container's default
};

class VideoContainerTest : public VideoEncoderTest, public ::testing::WithParamInterface<Case> {};

TEST_P(VideoContainerTest, DecodesToTheFramesGiven) {
    const Case& c = GetParam();
    const std::string file = path(c.name);
    const int width = 160, height = 96, frames = 30;
    encode({.path = file, .width = width, .height = height, .fps = 30, .codec = c.ask}, frames);
    const Decoded d = decode(file);
    EXPECT_EQ(d.codec, c.codec);
    EXPECT_EQ(d.width, width);
    EXPECT_EQ(d.height, height);
    ASSERT_EQ(int(d.frames.size()), frames);
    // GIF delays are whole centiseconds (3 or 4 at 30 fps): their mean is the rate.
    EXPECT_NEAR(d.seconds, 1.0, 0.02) << "30 frames at 30 fps";
    if (std::string(c.codec) != "gif") {
        EXPECT_NEAR(d.fps, 30.0, 1e-6);
    }
    for (int k : {0, frames / 2, frames - 1}) {
        const ImageDifference diff =
            compareImages(d.frames[size_t(k)], syntheticFrame(width, height, k));
        EXPECT_GE(diff.psnr, c.minPsnr) << "frame " << k;
    }
    EXPECT_TRUE(noTemporaryFiles(dir_));
}

INSTANTIATE_TEST_SUITE_P(
    Containers, VideoContainerTest,
    ::testing::Values(Case{"clip.mp4", "h264", 38.0}, Case{"clip.webm", "vp9", 36.0},
                      Case{"clip.mkv", "h264", 38.0}, Case{"clip.gif", "gif", 28.0},
                      Case{"hevc.mp4", "hevc", 38.0, "hevc"}, Case{"av1.webm", "av1", 36.0, "av1"}),
    [](const auto& info) {
        std::string n = info.param.name;
        n[n.find('.')] = '_';
        return n;
    });

TEST_F(VideoEncoderTest, FinishAfterFewerFramesGivesAPlayableFile) {
    // A run stopped early finishes with the frames so far.
    const std::string file = path("stopped.mp4");
    encode({.path = file, .width = 64, .height = 64, .fps = 24}, 7);
    const Decoded d = decode(file);
    EXPECT_EQ(d.frames.size(), 7u);
    EXPECT_NEAR(d.seconds, 7.0 / 24.0, 1e-3);
}

TEST_F(VideoEncoderTest, WithoutFinishNothingIsLeft) {
    const std::string file = path("abandoned.mp4");
    {
        VideoEncoder video({.path = file, .width = 64, .height = 64});
        video.write(syntheticFrame(64, 64, 0));
        EXPECT_FALSE(noTemporaryFiles(dir_)) << "the frames go to a temporary file";
    }
    EXPECT_FALSE(std::filesystem::exists(file));
    EXPECT_TRUE(noTemporaryFiles(dir_));
}

TEST_F(VideoEncoderTest, QualityAndRateOptionsReachTheEncoder) {
    // A lower crf keeps more; a bitrate bounds the size.
    auto size = [&](const VideoDesc& d) {
        encode(d, 30);
        return std::filesystem::file_size(d.path);
    };
    const auto fine = size({.path = path("fine.mp4"), .width = 160, .height = 96, .crf = 10});
    const auto coarse = size({.path = path("coarse.mp4"), .width = 160, .height = 96, .crf = 40});
    EXPECT_GT(fine, 2 * coarse);
    const auto low = size({.path = path("low.mp4"), .width = 160, .height = 96, .bitrate = 50000});
    // 50 kbit/s over 1 s is about 6 KB; rate control may overshoot a little.
    EXPECT_LT(low, 12000u);
}

TEST_F(VideoEncoderTest, BadDescriptionsAreRefusedWithClearErrors) {
    auto error = [&](const VideoDesc& d) { return errorOf([&] { VideoEncoder v(d); }, "none"); };
    const VideoDesc ok{.path = path("x.mp4"), .width = 64, .height = 64};
    auto with = [&](auto change) {
        VideoDesc d = ok;
        change(d);
        return error(d);
    };
    EXPECT_NE(with([](VideoDesc& d) { d.codec = "h263"; }).find("unknown video codec 'h263'"),
              std::string::npos);
    EXPECT_NE(with([](VideoDesc& d) { d.fps = 0; }).find("--fps 0"), std::string::npos);
    EXPECT_NE(with([](VideoDesc& d) { d.fps = -5; }).find("--fps -5"), std::string::npos);
    EXPECT_NE(with([](VideoDesc& d) {
                  d.crf = 20;
                  d.bitrate = 1000000;
              }).find("exclude each other"),
              std::string::npos);
    const std::string odd = with([](VideoDesc& d) {
        d.width = 161;
        d.height = 97;
    });
    EXPECT_NE(odd.find("even frame size"), std::string::npos) << odd;
    EXPECT_NE(odd.find("160x96"), std::string::npos) << odd;
    EXPECT_NE(with([&](VideoDesc& d) {
                  d.path = path("x.webm");
                  d.codec = "h264";
              }).find("WebM holds vp9 or av1 video, not h264"),
              std::string::npos);
    EXPECT_NE(with([&](VideoDesc& d) { d.path = path("x.avi"); }).find("expected a name ending"),
              std::string::npos);
    EXPECT_NE(with([](VideoDesc& d) { d.preset = "warp"; }).find("libx264"), std::string::npos);
    // A GIF has no rate control, and any size will do.
    EXPECT_NE(with([&](VideoDesc& d) {
                  d.path = path("x.gif");
                  d.crf = 10;
              }).find("gif takes neither --crf nor --bitrate"),
              std::string::npos);
    EXPECT_EQ(with([&](VideoDesc& d) {
                  d.path = path("odd.gif");
                  d.width = 33;
              }),
              "none");
    EXPECT_TRUE(noTemporaryFiles(dir_));
}

TEST_F(VideoEncoderTest, AnEncoderThisLibraryLacksIsNamed) {
    // The first of the encoders taken by name that this libavcodec lacks.
    const char* missing = nullptr;
    for (const char* name : {"libkvazaar", "libopenh264", "av1_nvenc", "librav1e"})
        if (!missing && !avcodec_find_encoder_by_name(name)) missing = name;
    if (!missing) GTEST_SKIP() << "this libavcodec has every encoder Sierra names";
    const std::string e = errorOf([&] {
        VideoEncoder v({.path = path("x.mkv"), .width = 64, .height = 64, .codec = missing});
    });
    EXPECT_NE(e.find(std::string("libavcodec here has no encoder ") + missing), std::string::npos)
        << e;
    EXPECT_NE(e.find("available: "), std::string::npos) << e;
    EXPECT_NE(e.find(availableVideoEncoders()), std::string::npos) << e;
}

TEST_F(VideoEncoderTest, NvencFallsBackToSoftwareWhenItCannotOpen) {
    // preferNvenc on a machine whose NVENC cannot open: the software encoder,
    // silently. Where NVENC works the video is NVENC's; both are H.264.
    const std::string file = path("nvenc.mp4");
    const std::string name =
        encode({.path = file, .width = 160, .height = 96, .preferNvenc = true}, 10);
    EXPECT_TRUE(name == "libx264" || name == "h264_nvenc") << name;
    EXPECT_EQ(decode(file).frames.size(), 10u);
    EXPECT_EQ(decode(file).codec, "h264");
}

}  // namespace
}  // namespace sierra::render
