// Terse construction of GraphDescs for the graph tests.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph::testgen {

inline SourceLocation at(int line, int column = 1, std::string path = {}) {
  SourceLocation l;
  l.file = "graph.json";
  l.line = line;
  l.column = column;
  l.path = std::move(path);
  return l;
}

inline ResourceDecl tex(std::string name, Format f = Format::rgba8, SizeSpec size = SizeSpec::output(),
                        uint32_t mips = 1, uint32_t samples = 1) {
  ResourceDecl r;
  r.name = std::move(name);
  r.kind = ResourceKind::texture;
  r.texture.format = f;
  r.texture.size = size;
  r.texture.mips = mips;
  r.texture.samples = samples;
  return r;
}

inline ResourceDecl importedTex(std::string name, bool hasContent = true, Format f = Format::rgba8) {
  ResourceDecl r = tex(std::move(name), f);
  r.imported = true;
  r.importedHasContent = hasContent;
  return r;
}

inline ResourceDecl buffer(std::string name, uint64_t bytes) {
  ResourceDecl r;
  r.name = std::move(name);
  r.kind = ResourceKind::buffer;
  r.bufferBytes = bytes;
  return r;
}

// Reading use.
inline ResourceUse rd(std::string slot, std::string input, Access a = Access::sampled) {
  ResourceUse u;
  u.slot = std::move(slot);
  u.access = a;
  u.input = std::move(input);
  return u;
}

// Writing use of a resource's first version.
inline ResourceUse wr(std::string slot, std::string output, Access a = Access::color_attachment) {
  ResourceUse u;
  u.slot = std::move(slot);
  u.access = a;
  u.output = std::move(output);
  return u;
}

// Read-modify-write: loads `input`, produces `output`.
inline ResourceUse rmw(std::string slot, std::string input, std::string output,
                       Access a = Access::color_attachment) {
  ResourceUse u = wr(std::move(slot), std::move(output), a);
  u.input = std::move(input);
  return u;
}

inline PassDecl pass(std::string name, std::vector<ResourceUse> uses, bool sideEffect = false, bool enabled = true) {
  PassDecl p;
  p.name = std::move(name);
  p.type = "test";
  p.uses = std::move(uses);
  p.sideEffect = sideEffect;
  p.enabled = enabled;
  return p;
}

// Index of a pass by name in a plan (-1 if absent).
inline int passIndex(const Plan& plan, const std::string& name) {
  for (size_t i = 0; i < plan.passes.size(); ++i)
    if (plan.passes[i].name == name) return static_cast<int>(i);
  return -1;
}
inline int orderOf(const Plan& plan, const std::string& name) {
  int i = passIndex(plan, name);
  if (i < 0) return -2;
  const StepIndex s = plan.passes[i].order;
  return s.valid() ? static_cast<int>(s.value()) : -1;
}
inline int resourceIndex(const Plan& plan, const std::string& name) {
  for (size_t i = 0; i < plan.resources.size(); ++i)
    if (plan.resources[i].name == name) return static_cast<int>(i);
  return -1;
}
inline const PlannedResource& res(const Plan& plan, const std::string& name) {
  static const PlannedResource none;
  int i = resourceIndex(plan, name);
  return i < 0 ? none : plan.resources[i];
}
// Names of the passes in execution order.
inline std::vector<std::string> orderNames(const Plan& plan) {
  std::vector<std::string> out;
  for (PassIndex p : plan.order) out.push_back(plan.pass(p).name);
  return out;
}
inline std::vector<const Diagnostic*> withCode(const Plan& plan, DiagCode c) {
  std::vector<const Diagnostic*> out;
  for (const auto& d : plan.diagnostics)
    if (d.code == c) out.push_back(&d);
  return out;
}
inline std::string dumpDiagnostics(const Plan& plan) {
  std::string s;
  for (const auto& d : plan.diagnostics) s += std::string(diagCodeName(d.code)) + ": " + formatDiagnostic(d) + "\n";
  return s;
}

}  // namespace rgraph::testgen
