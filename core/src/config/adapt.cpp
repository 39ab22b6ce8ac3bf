#include "rgraph/adapt.h"

#include <algorithm>
#include <set>

#include "rgraph/registry.h"

namespace rgraph {

AdaptReport adaptToScene(PipelineConfig& pipeline, const PassRegistry& registry, const SceneFeatures& features) {
  AdaptReport report;
  for (size_t i = 0; i < pipeline.graph.passes.size(); ++i) {
    PassDecl& pass = pipeline.graph.passes[i];
    const PassTypeDesc* type = registry.find(pass.type);
    if (!type || !type->adapt || !pass.enabled) continue;
    PassAdaptation a;
    a.params = pipeline.params[i];
    type->adapt(features, a);
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
