// Small pure helpers of the graph contract: sizes, byte counts, access kinds.
#include <algorithm>
#include <cmath>

#include "rgraph/graph.h"

namespace rgraph {

Extent resolveSize(const SizeSpec& s, Extent output) {
  switch (s.kind) {
    case SizeSpec::Kind::output: return output;
    case SizeSpec::Kind::absolute: return {s.width, s.height};
    case SizeSpec::Kind::scale: {
      auto scaled = [&](uint32_t v) -> uint32_t {
        double r = std::round(static_cast<double>(v) * static_cast<double>(s.scale));
        if (!(r >= 1.0)) return 1;  // also catches NaN and negative scales
        if (r > 4294967295.0) return 4294967295u;
        return static_cast<uint32_t>(r);
      };
      return {scaled(output.width), scaled(output.height)};
    }
  }
  return output;
}

uint64_t textureBytes(Format f, Extent e, uint32_t mips, uint32_t samples, uint32_t arrayLayers) {
  if (e.width == 0 || e.height == 0) return 0;
  uint32_t full = 1;
  for (uint32_t m = std::max(e.width, e.height); m > 1; m >>= 1) ++full;
  uint32_t levels = mips == 0 ? full : std::min(mips, full);
  const uint64_t perPixel =
      uint64_t{formatInfo(f).bytesPerPixel} * std::max<uint32_t>(samples, 1) * std::max<uint32_t>(arrayLayers, 1);
  uint64_t total = 0;
  for (uint32_t l = 0; l < levels; ++l) {
    uint64_t w = std::max<uint64_t>(1, e.width >> l), h = std::max<uint64_t>(1, e.height >> l);
    total += w * h * perPixel;
  }
  return total;
}

bool isWriteAccess(Access a) {
  switch (a) {
    case Access::color_attachment:
    case Access::depth_attachment:
    case Access::storage_write:
    case Access::blit_dst: return true;
    case Access::depth_attachment_read:
    case Access::sampled:
    case Access::storage_read:
    case Access::blit_src: return false;
  }
  return false;
}

bool isAttachmentAccess(Access a) {
  return a == Access::color_attachment || a == Access::depth_attachment || a == Access::depth_attachment_read;
}

std::string_view accessName(Access a) {
  switch (a) {
    case Access::color_attachment: return "color_attachment";
    case Access::depth_attachment: return "depth_attachment";
    case Access::depth_attachment_read: return "depth_attachment_read";
    case Access::sampled: return "sampled";
    case Access::storage_read: return "storage_read";
    case Access::storage_write: return "storage_write";
    case Access::blit_src: return "blit_src";
    case Access::blit_dst: return "blit_dst";
  }
  return "unknown";
}

}  // namespace rgraph
