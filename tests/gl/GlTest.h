#pragma once
// Shared set-up for GL tests: a debug EGL context per test; any KHR_debug
// error message during the test fails it.

#include <sierra/gpu/EglContext.h>
#include <sierra/render/Camera.h>

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <link.h>

namespace sierra::test {

// Straight down on `target` from `above` world units over it, orthographic,
// `orthoHeight` world units from the frame's bottom to its top (north up).
inline render::Camera topDownCamera(glm::vec3 target, float orthoHeight, float above = 100.0f) {
    render::Camera c;
    c.target = target;
    c.position = target + glm::vec3(0.0f, above, 0.0f);
    c.projection = render::Projection::Orthographic;
    c.orthoHeight = orthoHeight;
    c.nearPlane = 1.0f;
    c.farPlane = 2.0f * above;
    return c;
}

// Mesa (22.3, llvmpipe) unloads its DRI driver when the last EGL display is
// terminated, and the driver leaves two 56-byte blocks allocated at that point.
// Once the driver is unloaded, LeakSanitizer reports them with frames in
// "<unknown module>", which no suppression can name, and every GL test of a
// sanitizer build fails on driver memory. Keeping the driver mapped
// (RTLD_NODELETE) keeps its globals as roots, so they are not leaks; anything
// the driver still leaks is then named and suppressed in tests/lsan.supp.
inline void keepGlDriverLoaded() {
    std::vector<std::string> drivers;
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void* out) {
            const std::string name = info->dlpi_name ? info->dlpi_name : "";
            if (name.find("_dri.so") != std::string::npos ||
                name.find("libgallium") != std::string::npos)
                static_cast<std::vector<std::string>*>(out)->push_back(name);
            return 0;
        },
        &drivers);
    // The handles are kept on purpose: RTLD_NODELETE pins the already loaded driver.
    for (const std::string& name : drivers)
        dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}

class GlTest : public ::testing::Test {
  protected:
    void createContext(int width, int height) {
        context_.emplace(
            gpu::EglContext::create({.width = width, .height = height, .debug = true}));
        keepGlDriverLoaded();
    }
    void SetUp() override { createContext(640, 360); }
    void TearDown() override {
        if (context_) {
            EXPECT_EQ(context_->glErrorCount(), 0) << "GL errors were reported (see log)";
        }
    }
    gpu::EglContext& context() { return *context_; }

  private:
    std::optional<gpu::EglContext> context_;
};

}  // namespace sierra::test
