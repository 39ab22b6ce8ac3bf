// Hazard modes (issue 31): ways to run a pipeline that change what the graph
// does not promise (the content of a transient before it is written, which
// texture a transient shares, the order of independent passes, the GL state
// a pass did not set, whether culled passes run), so that a pass relying on
// any of it renders differently. `rgraph render --hazards`, RendererOptions::
// hazards, `rgraph check-hazards` and testing::expectHazardFree select them;
// docs/testing.md says what each catches. GL-free.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace rgraph {

struct CompileOptions;

enum class HazardMode : uint8_t {
  poison,         // each transient filled with a loud pattern when its lifetime begins
  noAlias,        // every transient its own texture
  aliasShuffle,   // another valid aliasing (the free list taken in reverse)
  reorder,        // another valid topological order (seeded)
  stateScramble,  // hostile GL state before each pass; state checks after it
  noCull,         // culled passes run too
};
inline constexpr std::array<HazardMode, 6> kHazardModes{HazardMode::poison,      HazardMode::noAlias,
                                                        HazardMode::aliasShuffle, HazardMode::reorder,
                                                        HazardMode::stateScramble, HazardMode::noCull};

// The command-line spelling: "poison", "no-alias", "alias-shuffle", "reorder",
// "state-scramble", "no-cull".
std::string_view hazardModeName(HazardMode mode);

// A set of modes (none: a plain run, what every frame does by default).
struct HazardModes {
  uint32_t bits = 0;
  // reorder: which seeded order (1, 2, ...): "reorder:K" in a mode list.
  // The harness (check-hazards) runs orders 1..K.
  uint32_t reorder = 1;

  bool any() const { return bits != 0; }
  bool has(HazardMode m) const { return (bits >> static_cast<uint32_t>(m)) & 1u; }
  HazardModes& add(HazardMode m) {
    bits |= 1u << static_cast<uint32_t>(m);
    return *this;
  }
  static HazardModes of(HazardMode m) { return HazardModes{}.add(m); }
  bool operator==(const HazardModes&) const = default;
};

// "poison,reorder:3" -> modes; an empty string is no mode. Returns an error
// message naming the bad word and the known modes (empty when it parsed).
std::string parseHazardModes(std::string_view text, HazardModes& out);
// The list back in that spelling ("none" for no mode).
std::string hazardModesLabel(const HazardModes& modes);
// What the modes change in the plan (no-alias, alias-shuffle, reorder, no-cull;
// rgraph/graph.h's CompileOptions), set in `options`.
void applyHazardModes(const HazardModes& modes, CompileOptions& options);

}  // namespace rgraph
