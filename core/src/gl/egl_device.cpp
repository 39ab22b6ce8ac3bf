#include "rgraph/gl/egl_device.h"

#include <algorithm>
#include <cstring>

namespace rgraph::gl {

bool hasEglExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

EglDeviceInfo eglDeviceFromExtensions(const std::string& extensions) {
  EglDeviceInfo d;
  d.software = hasEglExtension(extensions.c_str(), "EGL_MESA_device_software");
  d.cuda = hasEglExtension(extensions.c_str(), "EGL_NV_device_cuda");
  return d;
}

std::string describeEglDevice(const EglDeviceInfo& device) {
  std::string s = device.software ? "software (EGL_MESA_device_software)" : "hardware";
  if (device.cuda) s += ", CUDA (EGL_NV_device_cuda)";
  for (const std::string* part : {&device.drmNode, &device.vendor, &device.renderer})
    if (!part->empty()) s += ", " + *part;
  return s;
}

std::string listEglDevices(const std::vector<EglDeviceInfo>& devices) {
  if (devices.empty()) return "none";
  std::string s;
  for (size_t i = 0; i < devices.size(); ++i)
    s += (i ? "; " : "") + std::to_string(i) + ": " + describeEglDevice(devices[i]);
  return s;
}

EglDeviceChoice chooseEglDevice(const std::vector<EglDeviceInfo>& devices, const char* requested) {
  EglDeviceChoice choice;
  if (!requested || !*requested) {
    for (size_t i = 0; i < devices.size(); ++i)
      if (!devices[i].software) choice.candidates.push_back(i);
    return choice;
  }
  const std::string text = requested;
  const std::string found = "; EGL devices found: " + listEglDevices(devices);
  const bool digits = std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits) {
    choice.error = "RGRAPH_EGL_DEVICE='" + text + "' is not a device number (0-based)" + found;
    return choice;
  }
  // Past 9 digits a number is beyond every enumeration (and beyond what stoul takes everywhere).
  const size_t n = text.size() <= 9 ? std::stoul(text) : devices.size();
  if (n >= devices.size()) {
    choice.error = "RGRAPH_EGL_DEVICE=" + text + ": no such EGL device (0-based)" + found;
    return choice;
  }
  choice.candidates = {n};
  choice.fallback = false;
  return choice;
}

}  // namespace rgraph::gl
