// The scene option table (OptionTable.h): the entries of the frame, the
// outputs, the debug snapshot, zones and style.
#include "scene/OptionBuilder.h"

#include <sierra/scene/OptionTable.h>

namespace sierra::scene::detail {

void frameEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kFrameOptions, "Frame");
    OptionEntry& size = b.entry({"--size", "WxH", "", "", "Frame size in pixels"}, 1);
    size.shown = [](const Scene& s) { return msg(s.output.width, "x", s.output.height); };
    size.fromWords = [](Scene& s, Words w) {
        auto [width, height] = parseFrameSize(w[0], "--size");
        s.output.width = width;
        s.output.height = height;
    };
    b.integer(
        {"", "", "output.width", "integer 1..16384", "", "frame width in pixels", "--size WxH"},
        [](Scene& s) -> int& { return s.output.width; });
    b.integer(
        {"", "", "output.height", "integer 1..16384", "", "frame height in pixels", "--size WxH"},
        [](Scene& s) -> int& { return s.output.height; });
    b.integer(
        {"--msaa", "N", "output.msaa", "0, 2, 4 or 8", "Samples per pixel: 0 (off), 2, 4 or 8",
         "samples per pixel; 0 = off"},
        [](Scene& s) -> int& { return s.output.msaa; }, "0, 2, 4 or 8");
}

void outputEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kOutputOptions, "Output");
    b.string({"--out", "FILE.png|FILE.mp4", "output.frame", "string",
              "Frame PNG, or JPEG for .jpg / .jpeg (sequences: NAME_0000.png, ...), or a video of "
              "all frames: .mp4, .mov, .mkv, .webm or .gif",
              "frame PNG, or JPEG (`.png`, `.jpg` or `.jpeg`, any case); sequences write "
              "`NAME_0000.png`, ... A name ending in `.mp4`, `.mov`, `.mkv`, `.webm` or `.gif` "
              "is one video of all frames; with `path.range` the segment `NAME_AAAA.EXT`"},
             [](Scene& s) -> std::string& { return s.output.frame; });
    b.string({"--depth-out", "FILE.npy", "output.depth", "string",
              "Linear eye-space depth per pixel, float32 .npy (NaN where no terrain)",
              "linear eye-space depth of each pixel (float32 `.npy`, NaN where no terrain); "
              "`\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.depth; });
    b.string({"--normals-out", "FILE.npy|FILE.exr", "output.normals", "string",
              "Unit normals per pixel, .npy (H x W x 3) or .exr (R, G, B = x, y, z); NaN where "
              "no terrain",
              "unit normals of each pixel, `.npy` (height x width x 3) or `.exr` (channels R, G, "
              "B = x, y, z); NaN where no terrain; `\"\"` = none (docs/dataset.md)"},
             [](Scene& s) -> std::string& { return s.output.normals; });
    b.string(
        {"--normals-space", "camera|world", "output.normals_space", "`\"camera\"`, `\"world\"`",
         "Normals in camera axes (OpenCV: x right, y down, z forward) or world axes (x east, "
         "y up, z south)",
         "the axes of the normals: camera (OpenCV: x right, y down, z forward) or world (x "
         "east, y up, z south)"},
        [](Scene& s) -> std::string& { return s.output.normalsSpace; });
    b.string({"--normals-precision", "float32|float16", "output.normals_precision",
              "`\"float32\"`, `\"float16\"`", "Bits of each stored normal component",
              "the stored type of each normal component"},
             [](Scene& s) -> std::string& { return s.output.normalsPrecision; });
    b.string({"--zones-out", "FILE.png", "output.zone_ids", "string",
              "Zone ids per pixel as an 8-bit grey PNG (255 = no terrain), the palette as "
              "NAME.json beside it; needs --zones",
              "the zone id of each pixel, an 8-bit grey PNG (255 = no terrain), with the palette "
              "as `NAME.json` beside it; needs zones; `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.zoneIds; });
    b.string({"--mask-out", "FILE.png", "output.mask", "string",
              "Terrain (255) against sky (0) per pixel, an 8-bit grey PNG",
              "terrain (255) against sky (0), an 8-bit grey PNG; `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.mask; });
    b.string({"--camera-out", "FILE.json", "output.camera", "string",
              "Each frame's camera as JSON: K, R|t (OpenCV), the GL view and projection, near "
              "and far, the position in the DEM's reference system",
              "each frame's camera: intrinsics K, world-to-camera R and t (OpenCV), the GL view "
              "and projection matrices, near and far, the position in the terrain's reference "
              "system and its georeference; `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.camera; });
    b.string({"--transforms-out", "FILE.json", "output.transforms", "string",
              "One NeRF / instant-ngp transforms.json for the frames rendered",
              "one NeRF / instant-ngp `transforms.json` of the frames rendered; `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.transforms; });
    b.flag(
        {"--alpha", "", "output.alpha", "boolean", "RGBA PNG with a transparent sky",
         "RGBA PNG whose sky is transparent; not with a JPEG frame or a video"},
        [](Scene& s) -> bool& { return s.output.alpha; }, true);
    b.choice<PngCompression>(
        {"--png-compression", "fast|default|best", "output.png_compression",
         "`\"fast\"`, `\"default\"`, `\"best\"`",
         "PNG frames: fast (zlib level 1, run-length matches, one filter), default (level 6) or "
         "best (level 9), every filter tried per row for the last two",
         "zlib level 1 with run-length matches and the Sub filter, level 6 or level 9 with "
         "the filter chosen per row"},
        [](Scene& s) -> PngCompression& { return s.output.pngCompression; }, parsePngCompression,
        toString);
    b.integer(
        {"--jpeg-quality", "Q", "output.jpeg_quality", "integer 1..100",
         "JPEG frames (--out NAME.jpg): quality 1..100", "quality of JPEG frames"},
        [](Scene& s) -> int& { return s.output.jpegQuality; }, "an integer 1..100");
    b.integer(
        {"--max-queued-frames", "N", "output.max_queued_frames", "integer >= 0",
         "Sequences: frames read back and waiting for their encoder, at most (0 = from the "
         "memory available, 2..16)",
         "sequences: frames waiting for an encoder thread, at most; 0 = from the available memory "
         "(2..16)"},
        [](Scene& s) -> int& { return s.output.maxQueuedFrames; }, "an integer >= 0");
    b.heading("Video (--out NAME.mp4|.mov|.mkv|.webm|.gif)");
    b.integer({"--fps", "N", "output.fps", "integer 1..1000", "Video frames per second, 1..1000",
               "video frames per second"},
              [](Scene& s) -> int& { return s.output.fps; });
    OptionEntry& crf = b.integer(
        {"--crf", "Q", "output.crf", "integer -1..63",
         "Video constant quality, 0..63, lower is better (default: the codec's)",
         "video constant quality, lower is better; -1 = the codec's default"},
        [](Scene& s) -> int& { return s.output.crf; }, "an integer 0..63");
    crf.shown = [](const Scene& s) { return s.output.crf < 0 ? std::string() : msg(s.output.crf); };
    OptionEntry& rate =
        b.entry({"--bitrate", "BPS", "output.bitrate", "integer >= 0",
                 "Video average bitrate, bits per second (k and M suffixes), not with --crf",
                 "video bits per second; 0 = constant quality. Not with `crf`"},
                1);
    rate.shown = [](const Scene& s) {
        return s.output.bitrate > 0 ? msg(s.output.bitrate) : std::string();
    };
    rate.fromWords = [](Scene& s, Words w) { s.output.bitrate = parseBitrate(w[0], "--bitrate"); };
    rate.toJson = [](const Scene& s) { return Json(s.output.bitrate); };
    rate.fromJson = [](Scene& s, const JsonObject& r, const Json& v, const std::string& k) {
        s.output.bitrate = int64_t(
            std::min<uint64_t>(r.toUnsigned(v, k), uint64_t(std::numeric_limits<int64_t>::max())));
    };
    b.string({"--video-codec", "NAME", "output.video_codec", "string",
              "h264, hevc, av1, vp9, gif, or an encoder (libx264, h264_nvenc, ...); default: by "
              "container (H.264; VP9 for .webm)",
              "`\"\"` = by container (H.264; VP9 for `.webm`, GIF for `.gif`); `h264`, `hevc`, "
              "`av1`, `vp9`, `gif` or an encoder by name (`docs/options.md`)"},
             [](Scene& s) -> std::string& { return s.output.videoCodec; });
    b.string({"--video-preset", "NAME", "output.video_preset", "string",
              "Encoder speed preset (libx264: ultrafast..veryslow, default veryfast; NVENC "
              "p1..p7)",
              "the encoder's speed preset; `\"\"` = Sierra's default (`veryfast` for libx264)"},
             [](Scene& s) -> std::string& { return s.output.videoPreset; });
}

void debugEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kDebugOptions, "Debug");
    b.string({"--debug-out", "FILE.png", "output.debug", "string", "ImGui debug snapshot PNG",
              "ImGui debug snapshot PNG (the UI beside the frame); `\"\"` = none"},
             [](Scene& s) -> std::string& { return s.output.debug; });
    OptionEntry& snapshot =
        b.string({"--snapshot", "FILE.png", "", "",
                  "ImGui debug snapshot PNG: the UI beside the frame (same as --debug-out)"},
                 [](Scene& s) -> std::string& { return s.output.debug; });
    snapshot.shown = nullptr;
    OptionEntry& none = b.entry({"--no-debug", "", "", "", "Do not write the debug snapshot"}, 0);
    none.fromWords = [](Scene& s, Words) { s.output.debug.clear(); };
    none.excludes = {"--debug-out", "--snapshot"};
    OptionEntry& only = b.string({"--snapshot-only", "FILE.png", "output.snapshot_only", "string",
                                  "The debug UI alone on a plain background, as PNG"},
                                 [](Scene& s) -> std::string& { return s.output.snapshotOnly; });
    only.shown = nullptr;
    b.integer({"--snapshot-every", "N", "output.snapshot_every", "integer >= 0",
               "Sequences: a snapshot of every Nth frame (NAME_0000.png); 0 = the last only"},
              [](Scene& s) -> int& { return s.output.snapshotEvery; });
    b.flag(
        {"--snapshot-deterministic", "", "output.snapshot_deterministic", "boolean",
         "Snapshots show placeholders instead of measured times (golden images)"},
        [](Scene& s) -> bool& { return s.output.snapshotDeterministic; }, true);
}

void zoneEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kZoneOptions, "Zones");
    b.string({"--zones", "auto|MAP.png", "zones.map", "string",
              "Zone tiles: auto (from height and slope) or a zone-map PNG",
              "`\"\"` = no zones (the colour ramp); `\"auto\"` = zones from height and slope "
              "bands; else a zone-map PNG covering the terrain's extent"},
             [](Scene& s) -> std::string& { return s.zones.map; });
    OptionEntry& palette =
        b.string({"--palette", "P.json", "zones.palette", "string",
                  "Zone palette JSON (surface types, tiles, blend settings)",
                  "palette JSON (surface types, tiles, blend settings); `\"\"` = "
                  "`assets/palettes/default.json`"},
                 [](Scene& s) -> std::string& { return s.zones.palette; });
    palette.shown = [](const Scene& s) {
        return s.zones.palette.empty() ? "assets/palettes/default.json" : s.zones.palette;
    };
    OptionEntry& band =
        b.number({"--band", "W", "zones.band", "number",
                  "Transition band width in zone-map pixels (0 = none; default: the palette's)",
                  "transition band width in zone-map pixels; < 0 = the palette's; 0 = no bands"},
                 [](Scene& s) -> float& { return s.zones.band; });
    band.shown = [](const Scene& s) {
        return s.zones.band < 0.0f ? std::string("palette") : msg(s.zones.band);
    };
    b.number({"--zone-epsilon", "E", "zones.epsilon", "number >= 0",
              "Borderline simplification distance, zone-map pixels",
              "borderline simplification distance, zone-map pixels (rule 3)"},
             [](Scene& s) -> float& { return s.zones.epsilon; });
    // Auto-zoning thresholds (--zones auto).
    b.number({"--deep-water", "F", "zones.deep_water", "number 0..1",
              "Auto-zones: deep water below this fraction of the depth range, 0..1",
              "auto zones: deep water below this fraction of the depth range"},
             [](Scene& s) -> float& { return s.zones.deepWater; });
    b.number({"--sand-top", "F", "zones.sand_top", "number 0..1",
              "Auto-zones: sand up to this fraction of the land relief, 0..1",
              "auto zones: sand up to this fraction of the land relief"},
             [](Scene& s) -> float& { return s.zones.sandTop; });
    b.number({"--zone-snow-line", "F", "zones.snow_line", "number 0..1",
              "Auto-zones: snow above this fraction of the land relief, 0..1",
              "auto zones: snow above this fraction of the land relief"},
             [](Scene& s) -> float& { return s.zones.snowLine; });
    b.number({"--rock-slope", "DEG", "zones.rock_slope", "degrees, (0, 90)",
              "Auto-zones: rock steeper than this, degrees (0, 90)",
              "auto zones: rock on slopes steeper than this"},
             [](Scene& s) -> float& { return s.zones.rockSlope; });

    Builder shading(out, kZoneShadingOptions, "Zones");
    shading.string({"--blend", "linear|height", "zones.blend", "`\"linear\"`, `\"height\"`",
                    "Blend across a band: linear (by distance) or height (tile heights move it)",
                    "across a band: by distance, or moved by the tiles' height channels"},
                   [](Scene& s) -> std::string& { return s.zones.blend; });
    shading.flag(
        {"--triplanar", "", "zones.triplanar", "boolean",
         "Project tiles along the normal's axes on steep slopes",
         "project tiles along the normal's axes on steep slopes"},
        [](Scene& s) -> bool& { return s.zones.triplanar; }, true);
    shading.flag(
        {"--no-tile-variation", "", "zones.variation", "boolean",
         "No slow warp of the tile coordinates against visible repetition",
         "a slow warp of the tile coordinates against visible repetition"},
        [](Scene& s) -> bool& { return s.zones.variation; }, false);
    shading.string({"--debug-view", "none|zones|bands", "zones.debug_view",
                    "`\"none\"`, `\"zones\"`, `\"bands\"`",
                    "Flat zone colours (zones) or the band blend weight (bands)",
                    "flat zone colours, or the band blend weight"},
                   [](Scene& s) -> std::string& { return s.zones.debugView; });
}

void styleEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kStyleOptions, "Style");
    b.flag(
        {"--wireframe", "", "style.wireframe", "boolean", "Overlay the triangulation"},
        [](Scene& s) -> bool& { return s.style.wireframe; }, true);
    b.string({"--colour-by", "MODE", "style.colour_by", "`\"surface\"`, `\"level\"`, `\"error\"`",
              "Colour the polygons by surface, level (SBT level) or error (screen-space error "
              "heat map)"},
             [](Scene& s) -> std::string& { return s.style.colourBy; });
    OptionEntry& display =
        b.entry({"--display", "LIST", "", "",
                 "What to draw: any of points, wireframe, polygons, comma-separated"},
                1);
    display.shown = [](const Scene& s) {
        std::string list;
        for (auto [on, name] : {std::pair{s.style.points, "points"},
                                {s.style.wireframe, "wireframe"},
                                {s.style.polygons, "polygons"}})
            if (on) list += msg(list.empty() ? "" : ",", name);
        return list;
    };
    display.fromWords = [](Scene& s, Words w) {
        s.style.points = s.style.wireframe = s.style.polygons = false;
        for (const std::string& item : splitCommas(w[0])) {
            if (item == "points")
                s.style.points = true;
            else if (item == "wireframe")
                s.style.wireframe = true;
            else if (item == "polygons")
                s.style.polygons = true;
            else
                throw Error(msg("--display: unknown item '", item,
                                "'; expected points, wireframe or polygons, comma-separated"));
        }
    };
    b.flag(
        {"", "", "style.polygons", "boolean", "", "the shaded surface", "--display polygons"},
        [](Scene& s) -> bool& { return s.style.polygons; }, true);
    b.flag(
        {"", "", "style.points", "boolean", "", "the mesh's vertices as points",
         "--display points"},
        [](Scene& s) -> bool& { return s.style.points; }, true);
    b.number({"--tree-line", "M", "style.tree_line", "number > 0",
              "Metric heights: metres above which rock replaces vegetation"},
             [](Scene& s) -> float& { return s.style.treeLine; });
    b.number({"--snow-line", "M", "style.snow_line", "number >= tree_line",
              "Metric heights: metres above which snow lies"},
             [](Scene& s) -> float& { return s.style.snowLine; });
    OptionEntry& cpt =
        b.string({"--cpt", "FILE.cpt", "style.cpt", "string",
                  "Colour the surface with a GMT .cpt table (absolute stored heights)",
                  "GMT `.cpt` colour table of the surface; `\"\"` = none"},
                 [](Scene& s) -> std::string& { return s.style.cpt; });
    cpt.shown = nullptr;
}

// The curvature overlays (analysis/Style.h): command-line forms of the
// style's overlay keys, which the scene file reads as a whole (StyleJson.h).
// They apply in this order, so --preset comes first and the options after it
// override it.
void overlayEntries(std::vector<OptionEntry>& out) {
    Builder b(out, kStyleOptions, "Overlays");
    using analysis::StyleParams;
    auto add = [&](const Text& t, std::function<std::string(const StyleParams&)> shown,
                   std::function<void(StyleParams&, const std::string&)> set, int count = 1) {
        OptionEntry& e = b.entry(t, count);
        if (shown) e.shown = [shown](const Scene& s) { return shown(s.style.overlay); };
        e.fromWords = [set](Scene& s, Words w) { set(s.style.overlay, w.empty() ? "" : w[0]); };
    };
    OptionEntry& preset =
        b.entry({"--preset", "NAME", "", "",
                 "Overlay style preset: fig3a..fig3n (line shading), fig4a..fig4h (hatch shading)"},
                1);
    preset.fromWords = [](Scene& s, Words w) {
        s.style.overlay = loadPreset(w[0]);
        s.style.preset = w[0];
    };
    add(
        {"--style", "LIST", "", "",
         "Layers: any of shaded,lines,hatch,contours (without shaded: plain paper)"},
        [](const StyleParams&) { return std::string("shaded"); },
        [](StyleParams& o, const std::string& text) {
            analysis::StyleLayers layers{.shaded = false};
            for (const std::string& name : splitCommas(text))
                if (!layers.enable(name))
                    throw Error(msg("--style: unknown layer '", name, "' (expected ",
                                    analysis::kStyleLayerNames, ")"));
            o.layers = layers;
        });
    add(
        {"--curvature", "METHOD", "", "",
         "Curvature method: two-normal, three-normal, three-vertex or edge-angle"},
        [](const StyleParams& o) { return analysis::curvatureMethodName(o.curvature.method); },
        [](StyleParams& o, const std::string& w) {
            o.curvature.method = analysis::parseCurvatureMethod(w);
        });
    add(
        {"--curvature-distance", "D", "", "",
         "Curvature reinforcement distance in grid steps (1 = none)"},
        [](const StyleParams& o) { return msg(o.curvature.distance); },
        [](StyleParams& o, const std::string& w) {
            o.curvature.distance = parseInt(w, "--curvature-distance");
        });
    add(
        {"--curvature-scale", "S|auto", "", "",
         "Factor on every curvature value (>= 0), or 'auto': the top 5% of the samples reach the "
         "line threshold (hatches alone: full opacity)"},
        [](const StyleParams& o) { return msg(o.curvature.scale); },
        [](StyleParams& o, const std::string& w) {
            o.autoScale = w == "auto";
            if (!o.autoScale)
                o.curvature.scale = parseFloat(w, "--curvature-scale", "a number or 'auto'");
        });
    add(
        {"--normals", "KIND", "", "", "Vertex normals of the curvature: edge, triangle or quad"},
        [](const StyleParams& o) { return analysis::normalMethodName(o.curvature.normals); },
        [](StyleParams& o, const std::string& w) {
            o.curvature.normals = analysis::parseNormalMethod(w);
        });
    add(
        {"--signed", "", "", "", "Keep the sign of the curvature (ridges and valleys apart)"},
        nullptr, [](StyleParams& o, const std::string&) { o.curvature.signedValues = true; }, 0);
    add({"--levels", "B,W,G", "", "", "Curvature level control: black point, white point, gamma"},
        nullptr, [](StyleParams& o, const std::string& w) {
            std::vector<std::string> parts = splitCommas(w);
            if (parts.size() != 3)
                throw Error(
                    msg("--levels '", w, "': expected BLACK,WHITE,GAMMA, e.g. 0.1,0.9,1.5"));
            o.curvature.levels = {.enabled = true,
                                  .black = parseFloat(parts[0], "--levels"),
                                  .white = parseFloat(parts[1], "--levels"),
                                  .gamma = parseFloat(parts[2], "--levels")};
        });
    add(
        {"--line-width", "PX", "", "", "Curvature line width in pixels"},
        [](const StyleParams& o) { return msg(o.lines.width); },
        [](StyleParams& o, const std::string& w) {
            o.lines.width = parseFloat(w, "--line-width");
        });
    add(
        {"--min-length", "N", "", "", "Shortest curvature line kept, in vertices (>= 2)"},
        [](const StyleParams& o) { return msg(o.lines.minLength); },
        [](StyleParams& o, const std::string& w) {
            o.lines.minLength = parseInt(w, "--min-length");
        });
    add(
        {"--line-threshold", "K", "", "", "Curvature a vertex needs to be on a line"},
        [](const StyleParams& o) { return msg(o.lines.threshold); },
        [](StyleParams& o, const std::string& w) {
            o.lines.threshold = parseFloat(w, "--line-threshold");
        });
    add(
        {"--hatch-length", "L", "", "", "Hatch stroke length in grid units"},
        [](const StyleParams& o) { return msg(o.hatch.length); },
        [](StyleParams& o, const std::string& w) {
            o.hatch.length = parseFloat(w, "--hatch-length");
        });
    add(
        {"--hatch-width", "PX", "", "", "Hatch stroke width in pixels"},
        [](const StyleParams& o) { return msg(o.hatch.width); },
        [](StyleParams& o, const std::string& w) {
            o.hatch.width = parseFloat(w, "--hatch-width");
        });
    add(
        {"--hatch-direction", "DIR", "", "",
         "Hatch strokes along or across the direction of greatest curvature"},
        [](const StyleParams& o) { return analysis::hatchDirectionName(o.hatch.direction); },
        [](StyleParams& o, const std::string& w) {
            o.hatch.direction = analysis::parseHatchDirection(w);
        });
}

}  // namespace sierra::scene::detail
