// Subresources: parsing and printing the config's "NAME.mip[..].layer[..]"
// references, and the mip count a descriptor resolves to. GL-free.
#include <algorithm>
#include <array>
#include <charconv>
#include <string>
#include <string_view>

#include "rgraph/graph.h"

namespace rgraph {
namespace {

constexpr std::array<std::string_view, 6> kFaces = {"+x", "-x", "+y", "-y", "+z", "-z"};

bool parseIndex(std::string_view s, uint32_t& v) {
  if (s.empty()) return false;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

// "N", "N..M" (inclusive) or "*" into begin and count.
std::string parseRange(std::string_view part, std::string_view inside, uint32_t& begin, uint32_t& count) {
  if (inside == "*") {
    begin = 0, count = Subresource::kAll;
    return {};
  }
  const size_t dots = inside.find("..");
  uint32_t lo = 0, hi = 0;
  if (dots == std::string_view::npos) {
    if (!parseIndex(inside, lo))
      return std::string(part) + "[" + std::string(inside) + "]: not an index (a number, N..M or *)";
    begin = lo, count = 1;
    return {};
  }
  if (!parseIndex(inside.substr(0, dots), lo) || !parseIndex(inside.substr(dots + 2), hi))
    return std::string(part) + "[" + std::string(inside) + "]: not a range (N..M with numbers, inclusive)";
  if (hi < lo) return std::string(part) + "[" + std::string(inside) + "]: the range ends before it starts";
  begin = lo, count = hi - lo + 1;
  return {};
}

std::string rangeText(uint32_t begin, uint32_t count) {
  if (count == Subresource::kAll) return begin == 0 ? "*" : std::to_string(begin) + "..";
  if (count == 1) return std::to_string(begin);
  return std::to_string(begin) + ".." + std::to_string(begin + count - 1);
}

}  // namespace

uint32_t mipLevels(const TextureDesc& t, Extent e) {
  uint32_t full = 1;
  for (uint32_t m = std::max(e.width, e.height); m > 1; m >>= 1) ++full;
  return t.mips == 0 ? full : std::min(t.mips, full);
}

std::string parseSubresourceRef(std::string_view text, std::string& name, Subresource& sub) {
  sub = Subresource{};
  // The subresource starts at the first ".mip[", ".layer[" or ".face[".
  size_t start = std::string_view::npos;
  for (std::string_view key : {".mip[", ".layer[", ".face["}) start = std::min(start, text.find(key));
  name = std::string(text.substr(0, start));
  if (start == std::string_view::npos) return {};
  if (name.empty()) return "\"" + std::string(text) + "\": no resource name before the subresource";
  bool mip = false, layer = false;
  std::string_view rest = text.substr(start);
  while (!rest.empty()) {
    if (rest[0] != '.')
      return "\"" + std::string(text) + "\": expected .mip[..], .layer[..] or .face[..] at \"" + std::string(rest) +
             "\"";
    const size_t open = rest.find('['), close = rest.find(']');
    if (open == std::string_view::npos || close == std::string_view::npos || close < open)
      return "\"" + std::string(text) + "\": unclosed '[' in \"" + std::string(rest) + "\"";
    const std::string_view part = rest.substr(1, open - 1), inside = rest.substr(open + 1, close - open - 1);
    std::string err;
    if (part == "mip") {
      if (mip) return "\"" + std::string(text) + "\": mip given twice";
      mip = true;
      err = parseRange(part, inside, sub.mipBegin, sub.mipCount);
    } else if (part == "layer" || part == "face") {
      if (layer) return "\"" + std::string(text) + "\": layer or face given twice";
      layer = true;
      if (part == "layer") {
        err = parseRange(part, inside, sub.layerBegin, sub.layerCount);
      } else if (inside == "*") {
        sub.layerBegin = 0, sub.layerCount = 6;
      } else {
        const auto it = std::find(kFaces.begin(), kFaces.end(), inside);
        if (it == kFaces.end()) err = "face[" + std::string(inside) + "]: not a cube face (+x -x +y -y +z -z or *)";
        sub.layerBegin = static_cast<uint32_t>(it - kFaces.begin()), sub.layerCount = 1;
      }
    } else {
      return "\"" + std::string(text) + "\": \"" + std::string(part) + "\" is not mip, layer or face";
    }
    if (!err.empty()) return "\"" + std::string(text) + "\": " + err;
    rest = rest.substr(close + 1);
  }
  return {};
}

std::string subresourceLabel(std::string_view name, const Subresource& sub, bool cube) {
  std::string s(name);
  if (sub.mipBegin != 0 || sub.mipCount != Subresource::kAll)
    s += ".mip[" + rangeText(sub.mipBegin, sub.mipCount) + "]";
  if (sub.layerBegin != 0 || sub.layerCount != Subresource::kAll) {
    if (cube && sub.layerCount == 1 && sub.layerBegin < 6)
      s += ".face[" + std::string(kFaces[sub.layerBegin]) + "]";
    else
      s += ".layer[" + rangeText(sub.layerBegin, sub.layerCount) + "]";
  }
  return s;
}

}  // namespace rgraph
