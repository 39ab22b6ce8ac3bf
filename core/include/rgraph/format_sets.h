// Format sets that several pass types accept for a slot, stated once so that
// passes and plugins list the same formats (in `rgraph passes` too). Pure
// data, no GL include, like rgraph/format.h.
#pragma once

#include <string>
#include <vector>

#include "rgraph/format.h"

namespace rgraph {

// Every depth format (with or without stencil), in declaration order: what a
// depth attachment or a sampled depth slot may be bound to.
const std::vector<Format>& depthFormats();
// The formats an HDR colour image may have: rgba16f, rgba32f, r11g11b10f
// (float, colour-renderable, usable as image-store targets).
const std::vector<Format>& hdrFormats();
// The formats a motion-vector (velocity) target may have: rg16f, rgba16f,
// rgba32f (two float components at least, signed).
const std::vector<Format>& velocityFormats();

// "a, b or c": a set's format names for a message (so that a message that
// lists a set does not restate it).
std::string formatNameList(const std::vector<Format>& formats);

}  // namespace rgraph
