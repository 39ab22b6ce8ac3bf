// Small builders for pass-type declarations, so a pass folder declares its
// slots and parameters in a few readable lines. GL-free.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rgraph/pass.h"

namespace rgraph::decl {

// A pass type named `name` (the config's "type"), described for `rgraph
// passes` by `description`; the caller adds slots, params and programs.
inline PassTypeDesc passType(std::string name, std::string description) {
  PassTypeDesc d;
  d.name = std::move(name);
  d.description = std::move(description);
  return d;
}

inline SlotDecl slot(std::string name, Access access, bool required, SlotDecl::Load load, std::string description,
                     std::vector<Format> formats = {}, bool acceptsMultisample = false) {
  SlotDecl s;
  s.name = std::move(name);
  s.access = access;
  s.required = required;
  s.load = load;
  s.formats = std::move(formats);
  s.acceptsMultisample = acceptsMultisample;
  s.description = std::move(description);
  return s;
}

// `s` sampled through `state`, whatever the bound texture's own parameters
// (an imported texture's filter, a mip chain's trilinear default).
inline SlotDecl sampledWith(SlotDecl s, SamplerState state) {
  s.sampler = state;
  return s;
}

// Bilinear within the base level, clamped to the edge texels: for a shader
// whose taps fall between texel centres on purpose (a filter's weights, a
// reprojected history, an image scaled up).
inline SamplerState bilinearClamped() { return SamplerState{}; }

inline ParamDecl param(std::string name, ParamType type, ParamValue defaultValue, std::string description,
                       std::vector<std::string> choices = {}) {
  ParamDecl p;
  p.name = std::move(name);
  p.type = type;
  p.defaultValue = std::move(defaultValue);
  p.choices = std::move(choices);
  p.description = std::move(description);
  return p;
}

inline ParamDecl ranged(std::string name, ParamType type, ParamValue defaultValue, std::optional<double> min,
                        std::optional<double> max, std::string description) {
  ParamDecl p = param(std::move(name), type, std::move(defaultValue), std::move(description));
  p.min = min;
  p.max = max;
  return p;
}

}  // namespace rgraph::decl
