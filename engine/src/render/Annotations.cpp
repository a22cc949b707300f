#include <sierra/render/Annotations.h>

#include <sierra/core/Error.h>

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace sierra::render {
namespace {

constexpr float kMargin = 16.0f;       // pixels between furniture and the frame's edge
constexpr float kHalo = 2.0f;          // pixels of halo around text
constexpr float kGap = 6.0f;           // pixels between a label's anchor and its box
constexpr glm::vec2 kDot{4.0f, 4.0f};  // half the box kept free around an anchor's dot

struct Box {
    glm::vec2 min, max;
    bool overlaps(const Box& o) const {
        return min.x < o.max.x && o.min.x < max.x && min.y < o.max.y && o.min.y < max.y;
    }
    bool inside(float width, float height) const {
        return min.x >= 0.0f && min.y >= 0.0f && max.x <= width && max.y <= height;
    }
};

// Where furniture of `size` goes in `corner`, below (top corners) or above
// (bottom corners) what that corner holds already; `used` is the height taken.
glm::vec2 cornerOrigin(Corner corner, glm::vec2 size, int width, int height, float& used) {
    const bool right = corner == Corner::TopRight || corner == Corner::BottomRight;
    const bool bottom = corner == Corner::BottomLeft || corner == Corner::BottomRight;
    glm::vec2 origin;
    origin.x = right ? float(width) - kMargin - size.x : kMargin;
    origin.y = bottom ? float(height) - kMargin - used - size.y : kMargin + used;
    used += size.y + kMargin * 0.5f;
    return origin;
}

std::string formatLength(double metres, bool metric) {
    char text[64];
    if (!metric)
        std::snprintf(text, sizeof text, "%g units", metres);
    else if (metres >= 1000.0)
        std::snprintf(text, sizeof text, "%g km", metres / 1000.0);
    else
        std::snprintf(text, sizeof text, "%g m", metres);
    return text;
}

// The legend's box: title, then a ramp (a bar 12 px wide beside three
// values) or one row per swatch.
glm::vec2 legendSize(const Legend& legend, float textPixels, const TextMeasure& measure) {
    float width = measure(legend.title).x, height = legend.title.empty() ? 0.0f : textPixels * 1.3f;
    if (!legend.ramp.empty()) {
        for (const auto& stop : legend.ramp) {
            char value[48];
            std::snprintf(value, sizeof value, "%g %s", stop.value, legend.units.c_str());
            width = std::max(width, 12.0f + kGap + measure(value).x);
        }
        height += textPixels * 8.5f;  // half a line above and below the bar for its values
    }
    for (const auto& swatch : legend.swatches) {
        width = std::max(width, textPixels + kGap + measure(swatch.second).x);
        height += textPixels * 1.3f;
    }
    return {width + 2.0f * kGap, height + 2.0f * kGap};
}

// A segment's points from `skip` pixels past its start, every 2 pixels.
bool segmentHits(glm::vec2 a, glm::vec2 b, float skip, const Box& box) {
    const float length = glm::length(b - a);
    for (float s = skip; s <= length; s += 2.0f) {
        const glm::vec2 p = a + (b - a) * (s / length);
        if (p.x > box.min.x && p.x < box.max.x && p.y > box.min.y && p.y < box.max.y) return true;
    }
    return false;
}

struct Leader {
    glm::vec2 from, to;
};

// The labels' places: every visible anchor's dot is reserved first (one
// under the furniture is crowded out); then,
// highest priority first (ties in the order given), each label takes the first
// free place of four beside its anchor, or else of eight a leader's length
// away whose line crosses nothing drawn; boxes never cross earlier leaders.
void placeLabels(const AnnotationDesc& desc, const Camera& camera, const DepthImage* depth,
                 const TextMeasure& measure, std::vector<Box>& taken, AnnotationLayout& out) {
    const float w = float(out.width), h = float(out.height), t = desc.textPixels;
    std::vector<int> order(desc.labels.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return desc.labels[size_t(a)].priority > desc.labels[size_t(b)].priority;
    });
    const glm::mat4 vp = camera.viewProjection(w / h);
    const glm::vec3 forward = camera.forward();
    const size_t furniture = taken.size();
    std::vector<std::pair<int, glm::vec2>> visible;  // label, anchor
    for (int index : order) {
        const Label& label = desc.labels[size_t(index)];
        const glm::vec4 clip = vp * glm::vec4(label.point, 1.0f);
        const glm::vec2 anchor((clip.x / clip.w * 0.5f + 0.5f) * w,
                               (0.5f - clip.y / clip.w * 0.5f) * h);
        if (!(clip.w > 0.0f) || !(anchor.x >= 0.0f && anchor.x < w && anchor.y >= 0.0f &&
                                  anchor.y < h && std::abs(clip.z / clip.w) <= 1.0f)) {
            ++out.outsideFrame;
            continue;
        }
        if (depth && depth->width == out.width && depth->height == out.height) {
            const float terrain =
                depth->depth[size_t(int(anchor.y)) * size_t(out.width) + size_t(int(anchor.x))];
            const float along = glm::dot(label.point - camera.position, forward);
            if (std::isfinite(terrain) && terrain < along * 0.99f) {
                ++out.hiddenBehindTerrain;
                continue;
            }
        }
        const Box dot{anchor - kDot, anchor + kDot};
        if (std::any_of(taken.begin(), taken.begin() + ptrdiff_t(furniture),
                        [&](const Box& b) { return b.overlaps(dot); })) {
            ++out.crowdedOut;  // under the furniture
            continue;
        }
        visible.push_back({index, anchor});
        taken.push_back(dot);
    }
    std::vector<Leader> leaders;
    for (const auto& entry : visible) {
        const int index = entry.first;
        const glm::vec2 anchor = entry.second;  // a plain local: lambdas capture it
        const glm::vec2 size = measure(desc.labels[size_t(index)].text) + 2.0f * kHalo;
        bool placed = false;
        for (int ring = 0; ring < 2 && !placed; ++ring) {
            const float reach = ring == 0 ? kGap : kGap + 3.0f * t;
            const int places = ring == 0 ? 4 : 8;
            for (int k = 0; k < places && !placed; ++k) {
                glm::vec2 dir;
                if (ring == 0) {
                    dir = {k % 2 == 0 ? 1.0f : -1.0f, k < 2 ? -1.0f : 1.0f};
                } else {
                    const float a = float(k - 1) * 0.25f * 3.14159265f;
                    dir = {std::cos(a), std::sin(a)};
                }
                const glm::vec2 corner = anchor + dir * reach;
                Box box{{dir.x >= 0.0f ? corner.x : corner.x - size.x,
                         dir.y >= 0.0f ? corner.y : corner.y - size.y},
                        {}};
                if (std::abs(dir.x) < 0.3f) box.min.x = corner.x - 0.5f * size.x;
                if (std::abs(dir.y) < 0.3f) box.min.y = corner.y - 0.5f * size.y;
                box.max = box.min + size;
                if (!box.inside(w, h)) continue;
                const glm::vec2 end = glm::clamp(anchor, box.min, box.max);
                auto blocked = [&](const Box& other) {
                    return other.overlaps(box) ||
                           (ring > 0 && segmentHits(anchor, end, kDot.x + 1.0f, other));
                };
                if (std::any_of(taken.begin(), taken.end(), blocked)) continue;
                if (std::any_of(leaders.begin(), leaders.end(), [&](const Leader& l) {
                        return segmentHits(l.from, l.to, kDot.x + 1.0f, box);
                    }))
                    continue;
                taken.push_back(box);
                if (ring > 0) leaders.push_back({anchor, end});
                out.labels.push_back({index, anchor, box.min, box.max, ring > 0});
                placed = true;
            }
        }
        if (!placed) ++out.crowdedOut;
    }
}

}  // namespace

double worldUnitsPerPixel(const Camera& camera, int height) {
    if (camera.projection == Projection::Orthographic) return double(camera.orthoHeight) / height;
    const double distance = glm::length(glm::dvec3(camera.target - camera.position));
    return 2.0 * distance * std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5) / height;
}

ScaleBar chooseScaleBar(double metresPerPixel, float maxPixels) {
    SIERRA_CHECK(metresPerPixel > 0.0 && std::isfinite(metresPerPixel) && maxPixels > 0.0f,
                 "a scale bar needs a positive ground size per pixel, got ", metresPerPixel);
    const double longest = metresPerPixel * maxPixels;
    double unit = std::pow(10.0, std::floor(std::log10(longest)));
    double length = unit;
    for (double n : {5.0, 2.0, 1.0}) {
        if (n * unit <= longest * (1.0 + 1e-9)) {
            length = n * unit;
            break;
        }
    }
    ScaleBar bar;
    bar.groundLength = length;
    bar.pixels = float(length / metresPerPixel);
    bar.text = formatLength(length, true);
    return bar;
}

glm::vec2 northOnFrame(const Camera& camera, float aspect) {
    const glm::mat4 vp = camera.viewProjection(aspect);
    const float step = std::max(1e-3f, glm::length(camera.target - camera.position) * 1e-3f);
    auto project = [&](glm::vec3 p) {
        glm::vec4 c = vp * glm::vec4(p, 1.0f);
        return glm::vec2(c.x / c.w * aspect, -c.y / c.w);  // square units, y down
    };
    glm::vec2 d = project(camera.target + glm::vec3(0.0f, 0.0f, -step)) - project(camera.target);
    const float len = glm::length(d);
    if (!(len > 1e-7f)) return {0.0f, -1.0f};
    return d / len;
}

AnnotationLayout layoutAnnotations(const AnnotationDesc& desc, const Camera& camera, int width,
                                   int height, const DepthImage* depth,
                                   const TextMeasure& measure) {
    SIERRA_CHECK(width > 0 && height > 0, "annotations need a frame, got ", width, "x", height);
    AnnotationLayout out;
    out.width = width;
    out.height = height;
    const float w = float(width), h = float(height), t = desc.textPixels;
    std::vector<Box> taken;
    float used[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // per Corner

    if (!desc.title.empty()) {
        glm::vec2 size = measure(desc.title) * 1.5f + 2.0f * kHalo;
        glm::vec2 o =
            cornerOrigin(desc.titleCorner, size, width, height, used[int(desc.titleCorner)]);
        taken.push_back({o, o + size});
        out.titleOrigin = o;
    }
    if (desc.northArrow) {
        NorthArrow arrow;
        arrow.length = std::max(24.0f, 0.06f * std::min(w, h));
        arrow.direction = northOnFrame(camera, w / h);
        glm::vec2 size(arrow.length, arrow.length + t * 1.3f);  // the arrow's circle and its "N"
        glm::vec2 o = cornerOrigin(desc.northArrowCorner, size, width, height,
                                   used[int(desc.northArrowCorner)]);
        arrow.centre = o + glm::vec2(size.x * 0.5f, t * 1.3f + arrow.length * 0.5f);
        taken.push_back({o, o + size});
        out.northArrow = arrow;
    }
    if (desc.scaleBar) {
        const double unitsPerPixel = worldUnitsPerPixel(camera, height);
        const bool metric = desc.unitsPerMetre > 0.0f;
        ScaleBar bar =
            chooseScaleBar(metric ? unitsPerPixel / desc.unitsPerMetre : unitsPerPixel, 0.25f * w);
        bar.text = formatLength(bar.groundLength, metric);
        bar.atTarget = camera.projection == Projection::Perspective;
        if (bar.atTarget) bar.text += " at the target";
        glm::vec2 size(std::max(bar.pixels, measure(bar.text).x), t * 1.3f + 8.0f);
        glm::vec2 o =
            cornerOrigin(desc.scaleBarCorner, size, width, height, used[int(desc.scaleBarCorner)]);
        bar.origin = o + glm::vec2(0.0f, size.y - 4.0f);
        taken.push_back({o, o + size});
        out.scaleBar = bar;
    }
    if (desc.legend) {
        glm::vec2 size = legendSize(*desc.legend, t, measure);
        glm::vec2 o =
            cornerOrigin(desc.legend->corner, size, width, height, used[int(desc.legend->corner)]);
        taken.push_back({o, o + size});
        out.legendOrigin = o;
        out.legendSize = size;
    }

    placeLabels(desc, camera, depth, measure, taken, out);
    return out;
}

// ---------------------------------------------------------------- drawing

struct AnnotationOverlay::State {
    ImGuiContext* context = nullptr;
    ImFont* font = nullptr;
    float textPixels = 16.0f;
};

namespace {

// A TrueType or OpenType file by its first four bytes; stb_truetype (inside
// ImGui) trusts its input, so anything else is refused before it gets there.
void checkFont(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read the font " + path + " (apt-get install fonts-dejavu-core)");
    unsigned char magic[4] = {};
    in.read(reinterpret_cast<char*>(magic), 4);
    const bool ttf = in.gcount() == 4 &&
                     ((magic[0] == 0 && magic[1] == 1 && magic[2] == 0 && magic[3] == 0) ||
                      std::equal(magic, magic + 4, "true") || std::equal(magic, magic + 4, "OTTO"));
    if (!ttf) throw Error("the font " + path + " is not a TrueType or OpenType file");
}

ImU32 rgb(const std::array<float, 3>& c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c[0], c[1], c[2], alpha));
}

constexpr ImU32 kInk = IM_COL32(20, 20, 20, 255);
constexpr ImU32 kHaloColour = IM_COL32(255, 255, 255, 225);

}  // namespace

AnnotationOverlay::AnnotationOverlay(float textPixels, const std::string& fontPath)
    : state_(std::make_unique<State>()) {
    SIERRA_CHECK(textPixels >= 4.0f && textPixels <= 256.0f,
                 "annotation text must be 4 to 256 pixels high, got ", textPixels);
    checkFont(fontPath);
    state_->textPixels = textPixels;
    state_->context = ImGui::CreateContext();
    ImGui::SetCurrentContext(state_->context);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    // Rasterised at the title's size (1.5x): labels are drawn scaled down from it.
    state_->font = io.Fonts->AddFontFromFileTTF(fontPath.c_str(), textPixels * 1.5f);
    if (!state_->font || !io.Fonts->Build()) {
        ImGui::DestroyContext(state_->context);
        throw Error("cannot rasterise the font " + fontPath);
    }
    if (!ImGui_ImplOpenGL3_Init("#version 450 core")) {
        ImGui::DestroyContext(state_->context);
        throw Error("ImGui's OpenGL3 backend failed to initialise on this context");
    }
}

AnnotationOverlay::~AnnotationOverlay() {
    ImGui::SetCurrentContext(state_->context);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(state_->context);
}

glm::vec2 AnnotationOverlay::measure(const std::string& text) const {
    ImVec2 size = state_->font->CalcTextSizeA(state_->textPixels, 1e9f, 0.0f, text.c_str());
    return {size.x, size.y};
}

TextMeasure AnnotationOverlay::measurer() const {
    return [this](const std::string& text) { return measure(text); };
}

namespace {

void haloText(ImDrawList* list, ImFont* font, float size, glm::vec2 at, const std::string& text) {
    for (int k = 0; k < 8; ++k) {
        const float a = float(k) * 0.785398f;
        list->AddText(font, size, ImVec2(at.x + kHalo * std::cos(a), at.y + kHalo * std::sin(a)),
                      kHaloColour, text.c_str());
    }
    list->AddText(font, size, ImVec2(at.x, at.y), kInk, text.c_str());
}

void drawLegend(ImDrawList* list, ImFont* font, float t, const Legend& legend, glm::vec2 o,
                glm::vec2 size) {
    list->AddRectFilled(ImVec2(o.x, o.y), ImVec2(o.x + size.x, o.y + size.y),
                        IM_COL32(255, 255, 255, 200), 4.0f);
    glm::vec2 at = o + kGap;
    if (!legend.title.empty()) {
        list->AddText(font, t, ImVec2(at.x, at.y), kInk, legend.title.c_str());
        at.y += t * 1.3f;
    }
    if (!legend.ramp.empty()) {
        at.y += 0.5f * t;
        const float barHeight = t * 7.5f;
        const float lo = legend.ramp.front().value, hi = legend.ramp.back().value;
        const float span = hi > lo ? hi - lo : 1.0f;
        // Highest value at the top: one filled band between each pair of stops.
        for (size_t k = 0; k + 1 < legend.ramp.size(); ++k) {
            const auto& a = legend.ramp[k];
            const auto& b = legend.ramp[k + 1];
            const float ya = at.y + barHeight * (1.0f - (a.value - lo) / span);
            const float yb = at.y + barHeight * (1.0f - (b.value - lo) / span);
            list->AddRectFilledMultiColor(ImVec2(at.x, yb), ImVec2(at.x + 12.0f, ya), rgb(b.colour),
                                          rgb(b.colour), rgb(a.colour), rgb(a.colour));
        }
        list->AddRect(ImVec2(at.x, at.y), ImVec2(at.x + 12.0f, at.y + barHeight), kInk);
        for (const auto& stop : legend.ramp) {
            char value[48];
            std::snprintf(value, sizeof value, "%g %s", stop.value, legend.units.c_str());
            const float y = at.y + barHeight * (1.0f - (stop.value - lo) / span) - 0.5f * t;
            list->AddText(font, t, ImVec2(at.x + 12.0f + kGap, y), kInk, value);
        }
        at.y += t * 8.0f;
    }
    for (const auto& [colour, name] : legend.swatches) {
        list->AddRectFilled(ImVec2(at.x, at.y + 0.1f * t), ImVec2(at.x + t, at.y + 1.1f * t),
                            rgb(colour));
        list->AddRect(ImVec2(at.x, at.y + 0.1f * t), ImVec2(at.x + t, at.y + 1.1f * t), kInk);
        list->AddText(font, t, ImVec2(at.x + t + kGap, at.y), kInk, name.c_str());
        at.y += t * 1.3f;
    }
}

void drawScaleBar(ImDrawList* list, ImFont* font, float t, const ScaleBar& bar) {
    const glm::vec2 o = bar.origin;
    // Two halves, dark and light, on a halo, with the length written above.
    list->AddRectFilled(ImVec2(o.x - 1.0f, o.y - 4.0f), ImVec2(o.x + bar.pixels + 1.0f, o.y + 4.0f),
                        kHaloColour);
    list->AddRectFilled(ImVec2(o.x, o.y - 3.0f), ImVec2(o.x + 0.5f * bar.pixels, o.y + 3.0f), kInk);
    list->AddRect(ImVec2(o.x, o.y - 3.0f), ImVec2(o.x + bar.pixels, o.y + 3.0f), kInk);
    haloText(list, font, t, o + glm::vec2(0.0f, -4.0f - t * 1.2f), bar.text);
}

void drawNorthArrow(ImDrawList* list, ImFont* font, float t, const NorthArrow& arrow) {
    const glm::vec2 c = arrow.centre, d = arrow.direction, n(-d.y, d.x);
    const float r = arrow.length * 0.5f;
    const glm::vec2 tip = c + d * r, tail = c - d * r;
    list->AddCircleFilled(ImVec2(c.x, c.y), r + 3.0f, IM_COL32(255, 255, 255, 170));
    const glm::vec2 left = tail + n * (0.45f * r), right = tail - n * (0.45f * r);
    list->AddTriangleFilled(ImVec2(tip.x, tip.y), ImVec2(left.x, left.y), ImVec2(c.x, c.y), kInk);
    list->AddTriangle(ImVec2(tip.x, tip.y), ImVec2(right.x, right.y), ImVec2(c.x, c.y), kInk);
    const glm::vec2 letter = c + d * (r + 0.7f * t) - glm::vec2(0.3f * t, 0.55f * t);
    haloText(list, font, t, letter, "N");
}

}  // namespace

void AnnotationOverlay::draw(const AnnotationDesc& desc, const AnnotationLayout& layout) {
    ImGui::SetCurrentContext(state_->context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(layout.width), float(layout.height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    ImDrawList* list = ImGui::GetForegroundDrawList();
    ImFont* font = state_->font;
    const float t = state_->textPixels;

    for (const PlacedLabel& placed : layout.labels) {
        const Label& label = desc.labels.at(size_t(placed.index));
        const glm::vec2 a = placed.anchor;
        if (placed.leader) {
            glm::vec2 end = glm::clamp(a, placed.boxMin, placed.boxMax);
            list->AddLine(ImVec2(a.x, a.y), ImVec2(end.x, end.y), kHaloColour, 3.0f);
            list->AddLine(ImVec2(a.x, a.y), ImVec2(end.x, end.y), kInk, 1.2f);
        }
        list->AddCircleFilled(ImVec2(a.x, a.y), 3.5f, kHaloColour);
        list->AddCircleFilled(ImVec2(a.x, a.y), 2.2f, kInk);
        haloText(list, font, t, placed.boxMin + kHalo, label.text);
    }
    if (layout.titleOrigin) haloText(list, font, t * 1.5f, *layout.titleOrigin + kHalo, desc.title);
    if (layout.scaleBar) drawScaleBar(list, font, t, *layout.scaleBar);
    if (layout.northArrow) drawNorthArrow(list, font, t, *layout.northArrow);
    if (desc.legend && layout.legendOrigin)
        drawLegend(list, font, t, *desc.legend, *layout.legendOrigin, layout.legendSize);

    ImGui::Render();
    // The backend backs up and restores the GL state it touches.
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace sierra::render
