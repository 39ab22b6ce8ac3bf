// Which EGL device a headless context picks (rgraph/gl/egl_device.h), on
// made-up device lists: no context and no EGL call, so the NVIDIA and mixed
// machines are tested here, where Mesa enumerates only llvmpipe.
#include <gtest/gtest.h>

#include "rgraph/gl/egl_device.h"

using namespace rgraph::gl;

namespace {

EglDeviceInfo llvmpipe() { return eglDeviceFromExtensions("EGL_MESA_device_software EGL_EXT_device_drm_render_node"); }

// NVIDIA's device in a container: no DRM node it may open, CUDA and the name queries.
EglDeviceInfo nvidia(std::string drmNode = "") {
  EglDeviceInfo d = eglDeviceFromExtensions("EGL_NV_device_cuda EGL_EXT_device_drm EGL_EXT_device_query_name");
  d.drmNode = std::move(drmNode);
  d.vendor = "NVIDIA";
  d.renderer = "NVIDIA H200";
  return d;
}

// A Mesa GPU (radeonsi, iris): a render node, no software extension.
EglDeviceInfo mesaGpu() {
  EglDeviceInfo d = eglDeviceFromExtensions("EGL_EXT_device_drm EGL_EXT_device_drm_render_node");
  d.drmNode = "/dev/dri/renderD128";
  return d;
}

TEST(EglDevice, KindFromExtensions) {
  EXPECT_TRUE(llvmpipe().software);
  EXPECT_FALSE(llvmpipe().cuda);
  EXPECT_FALSE(nvidia().software);
  EXPECT_TRUE(nvidia().cuda);
  EXPECT_FALSE(mesaGpu().software);
  // Whole words only: a longer extension with the name as its prefix is not it.
  EXPECT_FALSE(eglDeviceFromExtensions("EGL_MESA_device_software_x EGL_NV_device_cudax").software);
  EXPECT_FALSE(eglDeviceFromExtensions("EGL_MESA_device_software_x EGL_NV_device_cudax").cuda);
  EXPECT_FALSE(eglDeviceFromExtensions("").software);
}

TEST(EglDevice, OnlySoftwareFallsBackAsBefore) {
  // This machine: llvmpipe alone. Nothing to try first; the surfaceless
  // platform and then the device itself, as before devices were chosen.
  const EglDeviceChoice c = chooseEglDevice({llvmpipe()}, nullptr);
  EXPECT_TRUE(c.error.empty()) << c.error;
  EXPECT_TRUE(c.candidates.empty());
  EXPECT_TRUE(c.fallback);
  const EglDeviceChoice none = chooseEglDevice({}, nullptr);
  EXPECT_TRUE(none.candidates.empty());
  EXPECT_TRUE(none.fallback);
}

TEST(EglDevice, HardwareFirstInEnumerationOrder) {
  // glvnd lists Mesa's devices and NVIDIA's in vendor order: the GPUs are
  // tried, in that order, before the software device is ever reached.
  const EglDeviceChoice c = chooseEglDevice({llvmpipe(), nvidia(), mesaGpu()}, nullptr);
  EXPECT_TRUE(c.error.empty()) << c.error;
  EXPECT_EQ(c.candidates, (std::vector<size_t>{1, 2}));
  EXPECT_TRUE(c.fallback) << "a GPU that gives no 4.5 context still leaves llvmpipe";
  // An NVIDIA device with no DRM node is hardware all the same.
  EXPECT_EQ(chooseEglDevice({nvidia(), llvmpipe()}, "").candidates, (std::vector<size_t>{0}))
      << "an empty RGRAPH_EGL_DEVICE is not set";
}

TEST(EglDevice, RequestedDeviceOnlyThatOne) {
  const std::vector<EglDeviceInfo> devices = {nvidia(), llvmpipe()};
  const EglDeviceChoice soft = chooseEglDevice(devices, "1");
  EXPECT_TRUE(soft.error.empty()) << soft.error;
  EXPECT_EQ(soft.candidates, (std::vector<size_t>{1}));
  EXPECT_FALSE(soft.fallback) << "a device asked for and failing is an error, not llvmpipe in its place";
  EXPECT_EQ(chooseEglDevice(devices, "0").candidates, (std::vector<size_t>{0}));
  EXPECT_EQ(chooseEglDevice(devices, "00").candidates, (std::vector<size_t>{0}));
}

TEST(EglDevice, InvalidRequestListsTheDevices) {
  const std::vector<EglDeviceInfo> devices = {llvmpipe(), nvidia("/dev/dri/renderD129")};
  const std::string list =
      "EGL devices found: 0: software (EGL_MESA_device_software); "
      "1: hardware, CUDA (EGL_NV_device_cuda), /dev/dri/renderD129, NVIDIA, NVIDIA H200";
  const EglDeviceChoice past = chooseEglDevice(devices, "2");
  EXPECT_EQ(past.error, "RGRAPH_EGL_DEVICE=2: no such EGL device (0-based); " + list);
  EXPECT_TRUE(past.candidates.empty());
  for (const char* bad : {"x", "-1", "1.0", " 1", "0x1", "+1"}) {
    SCOPED_TRACE(bad);
    const EglDeviceChoice c = chooseEglDevice(devices, bad);
    EXPECT_EQ(c.error, "RGRAPH_EGL_DEVICE='" + std::string(bad) + "' is not a device number (0-based); " + list);
    EXPECT_TRUE(c.candidates.empty());
  }
  EXPECT_NE(chooseEglDevice(devices, "99999999999999999999").error.find("no such EGL device"), std::string::npos)
      << "a number of any length is a number";
  EXPECT_EQ(chooseEglDevice({}, "0").error,
            "RGRAPH_EGL_DEVICE=0: no such EGL device (0-based); EGL devices found: none");
}

}  // namespace
