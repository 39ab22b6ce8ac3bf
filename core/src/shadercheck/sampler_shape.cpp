// Sampler types against bound shapes and compare modes (sampler_shape.h).
#include "sampler_shape.h"

#include <algorithm>
#include <string>

namespace rgraph {
namespace {

// The shape a slot binds: the layers of its subresource (one layer or face:
// a 2D image), a whole cube, a cube array, or a 2D array.
enum class BoundShape { tex2d, array2d, cube, cube_array };

BoundShape boundShape(const BoundSlot& b) {
  const uint32_t total = std::max<uint32_t>(1, b.layers) * (b.cube ? 6u : 1u);
  const uint32_t begin = std::min(b.sub.layerBegin, total);
  const uint32_t count = b.sub.layerCount == Subresource::kAll ? total - begin : b.sub.layerCount;
  if (count <= 1) return BoundShape::tex2d;
  if (b.cube && begin % 6 == 0 && count % 6 == 0) return count == 6 ? BoundShape::cube : BoundShape::cube_array;
  return BoundShape::array2d;
}

const char* shapeName(BoundShape s) {
  switch (s) {
    case BoundShape::tex2d: return "a 2D texture (sampler2D)";
    case BoundShape::array2d: return "a 2D array (sampler2DArray)";
    case BoundShape::cube: return "a cube map (samplerCube)";
    case BoundShape::cube_array: return "a cube-map array (samplerCubeArray)";
  }
  return "";
}

// A sampler's type against the bound shape, and a shadow sampler against the
// slot's compare mode. The message names the declaration; the diagnostic
// points at the binding.
}  // namespace

std::vector<std::string> samplerShapeProblems(const SamplerUniform& s, const SamplerSlot& m, const BoundSlot& b,
                                              const std::string& shader) {
  std::vector<std::string> out;
  const std::string declared = s.file.empty() ? shader : s.file + ":" + std::to_string(s.line);
  const std::string sampler = s.type + " '" + m.uniform + "' (" + declared + ")";
  const std::string input = "input '" + m.slot + "' (" + b.resource + ")";
  if (b.format) {
    const BoundShape shape = boundShape(b);
    bool fits = false;  // 1D, 3D, rect and buffer samplers read no graph texture
    if (s.dim == SamplerUniform::Dim::d2) fits = shape == (s.arrayed ? BoundShape::array2d : BoundShape::tex2d);
    if (s.dim == SamplerUniform::Dim::cube) fits = shape == (s.arrayed ? BoundShape::cube_array : BoundShape::cube);
    if (!fits) {
      std::string what = shapeName(shape);
      if (!b.sub.whole()) what += " (the subresource " + subresourceLabel(b.resource, b.sub, b.cube) + ")";
      else if (b.layers > 1 || b.cube) what += " (" + std::to_string(b.layers) + (b.cube ? " cube" : " layer") +
                                               (b.layers == 1 ? "" : "s") + ")";
      out.push_back(sampler + " cannot read " + input + ", which binds " + what +
                    ": the sampler's type must match the bound texture's shape");
    }
  }
  const bool compares = b.sampler && b.sampler->compare != SamplerState::Compare::none;
  const std::string stateFrom = b.samplerWhere.known() ? "its \"samplers\" entry at " + locationText(b.samplerWhere)
                                                       : std::string("its slot declaration");
  if (s.shadow && !compares)
    out.push_back("shadow sampler " + sampler + " reads " + input + " but the slot's sampler state has no compare " +
              "mode (" + (b.sampler ? "from " + stateFrom : std::string("the slot declares no sampler state")) +
                  "): give it one, e.g. \"samplers\": {\"" + m.slot + "\": {\"compare\": \"less_equal\"}}");
  if (!s.shadow && compares)
    out.push_back(sampler + " is not a shadow sampler but " + input + " samples with compare mode " +
                  std::string(compareName(b.sampler->compare)) + " (from " + stateFrom + "): use a shadow sampler (" +
                  s.type + "Shadow) or set \"compare\": \"none\"");
  return out;
}

}  // namespace rgraph
