// freeDeviceMemory (device_memory.h).
#include "device_memory.h"

#include <GL/glcorearb.h>

#include <cstring>

#include "rgraph/gl/context.h"

namespace rgraph::gl {

namespace {

// Tokens of the two extensions (their specifications; glcorearb.h has neither).
constexpr GLenum kNvxCurrentAvailableKb = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
constexpr GLenum kAtiTextureFreeMemory = 0x87FC;   // GL_TEXTURE_FREE_MEMORY_ATI: 4 values, [0] the free KB


}  // namespace

std::optional<DeviceMemory> freeDeviceMemory() {
  GLint kb[4] = {0, 0, 0, 0};
  if (hasExtension("GL_NVX_gpu_memory_info")) {
    glGetIntegerv(kNvxCurrentAvailableKb, kb);
    if (kb[0] > 0) return DeviceMemory{uint64_t(kb[0]) * 1024, "GL_NVX_gpu_memory_info"};
  }
  if (hasExtension("GL_ATI_meminfo")) {
    glGetIntegerv(kAtiTextureFreeMemory, kb);
    if (kb[0] > 0) return DeviceMemory{uint64_t(kb[0]) * 1024, "GL_ATI_meminfo"};
  }
  return std::nullopt;
}

}  // namespace rgraph::gl
