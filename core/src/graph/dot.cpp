// Graphviz export of a compiled graph.
#include <array>
#include <string>
#include <string_view>
#include <unordered_map>

#include "rgraph/graph.h"

namespace rgraph {
namespace {

// A DOT double-quoted string (quotes, backslashes and newlines escaped).
std::string dq(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  out += '"';
  return out;
}

constexpr std::array<std::string_view, 12> kPalette = {
    "#a6cee3", "#b2df8a", "#fb9a99", "#fdbf6f", "#cab2d6", "#ffff99",
    "#8dd3c7", "#bebada", "#fb8072", "#80b1d3", "#fdb462", "#b3de69",
};

}  // namespace

std::string toDot(const GraphDesc& desc, const Plan& plan) {
  std::string out;
  out.reserve(256 + desc.passes.size() * 160);
  out += "digraph rgraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=11];\n";
  out += "  edge [fontname=\"Helvetica\", fontsize=9];\n";

  // Passes.
  for (size_t p = 0; p < desc.passes.size(); ++p) {
    const PassDecl& pd = desc.passes[p];
    const PlannedPass* pp = p < plan.passes.size() ? &plan.passes[p] : nullptr;
    std::string label = pd.name;
    if (!pd.type.empty()) label += "\n(" + pd.type + ")";
    if (pp && pp->order.valid()) label += "\n#" + std::to_string(pp->order.value());
    out += "  p" + std::to_string(p) + " [shape=box, label=";
    if (pp && pp->culled) {
      label += "\nculled: " + pp->reason;
      out += dq(label) + ", style=dashed, color=grey, fontcolor=grey, tooltip=" + dq(pp->reason);
    } else {
      out += dq(label);
      if (pd.sideEffect) out += ", peripheries=2";
    }
    out += "];\n";
  }

  // Resource versions, one node per version name.
  std::unordered_map<std::string_view, size_t> node;
  size_t next = 0;
  auto versionNode = [&](std::string_view name, const PlannedResource* r) {
    auto [it, inserted] = node.try_emplace(name, next);
    if (!inserted) return;
    ++next;
    std::string label(name);
    std::string attrs = "shape=ellipse";
    if (!r) {
      label += "\n(unknown)";
      attrs += ", color=red, fontcolor=red";
    } else {
      if (r->imported) {
        label += "\n(imported)";
        attrs += ", peripheries=2";
      }
      if (r->historyOf.valid()) label += "\n(history of " + plan.resource(r->historyOf).name + ")";
      if (r->physical.valid()) {
        label += "\nphys #" + std::to_string(r->physical.value());
        attrs += ", style=filled, fillcolor=\"";
        attrs += kPalette[r->physical.value() % kPalette.size()];
        attrs += "\"";
      } else if (!r->firstPass.valid() && !r->imported) {
        attrs += ", style=dotted";
      }
    }
    if (name == plan.outputVersion && !plan.outputVersion.empty()) {
      label += "\n(output)";
      attrs += ", penwidth=3";
    }
    out += "  v" + std::to_string(it->second) + " [" + attrs + ", label=" + dq(label) + "];\n";
  };
  for (const PlannedResource& r : plan.resources)
    for (const std::string& v : r.versions) versionNode(v, &r);
  for (const PassDecl& pd : desc.passes)
    for (const ResourceUse& u : pd.uses) {
      if (!u.input.empty()) versionNode(u.input, nullptr);
      if (isWriteAccess(u.access) && !u.output.empty()) versionNode(u.output, nullptr);
    }

  // Edges: version -> pass for reads (and loads), pass -> version for writes.
  for (size_t p = 0; p < desc.passes.size(); ++p) {
    const bool culled = p < plan.passes.size() && plan.passes[p].culled;
    const std::string pid = "p" + std::to_string(p);
    const std::string style = culled ? " [color=grey, style=dashed" : " [";
    auto attrs = [&](std::string_view label) {
      std::string a = style;
      if (!label.empty()) {
        if (a.size() > 2) a += ", ";
        a += "label=" + dq(label);
      }
      return a + "]";
    };
    for (const ResourceUse& u : desc.passes[p].uses) {
      const bool write = isWriteAccess(u.access);
      if (!u.input.empty()) {
        out += "  v" + std::to_string(node[u.input]) + " -> " + pid;
        out += attrs(write ? "load " + u.slot : u.slot) + ";\n";
      }
      if (write && !u.output.empty()) {
        out += "  " + pid + " -> v" + std::to_string(node[u.output]);
        out += attrs(u.slot) + ";\n";
      }
    }
  }
  // A history holds its source's last version of the previous frame: the
  // executor copies it after the frame, so the edge crosses into the next one.
  for (const PlannedResource& r : plan.resources) {
    if (!r.history.valid() || r.versions.empty()) continue;
    const PlannedResource& h = plan.resource(r.history);
    auto from = node.find(r.versions.back()), to = node.find(h.name);
    if (from == node.end() || to == node.end()) continue;
    out += "  v" + std::to_string(from->second) + " -> v" + std::to_string(to->second) +
           " [style=dashed, color=\"#1f78b4\", fontcolor=\"#1f78b4\", constraint=false, label=\"next frame\"];\n";
  }
  out += "}\n";
  return out;
}

}  // namespace rgraph
