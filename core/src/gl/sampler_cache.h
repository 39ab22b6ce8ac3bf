// Sampler objects for the sampler states passes declare with their slots
// (SlotDecl::sampler, the config's "samplers"): one GL sampler per distinct
// state, made at its first request and kept for the cache's lifetime (the
// executor's build), so that binding a slot costs one glBindSampler.
#pragma once

#include <cstdint>
#include <map>

#include "rgraph/gl/objects.h"
#include "rgraph/sampler_state.h"

namespace rgraph::gl {

class SamplerCache {
 public:
  // The sampler for `s` (a current GL context is needed).
  uint32_t get(const SamplerState& s);
  size_t size() const { return samplers_.size(); }
  void clear() { samplers_.clear(); }
  // The device's GL_MAX_TEXTURE_MAX_ANISOTROPY; 1 without anisotropic
  // filtering (the anisotropy of a state is clamped to it).
  float maxAnisotropy();

 private:
  std::map<SamplerState, Sampler> samplers_;
  float maxAnisotropy_ = 0.0f;  // 0: not queried yet
};

}  // namespace rgraph::gl
