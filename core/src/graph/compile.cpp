// The graph compiler: validation, versions, ordering, culling, lifetimes and
// aliasing. Pure C++ (no GL). See rgraph/graph.h for the contract.
//
// Outline (every step is linear in the size of the description, apart from the
// heap in the topological sort and the per-descriptor heaps in aliasing; the
// description is large and scattered, so it is swept once and everything after
// works on compact arrays):
//  1. resources: names, resolved extents, descriptor checks.
//  2. one sweep over the passes builds 32-byte use records, emits Plan::passes
//     and Plan::bindings, and registers every write. Versions: the first
//     version of resource R is node R; every in-place write (a writing use with
//     an input) is a node named by its output whose parent is the node its
//     input names. Names resolve through one open-addressing table (no string
//     copies, no allocation per name).
//  3. a DFS from every resource gives each version its resource, its chain
//     successor, and its *effective* version: a disabled pass's in-place write
//     is a pass-through, so its output means the same contents as its input.
//  4. per pass: reads resolved, binding checks, and the edges between enabled
//     passes: RAW (writer of the effective version read -> reader) and WAR
//     (reader of version k -> writer of the next real version).
//  5. Kahn with a min-heap on declaration index (ties keep declaration order);
//     leftovers are cycles, reported as "cycle: a -> b -> a".
//  6. culling: backwards over RAW edges from the writer of the output's final
//     version and from side-effect passes (WAR edges order, they never keep alive).
//  7. lifetimes over the execution order, then greedy aliasing by first use.
// History resources (compile_history.cpp) are checked after the output; a
// history read by a pass that runs keeps its source's writers (step 6), adds
// no edge (the copy happens after the frame), and gives the history and its
// source whole-frame lifetimes and textures of their own (step 7).
//
// The steps are member functions of Compiler (compile_internal.h), one file
// per subject.
#include <cassert>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compile_internal.h"
#include "rgraph/diagnostics.h"  // closestMatch

namespace rgraph {
namespace graph_detail {

void Compiler::run() {
  plan_.output = o_.output;
  nRes_ = static_cast<uint32_t>(d_.resources.size());
  nPass_ = static_cast<uint32_t>(d_.passes.size());
  resources();
  sweep();
  chains();
  resolve();
  output();
  history();
  order();
  if (!cyclic_) {
    cull();
    lifetimesAndAliasing();
  }
  finish();
}

Diagnostic& Compiler::diag(DiagCode code, std::string message, std::string_view pass, std::string_view slot,
                           std::string_view resource, const SourceLocation& where) {
  Diagnostic dg;
  dg.code = code;
  dg.severity = Severity::error;
  dg.message = std::move(message);
  dg.pass = pass;
  dg.slot = slot;
  dg.resource = resource;
  dg.where = where;
  plan_.diagnostics.push_back(std::move(dg));
  return plan_.diagnostics.back();
}

// Budgeted: see kSuggestionBudget.
std::string Compiler::suggestion(std::string_view word) {
  if (candidates_.empty()) {
    candidates_.reserve(nRes_ + defUse_.size());
    for (const auto& r : d_.resources) candidates_.push_back(r.name);
    for (int f : defUse_) candidates_.push_back(u_[f].ru->output);
  }
  if (candidates_.size() > kSuggestionBudget - suggestionWork_) return {};
  suggestionWork_ += candidates_.size();
  std::string best = closestMatch(word, candidates_);
  if (best.empty() || best == word) return {};
  return " (did you mean " + q(best) + "?)";
}

// Writes the per-pass and per-resource results into the plan.
void Compiler::finish() {
  for (uint32_t i = 0; i < plan_.order.size(); ++i) plan_.passes[plan_.order[i].value()].order = StepIndex(i);
  for (uint32_t p = 0; p < nPass_; ++p) {
    PlannedPass& pp = plan_.passes[p];
    if (!(passFlags_[p] & kEnabled)) {
      pp.culled = true;
      pp.reason = "disabled";
    } else if (!cyclic_ && needed_[p] && !keptFor_.empty() && keptFor_[p] >= 0) {
      // Runs, but only for the next frame: say so where culling reasons show.
      const int h = keptFor_[p];
      pp.reason = "kept: it feeds " + q(resName_[histSrc_[h]]) + ", whose history " + q(resName_[h]) +
                  " is read in the next frame";
    } else if (!cyclic_ && !needed_[p]) {
      pp.culled = true;
      std::string outs, later;
      for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
        if (!u_[f].write) continue;
        const int wv = u_[f].writeVer;
        const std::string_view out = wv >= 0 ? versionName(wv) : std::string_view(u_[f].ru->output);
        if (out.empty()) continue;
        if (!outs.empty()) outs += ", ";
        outs += out;
        if (wv >= 0 && vers_[wv].afterOutput) later = out;
      }
      if (!later.empty())
        pp.reason = "it writes " + q(later) + ", a later version of " + q(resName_[plan_.outputResource.value()]) +
                    " than the output " + q(d_.output) + ", and nothing that reaches the output reads its outputs (" +
                    outs + ")";
      else
        pp.reason = outs.empty() ? "it writes nothing and has no side effect"
                                 : "its outputs (" + outs + ") are never read by a pass that reaches the output";
    }
  }
  plan_.resources.resize(nRes_);
  for (uint32_t r = 0; r < nRes_; ++r) {
    const Res& rs = r_[r];
    PlannedResource& pr = plan_.resources[r];
    pr.name = versionName(static_cast<int>(r));
    pr.kind = rs.kind;
    pr.imported = rs.imported;
    pr.extent = rs.extent;
    pr.bytes = rs.bytes;
    pr.persistent = d_.resources[r].persistent;
    if (rs.first >= 0) {
      pr.firstPass = StepIndex(static_cast<uint32_t>(rs.first));
      pr.lastPass = StepIndex(static_cast<uint32_t>(rs.last));
    }
    if (rs.physical >= 0) pr.physical = PhysicalIndex(static_cast<uint32_t>(rs.physical));
    // Linked only when the history is live (read by a pass that runs): then
    // both have textures of their own for the executor's copy.
    if (historyCount_ > 0 && histSrc_[r] >= 0 && rs.physical >= 0 && r_[histSrc_[r]].physical >= 0) {
      pr.historyOf = ResourceIndex(static_cast<uint32_t>(histSrc_[r]));
      plan_.resources[histSrc_[r]].history = ResourceIndex(r);
    }
    const uint32_t b = resVersionsBegin_[r], e = resVersionsBegin_[r + 1];
    pr.versions.reserve(e - b);
    for (uint32_t i = b; i < e; ++i) pr.versions.emplace_back(versionName(preorder_[i]));
  }
}

}  // namespace graph_detail

Plan compile(const GraphDesc& desc, const CompileOptions& options) {
  Plan plan = graph_detail::compileSubresources(desc, options);
  assert(checkPlanContract(plan).empty());  // rgraph/graph.h: what the plan promises its readers
  return plan;
}

}  // namespace rgraph
