#pragma once
// A headless OpenGL 4.5 core context through EGL, drawing into a pbuffer.
//
// Device choice: EGL devices are enumerated (EGL_EXT_device_enumeration, or
// EGL_EXT_device_base as NVIDIA exposes it); a hardware device is preferred,
// SIERRA_EGL_DEVICE=<index> picks one explicitly, and when no device platform
// works Mesa's surfaceless platform is used (llvmpipe on a machine with no GPU).

#include <memory>
#include <string>
#include <vector>

namespace sierra::gpu {

struct ContextDesc {
    int width = 640;  // pbuffer size in pixels: the frame
    int height = 360;
    // Route KHR_debug messages to the log and count errors (see glErrorCount()).
    // Also switched on by SIERRA_GL_DEBUG=1.
    bool debug = false;
    // EGL device index; -1 = SIERRA_EGL_DEVICE if set, else automatic.
    int device = -1;
};

struct EglDeviceInfo {
    int index = 0;
    std::string extensions;  // device extension string
    std::string drmFile;     // e.g. /dev/dri/card0, empty if none
    bool software = false;   // Mesa's software device (llvmpipe)
};

class EglContext {
  public:
    // Creates the display, a 4.5 core context and a pbuffer, and makes them
    // current on the calling thread. Throws sierra::Error naming the cause (no
    // libEGL device, no 4.5 core, ...) and the Debian packages that provide it.
    static EglContext create(const ContextDesc& desc = {});

    EglContext(EglContext&& other) noexcept;
    EglContext& operator=(EglContext&& other) noexcept;
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;
    ~EglContext();

    void makeCurrent();
    int width() const;
    int height() const;

    // GL_RENDERER, GL_VENDOR, GL_VERSION of the context; and how it was reached
    // ("device 0 (software)", "surfaceless platform").
    const std::string& renderer() const;
    const std::string& vendor() const;
    const std::string& version() const;
    const std::string& platform() const;

    // Number of KHR_debug messages of type error seen since creation (debug only).
    int glErrorCount() const;
    void resetGlErrorCount();

    // Devices visible through EGL_EXT_device_enumeration (empty if unsupported).
    static std::vector<EglDeviceInfo> listDevices();

  private:
    struct State;
    explicit EglContext(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::gpu
