#include "rgraph/format.h"

#include <array>

namespace rgraph {
namespace {
// name, bytes per pixel, components, depth, stencil, float, colour-renderable, integer
const std::array<FormatInfo, 17> kFormats = {{
    {Format::rgba8, "rgba8", 4, 4, false, false, false, true, false},
    {Format::srgb8_alpha8, "srgb8_alpha8", 4, 4, false, false, false, true, false},
    {Format::rgba16f, "rgba16f", 8, 4, false, false, true, true, false},
    {Format::rgba32f, "rgba32f", 16, 4, false, false, true, true, false},
    {Format::rg16f, "rg16f", 4, 2, false, false, true, true, false},
    {Format::rg8, "rg8", 2, 2, false, false, false, true, false},
    {Format::r8, "r8", 1, 1, false, false, false, true, false},
    {Format::r16f, "r16f", 2, 1, false, false, true, true, false},
    {Format::r32f, "r32f", 4, 1, false, false, true, true, false},
    {Format::r11g11b10f, "r11g11b10f", 4, 3, false, false, true, true, false},
    {Format::rgb16f, "rgb16f", 6, 3, false, false, true, false, false},
    {Format::rgb32f, "rgb32f", 12, 3, false, false, true, false, false},
    {Format::depth24, "depth24", 4, 1, true, false, false, true, false},
    {Format::depth32f, "depth32f", 4, 1, true, false, true, true, false},
    {Format::depth24_stencil8, "depth24_stencil8", 4, 1, true, true, false, true, false},
    {Format::depth32f_stencil8, "depth32f_stencil8", 8, 1, true, true, true, true, false},
    {Format::rg32ui, "rg32ui", 8, 2, false, false, false, true, true},
}};
}  // namespace

const FormatInfo& formatInfo(Format f) { return kFormats[static_cast<size_t>(f)]; }
std::string_view formatName(Format f) { return formatInfo(f).name; }

std::optional<Format> parseFormat(std::string_view name) {
  for (const auto& info : kFormats)
    if (info.name == name) return info.format;
  return std::nullopt;
}

const std::vector<Format>& allFormats() {
  static const std::vector<Format> all = [] {
    std::vector<Format> v;
    for (const auto& info : kFormats) v.push_back(info.format);
    return v;
  }();
  return all;
}

}  // namespace rgraph
