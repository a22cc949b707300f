#pragma once
// Shared set-up for GL tests: a debug EGL context per test; any KHR_debug
// error message during the test fails it.

#include <sierra/gpu/EglContext.h>

#include <gtest/gtest.h>

#include <optional>

namespace sierra::test {

class GlTest : public ::testing::Test {
protected:
    void createContext(int width, int height) {
        context_.emplace(gpu::EglContext::create({.width = width, .height = height, .debug = true}));
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
