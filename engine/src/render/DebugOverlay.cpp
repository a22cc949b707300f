#include <sierra/render/DebugOverlay.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/Gl.h>

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <sierra/core/Progress.h>

#include <algorithm>
#include <cmath>

namespace sierra::render {

struct DebugOverlay::State {
    ImGuiContext* context = nullptr;
    float contentHeight = 0.0f;  // of the last layout: where its content ends, padding included
};

DebugOverlay::DebugOverlay() : state_(std::make_unique<State>()) {
    IMGUI_CHECKVERSION();
    state_->context = ImGui::CreateContext();
    ImGui::SetCurrentContext(state_->context);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // headless: never write imgui.ini
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    if (!ImGui_ImplOpenGL3_Init("#version 450 core")) {
        ImGui::DestroyContext(state_->context);
        throw Error("ImGui's OpenGL3 backend failed to initialise on this context");
    }
}

DebugOverlay::~DebugOverlay() {
    ImGui::SetCurrentContext(state_->context);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(state_->context);
}

std::pair<float, float> medianAndP95(std::vector<float> values) {
    if (values.empty()) return {0.0f, 0.0f};
    std::sort(values.begin(), values.end());
    auto rank =
        [&](double q) {  // nearest rank: the smallest value with >= q of the values at or below it
            size_t k = size_t(std::ceil(q * double(values.size())));
            return values[std::clamp<size_t>(k, 1, values.size()) - 1];
        };
    return {rank(0.5), rank(0.95)};
}

int snapshotFrameWidth(int width, int columnWidth) {
    if (columnWidth <= 0) return width;
    if (columnWidth >= width) return 0;  // the UI alone
    return std::max(width / 3, width - columnWidth);
}

void DebugOverlay::layOutTwice(const DebugPanel& panel, int width, int height, bool render) {
    ImGui::SetCurrentContext(state_->context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = 1.0f / 60.0f;
    // An auto-sized window is measured on its first frame and shown from the
    // second: the panel is laid out twice and the second counts.
    for (int pass = 0; pass < 2; ++pass) {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui::NewFrame();
        layout(panel, width, height);
        if (render)
            ImGui::Render();
        else
            ImGui::EndFrame();
    }
}

void DebugOverlay::draw(const DebugPanel& panel, int width, int height) {
    layOutTwice(panel, width, height, true);
    // The backend backs up and restores the GL state it touches.
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

int DebugOverlay::contentHeight(const DebugPanel& panel, int width, int height) {
    layOutTwice(panel, width, height, false);
    return int(std::ceil(state_->contentHeight));
}

namespace {

void rowsTable(const char* id, const std::vector<std::pair<std::string, std::string>>& rows) {
    if (rows.empty()) return;
    if (ImGui::BeginTable(id, 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        // Labels are short: a fixed label column leaves the values room to
        // stay on one line.
        ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthFixed, 120.0f);
        ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
        for (const auto& [label, value] : rows) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(label.c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::TextWrapped("%s", value.c_str());
        }
        ImGui::EndTable();
    }
}

void series(const StageSeries& s, bool deterministic, float width) {
    if (deterministic) {
        ImGui::Text("%s: -- %s", s.name.c_str(), s.unit.c_str());  // placeholder for median and p95
        return;
    }
    auto [median, p95] = medianAndP95(s.values);
    const std::string overlay =
        msg("median ", fixed(median, 2), " ", s.unit, ", p95 ", fixed(p95, 2), " ", s.unit);
    // Wrapped: a narrow column (a small frame's panel) must not clip the heading.
    ImGui::TextWrapped("%s", msg(s.name, " (", s.unit, ", ", s.values.size(), " frames)").c_str());
    if (s.values.size() >= 2) {
        const float top = *std::max_element(s.values.begin(), s.values.end());
        ImGui::PlotLines(("##" + s.name).c_str(), s.values.data(), int(s.values.size()), 0,
                         overlay.c_str(), 0.0f, std::max(top * 1.15f, 1e-3f), ImVec2(width, 26.0f));
    } else {
        ImGui::TextWrapped("%s", overlay.c_str());
    }
}

void histogram(const Histogram& h, float width) {
    std::vector<float> values(h.counts.begin(), h.counts.end());
    double total = 0.0, top = 0.0;
    int first = -1, last = -1;
    for (size_t k = 0; k < h.counts.size(); ++k) {
        total += h.counts[k];
        top = std::max(top, h.counts[k]);
        if (h.counts[k] > 0) last = int(k), first = first < 0 ? int(k) : first;
    }
    ImGui::TextWrapped("%s (%s %d..%d)", h.name.c_str(), h.binLabel.c_str(), h.firstBin,
                       h.firstBin + int(h.counts.size()) - 1);
    const std::string overlay =
        first < 0 ? std::string("empty")
                  : msg(fixed(total, 0), " in ", h.binLabel, " ", h.firstBin + first, "..",
                        h.firstBin + last, ", peak ", fixed(top, 0));
    ImGui::PlotHistogram(("##" + h.name).c_str(), values.data(), int(values.size()), 0,
                         overlay.c_str(), 0.0f, float(std::max(top, 1.0) * 1.15),
                         ImVec2(width, 44.0f));
}

void param(const StyleParam& p) {
    ImGui::BeginDisabled();  // shown, not edited: the snapshot documents the frame
    switch (p.kind) {
        case StyleParam::Kind::Flag: {
            bool v = p.flag;
            ImGui::Checkbox(p.name.c_str(), &v);
            break;
        }
        case StyleParam::Kind::Number: {
            float v = p.value;
            ImGui::SliderFloat(p.name.c_str(), &v, p.min, p.max, ("%.1f " + p.text).c_str());
            break;
        }
        case StyleParam::Kind::Text:
            ImGui::LabelText(p.name.c_str(), "%s", p.text.empty() ? "(none)" : p.text.c_str());
            break;
    }
    ImGui::EndDisabled();
}

}  // namespace

void DebugOverlay::layout(const DebugPanel& panel, int width, int height) {
    ImGuiWindowFlags flags = ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;
    if (panel.columnWidth > 0) {
        const float column = float(width - snapshotFrameWidth(width, panel.columnWidth));
        ImGui::SetNextWindowPos(ImVec2(float(width) - column, 0.0f), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(column, float(height)), ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(1.0f);
        flags |= ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse;
    } else {
        ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(0.85f);
        flags |= ImGuiWindowFlags_AlwaysAutoResize;
    }
    ImGui::Begin(panel.title.c_str(), nullptr, flags);
    rowsTable("figures", panel.rows);
    if (panel.frameTimesMs.size() >= 2) {
        float top = *std::max_element(panel.frameTimesMs.begin(), panel.frameTimesMs.end());
        ImGui::PlotLines("frame ms", panel.frameTimesMs.data(), int(panel.frameTimesMs.size()), 0,
                         nullptr, 0.0f, top * 1.1f, ImVec2(260.0f, 60.0f));
    }
    // Two halves side by side from a column of kHalvesWidth pixels on; a
    // narrower one stacks the sections, or every value would wrap a few
    // characters to a line.
    constexpr int kHalvesWidth = 480;
    const bool halves =
        panel.columnWidth >= kHalvesWidth && !panel.sections.empty() &&
        ImGui::BeginTable("halves", 2,
                          ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerV);
    if (halves) ImGui::TableNextRow();
    for (int half = 0; half < (halves ? 2 : 1); ++half) {
        if (halves) ImGui::TableSetColumnIndex(half);
        const float plotWidth = halves ? ImGui::GetContentRegionAvail().x : 260.0f;
        for (const DebugSection& section : panel.sections) {
            if (halves && std::min(section.column, 1) != half) continue;
            ImGui::SetNextItemOpen(true, ImGuiCond_Always);
            if (!ImGui::CollapsingHeader(section.title.c_str())) continue;
            ImGui::PushID(section.title.c_str());
            rowsTable("rows", section.rows);
            for (const auto& s : section.series) series(s, panel.deterministic, plotWidth);
            for (const auto& h : section.histograms) histogram(h, plotWidth);
            if (!section.params.empty()) ImGui::PushItemWidth(plotWidth * 0.5f);
            for (const auto& p : section.params) param(p);
            if (!section.params.empty()) ImGui::PopItemWidth();
            for (const auto& [rgb, label] : section.swatches) {
                ImGui::ColorButton(("##" + label).c_str(), ImVec4(rgb[0], rgb[1], rgb[2], 1.0f),
                                   ImGuiColorEditFlags_NoTooltip, ImVec2(28.0f, 12.0f));
                ImGui::SameLine();
                ImGui::TextUnformatted(label.c_str());
            }
            if (!section.note.empty()) ImGui::TextWrapped("%s", section.note.c_str());
            ImGui::PopID();
        }
    }
    if (halves) ImGui::EndTable();
    // Where the content ends (window coordinates, scrolled to the top) and
    // the bottom padding: the window height that shows it all.
    state_->contentHeight = ImGui::GetCursorPosY() + ImGui::GetStyle().WindowPadding.y;
    ImGui::End();
}

}  // namespace sierra::render
