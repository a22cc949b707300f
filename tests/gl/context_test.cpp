#include "GlTest.h"

#include <sierra/core/Error.h>
#include <sierra/gpu/EmbeddedShaders.h>
#include <sierra/gpu/Gl.h>
#include <sierra/gpu/Program.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/gpu/StreamRing.h>

#include <gmock/gmock.h>

#include <cstdlib>
#include <cstring>

using namespace sierra;
using ::testing::HasSubstr;

namespace {

class GlContext : public test::GlTest {};

TEST_F(GlContext, ComesUpWith45CoreAndLogsRenderer) {
    std::printf("renderer: %s | %s | %s\n", context().renderer().c_str(),
                context().version().c_str(), context().platform().c_str());
    EXPECT_FALSE(context().renderer().empty());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_EQ(context().width(), 640);
    EXPECT_EQ(context().height(), 360);
}

TEST_F(GlContext, ClearedPbufferReadsBackExactly) {
    glViewport(0, 0, 640, 360);
    glClearColor(64.0f / 255.0f, 128.0f / 255.0f, 191.0f / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    gpu::Image image = gpu::readFramebuffer(640, 360);
    ASSERT_EQ(image.rgba.size(), 640u * 360u * 4u);
    for (size_t p = 0; p < 640u * 360u; ++p) {
        ASSERT_EQ(image.rgba[p * 4 + 0], 64) << "pixel " << p;
        ASSERT_EQ(image.rgba[p * 4 + 1], 128) << "pixel " << p;
        ASSERT_EQ(image.rgba[p * 4 + 2], 191) << "pixel " << p;
        ASSERT_EQ(image.rgba[p * 4 + 3], 255) << "pixel " << p;
    }
}

TEST_F(GlContext, ReadBackIsInImageOrder) {
    // Bottom half red, top half blue in GL coordinates: the image's first row
    // (top) must be blue.
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 640, 180);
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(0, 180, 640, 180);
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    gpu::Image image = gpu::readFramebuffer(640, 360);
    EXPECT_EQ(image.rgba[2], 255);  // top-left blue
    EXPECT_EQ(image.rgba[0], 0);
    EXPECT_EQ(image.rgba[(359u * 640u) * 4 + 0], 255);  // bottom-left red
}

TEST_F(GlContext, PixelReaderReturnsEachFrameOnceInOrder) {
    gpu::PixelReader reader(640, 360);
    gpu::Image got;
    std::vector<int> reds;
    for (int frame = 0; frame < 4; ++frame) {
        glClearColor(float(frame * 50) / 255.0f, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        if (reader.start(got)) reds.push_back(got.rgba[0]);
    }
    if (reader.finish(got)) reds.push_back(got.rgba[0]);
    EXPECT_EQ(reds, (std::vector<int>{0, 50, 100, 150}));
    EXPECT_FALSE(reader.finish(got));
}

TEST_F(GlContext, StreamRingCyclesRegionsAndGrows) {
    gpu::StreamRing ring = gpu::StreamRing::create({.regionBytes = 4096});
    std::vector<size_t> offsets;
    for (int frame = 0; frame < 4; ++frame) {
        std::span<std::byte> region = ring.beginFrame(1000);
        ASSERT_GE(region.size(), 1000u);
        std::memset(region.data(), frame, 1000);
        offsets.push_back(ring.offset());
        ring.finishFrame();
    }
    EXPECT_EQ(offsets, (std::vector<size_t>{0, 4096, 8192, 0}));
    std::span<std::byte> big = ring.beginFrame(10000);
    EXPECT_GE(big.size(), 10000u);
    EXPECT_EQ(ring.growCount(), 1);
    // The data written lands in the buffer the GPU reads.
    std::memset(big.data(), 0x5a, 10000);
    ring.finishFrame();
    std::vector<uint8_t> back(16);
    glGetNamedBufferSubData(ring.buffer(), GLintptr(0), 16, back.data());
    EXPECT_EQ(back[0], 0x5a);
}

TEST_F(GlContext, EveryShaderFileCompilesAndLinks) {
    // A stage that includes "surface.glsl" is built once per surface function.
    std::vector<std::string> surfaces;
    for (const gpu::EmbeddedShader& s : gpu::embeddedShaders())
        if (s.name.starts_with("surface_")) surfaces.emplace_back(s.name);
    ASSERT_FALSE(surfaces.empty());
    int stages = 0;
    for (const gpu::EmbeddedShader& s : gpu::embeddedShaders()) {
        std::string name(s.name);
        gpu::ProgramDesc desc;
        if (name.ends_with(".vert"))
            desc.vertex = s.name;
        else if (name.ends_with(".frag"))
            desc.fragment = s.name;
        else if (name.ends_with(".comp"))
            desc.compute = s.name;
        else
            continue;
        if (s.source.find("#include \"surface.glsl\"") == std::string_view::npos) {
            EXPECT_NO_THROW(gpu::Program::create(desc)) << name;
        } else {
            for (const std::string& surface : surfaces) {
                // A surface over another (the drapes) over the ramp.
                const gpu::IncludeAlias aliases[] = {
                    {"surface.glsl", surface}, {"surface_base.glsl", "surface_hypsometric.glsl"}};
                desc.aliases = std::span<const gpu::IncludeAlias>(aliases, 2);
                EXPECT_NO_THROW(gpu::Program::create(desc)) << name << " with " << surface;
            }
        }
        ++stages;
    }
    EXPECT_GE(stages, 4);
    // The programs Sierra draws with.
    gpu::IncludeAlias hypsometric{"surface.glsl", "surface_hypsometric.glsl"};
    EXPECT_NO_THROW(
        gpu::Program::create({.vertex = "terrain.vert",
                              .fragment = "terrain.frag",
                              .aliases = std::span<const gpu::IncludeAlias>(&hypsometric, 1)}));
    EXPECT_NO_THROW(gpu::Program::create({.vertex = "terrain.vert", .fragment = "depth.frag"}));
    EXPECT_NO_THROW(gpu::Program::create({.vertex = "terrain.vert", .fragment = "wire.frag"}));
    EXPECT_NO_THROW(gpu::Program::create({.vertex = "solid.vert", .fragment = "solid.frag"}));
}

TEST_F(GlContext, ShaderErrorsNameFileAndLine) {
    try {
        gpu::Program::create({.vertex = "terrain.vert", .defines = "#define vec3 nonsense_type\n"});
        FAIL() << "a broken shader compiled";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("failed to compile"));
        EXPECT_THAT(e.what(), HasSubstr(".glsl:"));  // the error is in the included file
    }
    EXPECT_THROW(gpu::Program::create({.vertex = "no_such_file.vert"}), Error);
    // Mesa also reports the failed compile through KHR_debug; it was expected.
    context().resetGlErrorCount();
}

TEST(GlContextErrors, BadDeviceIndexIsReported) {
    ::setenv("SIERRA_EGL_DEVICE", "99", 1);
    try {
        gpu::EglContext::create({});
        ::unsetenv("SIERRA_EGL_DEVICE");
        FAIL() << "device 99 accepted";
    } catch (const Error& e) {
        ::unsetenv("SIERRA_EGL_DEVICE");
        EXPECT_THAT(e.what(), HasSubstr("EGL device 99"));
    }
}

TEST(GlDeviceChoice, ParsesTheThreeForms) {
    EXPECT_EQ(gpu::parseDeviceChoice("").kind, gpu::DeviceChoice::Kind::Automatic);
    EXPECT_EQ(gpu::parseDeviceChoice("auto").kind, gpu::DeviceChoice::Kind::Automatic);
    gpu::DeviceChoice index = gpu::parseDeviceChoice("3");
    EXPECT_EQ(index.kind, gpu::DeviceChoice::Kind::EglIndex);
    EXPECT_EQ(index.value, 3);
    gpu::DeviceChoice cuda = gpu::parseDeviceChoice("cuda:12");
    EXPECT_EQ(cuda.kind, gpu::DeviceChoice::Kind::CudaOrdinal);
    EXPECT_EQ(cuda.value, 12);
    for (const char* bad : {"cuda:x", "cuda:", "cuda:-1", "-1", "2a", "gpu0", "cuda:1.5"}) {
        try {
            gpu::parseDeviceChoice(bad);
            ADD_FAILURE() << "'" << bad << "' accepted";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr(bad));
        }
    }
}

TEST(GlDeviceChoice, ReadsCudaVisibleDevicesAsCudaDoes) {
    using V = std::vector<std::string>;
    EXPECT_EQ(gpu::cudaVisibleDevices(nullptr), V{});
    EXPECT_EQ(gpu::cudaVisibleDevices("2,3"), (V{"2", "3"}));
    EXPECT_EQ(gpu::cudaVisibleDevices(" 1, 0 "), (V{"1", "0"}));
    // The list ends at the first entry CUDA cannot read.
    EXPECT_EQ(gpu::cudaVisibleDevices("3,-1,0"), (V{"3"}));
    EXPECT_EQ(gpu::cudaVisibleDevices(""), V{});
    EXPECT_EQ(gpu::cudaVisibleDevices("GPU-8f2a,1"), (V{"GPU-8f2a", "1"}));
}

// Sets an environment variable for one scope.
struct ScopedEnv {
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value, 1);
    }
    ~ScopedEnv() {
        if (old_.empty())
            ::unsetenv(name_);
        else
            ::setenv(name_, old_.c_str(), 1);
    }
    const char* name_;
    std::string old_;
};

TEST(GlContextErrors, BadDeviceChoicesAreReported) {
    {
        ScopedEnv env("SIERRA_EGL_DEVICE", "cuda:x");
        try {
            gpu::EglContext::create({});
            FAIL() << "cuda:x accepted";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("SIERRA_EGL_DEVICE"));
            EXPECT_THAT(e.what(), HasSubstr("cuda:x"));
        }
    }
    bool cudaDevices = false;
    for (const auto& d : gpu::EglContext::listDevices()) cudaDevices |= d.cudaDevice >= 0;
    {
        ScopedEnv env("SIERRA_EGL_DEVICE", "cuda:99");
        try {
            gpu::EglContext::create({});
            FAIL() << "cuda:99 accepted";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("cuda:99"));
        }
    }
    {
        // Past the end of the visible list, whatever the machine has.
        ScopedEnv visible("CUDA_VISIBLE_DEVICES", "0");
        try {
            gpu::EglContext::create({.choice = gpu::parseDeviceChoice("cuda:1")});
            FAIL() << "cuda:1 accepted with one visible device";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("CUDA_VISIBLE_DEVICES='0'"));
        }
    }
    if (!cudaDevices) {
        // Mesa: no device has a CUDA ordinal, and cuda:0 says so.
        try {
            gpu::EglContext::create({.choice = gpu::parseDeviceChoice("cuda:0")});
            FAIL() << "cuda:0 accepted without a CUDA device";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("none of the"));
            EXPECT_THAT(e.what(), HasSubstr("CUDA device"));
        }
    }
}

TEST(GlContextErrors, ListedDevicesNameTheirRenderer) {
    // A context of this test's own holds the display (and, pinned, the driver)
    // while the probe makes and ends its own contexts on it.
    gpu::EglContext held = gpu::EglContext::create({.width = 16, .height = 16});
    test::keepGlDriverLoaded();
    for (const auto& d : gpu::EglContext::listDevices(true)) {
        // Every device this machine's contexts run on makes a context.
        if (d.software) {
            EXPECT_FALSE(d.renderer.empty()) << "device " << d.index;
        }
    }
}

TEST(GlContextErrors, BadFrameSizeIsReported) {
    EXPECT_THROW(gpu::EglContext::create({.width = 0, .height = 10}), Error);
}

}  // namespace
