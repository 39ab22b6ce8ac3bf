// Which EGL device a headless GlContext runs on (EGL_EXT_device_enumeration,
// EGL_EXT_platform_device). The choice is GL-free and EGL-free: it works on
// descriptions of the devices, so it is tested with made-up lists (an NVIDIA
// machine's among them) on a machine whose only device is Mesa's llvmpipe.
// rgraph/gl/context.h enumerates the real devices and follows the choice.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rgraph::gl {

// One device of EGL's enumeration, as eglQueryDeviceStringEXT describes it.
struct EglDeviceInfo {
  bool software = false;  // EGL_MESA_device_software among its extensions: llvmpipe, no GPU
  bool cuda = false;      // EGL_NV_device_cuda: an NVIDIA GPU (usable with no DRM node, e.g. in a container)
  std::string drmNode;    // EGL_DRM_RENDER_NODE_FILE_EXT, else EGL_DRM_DEVICE_FILE_EXT; empty where EGL gives none
  std::string vendor;     // EGL_VENDOR (EGL_EXT_device_query_name); empty where EGL gives none
  std::string renderer;   // EGL_RENDERER_EXT (EGL_EXT_device_query_name); empty where EGL gives none
};

// Whether a space-separated extension list (EGL_EXTENSIONS) names `name`
// (a whole word: EGL_EXT_device_drm is not EGL_EXT_device_drm_render_node).
bool hasEglExtension(const char* list, const char* name);

// The kind of a device from its EGL_EXTENSIONS string (software, cuda; the
// strings are left empty).
EglDeviceInfo eglDeviceFromExtensions(const std::string& extensions);

// "hardware, /dev/dri/renderD128, NVIDIA Corporation" / "software (EGL_MESA_device_software)".
std::string describeEglDevice(const EglDeviceInfo& device);
// "0: software (...); 1: hardware, ..." or "none".
std::string listEglDevices(const std::vector<EglDeviceInfo>& devices);

struct EglDeviceChoice {
  std::vector<size_t> candidates;  // device indices to try in this order, each until one gives a 4.5 context
  bool fallback = true;            // then, as without devices: Mesa surfaceless, the other devices, the default display
  std::string error;               // not empty: the request is invalid; the whole message (the devices listed)
};

// What to try, given the enumeration and $RGRAPH_EGL_DEVICE (`requested`;
// null or empty: not set). Not set: every hardware device in enumeration
// order, then the fallback (so a machine with only llvmpipe renders as it
// did before devices were chosen). Set to N (decimal digits): device N only,
// no fallback (a failure is the user's to see). Anything else, or N past the
// last device: `error`.
EglDeviceChoice chooseEglDevice(const std::vector<EglDeviceInfo>& devices, const char* requested);

}  // namespace rgraph::gl
