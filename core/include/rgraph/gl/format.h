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

// The GL target of a texture of this shape (rgraph/graph.h TextureDesc):
// GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY (layers > 1), GL_TEXTURE_CUBE_MAP (cube),
// GL_TEXTURE_CUBE_MAP_ARRAY (cube, layers > 1 cubes),
// GL_TEXTURE_2D_MULTISAMPLE(_ARRAY) (samples > 1).
unsigned textureTarget(uint32_t samples, uint32_t layers, bool cube);
// An immutable-storage texture of any shape (layers: array layers, or cubes
// when `cube`: 6 layer-faces each), sampled as createTexture2D's; immutable
// so that texture views of its levels and layers can be made.
Texture createTexture(Format f, Extent e, uint32_t mips, uint32_t samples, uint32_t layers, bool cube);

}  // namespace rgraph::gl
