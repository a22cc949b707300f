#pragma once
// Shared set-up for GL tests: a debug EGL context per test; any KHR_debug
// error message during the test fails it.

#include <sierra/gpu/EglContext.h>

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <link.h>

namespace sierra::test {

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
