// The plan's promise to its readers (see the comment above Plan in
// rgraph/graph.h), as code, and how plan indices print.
#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph {

template <class Tag>
std::ostream& operator<<(std::ostream& os, PlanIndex<Tag> i) {
  if (!i.valid()) return os << "none";
  return os << i.value();
}
template std::ostream& operator<<(std::ostream&, PassIndex);
template std::ostream& operator<<(std::ostream&, StepIndex);
template std::ostream& operator<<(std::ostream&, ResourceIndex);
template std::ostream& operator<<(std::ostream&, PhysicalIndex);

namespace {

template <class Tag>
bool inRange(PlanIndex<Tag> i, size_t size) {
  return i.valid() && i.value() < size;
}

}  // namespace

std::string checkPlanContract(const Plan& plan) {
  if (plan.bindings.size() != plan.passes.size())
    return std::to_string(plan.bindings.size()) + " binding lists for " + std::to_string(plan.passes.size()) +
           " passes";
  for (uint32_t p = 0; p < plan.passes.size(); ++p)
    if (plan.passes[p].decl != PassIndex(p))
      return "pass '" + plan.passes[p].name + "' is not at its declaration index";
  if (!plan.ok()) return {};

  const auto resourceName = [&](ResourceIndex r) { return "resource '" + plan.resource(r).name + "'"; };
  for (uint32_t p = 0; p < plan.passes.size(); ++p)
    for (const BoundUse& u : plan.bindings[p])
      if (!inRange(u.resource, plan.resources.size()))
        return "slot '" + u.slot + "' of pass '" + plan.passes[p].name + "' binds no resource";

  for (uint32_t s = 0; s < plan.order.size(); ++s) {
    if (!inRange(plan.order[s], plan.passes.size())) return "step " + std::to_string(s) + " names no pass";
    const PlannedPass& pp = plan.pass(plan.order[s]);
    if (pp.order != StepIndex(s) || pp.culled) return "pass '" + pp.name + "' is not at its step";
  }

  // Which resources the passes that run touch, from the bindings themselves.
  std::vector<char> used(plan.resources.size(), 0);
  for (PassIndex p : plan.order)
    for (const BoundUse& u : plan.uses(p)) used[u.resource.value()] = 1;
  // Which physical lists each resource (linear: a long chain aliases many
  // resources into one texture).
  std::vector<PhysicalIndex> listedBy(plan.resources.size());
  for (uint32_t t = 0; t < plan.physical.size(); ++t)
    for (ResourceIndex r : plan.physical[t].resources)
      if (inRange(r, plan.resources.size())) listedBy[r.value()] = PhysicalIndex(t);
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const ResourceIndex ri(r);
    const PlannedResource& pr = plan.resource(ri);
    if (used[r] != (inRange(pr.firstPass, plan.order.size()) && inRange(pr.lastPass, plan.order.size())))
      return resourceName(ri) + ": its lifetime does not match the passes that use it";
    if (pr.physical.valid()) {
      if (!inRange(pr.physical, plan.physical.size())) return resourceName(ri) + " has a physical out of range";
      if (pr.imported || !used[r]) return resourceName(ri) + " has a physical but is imported or unused";
      if (listedBy[r] != pr.physical) return resourceName(ri) + " is not listed by its physical";
    } else if (used[r] && !pr.imported) {
      return resourceName(ri) + " is used but neither imported nor given a physical";
    }
  }

  // A live history and its source: linked both ways, each alone on a
  // physical of its own (the executor copies one into the other after the
  // frame), both alive for the whole frame.
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const ResourceIndex ri(r);
    const PlannedResource& pr = plan.resource(ri);
    if (!pr.history.valid()) continue;
    if (!inRange(pr.history, plan.resources.size()) || plan.resource(pr.history).historyOf != ri)
      return resourceName(ri) + " and its history are not linked both ways";
    for (ResourceIndex x : {ri, pr.history}) {
      const PlannedResource& xr = plan.resource(x);
      if (!xr.physical.valid() || plan.physicalTexture(xr.physical).resources.size() != 1)
        return resourceName(x) + " keeps a history but does not own its physical";
      if (xr.firstPass != StepIndex(0) || xr.lastPass != StepIndex(static_cast<uint32_t>(plan.order.size() - 1)))
        return resourceName(x) + " keeps a history but does not live for the whole frame";
    }
  }
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const ResourceIndex of = plan.resources[r].historyOf;
    if (of.valid() && (!inRange(of, plan.resources.size()) || plan.resource(of).history != ResourceIndex(r)))
      return resourceName(ResourceIndex(r)) + " is a history whose source does not name it";
  }

  if (!inRange(plan.outputResource, plan.resources.size())) return "no output resource";
  const PlannedResource& out = plan.resource(plan.outputResource);
  if (out.kind != ResourceKind::texture || !used[plan.outputResource.value()])
    return "output " + resourceName(plan.outputResource) + " is not a texture used by a pass that runs";
  return {};
}

}  // namespace rgraph
