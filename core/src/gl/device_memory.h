// How much memory the GL device says it has free, where it says so: NVIDIA's
// GL_NVX_gpu_memory_info, AMD's GL_ATI_meminfo. Others (Mesa llvmpipe, Intel)
// tell nothing: then only RendererOptions::maxMemoryBytes bounds a build.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace rgraph::gl {

struct DeviceMemory {
  uint64_t freeBytes = 0;
  std::string source;  // the extension that said it
};

// Needs a current context.
std::optional<DeviceMemory> freeDeviceMemory();

}  // namespace rgraph::gl
