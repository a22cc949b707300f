#include <sierra/render/Video.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include "render/VideoPalette.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

namespace sierra::render {
namespace {

// A codec family: its software encoders (the first found is used), its
// NVENC encoder, and other encoders FFmpeg builds may have, taken by name only.
struct Family {
    const char* name;
    std::vector<const char*> encoders;
    const char* nvenc;  // or null
    std::vector<const char*> others;
};
const Family kFamilies[] = {
    {"h264", {"libx264"}, "h264_nvenc", {"libopenh264"}},
    {"hevc", {"libx265"}, "hevc_nvenc", {"libkvazaar"}},
    {"av1", {"libsvtav1", "libaom-av1"}, "av1_nvenc", {"librav1e"}},
    {"vp9", {"libvpx-vp9"}, nullptr, {}},
    {"gif", {"gif"}, nullptr, {}},
};

struct Container {
    const char* extension;
    const char* muxer;                  // libavformat's name
    const char* label;                  // for messages
    std::vector<const char*> families;  // the first is the default
};
const Container kContainers[] = {
    {".mp4", "mp4", "MP4", {"h264", "hevc", "av1", "vp9"}},
    {".mov", "mov", "QuickTime (.mov)", {"h264", "hevc"}},
    {".mkv", "matroska", "Matroska (.mkv)", {"h264", "hevc", "av1", "vp9"}},
    {".webm", "webm", "WebM", {"vp9", "av1"}},
    {".gif", "gif", "GIF", {"gif"}},
};

const Container* containerOf(const std::string& path) {
    const std::string ext = lowerExtension(path);
    for (const Container& c : kContainers)
        if (ext == c.extension) return &c;
    return nullptr;
}

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

std::string join(const std::vector<const char*>& names, const char* last = " or ") {
    std::string out;
    for (size_t k = 0; k < names.size(); ++k)
        out += msg(k == 0 ? "" : (k + 1 == names.size() ? last : ", "), names[k]);
    return out;
}

// What VideoDesc::codec names: a family, and the encoders to try in order.
struct Choice {
    const Family* family = nullptr;
    std::vector<const char*> encoders;
    bool fallback = false;  // the first (NVENC) may fail to open; the next is then used
};

Choice chooseEncoders(const VideoDesc& d, const Container& container) {
    Choice choice;
    const std::string name = d.codec.empty() ? container.families.front() : d.codec;
    for (const Family& f : kFamilies) {
        if (name == f.name) {
            choice.family = &f;
            if (d.preferNvenc && f.nvenc && avcodec_find_encoder_by_name(f.nvenc)) {
                choice.encoders.push_back(f.nvenc);
                choice.fallback = true;
            }
            choice.encoders.insert(choice.encoders.end(), f.encoders.begin(), f.encoders.end());
        }
        for (const auto* list : {&f.encoders, &f.others})
            for (const char* e : *list)
                if (name == e) choice = {&f, {e}};
        if (f.nvenc && name == f.nvenc) choice = {&f, {f.nvenc}};
    }
    if (!choice.family) {
        std::vector<const char*> names;
        for (const Family& f : kFamilies) names.push_back(f.name);
        throw Error(
            msg("unknown video codec '", d.codec, "' (--video-codec): expected ", join(names),
                ", or an encoder by name (available here: ", availableVideoEncoders(), ")"));
    }
    bool fits = false;
    for (const char* f : container.families)
        fits = fits || std::strcmp(f, choice.family->name) == 0;
    if (!fits)
        throw Error(msg(d.path, ": ", container.label, " holds ", join(container.families),
                        " video, not ", choice.family->name,
                        " (--video-codec); pick one of those or another container"));
    return choice;
}

const Container& containerOf(const VideoDesc& d) {
    const Container* container = containerOf(d.path);
    if (!container) {
        std::vector<const char*> extensions;
        for (const Container& c : kContainers) extensions.push_back(c.extension);
        throw Error(
            msg("cannot write video ", d.path, ": expected a name ending in ", join(extensions)));
    }
    return *container;
}

// Everything about `d` that can be told without opening anything: the
// encoders to try, of which at least the last is in this libavcodec.
Choice checked(const VideoDesc& d, const Container& container) {
    if (d.fps < 1 || d.fps > 1000)
        throw Error(msg("--fps ", d.fps, ": expected frames per second 1..1000"));
    if (d.crf >= 0 && d.bitrate > 0)
        throw Error("--crf and --bitrate exclude each other: give constant quality or a bitrate");
    if (d.crf < -1 || d.bitrate < 0)
        throw Error(msg("--crf ", d.crf, " / --bitrate ", d.bitrate,
                        ": expected crf >= 0 (or -1, the codec's default) and bitrate >= 0"));
    SIERRA_CHECK(d.width > 0 && d.height > 0, "video frame size ", d.width, "x", d.height,
                 " is empty");
    Choice choice = chooseEncoders(d, container);
    const bool gif = std::strcmp(choice.family->name, "gif") == 0;
    if (!gif && (d.width % 2 != 0 || d.height % 2 != 0)) {
        auto down = [](int v) { return std::max(2, v - v % 2); };
        auto up = [](int v) { return v + v % 2; };
        throw Error(msg(d.path, ": ", choice.family->name,
                        " video is yuv420p, which needs an even frame size, got ", d.width, "x",
                        d.height, "; use --size ", down(d.width), "x", down(d.height), " (or ",
                        up(d.width), "x", up(d.height), ")"));
    }
    std::vector<const char*> missing;
    for (const char* name : choice.encoders)
        if (!avcodec_find_encoder_by_name(name)) missing.push_back(name);
    if (missing.size() == choice.encoders.size())
        throw Error(msg("libavcodec here has no encoder ", join(missing), " for ",
                        choice.family->name, " video; available: ", availableVideoEncoders()));
    return choice;
}

// Sierra's defaults and the user's crf, bitrate and preset, as the options of `encoder`.
void encoderOptions(const std::string& encoder, const VideoDesc& d, AVCodecContext* c,
                    AVDictionary** options) {
    auto set = [&](const char* key, const std::string& value) {
        av_dict_set(options, key, value.c_str(), 0);
    };
    const bool nvenc = encoder.find("_nvenc") != std::string::npos;
    struct Defaults {
        const char* name;
        const char* quality;  // the constant-quality option
        int crf, maxCrf;
        const char* speed;  // the preset option
        const char* preset;
    };
    static const Defaults kDefaults[] = {
        {"libx264", "crf", 23, 51, "preset", "veryfast"},
        {"libx265", "crf", 28, 51, "preset", "veryfast"},
        {"libsvtav1", "crf", 35, 63, "preset", "8"},
        {"libaom-av1", "crf", 30, 63, "cpu-used", "6"},
        {"libvpx-vp9", "crf", 31, 63, "cpu-used", "4"},
        {"h264_nvenc", "cq", 23, 51, "preset", "p4"},
        {"hevc_nvenc", "cq", 23, 51, "preset", "p4"},
        {"av1_nvenc", "cq", 30, 63, "preset", "p4"},
    };
    const Defaults* k = nullptr;
    for (const Defaults& x : kDefaults)
        if (encoder == x.name) k = &x;
    if (encoder == "gif") {  // a palette, no rate control
        if (d.crf >= 0 || d.bitrate > 0)
            throw Error(msg(d.path, ": ", encoder, " takes neither --crf nor --bitrate"));
        if (!d.preset.empty()) throw Error(msg(d.path, ": ", encoder, " takes no --video-preset"));
        return;
    }
    if (!k) {  // another encoder by name: its own defaults; options it lacks are refused
        if (d.crf >= 0) set("crf", msg(d.crf));
        if (!d.preset.empty()) set("preset", d.preset);
        c->bit_rate = d.bitrate;
        return;
    }
    if (d.crf > k->maxCrf)
        throw Error(msg("--crf ", d.crf, " is out of ", encoder, "'s range 0..", k->maxCrf));
    set(k->speed, d.preset.empty() ? k->preset : d.preset);
    if (d.bitrate > 0) {
        c->bit_rate = d.bitrate;
    } else {
        set(k->quality, msg(d.crf >= 0 ? d.crf : k->crf));
        c->bit_rate = 0;  // libvpx and libaom: constant quality only without a target rate
    }
    if (nvenc && d.bitrate == 0) set("rc", "vbr");
    if (encoder == "libvpx-vp9" || encoder == "libaom-av1") set("row-mt", "1");
    if (encoder == "libx265") set("x265-params", "log-level=error");
}

// Files the encoder writes into; removed unless kept.
struct TempFile {
    std::string path;
    bool keep = false;
    ~TempFile() {
        if (!keep && !path.empty()) std::remove(path.c_str());
    }
};

}  // namespace

std::string availableVideoEncoders() {
    std::vector<const char*> names;
    for (const Family& f : kFamilies) {
        std::vector<const char*> all = f.encoders;
        if (f.nvenc) all.push_back(f.nvenc);
        all.insert(all.end(), f.others.begin(), f.others.end());
        for (const char* e : all)
            if (avcodec_find_encoder_by_name(e)) names.push_back(e);
    }
    return names.empty() ? std::string("none") : join(names, ", ");
}

struct VideoEncoder::State {
    VideoDesc desc;
    std::string encoder;
    TempFile temp;
    AVFormatContext* format = nullptr;
    AVCodecContext* codec = nullptr;
    AVStream* stream = nullptr;
    SwsContext* scale = nullptr;
    AVFrame* frame = nullptr;
    AVPacket* packet = nullptr;
    std::optional<detail::GifPalette> palette;
    int64_t next = 0;
    bool finished = false;

    ~State() {
        sws_freeContext(scale);
        av_frame_free(&frame);
        av_packet_free(&packet);
        avcodec_free_context(&codec);
        if (format) {
            avio_closep(&format->pb);
            avformat_free_context(format);
        }
    }

    [[noreturn]] void fail(const char* call, int code) const {
        throw Error(
            msg("cannot write video ", desc.path, ": ", call, " (", encoder, "): ", avError(code)));
    }

    void open(const Container& container);
    void openCodec(const Choice& choice);
    void drain();
};

void VideoEncoder::State::openCodec(const Choice& choice) {
    std::vector<const char*> missing;
    for (size_t k = 0; k < choice.encoders.size(); ++k) {
        const char* name = choice.encoders[k];
        const AVCodec* found = avcodec_find_encoder_by_name(name);
        if (!found) {
            missing.push_back(name);
            continue;
        }
        const bool gif = found->id == AV_CODEC_ID_GIF;
        const bool mayFail = choice.fallback && k + 1 < choice.encoders.size();
        avcodec_free_context(&codec);
        codec = avcodec_alloc_context3(found);
        if (!codec) throw Error(msg("cannot write video ", desc.path, ": out of memory"));
        codec->width = desc.width;
        codec->height = desc.height;
        codec->time_base = AVRational{1, desc.fps};
        codec->framerate = AVRational{desc.fps, 1};
        codec->pix_fmt = gif ? AV_PIX_FMT_PAL8 : AV_PIX_FMT_YUV420P;
        codec->thread_count = 0;  // the encoder's own choice from the cores
        if (!gif) {
            // Rendered frames are sRGB; tagged BT.709, limited range, as HD video is.
            codec->color_range = AVCOL_RANGE_MPEG;
            codec->colorspace = AVCOL_SPC_BT709;
            codec->color_primaries = AVCOL_PRI_BT709;
            codec->color_trc = AVCOL_TRC_BT709;
        }
        if (format->oformat->flags & AVFMT_GLOBALHEADER)
            codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
        encoder = name;
        AVDictionary* options = nullptr;
        encoderOptions(encoder, desc, codec, &options);
        // An NVENC session that cannot open (no NVIDIA driver, or a GPU without
        // NVENC such as the H100) reports it at error level: quiet, as the
        // software encoder takes over.
        const int level = av_log_get_level();
        if (mayFail) av_log_set_level(AV_LOG_QUIET);
        const int rc = avcodec_open2(codec, found, &options);
        if (mayFail) av_log_set_level(level);
        const AVDictionaryEntry* unused = av_dict_get(options, "", nullptr, AV_DICT_IGNORE_SUFFIX);
        const std::string unusedKey = unused ? unused->key : "";
        av_dict_free(&options);
        if (rc < 0 && mayFail) continue;
        if (rc < 0 && std::strstr(name, "_nvenc"))
            throw Error(msg("cannot write video ", desc.path, ": ", name, " does not open (",
                            avError(rc),
                            "): NVENC needs an NVIDIA GPU that has it and the NVIDIA driver; "
                            "--video-codec ",
                            choice.family->name, " falls back to software"));
        if (rc < 0) fail("avcodec_open2", rc);
        if (!unusedKey.empty())
            throw Error(msg("cannot write video ", desc.path, ": ", encoder, " has no option '",
                            unusedKey, "'"));
        return;
    }
    throw Error(msg("libavcodec here has no encoder ", join(missing), " for ", choice.family->name,
                    " video; available: ", availableVideoEncoders()));
}

void VideoEncoder::State::open(const Container& container) {
    const Choice choice = checked(desc, container);
    const bool gif = std::strcmp(choice.family->name, "gif") == 0;
    ensureWritableLocation(desc.path);
    // The temporary name keeps the directory, so the rename stays on one file system.
    std::string pattern = desc.path + ".tmp-XXXXXX";
    const int fd = mkstemp(pattern.data());
    if (fd < 0)
        throw Error(msg("cannot write video ", desc.path,
                        ": cannot create a temporary file: ", std::strerror(errno)));
    ::fchmod(fd, 0644);  // as every file Sierra writes (mkstemp makes it 0600)
    ::close(fd);
    temp.path = pattern;

    int rc = avformat_alloc_output_context2(&format, nullptr, container.muxer, temp.path.c_str());
    if (rc < 0 || !format) fail("avformat_alloc_output_context2", rc < 0 ? rc : AVERROR(ENOMEM));
    openCodec(choice);
    stream = avformat_new_stream(format, nullptr);
    if (!stream) fail("avformat_new_stream", AVERROR(ENOMEM));
    stream->time_base = codec->time_base;
    stream->avg_frame_rate = codec->framerate;
    if ((rc = avcodec_parameters_from_context(stream->codecpar, codec)) < 0)
        fail("avcodec_parameters_from_context", rc);
    if ((rc = avio_open(&format->pb, temp.path.c_str(), AVIO_FLAG_WRITE)) < 0)
        fail("avio_open", rc);
    if ((rc = avformat_write_header(format, nullptr)) < 0) fail("avformat_write_header", rc);

    frame = av_frame_alloc();
    packet = av_packet_alloc();
    if (!frame || !packet) fail("av_frame_alloc", AVERROR(ENOMEM));
    frame->format = codec->pix_fmt;
    frame->width = desc.width;
    frame->height = desc.height;
    if ((rc = av_frame_get_buffer(frame, 0)) < 0) fail("av_frame_get_buffer", rc);
    if (!gif) {
        // Same size, so only chroma is resampled; exact rounding keeps flat
        // colours flat.
        scale = sws_getContext(desc.width, desc.height, AV_PIX_FMT_RGBA, desc.width, desc.height,
                               AV_PIX_FMT_YUV420P, SWS_BILINEAR | SWS_ACCURATE_RND, nullptr,
                               nullptr, nullptr);
        if (!scale) fail("sws_getContext", AVERROR(EINVAL));
        sws_setColorspaceDetails(scale, sws_getCoefficients(SWS_CS_DEFAULT), 1,
                                 sws_getCoefficients(SWS_CS_ITU709), 0, 0, 1 << 16, 1 << 16);
    }
}

void VideoEncoder::State::drain() {
    for (;;) {
        int rc = avcodec_receive_packet(codec, packet);
        if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
        if (rc < 0) fail("avcodec_receive_packet", rc);
        // One frame each: the muxer then knows the last frame's duration too,
        // so a segment's length is its frame count and segments join exactly.
        if (packet->duration <= 0) packet->duration = 1;
        av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
        packet->stream_index = stream->index;
        rc = av_interleaved_write_frame(format, packet);
        av_packet_unref(packet);
        if (rc < 0) fail("av_interleaved_write_frame", rc);
    }
}

void checkVideo(const VideoDesc& desc) {
    checked(desc, containerOf(desc));
}

VideoEncoder::VideoEncoder(const VideoDesc& desc) : state_(std::make_unique<State>()) {
    // libavcodec's default level prints the encoders' banners and statistics
    // (libx264's "using cpu capabilities", its frame counts at the end):
    // warnings and errors only, unless the embedding program chose a level.
    if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_WARNING);
    state_->desc = desc;
    state_->open(containerOf(desc));
}

VideoEncoder::~VideoEncoder() = default;
VideoEncoder::VideoEncoder(VideoEncoder&&) noexcept = default;
VideoEncoder& VideoEncoder::operator=(VideoEncoder&&) noexcept = default;

void VideoEncoder::write(const gpu::Image& rgba) {
    State& s = *state_;
    SIERRA_CHECK(!s.finished, "video ", s.desc.path, " is finished; no frame can follow");
    SIERRA_CHECK(rgba.width == s.desc.width && rgba.height == s.desc.height &&
                     rgba.rgba.size() == size_t(rgba.width) * size_t(rgba.height) * 4,
                 "video ", s.desc.path, " is ", s.desc.width, "x", s.desc.height, ", got a ",
                 rgba.width, "x", rgba.height, " frame");
    int rc = av_frame_make_writable(s.frame);
    if (rc < 0) s.fail("av_frame_make_writable", rc);
    if (s.scale) {
        const uint8_t* source[1] = {rgba.rgba.data()};
        const int stride[1] = {rgba.width * 4};
        sws_scale(s.scale, source, stride, 0, rgba.height, s.frame->data, s.frame->linesize);
    } else {
        if (!s.palette) s.palette.emplace(rgba.rgba.data(), rgba.width, rgba.height);
        s.palette->map(rgba.rgba.data(), rgba.width, rgba.height, s.frame->data[0],
                       s.frame->linesize[0]);
        std::memcpy(s.frame->data[1], s.palette->argb().data(), 256 * sizeof(uint32_t));
    }
    s.frame->pts = s.next++;
    if ((rc = avcodec_send_frame(s.codec, s.frame)) < 0) s.fail("avcodec_send_frame", rc);
    s.drain();
}

void VideoEncoder::finish() {
    State& s = *state_;
    SIERRA_CHECK(!s.finished, "video ", s.desc.path, " is already finished");
    s.finished = true;
    int rc = avcodec_send_frame(s.codec, nullptr);
    if (rc < 0) s.fail("avcodec_send_frame", rc);
    s.drain();
    if ((rc = av_write_trailer(s.format)) < 0) s.fail("av_write_trailer", rc);
    if ((rc = avio_closep(&s.format->pb)) < 0) s.fail("avio_close", rc);
    // On disk before the rename, so the name never points at a file a crash cut short.
    if (int fd = ::open(s.temp.path.c_str(), O_RDONLY); fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
    std::error_code ec;
    std::filesystem::rename(s.temp.path, s.desc.path, ec);
    if (ec) throw Error(msg("cannot write video ", s.desc.path, ": rename: ", ec.message()));
    s.temp.keep = true;
    const std::filesystem::path parent = std::filesystem::path(s.desc.path).parent_path();
    if (int dir = ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY); dir >= 0) {
        ::fsync(dir);  // the new name, too, survives a power loss
        ::close(dir);
    }
}

const std::string& VideoEncoder::encoderName() const {
    return state_->encoder;
}

int VideoEncoder::framesWritten() const {
    return int(state_->next);
}

}  // namespace sierra::render
