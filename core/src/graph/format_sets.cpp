#include "rgraph/format_sets.h"

namespace rgraph {

const std::vector<Format>& depthFormats() {
  static const std::vector<Format> formats = [] {
    std::vector<Format> v;
    for (Format f : allFormats())
      if (isDepthFormat(f)) v.push_back(f);
    return v;
  }();
  return formats;
}

const std::vector<Format>& hdrFormats() {
  static const std::vector<Format> formats = {Format::rgba16f, Format::rgba32f, Format::r11g11b10f};
  return formats;
}

const std::vector<Format>& velocityFormats() {
  static const std::vector<Format> formats = {Format::rg16f, Format::rgba16f, Format::rgba32f};
  return formats;
}

std::string formatNameList(const std::vector<Format>& formats) {
  std::string out;
  for (size_t i = 0; i < formats.size(); ++i) {
    if (i > 0) out += i + 1 == formats.size() ? " or " : ", ";
    out += formatName(formats[i]);
  }
  return out;
}

}  // namespace rgraph
