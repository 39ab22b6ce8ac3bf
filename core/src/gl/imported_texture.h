// Checking a caller's texture against the resource it is imported as
// (rgraph/renderer.h importTexture): the executor trusts nothing about a GL
// name it did not create.
#pragma once

#include <cstdint>
#include <string>

#include "rgraph/graph.h"

namespace rgraph::gl {

// What a resource is, as the executor will create or bind it.
struct TextureShape {
  Format format = Format::rgba8;
  Extent extent;
  uint32_t samples = 1;
  uint32_t mips = 1;  // 0: a full chain
  uint32_t layers = 1;  // array layers, or cubes when `cube` (TextureDesc::layers)
  bool cube = false;
};

// What a texture resource declaration asks for at its planned extent.
TextureShape declaredShape(const ResourceDecl& decl, Extent planned);

// "" when `resource` can be given a caller's texture (declared, imported, a
// texture); otherwise why not, with a suggestion for a misspelt name.
std::string checkImportName(const GraphDesc& graph, const std::string& resource);

// "" when `texture` (a GL name) can stand for `declared`; otherwise one line
// naming the resource and both descriptions, e.g.
//   imported texture 7 for resource 'hdr' does not match its declaration:
//   the resource is rgba16f 640x360, 1 sample; the texture is rgba8 640x360, 1 sample
std::string checkImportedTexture(const std::string& resource, const TextureShape& declared, uint32_t texture);

}  // namespace rgraph::gl
