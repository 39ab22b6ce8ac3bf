// Texture formats known to the graph. Pure data: no GL include here, the GL
// backend maps each Format to its GL enums in core/src/gl/gl_format.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rgraph {

enum class Format : uint8_t {
  rgba8,
  srgb8_alpha8,
  rgba16f,
  rgba32f,
  rg16f,
  rg8,
  r8,
  r16f,
  r32f,
  r11g11b10f,
  // Three-channel float formats exist so a config can name them and be told
  // why they are refused as attachments (not required colour-renderable in
  // GL 4.5; many drivers silently fall back or fail FBO completeness).
  rgb16f,
  rgb32f,
  depth24,
  depth32f,
  depth24_stencil8,
  depth32f_stencil8,
  // Unsigned integers: ids, not colours (never filtered or blended; the
  // object_id G-buffer target, gbuffer_layout.h). Last, so the formats above
  // keep their values.
  rg32ui,
};

struct FormatInfo {
  Format format;
  std::string_view name;  // the config spelling, e.g. "rgba16f"
  uint32_t bytesPerPixel;
  uint32_t components;    // colour components, 1 for depth-only formats
  bool isDepth;
  bool hasStencil;
  bool isFloat;
  bool colorRenderable;   // false for rgb16f / rgb32f
  bool isInteger = false; // unsigned integer components (rg32ui): read and cleared as integers
};

const FormatInfo& formatInfo(Format f);
std::string_view formatName(Format f);
std::optional<Format> parseFormat(std::string_view name);
// Every format, in declaration order (for listings and "did you mean").
const std::vector<Format>& allFormats();

inline bool isDepthFormat(Format f) { return formatInfo(f).isDepth; }

}  // namespace rgraph
