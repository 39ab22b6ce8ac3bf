// The config Builder: a pass's "samplers" object, per-slot overrides of the
// sampler state its type declares (rgraph/sampler_state.h). See
// docs/pipeline-format.md for the syntax. Every bad key or value is an error
// at its own location; the rest of the entry is still read.
#include <string>
#include <vector>

#include "config_builder.h"
#include "rgraph/pass.h"

namespace rgraph::config_detail {

namespace {

const std::vector<std::string> kSamplerKeys = {"filter", "mip", "wrap", "border", "compare", "anisotropy"};
const std::vector<std::string> kWrapAxes = {"s", "t", "r"};

}  // namespace

// Reads a named choice (filter, mip, wrap, compare): `parse` maps a name to
// its value; an unknown name lists the choices.
template <class E, class Parse>
bool Builder::samplerChoice(const Json& v, const std::string& pointer, const std::string& what,
                            const std::vector<std::string>& names, Parse parse, E& out, const std::string& passName) {
  if (!v.is_string()) {
    typeError(pointer, "a " + what + " name (one of " + quotedList(names) + ")", v);
    diags_.back().pass = passName;
    return false;
  }
  if (auto e = parse(v.get<std::string>())) {
    out = *e;
    return true;
  }
  const std::string hint = didYouMean(v.get<std::string>(), names);
  error(DiagCode::config_schema, at(pointer),
        "unknown " + what + " '" + v.get<std::string>() + "'" +
            (hint.empty() ? "; expected one of " + quotedList(names) : hint))
      .pass = passName;
  return false;
}

void Builder::checkSamplerOverrides(const Json& samplers, const std::string& pointer, const PassInfo& info,
                                    const std::string& passName) {
  const size_t passIndex = config_.graph.passes.size();  // this pass is pushed after checkPass
  if (!samplers.is_object()) {
    typeError(pointer, "an object mapping sampled slots to sampler states", samplers);
    diags_.back().pass = passName;
    return;
  }
  if (!info.type) return;  // an unknown type is reported already
  std::vector<SamplerOverride> out;
  for (auto it = samplers.begin(); it != samplers.end(); ++it) {
    const std::string vp = pointer + "/" + escapePointerToken(it.key());
    const SlotDecl* slot = info.type->findSlot(it.key());
    if (!slot) {
      std::vector<std::string> names;
      for (const auto& s : info.type->slots)
        if (s.access == Access::sampled) names.push_back(s.name);
      std::string hint = didYouMean(it.key(), names);
      if (hint.empty())
        hint = names.empty() ? "; it has no sampled slots" : "; its sampled slots are " + quotedList(names);
      Diagnostic& d = error(DiagCode::unknown_slot, keyAt(vp), info.label + " has no slot '" + it.key() + "'" + hint);
      d.pass = passName;
      d.slot = it.key();
      continue;
    }
    if (slot->access != Access::sampled) {
      Diagnostic& d = error(DiagCode::config_schema, keyAt(vp),
                            "slot '" + slot->name + "' of " + info.label + " is not sampled (" +
                                std::string(accessName(slot->access)) + "): only sampled slots have a sampler state");
      d.pass = passName;
      d.slot = slot->name;
      continue;
    }
    if (!it->is_object()) {
      typeError(vp, "a sampler state object (keys " + quotedList(kSamplerKeys) + ")", *it);
      diags_.back().pass = passName;
      continue;
    }
    SamplerOverride o;
    o.slot = slot->name;
    o.where = keyAt(vp);
    o.state = slot->sampler.value_or(SamplerState{});
    readSamplerState(*it, vp, info, passName, o.state);
    out.push_back(std::move(o));
  }
  if (out.empty()) return;
  if (config_.samplers.size() <= passIndex) config_.samplers.resize(passIndex + 1);
  config_.samplers[passIndex] = std::move(out);
}

void Builder::readSamplerState(const Json& object, const std::string& pointer, const PassInfo& info,
                               const std::string& passName, SamplerState& s) {
  const size_t before = diags_.size();
  checkKeys(object, pointer, kSamplerKeys, "sampler key");
  for (size_t i = before; i < diags_.size(); ++i) diags_[i].pass = passName;
  bool borderGiven = false;
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string vp = pointer + "/" + escapePointerToken(it.key());
    const std::string& key = it.key();
    if (key == "filter") {
      samplerChoice(*it, vp, "filter", filterNames(), parseFilter, s.filter, passName);
    } else if (key == "mip") {
      samplerChoice(*it, vp, "mip filter", mipFilterNames(), parseMipFilter, s.mip, passName);
    } else if (key == "compare") {
      samplerChoice(*it, vp, "compare mode", compareNames(), parseCompare, s.compare, passName);
    } else if (key == "wrap") {
      readSamplerWrap(*it, vp, passName, s);
    } else if (key == "border") {
      borderGiven = readSamplerBorder(*it, vp, passName, s) || borderGiven;
    } else if (key == "anisotropy") {
      if (!it->is_number()) {
        typeError(vp, "a number from 1 to 16", *it);
        diags_.back().pass = passName;
      } else if (double a = it->get<double>(); !(a >= 1.0 && a <= 16.0)) {
        error(DiagCode::config_schema, at(vp),
              "anisotropy " + describeValue(*it) + " is out of range: from 1 (off) to 16 (the executor clamps it "
              "to the device's maximum)")
            .pass = passName;
      } else {
        s.anisotropy = static_cast<float>(a);
      }
    }
  }
  const bool borderWrap = s.wrap[0] == SamplerState::Wrap::border || s.wrap[1] == SamplerState::Wrap::border ||
                          s.wrap[2] == SamplerState::Wrap::border;
  if (borderGiven && !borderWrap) {
    Diagnostic& d = error(DiagCode::config_schema, at(pointer + "/border"),
                          "a border colour has no effect unless an axis wraps with \"border\" (slot '" +
                              pointer.substr(pointer.rfind('/') + 1) + "' of " + info.label + " samples with " +
                              describeSampler(s) + ")");
    d.severity = Severity::warning;
    d.pass = passName;
  }
}

// "wrap": one mode for every axis, or {"s": ..., "t": ..., "r": ...} (axes
// left out keep the declared mode).
void Builder::readSamplerWrap(const Json& v, const std::string& pointer, const std::string& passName,
                              SamplerState& s) {
  if (v.is_string()) {
    SamplerState::Wrap w{};
    if (samplerChoice(v, pointer, "wrap mode", wrapNames(), parseWrap, w, passName)) s.wrap = {w, w, w};
    return;
  }
  if (!v.is_object()) {
    typeError(pointer, "a wrap mode (one of " + quotedList(wrapNames()) + ") or an object of axes \"s\", \"t\", \"r\"",
              v);
    diags_.back().pass = passName;
    return;
  }
  const size_t before = diags_.size();
  checkKeys(v, pointer, kWrapAxes, "wrap axis");
  for (size_t i = before; i < diags_.size(); ++i) diags_[i].pass = passName;
  for (size_t a = 0; a < kWrapAxes.size(); ++a) {
    auto it = v.find(kWrapAxes[a]);
    if (it != v.end())
      samplerChoice(*it, pointer + "/" + kWrapAxes[a], "wrap mode", wrapNames(), parseWrap, s.wrap[a], passName);
  }
}

// "border": [r, g, b, a], four numbers a float holds. Returns whether it was read.
bool Builder::readSamplerBorder(const Json& v, const std::string& pointer, const std::string& passName,
                                SamplerState& s) {
  if (!v.is_array() || v.size() != 4) {
    if (v.is_array())
      error(DiagCode::config_schema, at(pointer),
            "a border colour has 4 components (r, g, b, a), got " + std::to_string(v.size()))
          .pass = passName;
    else
      typeError(pointer, "a border colour (an array of 4 numbers)", v);
      diags_.back().pass = passName;
    return false;
  }
  std::array<float, 4> c{};
  bool ok = true;
  for (size_t i = 0; i < 4; ++i) {
    const std::string cp = pointer + "/" + std::to_string(i);
    if (!v[i].is_number()) {
      typeError(cp, "a number", v[i]);
      diags_.back().pass = passName;
      ok = false;
    } else if (std::string why = floatProblem(v[i].get<double>()); !why.empty()) {
      error(DiagCode::config_schema, at(cp), "border colour component " + describeValue(v[i]) + ": " + why).pass =
          passName;
      ok = false;
    } else {
      c[i] = static_cast<float>(v[i].get<double>());
    }
  }
  if (ok) s.border = c;
  return ok;
}

}  // namespace rgraph::config_detail

namespace rgraph {

std::optional<SamplerState> slotSamplerState(const PipelineConfig& pipeline, size_t pass, const SlotDecl& slot,
                                             SourceLocation* where) {
  if (pass < pipeline.samplers.size())
    for (const SamplerOverride& o : pipeline.samplers[pass])
      if (o.slot == slot.name) {
        if (where) *where = o.where;
        return o.state;
      }
  return slot.sampler;
}

}  // namespace rgraph
