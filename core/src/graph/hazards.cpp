// Hazard mode names (rgraph/hazards.h).
#include "rgraph/hazards.h"

#include <charconv>

#include "rgraph/graph.h"

namespace rgraph {

std::string_view hazardModeName(HazardMode mode) {
  switch (mode) {
    case HazardMode::poison: return "poison";
    case HazardMode::noAlias: return "no-alias";
    case HazardMode::aliasShuffle: return "alias-shuffle";
    case HazardMode::reorder: return "reorder";
    case HazardMode::stateScramble: return "state-scramble";
    case HazardMode::noCull: return "no-cull";
  }
  return "?";
}

namespace {
std::string knownModes() {
  std::string s;
  for (HazardMode m : kHazardModes) s += (s.empty() ? "" : ", ") + std::string(hazardModeName(m));
  return s + " (reorder:K picks the K-th seeded order)";
}
}  // namespace

std::string parseHazardModes(std::string_view text, HazardModes& out) {
  HazardModes modes;
  while (!text.empty()) {
    const size_t comma = text.find(',');
    std::string_view word = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    std::string_view arg;
    if (const size_t colon = word.find(':'); colon != std::string_view::npos) {
      arg = word.substr(colon + 1);
      word = word.substr(0, colon);
    }
    bool known = false;
    for (HazardMode m : kHazardModes)
      if (word == hazardModeName(m)) {
        known = true;
        modes.add(m);
        if (m == HazardMode::reorder && !arg.empty()) {
          uint32_t k = 0;
          const auto [end, ec] = std::from_chars(arg.data(), arg.data() + arg.size(), k);
          if (ec != std::errc() || end != arg.data() + arg.size() || k == 0 || k > 1000)
            return "hazard mode 'reorder:" + std::string(arg) + "': K must be a whole number from 1 to 1000";
          modes.reorder = k;
        } else if (!arg.empty()) {
          return "hazard mode '" + std::string(word) + "' takes no ':" + std::string(arg) + "'";
        }
      }
    if (!known) return "unknown hazard mode '" + std::string(word) + "' (known: " + knownModes() + ")";
  }
  out = modes;
  return {};
}

void applyHazardModes(const HazardModes& modes, CompileOptions& options) {
  if (modes.has(HazardMode::noAlias)) options.alias = false;
  options.reverseAliasing = modes.has(HazardMode::aliasShuffle);
  options.reorderSeed = modes.has(HazardMode::reorder) ? modes.reorder : 0;
  options.cull = !modes.has(HazardMode::noCull);
}

std::string hazardModesLabel(const HazardModes& modes) {
  std::string s;
  for (HazardMode m : kHazardModes) {
    if (!modes.has(m)) continue;
    if (!s.empty()) s += ',';
    s += hazardModeName(m);
    if (m == HazardMode::reorder) s += ":" + std::to_string(modes.reorder);
  }
  return s.empty() ? "none" : s;
}

}  // namespace rgraph
