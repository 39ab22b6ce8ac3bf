// How a sampled slot is filtered, wrapped and compared: declared by the pass
// type with the slot (SlotDecl::sampler), optionally overridden per pass in
// the pipeline JSON (pass key "samplers", docs/pipeline-format.md). GL-free:
// the executor turns each distinct state into one sampler object
// (core/src/gl/sampler_cache.h) bound with the slot's texture; a slot with no
// state samples with the texture's own parameters (sampler 0).
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rgraph {

struct SamplerState {
  enum class Filter : uint8_t { nearest, linear };
  enum class MipFilter : uint8_t { none, nearest, linear };  // none: level base only
  enum class Wrap : uint8_t { clamp, repeat, mirror, border };  // clamp: to the edge texel
  // none: an ordinary sampler. Any other: a depth comparison (a shadow
  // sampler: sampler2DShadow, samplerCubeShadow, ...), the texture's depth
  // `op` the reference coordinate gives 1, else 0.
  enum class Compare : uint8_t { none, never, less, less_equal, equal, not_equal, greater_equal, greater, always };

  Filter filter = Filter::linear;  // minification and magnification
  MipFilter mip = MipFilter::none;
  std::array<Wrap, 3> wrap{Wrap::clamp, Wrap::clamp, Wrap::clamp};  // s, t, r
  std::array<float, 4> border{0.0f, 0.0f, 0.0f, 0.0f};               // Wrap::border's colour (rgba)
  Compare compare = Compare::none;
  float anisotropy = 1.0f;  // 1..16, clamped to the device's maximum by the executor

  // Ordered so that the executor keys its sampler objects by the state.
  auto operator<=>(const SamplerState&) const = default;
  bool operator==(const SamplerState&) const = default;
};

// The names the config uses ("nearest", "less_equal", ...), and back
// (nullopt for an unknown name).
std::string_view filterName(SamplerState::Filter f);
std::string_view mipFilterName(SamplerState::MipFilter f);
std::string_view wrapName(SamplerState::Wrap w);
std::string_view compareName(SamplerState::Compare c);
std::optional<SamplerState::Filter> parseFilter(std::string_view s);
std::optional<SamplerState::MipFilter> parseMipFilter(std::string_view s);
std::optional<SamplerState::Wrap> parseWrap(std::string_view s);
std::optional<SamplerState::Compare> parseCompare(std::string_view s);
// Every name of each kind, in enum order (for messages and docs).
std::vector<std::string> filterNames();
std::vector<std::string> mipFilterNames();
std::vector<std::string> wrapNames();
std::vector<std::string> compareNames();

// One line for messages and listings: "nearest, mip none, wrap clamp/repeat/clamp, compare less_equal".
std::string describeSampler(const SamplerState& s);

}  // namespace rgraph
