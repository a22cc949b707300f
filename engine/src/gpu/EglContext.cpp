// All of Sierra's EGL code lives in this file: device enumeration, display and
// context creation, the pbuffer, KHR_debug routing, and tear-down in order.
#include <sierra/gpu/EglContext.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/gpu/Gl.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>

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
    PFNEGLQUERYDEVICEATTRIBEXTPROC queryDeviceAttrib = nullptr;
    PFNEGLQUERYDEVICEBINARYEXTPROC queryDeviceBinary = nullptr;
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
            api.queryDeviceAttrib =
                eglProc<PFNEGLQUERYDEVICEATTRIBEXTPROC>("eglQueryDeviceAttribEXT");
            api.queryDeviceBinary =
                eglProc<PFNEGLQUERYDEVICEBINARYEXTPROC>("eglQueryDeviceBinaryEXT");
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
    EGLAttrib cuda = -1;
    if (api.queryDeviceAttrib && hasExtension(info.extensions.c_str(), "EGL_NV_device_cuda") &&
        api.queryDeviceAttrib(device, EGL_CUDA_DEVICE_NV, &cuda))
        info.cudaDevice = int(cuda);
    unsigned char uuid[16];
    EGLint size = 0;
    if (api.queryDeviceBinary &&
        hasExtension(info.extensions.c_str(), "EGL_EXT_device_persistent_id") &&
        api.queryDeviceBinary(device, EGL_DEVICE_UUID_EXT, 16, uuid, &size) && size == 16) {
        // CUDA's spelling: GPU-8-4-4-4-12 hex digits.
        static const char* hex = "0123456789abcdef";
        info.uuid = "GPU-";
        for (int k = 0; k < 16; ++k) {
            if (k == 4 || k == 6 || k == 8 || k == 10) info.uuid += '-';
            info.uuid += hex[uuid[k] >> 4];
            info.uuid += hex[uuid[k] & 15];
        }
    }
    return info;
}

// A non-negative decimal integer, the whole of `text`; -1 otherwise.
int parseIndex(const std::string& text) {
    if (text.empty() || text.size() > 6) return -1;
    for (char c : text)
        if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
    return std::atoi(text.c_str());
}

// The EGL device index of visible CUDA ordinal `ordinal` (see the header).
int cudaToEgl(const std::vector<EglDeviceInfo>& infos, int ordinal) {
    const char* env = std::getenv("CUDA_VISIBLE_DEVICES");
    std::vector<std::string> visible = cudaVisibleDevices(env);
    std::string physical = std::to_string(ordinal);
    if (env) {
        if (ordinal >= int(visible.size()))
            throw Error(msg("cuda:", ordinal, " requested but CUDA_VISIBLE_DEVICES='", env,
                            "' makes ", visible.size(), " CUDA device(s) visible"));
        physical = visible[size_t(ordinal)];
    }
    bool anyCuda = false;
    for (const auto& d : infos) {
        anyCuda = anyCuda || d.cudaDevice >= 0 || !d.uuid.empty();
        bool uuidMatch =
            physical.rfind("GPU-", 0) == 0 && !d.uuid.empty() && d.uuid.rfind(physical, 0) == 0;
        if (uuidMatch || (d.cudaDevice >= 0 && std::to_string(d.cudaDevice) == physical))
            return d.index;
    }
    if (!anyCuda)
        throw Error(
            msg("cuda:", ordinal, " requested but none of the ", infos.size(),
                " EGL device(s) is a CUDA device (EGL_NV_device_cuda is NVIDIA's; Mesa "
                "and llvmpipe have no CUDA ordinal): use an EGL index, see --list-devices"));
    throw Error(msg("cuda:", ordinal, " (physical device ", physical,
                    ") matches none of the EGL devices; see --list-devices"));
}

// EGL hands out one display per device and eglTerminate ends every context on
// it, so a display is terminated only when the last of this process's contexts
// on it goes: two renderers in one program stay independent.
std::mutex displayMutex;
std::map<EGLDisplay, int> displayUsers;

void retainDisplay(EGLDisplay display) {
    std::lock_guard lock(displayMutex);
    ++displayUsers[display];
}

void releaseDisplay(EGLDisplay display) {
    std::lock_guard lock(displayMutex);
    auto it = displayUsers.find(display);
    if (it != displayUsers.end() && --it->second > 0) return;
    if (it != displayUsers.end()) displayUsers.erase(it);
    eglTerminate(display);
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
        releaseDisplay(display);
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
EGLDisplay openDisplay(const DeviceApi& api, int requested, DeviceChoice choice,
                       std::string& platform) {
    std::vector<EGLDeviceEXT> devices = queryDevices(api);
    std::string source = "the device choice";
    if (requested < 0 && choice.kind == DeviceChoice::Kind::Automatic)
        if (const char* env = std::getenv("SIERRA_EGL_DEVICE")) {
            try {
                choice = parseDeviceChoice(env);
            } catch (const Error& e) {
                throw Error(msg("SIERRA_EGL_DEVICE: ", e.what()));
            }
            source = "SIERRA_EGL_DEVICE";
        }
    if (requested < 0 && choice.kind == DeviceChoice::Kind::EglIndex) requested = choice.value;
    if (requested < 0 && choice.kind == DeviceChoice::Kind::CudaOrdinal) {
        std::vector<EglDeviceInfo> infos;
        for (int k = 0; k < int(devices.size()); ++k)
            infos.push_back(describe(api, devices[size_t(k)], k));
        requested = cudaToEgl(infos, choice.value);
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
            throw Error(msg("EGL device ", requested, " requested (", source, ") but ",
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
    state->display = openDisplay(api, desc.device, desc.choice, state->platform);
    retainDisplay(state->display);

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

std::vector<EglDeviceInfo> EglContext::listDevices(bool probe) {
    DeviceApi api = DeviceApi::load();
    std::vector<EglDeviceInfo> result;
    std::vector<EGLDeviceEXT> devices = queryDevices(api);
    for (int k = 0; k < int(devices.size()); ++k) {
        EglDeviceInfo info = describe(api, devices[size_t(k)], k);
        if (probe && api.getPlatformDisplay) {
            // Opening a device display is reference-counted by EGL; the
            // context below terminates it again.
            try {
                EglContext context = create({.width = 1, .height = 1, .device = k});
                info.renderer = context.renderer();
                info.vendor = eglQueryString(context.state_->display, EGL_VENDOR);
            } catch (const Error& e) {
                log::debug("EGL device ", k, ": ", e.what());
            }
        }
        result.push_back(std::move(info));
    }
    return result;
}

DeviceChoice parseDeviceChoice(const std::string& text) {
    const char* forms = "an EGL device index (0, 1, ...), cuda:N (a CUDA ordinal) or auto";
    if (text.empty() || text == "auto") return {};
    if (text.rfind("cuda:", 0) == 0) {
        int v = parseIndex(text.substr(5));
        if (v < 0)
            throw Error(msg("'", text, "' is not a CUDA ordinal: write cuda:0, cuda:1, ..."));
        return {DeviceChoice::Kind::CudaOrdinal, v};
    }
    int v = parseIndex(text);
    if (v < 0) throw Error(msg("'", text, "' is not a device: give ", forms));
    return {DeviceChoice::Kind::EglIndex, v};
}

std::vector<std::string> cudaVisibleDevices(const char* value) {
    std::vector<std::string> entries;
    if (!value) return entries;
    std::string text;
    for (const char* p = value; *p; ++p)
        if (*p != ' ') text += *p;
    size_t start = 0;
    while (start <= text.size()) {
        size_t comma = text.find(',', start);
        std::string entry = text.substr(start, comma == std::string::npos ? comma : comma - start);
        bool uuid = entry.rfind("GPU-", 0) == 0 || entry.rfind("MIG-", 0) == 0;
        if (!uuid && parseIndex(entry) < 0) break;
        entries.push_back(entry);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return entries;
}

EglContext::EglContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
EglContext::EglContext(EglContext&& other) noexcept = default;
EglContext& EglContext::operator=(EglContext&& other) noexcept = default;
EglContext::~EglContext() = default;

void EglContext::makeCurrent() {
    if (!eglMakeCurrent(state_->display, state_->surface, state_->surface, state_->context))
        failEgl("eglMakeCurrent");
}
void EglContext::release() {
    if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT))
        failEgl("eglMakeCurrent (release)");
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
