// Scene drawing with forward shading, shared by the forward pass (blended
// surfaces over a deferred image) and forward_lit (the whole scene): one
// program per lighting configuration, every point light per fragment.
#pragma once

#include <cstdint>

#include "rgraph/pass.h"

namespace rgraph::forward {

// Compiles forward_lit for the pass's lighting params (and the scene's normal maps).
uint32_t program(PassContext& ctx);
// Draws the scene's surfaces of one kind with `prog`: opaque (depth written)
// or blended (back to front, alpha blending, depth tested but not written).
void drawSurfaces(PassContext& ctx, uint32_t prog, bool blended);

}  // namespace rgraph::forward
