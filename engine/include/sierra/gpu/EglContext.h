#pragma once
// A headless OpenGL 4.5 core context through EGL, drawing into a pbuffer.
//
// Device choice: EGL devices are enumerated (EGL_EXT_device_enumeration, or
// EGL_EXT_device_base as NVIDIA exposes it); a hardware device is preferred,
// SIERRA_EGL_DEVICE picks one explicitly (an EGL index, or cuda:N), and when
// no device platform works Mesa's surfaceless platform is used (llvmpipe on a
// machine with no GPU).
//
// EGL numbers devices in its own order, not CUDA's, and ignores
// CUDA_VISIBLE_DEVICES, through which a batch scheduler (Slurm) hands a job its
// GPUs. cuda:N therefore takes the CUDA ordinal as the job's CUDA programs count
// it: the Nth entry of CUDA_VISIBLE_DEVICES (all devices when it is unset),
// matched to the EGL device whose EGL_NV_device_cuda attribute is that
// physical ordinal, or whose EGL_EXT_device_persistent_id UUID the entry names
// (GPU-xxxxxxxx-...).

#include <memory>
#include <string>
#include <vector>

namespace sierra::gpu {

// A device as SIERRA_EGL_DEVICE writes it: "" or "auto" (automatic), "N" (EGL
// device index N) or "cuda:N" (CUDA ordinal N, see above).
struct DeviceChoice {
    enum class Kind { Automatic, EglIndex, CudaOrdinal };
    Kind kind = Kind::Automatic;
    int value = -1;  // the index or ordinal; -1 when automatic
};
// Parses the forms above; throws sierra::Error naming them for anything else
// ("cuda:x", "-1", "2a").
DeviceChoice parseDeviceChoice(const std::string& text);
// The entries of a CUDA_VISIBLE_DEVICES value in CUDA's order, as CUDA reads
// it: comma-separated, spaces ignored, the list ending at the first entry that
// is neither a non-negative integer nor a GPU-/MIG- UUID. nullptr (unset) gives
// an empty list, which means every device in its physical order.
std::vector<std::string> cudaVisibleDevices(const char* value);

struct ContextDesc {
    int width = 640;  // pbuffer size in pixels: the frame
    int height = 360;
    // Route KHR_debug messages to the log and count errors (see glErrorCount()).
    // Also switched on by SIERRA_GL_DEBUG=1.
    bool debug = false;
    // EGL device index; -1 = `choice` if it is not automatic, else
    // SIERRA_EGL_DEVICE if set, else automatic.
    int device = -1;
    DeviceChoice choice;
};

struct EglDeviceInfo {
    int index = 0;
    std::string extensions;  // device extension string
    std::string drmFile;     // e.g. /dev/dri/card0, empty if none
    bool software = false;   // Mesa's software device (llvmpipe)
    std::string vendor;      // EGL_VENDOR of the device's display ("" if it cannot be opened)
    std::string renderer;    // GL_RENDERER of a context on it ("" if none could be made)
    int cudaDevice = -1;     // physical CUDA ordinal (EGL_NV_device_cuda), -1 if none
    std::string uuid;        // GPU-xxxxxxxx-... (EGL_EXT_device_persistent_id), "" if none
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
    // Makes no context current on the calling thread, so that another thread
    // can make this one current (EGL refuses a context current elsewhere).
    void release();
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

    // Devices visible through EGL_EXT_device_enumeration (empty if
    // unsupported). With `probe`, each device's display is opened and a small
    // context made on it to fill in vendor and renderer.
    static std::vector<EglDeviceInfo> listDevices(bool probe = false);

  private:
    struct State;
    explicit EglContext(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace sierra::gpu
