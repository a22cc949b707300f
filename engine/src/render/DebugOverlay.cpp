#include <sierra/render/DebugOverlay.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/Gl.h>

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>

namespace sierra::render {

struct DebugOverlay::State {
    ImGuiContext* context = nullptr;
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

void DebugOverlay::draw(const DebugPanel& panel, int width, int height) {
    ImGui::SetCurrentContext(state_->context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = 1.0f / 60.0f;
    // An auto-sized window is measured on its first frame and shown from the
    // second: lay the panel out twice and draw only the second.
    for (int pass = 0; pass < 2; ++pass) {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui::NewFrame();
        layout(panel);
        ImGui::Render();
    }
    // The backend backs up and restores the GL state it touches.
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void DebugOverlay::layout(const DebugPanel& panel) {

    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin(panel.title.c_str(), nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing);
    if (ImGui::BeginTable("figures", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        for (const auto& [label, value] : panel.rows) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(label.c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::TextUnformatted(value.c_str());
        }
        ImGui::EndTable();
    }
    if (panel.frameTimesMs.size() >= 2) {
        float top = *std::max_element(panel.frameTimesMs.begin(), panel.frameTimesMs.end());
        ImGui::PlotLines("frame ms", panel.frameTimesMs.data(), int(panel.frameTimesMs.size()), 0,
                         nullptr, 0.0f, top * 1.1f, ImVec2(260.0f, 60.0f));
    }
    ImGui::End();
}

}  // namespace sierra::render
