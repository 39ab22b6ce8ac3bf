// Mapping of rgraph::Format to GL enums (the GL side of rgraph/format.h).
#pragma once

#include <cstdint>

#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/gl/objects.h"

namespace rgraph::gl {

struct GlFormat {
  unsigned internalFormat = 0;  // e.g. GL_RGBA16F
  unsigned format = 0;          // pixel-transfer format for readback/clear, e.g. GL_RGBA, GL_DEPTH_COMPONENT
  unsigned type = 0;            // pixel-transfer type, e.g. GL_FLOAT
};

GlFormat glFormat(Format f);
// GL_DEPTH_ATTACHMENT, GL_DEPTH_STENCIL_ATTACHMENT, or GL_COLOR_ATTACHMENT0.
unsigned attachmentPoint(Format f);
bool isDepth(Format f);
bool hasStencil(Format f);
bool isSrgb(Format f);
// Full mip chain length for an extent.
uint32_t fullMipCount(Extent e);

// An immutable-storage 2D texture (GL_TEXTURE_2D, or GL_TEXTURE_2D_MULTISAMPLE
// when samples > 1), mips == 0 meaning a full chain. Linear filtering,
// clamp-to-edge, so it samples with texture() and texelFetch().
Texture createTexture2D(Format f, Extent e, uint32_t mips = 1, uint32_t samples = 1);

}  // namespace rgraph::gl
