#include "rgraph/adapt.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <set>

#include "rgraph/registry.h"

namespace rgraph {

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// The declared resource a version name is of, as the compiler resolves it: a
// resource's name is its first version; an in-place write's output is of
// its input's resource. nullptr when no resource has that version.
ResourceDecl* resourceOfVersion(GraphDesc& graph, const std::string& version) {
  std::map<std::string, size_t> of;
  for (size_t r = 0; r < graph.resources.size(); ++r) of.emplace(graph.resources[r].name, r);
  for (bool changed = true; changed && !of.count(version);) {
    changed = false;
    for (const PassDecl& p : graph.passes)
      for (const ResourceUse& u : p.uses) {
        if (u.input.empty() || u.output.empty() || !isWriteAccess(u.access) || of.count(u.output)) continue;
        if (auto it = of.find(u.input); it != of.end()) {
          of.emplace(u.output, it->second);
          changed = true;
        }
      }
  }
  auto it = of.find(version);
  return it == of.end() ? nullptr : &graph.resources[it->second];
}

// The textures the template's slots bind get the layer counts the hook asks
// for. Imported textures (owned by the caller), cubes and buffers keep
// their shape: a note says so.
void applyReshape(PipelineConfig& pipeline, const PassDecl& pass, const PassAdaptation& a, AdaptReport& report) {
  for (const PassAdaptation::Reshape& r : a.reshape) {
    if (r.layers == 0 && r.size == 0 && r.bytes == 0) continue;
    auto use = std::find_if(pass.uses.begin(), pass.uses.end(), [&](const ResourceUse& u) { return u.slot == r.slot; });
    const std::string prefix = "pass " + q(pass.name) + ": slot " + q(r.slot);
    if (use == pass.uses.end()) {
      report.notes.push_back(prefix + " is not bound: nothing reshaped");
      continue;
    }
    const std::string& version = use->output.empty() ? use->input : use->output;
    ResourceDecl* res = resourceOfVersion(pipeline.graph, version);
    if (!res) continue;  // an unknown name: the compiler reports it
    if (res->imported) {
      report.notes.push_back(prefix + " binds " + q(res->name) + ", imported: not reshaped");
      continue;
    }
    if (res->kind == ResourceKind::buffer) {
      if (r.bytes) res->bufferBytes = r.bytes;
      continue;
    }
    if (res->texture.cube && r.layers) {
      report.notes.push_back(prefix + " binds " + q(res->name) + ", a cube map: not reshaped to " +
                             std::to_string(r.layers) + " layers");
      continue;
    }
    if (r.layers) res->texture.layers = r.layers;
    if (r.size) res->texture.size = SizeSpec::absolute(r.size, r.size);
  }
}

// An instance: the template under its own name and params, binding only the
// slots listed, each narrowed to its part. Locations stay the template's.
PassDecl makeInstance(const PassDecl& pass, const ExpandedPass& e) {
  PassDecl inst = pass;
  inst.name = pass.name + "." + e.suffix;
  inst.uses.clear();
  for (const ResourceUse& u : pass.uses) {
    auto b = std::find_if(e.bindings.begin(), e.bindings.end(),
                          [&](const ExpandedPass::Binding& b) { return b.slot == u.slot; });
    if (b == e.bindings.end()) continue;
    ResourceUse& kept = inst.uses.emplace_back(u);
    if (b->part) kept.sub = *b->part;
  }
  return inst;
}

// Replaces pass `i` by its instances (parallel vectors kept in step) and
// returns how many there are.
size_t expandPass(PipelineConfig& pipeline, size_t i, std::vector<ExpandedPass>& expand,
                  const std::vector<std::string>& hookNotes, AdaptReport& report) {
  const PassDecl pass = pipeline.graph.passes[i];
  std::vector<PassDecl> passes;
  std::vector<ParamSet> params;
  std::vector<std::vector<SamplerOverride>> samplers;
  const bool hasSamplers = i < pipeline.samplers.size();
  std::string names;
  for (ExpandedPass& e : expand) {
    passes.push_back(makeInstance(pass, e));
    params.push_back(std::move(e.params));  // moved, here and below: an expansion can make dozens
    names += (names.empty() ? "" : ", ") + passes.back().name;
    if (!hasSamplers) continue;
    std::vector<SamplerOverride>& kept = samplers.emplace_back();
    for (const SamplerOverride& s : pipeline.samplers[i])
      if (std::any_of(passes.back().uses.begin(), passes.back().uses.end(),
                      [&](const ResourceUse& u) { return u.slot == s.slot; }))
        kept.push_back(s);
  }
  auto replace = [i](auto& vec, auto& with) {
    vec.erase(vec.begin() + static_cast<std::ptrdiff_t>(i));
    vec.insert(vec.begin() + static_cast<std::ptrdiff_t>(i), std::make_move_iterator(with.begin()),
               std::make_move_iterator(with.end()));
  };
  replace(pipeline.graph.passes, passes);
  replace(pipeline.params, params);
  if (hasSamplers) replace(pipeline.samplers, samplers);
  if (expand.empty()) {
    std::string why;
    for (const std::string& n : hookNotes) why += (why.empty() ? "" : "; ") + n;
    report.notes.push_back("pass " + q(pass.name) + ": removed (" +
                           (why.empty() ? std::string("its adapt hook made no instances") : why) + ")");
  } else {
    for (const std::string& n : hookNotes) report.notes.push_back("pass " + q(pass.name) + ": " + n);
    report.notes.push_back("pass " + q(pass.name) + ": expanded into " + std::to_string(expand.size()) +
                           (expand.size() == 1 ? " pass (" : " passes (") + names + ")");
  }
  return expand.size();
}

}  // namespace

AdaptReport adaptToScene(PipelineConfig& pipeline, const PassRegistry& registry, const SceneFeatures& features) {
  AdaptReport report;
  for (size_t i = 0; i < pipeline.graph.passes.size(); ++i) {
    PassDecl& pass = pipeline.graph.passes[i];
    const PassTypeDesc* type = registry.find(pass.type);
    if (!type || !type->adapt || !pass.enabled) continue;
    PassAdaptation a;
    a.params = pipeline.params[i];
    type->adapt(features, a);
    if (!a.report.empty()) report.tables.push_back({pass.name, a.report});
    if (a.expand && !a.disable) {
      applyReshape(pipeline, pass, a, report);
      // The instances are not adapted again: the hook made them for these features.
      const size_t n = expandPass(pipeline, i, *a.expand, a.notes, report);
      i = i + n - 1;  // n == 0: the next pass is at i now (the loop's ++i wraps the -1)
      continue;
    }
    for (const auto& note : a.notes) report.notes.push_back("pass '" + pass.name + "': " + note);
    pipeline.params[i] = std::move(a.params);
    if (a.disable) {
      pass.enabled = false;
      continue;
    }
    // Only optional slots may be dropped: a required one stays (the hook is wrong).
    auto droppable = [&](const ResourceUse& use) {
      if (std::find(a.unbindSlots.begin(), a.unbindSlots.end(), use.slot) == a.unbindSlots.end()) return false;
      const SlotDecl* slot = type->findSlot(use.slot);
      return slot && !slot->required;
    };
    pass.uses.erase(std::remove_if(pass.uses.begin(), pass.uses.end(), droppable), pass.uses.end());
  }
  return report;
}
uint32_t gbufferBytesPerPixel(const PipelineConfig& pipeline, const Plan& plan, const PassRegistry& registry) {
  std::set<ResourceIndex> counted;
  uint32_t bytes = 0;
  for (size_t i = 0; i < plan.passes.size() && i < pipeline.graph.passes.size(); ++i) {
    const PassTypeDesc* type = registry.find(pipeline.graph.passes[i].type);
    if (plan.passes[i].culled || !type) continue;
    for (const BoundUse& use : plan.bindings[i]) {
      const SlotDecl* slot = type->findSlot(use.slot);
      if (!slot || !slot->gbufferTarget) continue;
      if (!isAttachmentAccess(use.access) || !use.resource.valid() || !counted.insert(use.resource).second) continue;
      if (!plan.resource(use.resource).firstPass.valid()) continue;
      const TextureDesc& t = pipeline.graph.resources[use.resource.value()].texture;
      bytes += formatInfo(t.format).bytesPerPixel * t.samples;
    }
  }
  return bytes;
}

}  // namespace rgraph
