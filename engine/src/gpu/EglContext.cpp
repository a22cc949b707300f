// All of Sierra's EGL code lives in this file: device enumeration, display and
// context creation, the pbuffer, KHR_debug routing, and tear-down in order.
#include <sierra/gpu/EglContext.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/gpu/Gl.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>

namespace sierra::gpu {
namespace {

constexpr const char* kEglPackages =
    "libegl1 libegl-mesa0 libgl1-mesa-dri (and libegl-dev to build)";

std::string eglErrorName(EGLint error) {
    switch (error) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE:
            return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP:
            return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW:
            return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST:
            return "EGL_CONTEXT_LOST";
        default:
            return msg("EGL error 0x", std::hex, error);
    }
}

[[noreturn]] void failEgl(const std::string& call, const std::string& hint = {}) {
    std::string text = call + " failed: " + eglErrorName(eglGetError());
    if (!hint.empty()) text += "; " + hint;
    throw Error(text);
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name)) {
        bool startOk = p == list || p[-1] == ' ';
        bool endOk = p[n] == '\0' || p[n] == ' ';
        if (startOk && endOk) return true;
    }
    return false;
}

template <typename Fn>
Fn eglProc(const char* name) {
    return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

struct DeviceApi {
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;

    static DeviceApi load() {
        DeviceApi api;
        const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!clientExtensions) return api;  // EGL < 1.5 without client extensions
        // NVIDIA exposes EGL_EXT_device_base rather than device_enumeration.
        if (hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
            hasExtension(clientExtensions, "EGL_EXT_device_base")) {
            api.queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
            api.queryDeviceString =
                eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
        }
        if (hasExtension(clientExtensions, "EGL_EXT_platform_base"))
            api.getPlatformDisplay =
                eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
        return api;
    }
};

std::vector<EGLDeviceEXT> queryDevices(const DeviceApi& api) {
    if (!api.queryDevices) return {};
    EGLint count = 0;
    if (!api.queryDevices(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
    api.queryDevices(count, devices.data(), &count);
    devices.resize(size_t(count));
    return devices;
}

EglDeviceInfo describe(const DeviceApi& api, EGLDeviceEXT device, int index) {
    EglDeviceInfo info;
    info.index = index;
    if (api.queryDeviceString) {
        if (const char* ext = api.queryDeviceString(device, EGL_EXTENSIONS)) info.extensions = ext;
        if (hasExtension(info.extensions.c_str(), "EGL_EXT_device_drm"))
            if (const char* file = api.queryDeviceString(device, EGL_DRM_DEVICE_FILE_EXT))
                info.drmFile = file;
    }
    info.software = hasExtension(info.extensions.c_str(), "EGL_MESA_device_software");
    return info;
}

}  // namespace

struct EglContext::State {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    int width = 0;
    int height = 0;
    std::string renderer, vendor, version, platform;
    int glErrors = 0;

    ~State() {
        if (display == EGL_NO_DISPLAY) return;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
        eglTerminate(display);
    }
};

namespace {

void APIENTRY debugCallback(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei,
                            const GLchar* message, const void* user) {
    // user points at the context's error counter.
    auto* errorCount = static_cast<int*>(const_cast<void*>(user));
    if (type == GL_DEBUG_TYPE_ERROR) {
        ++*errorCount;
        log::error("GL error (id ", id, "): ", message);
    } else if (severity != GL_DEBUG_SEVERITY_NOTIFICATION) {
        log::debug("GL: ", message);
    }
}

// Opens a display: the chosen or first hardware device, else the software
// device, else Mesa's surfaceless platform, else the default display.
EGLDisplay openDisplay(const DeviceApi& api, int requested, std::string& platform) {
    std::vector<EGLDeviceEXT> devices = queryDevices(api);
    if (requested < 0)
        if (const char* env = std::getenv("SIERRA_EGL_DEVICE")) {
            char* end = nullptr;
            long v = std::strtol(env, &end, 10);
            if (end == env || *end != '\0' || v < 0)
                throw Error(msg("SIERRA_EGL_DEVICE='", env, "' is not a device index (0..",
                                int(devices.size()) - 1, ")"));
            requested = int(v);
        }
    auto tryDevice = [&](int index) -> EGLDisplay {
        if (!api.getPlatformDisplay) return EGL_NO_DISPLAY;
        EGLDisplay d =
            api.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[size_t(index)], nullptr);
        if (d == EGL_NO_DISPLAY) return d;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(d, &major, &minor)) return EGL_NO_DISPLAY;
        EglDeviceInfo info = describe(api, devices[size_t(index)], index);
        platform = msg("EGL device ", index, info.software ? " (software)" : " (hardware)",
                       info.drmFile.empty() ? "" : " " + info.drmFile, ", EGL ", major, ".", minor);
        return d;
    };
    if (requested >= 0) {
        if (requested >= int(devices.size()))
            throw Error(msg("EGL device ", requested, " requested (SIERRA_EGL_DEVICE) but ",
                            devices.size(), " device(s) found"));
        EGLDisplay d = tryDevice(requested);
        if (d == EGL_NO_DISPLAY) failEgl(msg("eglInitialize on EGL device ", requested));
        return d;
    }
    // Hardware devices first, then software ones.
    for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < int(devices.size()); ++k) {
            bool software = describe(api, devices[size_t(k)], k).software;
            if (software != (pass == 1)) continue;
            EGLDisplay d = tryDevice(k);
            if (d != EGL_NO_DISPLAY) return d;
        }
    if (api.getPlatformDisplay) {
        EGLDisplay d =
            api.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
            platform = msg("Mesa surfaceless platform, EGL ", major, ".", minor);
            return d;
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
        platform = msg("default EGL display, EGL ", major, ".", minor);
        return d;
    }
    throw Error(msg("no EGL device or display could be initialised (", devices.size(),
                    " device(s) enumerated); install ", kEglPackages,
                    ", or on NVIDIA the driver's libnvidia-egl"));
}

}  // namespace

EglContext EglContext::create(const ContextDesc& desc) {
    SIERRA_CHECK(desc.width > 0 && desc.height > 0 && desc.width <= 16384 && desc.height <= 16384,
                 "frame size ", desc.width, "x", desc.height, " is outside 1..16384");
    auto state = std::make_unique<State>();
    DeviceApi api = DeviceApi::load();
    state->display = openDisplay(api, desc.device, state->platform);

    if (!eglBindAPI(EGL_OPENGL_API))
        failEgl("eglBindAPI(EGL_OPENGL_API)", "this EGL has no desktop OpenGL");

    const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                    EGL_PBUFFER_BIT,
                                    EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT,
                                    EGL_RED_SIZE,
                                    8,
                                    EGL_GREEN_SIZE,
                                    8,
                                    EGL_BLUE_SIZE,
                                    8,
                                    EGL_ALPHA_SIZE,
                                    8,
                                    EGL_DEPTH_SIZE,
                                    24,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglChooseConfig(state->display, configAttribs, &config, 1, &configCount) ||
        configCount < 1)
        throw Error(msg("no EGL config with an RGBA8 + depth24 pbuffer for desktop OpenGL on ",
                        state->platform));

    bool debug = desc.debug;
    if (const char* env = std::getenv("SIERRA_GL_DEBUG"))
        debug = debug || std::strcmp(env, "0") != 0;
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
    state->context = eglCreateContext(state->display, config, EGL_NO_CONTEXT, contextAttribs);
    if (state->context == EGL_NO_CONTEXT)
        failEgl(
            msg("eglCreateContext (OpenGL 4.5 core) on ", state->platform),
            "the driver does not offer OpenGL 4.5 core; Mesa >= 20 (libgl1-mesa-dri) gives it on "
            "the CPU through llvmpipe");

    const EGLint surfaceAttribs[] = {EGL_WIDTH, desc.width, EGL_HEIGHT, desc.height, EGL_NONE};
    state->surface = eglCreatePbufferSurface(state->display, config, surfaceAttribs);
    if (state->surface == EGL_NO_SURFACE)
        failEgl(msg("eglCreatePbufferSurface ", desc.width, "x", desc.height));
    state->width = desc.width;
    state->height = desc.height;
    if (!eglMakeCurrent(state->display, state->surface, state->surface, state->context))
        failEgl("eglMakeCurrent");

    auto str = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    state->renderer = str(GL_RENDERER);
    state->vendor = str(GL_VENDOR);
    state->version = str(GL_VERSION);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw Error(msg("OpenGL ", major, ".", minor, " context on ", state->renderer,
                        "; Sierra needs 4.5 core (Mesa >= 20 via libgl1-mesa-dri)"));

    if (debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, &state->glErrors);
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    }
    log::debug("OpenGL ", state->version, " on ", state->renderer, " via ", state->platform);
    return EglContext(std::move(state));
}

std::vector<EglDeviceInfo> EglContext::listDevices() {
    DeviceApi api = DeviceApi::load();
    std::vector<EglDeviceInfo> result;
    std::vector<EGLDeviceEXT> devices = queryDevices(api);
    for (int k = 0; k < int(devices.size()); ++k)
        result.push_back(describe(api, devices[size_t(k)], k));
    return result;
}

EglContext::EglContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
EglContext::EglContext(EglContext&& other) noexcept = default;
EglContext& EglContext::operator=(EglContext&& other) noexcept = default;
EglContext::~EglContext() = default;

void EglContext::makeCurrent() {
    if (!eglMakeCurrent(state_->display, state_->surface, state_->surface, state_->context))
        failEgl("eglMakeCurrent");
}
int EglContext::width() const {
    return state_->width;
}
int EglContext::height() const {
    return state_->height;
}
const std::string& EglContext::renderer() const {
    return state_->renderer;
}
const std::string& EglContext::vendor() const {
    return state_->vendor;
}
const std::string& EglContext::version() const {
    return state_->version;
}
const std::string& EglContext::platform() const {
    return state_->platform;
}
int EglContext::glErrorCount() const {
    return state_->glErrors;
}
void EglContext::resetGlErrorCount() {
    state_->glErrors = 0;
}

}  // namespace sierra::gpu
