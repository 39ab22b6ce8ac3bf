// The config Builder: passes, their "inputs"/"outputs" bindings, required
// slots, and parameters. See config_builder.h.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config_builder.h"

namespace rgraph::config_detail {

namespace {

const std::vector<std::string> kPassKeys = {"name",   "type",    "description", "enabled", "side_effect",
                                            "inputs", "outputs", "params",      "jitter",  "samplers"};

}  // namespace

void Builder::checkPasses(const Json& passes) {
  std::map<std::string, std::string> names;  // pass name -> pointer of its first "name"
  for (size_t i = 0; i < passes.size(); ++i) {
    const Json& pass = passes[i];
    PassInfo info;
    info.pointer = "/passes/" + std::to_string(i);
    PassDecl decl;
    decl.where = at(info.pointer);
    ParamSet params;
    if (!pass.is_object()) {
      typeError(info.pointer, "a pass object", pass);
    } else {
      checkPass(pass, info, names, decl, params);
    }
    config_.graph.passes.push_back(std::move(decl));
    config_.params.push_back(std::move(params));
    passInfo_.push_back(std::move(info));
  }
}

void Builder::checkPass(const Json& pass, PassInfo& info, std::map<std::string, std::string>& names, PassDecl& decl,
                        ParamSet& params) {
  const std::string& p = info.pointer;
  std::set<std::string> typos = checkKeys(pass, p, kPassKeys, "pass key");
  info.inputsTypo = typos.count("inputs") != 0;
  info.outputsTypo = typos.count("outputs") != 0;
  auto member = [&](const char* key) -> const Json* {
    auto it = pass.find(key);
    return it == pass.end() ? nullptr : &*it;
  };

  if (const Json* name = member("name"); !name) {
    if (!typos.count("name")) error(DiagCode::config_schema, at(p), "missing required key 'name'");
  } else if (!name->is_string()) {
    typeError(p + "/name", "a pass name (string)", *name);
  } else if (name->get<std::string>().empty()) {
    error(DiagCode::config_schema, at(p + "/name"), "a pass name must not be empty");
  } else {
    decl.name = name->get<std::string>();
    auto [it, inserted] = names.emplace(decl.name, p + "/name");
    if (!inserted) {
      SourceLocation first = at(it->second);
      error(DiagCode::duplicate_pass, at(p + "/name"),
            "pass name '" + decl.name + "' is already used (first at line " + std::to_string(first.line) + ")")
          .pass = decl.name;
    }
  }
  std::string display = decl.name.empty() ? "#" + p.substr(p.rfind('/') + 1) : "'" + decl.name + "'";

  if (const Json* type = member("type"); !type) {
    if (!typos.count("type"))
      error(DiagCode::config_schema, at(p), "missing required key 'type' (the pass type)").pass = decl.name;
  } else if (!type->is_string()) {
    typeError(p + "/type", "a pass type name (string)", *type);
  } else {
    decl.type = type->get<std::string>();
    info.type = registry_.find(decl.type);
    if (!info.type) {
      std::string best = registry_.suggest(decl.type);
      error(DiagCode::unknown_pass_type, at(p + "/type"),
            "unknown pass type '" + decl.type + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)"))
          .pass = decl.name;
    }
  }
  info.label = "pass " + display + (decl.type.empty() ? "" : " (type " + decl.type + ")");

  if (const Json* d = member("description"); d && !d->is_string()) typeError(p + "/description", "a string", *d);
  if (const Json* enabled = member("enabled")) {
    if (enabled->is_boolean())
      decl.enabled = enabled->get<bool>();
    else
      typeError(p + "/enabled", "true or false", *enabled);
  }
  bool sideEffect = false;
  if (const Json* se = member("side_effect")) {
    if (se->is_boolean())
      sideEffect = se->get<bool>();
    else
      typeError(p + "/side_effect", "true or false", *se);
  }
  decl.sideEffect = sideEffect || (info.type && info.type->sideEffect);
  // false: the pass sees the unjittered camera (a UI overlay drawn over a
  // jittered scene would shimmer).
  if (const Json* jitter = member("jitter")) {
    if (jitter->is_boolean())
      decl.jitter = jitter->get<bool>();
    else
      typeError(p + "/jitter", "true or false", *jitter);
  }

  readBindings(member("inputs"), p + "/inputs", info, decl.name, true);
  readBindings(member("outputs"), p + "/outputs", info, decl.name, false);
  if (info.type) checkSlots(info, decl);

  if (info.type) params = defaultParams(info.type->params);
  if (const Json* ps = member("params")) {
    if (!ps->is_object())
      typeError(p + "/params", "an object of parameter values", *ps);
    else if (info.type)
      checkParams(*ps, p + "/params", info, decl.name, params);
  }
  if (const Json* ss = member("samplers")) checkSamplerOverrides(*ss, p + "/samplers", info, decl.name);
}

// Reads "inputs" or "outputs": slot -> resource/version name.
void Builder::readBindings(const Json* object, const std::string& pointer, PassInfo& info, const std::string& passName,
                           bool inputs) {
  if (!object) return;
  (inputs ? info.hasInputs : info.hasOutputs) = true;
  std::map<std::string, Binding>& out = inputs ? info.inputs : info.outputs;
  if (!object->is_object()) {
    typeError(pointer, std::string("an object mapping ") + (inputs ? "input" : "output") + " slots to names",
              *object);
    return;
  }
  for (auto it = object->begin(); it != object->end(); ++it) {
    (inputs ? info.inputKeys : info.outputKeys).insert(it.key());
    std::string valuePointer = pointer + "/" + escapePointerToken(it.key());
    if (!it->is_string()) {
      typeError(valuePointer, "a resource name (string)", *it);
    } else if (it->get<std::string>().empty()) {
      error(DiagCode::config_schema, at(valuePointer), "expected a resource name, got an empty string").pass =
          passName;
    } else {
      Binding b{{}, valuePointer, {}};
      if (std::string why = parseSubresourceRef(it->get<std::string>(), b.name, b.sub); !why.empty())
        error(DiagCode::config_schema, at(valuePointer), "bad subresource " + why).pass = passName;
      else
        out[it.key()] = std::move(b);
    }
    if (info.type) checkSlotName(it.key(), valuePointer, inputs, info, passName);
  }
}

void Builder::checkSlotName(const std::string& slot, const std::string& pointer, bool inInputs, PassInfo& info,
                            const std::string& passName) {
  const PassTypeDesc& type = *info.type;
  const SlotDecl* decl = type.findSlot(slot);
  if (!decl) {
    std::vector<std::string> names;
    for (const auto& s : type.slots) names.push_back(s.name);
    std::string best = closestMatch(slot, names);
    std::string hint = " (did you mean '" + best + "'?)";
    if (best.empty())
      hint = names.empty() ? "; it has no slots" : "; its slots are " + quotedList(names);
    else
      info.slotTypos.insert(best);
    Diagnostic& d = error(DiagCode::unknown_slot, keyAt(pointer),
                          info.label + " has no " + (inInputs ? "input" : "output") + " slot '" + slot + "'" + hint);
    d.pass = passName;
    d.slot = slot;
    return;
  }
  bool writing = isWriteAccess(decl->access);
  if (inInputs && writing && decl->load == SlotDecl::Load::never) {
    Diagnostic& d =
        error(DiagCode::unknown_slot, keyAt(pointer),
              "slot '" + slot + "' of " + info.label + " is output-only (" + std::string(accessName(decl->access)) +
                  ", it cannot load a previous version): bind it under \"outputs\"");
    d.pass = passName;
    d.slot = slot;
  } else if (!inInputs && !writing) {
    Diagnostic& d = error(DiagCode::unknown_slot, keyAt(pointer),
                          "slot '" + slot + "' of " + info.label + " is an input (" +
                              std::string(accessName(decl->access)) + "): bind it under \"inputs\"");
    d.pass = passName;
    d.slot = slot;
  }
}

// Required slots and the ResourceUses, in slot-declaration order.
void Builder::checkSlots(const PassInfo& info, PassDecl& decl) {
  const std::string& p = info.pointer;
  std::string inputsAt = info.hasInputs ? p + "/inputs" : p;
  std::string outputsAt = info.hasOutputs ? p + "/outputs" : p;
  // `input`: the binding is missing from "inputs" (else from "outputs").
  auto missing = [&](bool input, const std::string& message, const std::string& slot) {
    if (info.slotTypos.count(slot)) return;
    if (input ? !info.hasInputs && info.inputsTypo : !info.hasOutputs && info.outputsTypo) return;
    Diagnostic& d = error(DiagCode::missing_slot, at(input ? inputsAt : outputsAt), message);
    d.pass = decl.name;
    d.slot = slot;
  };
  for (const SlotDecl& slot : info.type->slots) {
    bool writing = isWriteAccess(slot.access);
    auto in = info.inputs.find(slot.name);
    auto out = info.outputs.find(slot.name);
    bool mayLoad = writing && slot.load != SlotDecl::Load::never;
    // A slot bound under the wrong object (already reported by
    // checkSlotName) counts as bound, so it is not also reported missing.
    bool inBound = info.inputKeys.count(slot.name) != 0 || (!writing && info.outputKeys.count(slot.name) != 0);
    bool outBound = info.outputKeys.count(slot.name) != 0 || (writing && !mayLoad && info.inputKeys.count(slot.name));
    ResourceUse use;  // the slot as its pass type declares it; what it is bound to below
    use.slot = slot.name;
    use.access = slot.access;
    use.acceptsMultisample = slot.acceptsMultisample;

    if (!writing) {
      if (slot.required && !inBound)
        missing(true, "input '" + slot.name + "' of " + info.label + " is required but not bound", slot.name);
      if (in != info.inputs.end()) {
        use.input = in->second.name;
        use.inputWhere = at(in->second.pointer);
        use.sub = in->second.sub;
        decl.uses.push_back(std::move(use));
      }
      continue;
    }

    if (slot.required && !outBound)
      missing(false, "output '" + slot.name + "' of " + info.label + " is required but not bound", slot.name);
    if (slot.load == SlotDecl::Load::required && !inBound && (slot.required || outBound))
      missing(true,
              "input '" + slot.name + "' of " + info.label +
                  " is required but not bound: the pass loads the previous version of its output '" + slot.name + "'",
              slot.name);
    if (mayLoad && inBound && !outBound && !slot.required)
      missing(false,
              "output '" + slot.name + "' of " + info.label +
                  " is not bound but its input is: name the version the pass produces",
              slot.name);
    if (out != info.outputs.end()) {
      use.output = out->second.name;
      use.outputWhere = at(out->second.pointer);
      use.sub = out->second.sub;
      if (mayLoad && in != info.inputs.end()) {
        use.input = in->second.name;
        use.inputWhere = at(in->second.pointer);
        loadedPart(in->second, out->second, slot.name, decl.name, use.sub);
      }
      decl.uses.push_back(std::move(use));
    }
  }
}

// A slot that loads a version and writes its successor touches one part of
// the texture: the part named on either side, or on both alike.
void Builder::loadedPart(const Binding& in, const Binding& out, const std::string& slot, const std::string& passName,
                         Subresource& sub) {
  if (in.sub == out.sub || in.sub.whole()) return;
  if (out.sub.whole()) {
    sub = in.sub;
    return;
  }
  Diagnostic& d = error(DiagCode::config_schema, at(out.pointer),
                        "slot '" + slot + "' loads '" + subresourceLabel(in.name, in.sub) + "' but writes '" +
                            subresourceLabel(out.name, out.sub) + "'" +
                            "; a slot that loads a version writes the same part of it (name the part once, or alike)");
  d.pass = passName;
  d.slot = slot;
}

// ------------------------------------------------------------ params

void Builder::checkParams(const Json& values, const std::string& pointer, const PassInfo& info,
                          const std::string& passName, ParamSet& params) {
  const PassTypeDesc& type = *info.type;
  for (auto it = values.begin(); it != values.end(); ++it) {
    std::string vp = pointer + "/" + escapePointerToken(it.key());
    const ParamDecl* decl = type.findParam(it.key());
    if (!decl) {
      std::vector<std::string> names;
      for (const auto& pd : type.params) names.push_back(pd.name);
      std::string hint = didYouMean(it.key(), names);
      if (hint.empty()) hint = names.empty() ? "; it has no parameters" : "; its parameters are " + quotedList(names);
      error(DiagCode::unknown_param, keyAt(vp), info.label + " has no parameter '" + it.key() + "'" + hint).pass =
          passName;
      continue;
    }
    if (auto v = checkParam(*decl, *it, vp, info, passName)) params.set(decl->name, std::move(*v));
  }
}

std::optional<ParamValue> Builder::checkParam(const ParamDecl& decl, const Json& v, const std::string& pointer,
                                              const PassInfo& info, const std::string& passName) {
  std::vector<config_detail::ValueProblem> problems;
  std::optional<ParamValue> value = config_detail::checkParamValue(decl, v, pointer, problems);
  for (const auto& p : problems)
    error(p.code, at(p.pointer), "parameter '" + decl.name + "' of " + info.label + ": " + p.message).pass = passName;
  return value;
}

}  // namespace rgraph::config_detail
