// Sampler-state names (rgraph/sampler_state.h): one table per kind, read both
// ways, so that the config, messages and docs spell them alike.
#include "rgraph/sampler_state.h"

#include <cstdio>

namespace rgraph {
namespace {

constexpr std::array<std::string_view, 2> kFilters = {"nearest", "linear"};
constexpr std::array<std::string_view, 3> kMipFilters = {"none", "nearest", "linear"};
constexpr std::array<std::string_view, 4> kWraps = {"clamp", "repeat", "mirror", "border"};
constexpr std::array<std::string_view, 9> kCompares = {"none",          "never",   "less",  "less_equal", "equal",
                                                       "not_equal",     "greater_equal", "greater", "always"};

template <class E, size_t N>
std::optional<E> parse(const std::array<std::string_view, N>& names, std::string_view s) {
  for (size_t i = 0; i < N; ++i)
    if (names[i] == s) return static_cast<E>(i);
  return std::nullopt;
}

template <size_t N>
std::vector<std::string> all(const std::array<std::string_view, N>& names) {
  return std::vector<std::string>(names.begin(), names.end());
}

std::string number(float v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", static_cast<double>(v));
  return b;
}

}  // namespace

std::string_view filterName(SamplerState::Filter f) { return kFilters[static_cast<size_t>(f)]; }
std::string_view mipFilterName(SamplerState::MipFilter f) { return kMipFilters[static_cast<size_t>(f)]; }
std::string_view wrapName(SamplerState::Wrap w) { return kWraps[static_cast<size_t>(w)]; }
std::string_view compareName(SamplerState::Compare c) { return kCompares[static_cast<size_t>(c)]; }
std::optional<SamplerState::Filter> parseFilter(std::string_view s) { return parse<SamplerState::Filter>(kFilters, s); }
std::optional<SamplerState::MipFilter> parseMipFilter(std::string_view s) {
  return parse<SamplerState::MipFilter>(kMipFilters, s);
}
std::optional<SamplerState::Wrap> parseWrap(std::string_view s) { return parse<SamplerState::Wrap>(kWraps, s); }
std::optional<SamplerState::Compare> parseCompare(std::string_view s) {
  return parse<SamplerState::Compare>(kCompares, s);
}
std::vector<std::string> filterNames() { return all(kFilters); }
std::vector<std::string> mipFilterNames() { return all(kMipFilters); }
std::vector<std::string> wrapNames() { return all(kWraps); }
std::vector<std::string> compareNames() { return all(kCompares); }

std::string describeSampler(const SamplerState& s) {
  std::string out = std::string(filterName(s.filter)) + ", mip " + std::string(mipFilterName(s.mip)) + ", wrap ";
  if (s.wrap[0] == s.wrap[1] && s.wrap[1] == s.wrap[2])
    out += wrapName(s.wrap[0]);
  else
    out += std::string(wrapName(s.wrap[0])) + "/" + std::string(wrapName(s.wrap[1])) + "/" +
           std::string(wrapName(s.wrap[2]));
  for (auto w : s.wrap)
    if (w == SamplerState::Wrap::border) {
      out += " (border " + number(s.border[0]) + " " + number(s.border[1]) + " " + number(s.border[2]) + " " +
             number(s.border[3]) + ")";
      break;
    }
  out += ", compare " + std::string(compareName(s.compare));
  if (s.anisotropy > 1.0f) out += ", anisotropy " + number(s.anisotropy);
  return out;
}

}  // namespace rgraph
