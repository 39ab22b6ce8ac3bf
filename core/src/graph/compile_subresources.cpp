// Subresources: a slot bound to part of a texture ("bloom.mip[2]",
// "shadow.layer[3]", "env.face[+x]") is compiled by lowering. Each texture
// that any slot binds in part is cut into *cells* along the boundaries of the
// ranges the graph names (one cell per mip level; per array layer, or per run
// of layers no range splits when there are more than kLayerCells), and each
// cell becomes a resource of a lowered description, named by its label
// ("bloom.mip[3]"), its versions likewise ("bloom_up.mip[3]"). A use becomes
// one use per cell it covers. The one compiler then versions, orders, culls
// and checks hazards per cell, so its diagnostics name the subresource;
// lifetimes and aliasing stay per texture (CellUnits). The plan is folded
// back: one resource and one binding per declared one, each binding with its
// resolved range. A graph that binds no part of any texture compiles as it is.
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "compile_internal.h"

namespace rgraph::graph_detail {
namespace {

// Arrays with at most this many layers get one cell per layer (diagnostics
// name single layers); larger ones get a cell per run of layers.
constexpr uint32_t kLayerCells = 64;

struct Span {
  uint32_t begin = 0, end = 0;  // [begin, end)
};

// A texture cut into cells: mip spans x layer spans.
struct Cutting {
  uint32_t mips = 1, layers = 1;
  bool cube = false;
  std::set<uint32_t> mipCuts, layerCuts;  // boundaries the graph's ranges name
  std::vector<Span> mipSpans, layerSpans;
  uint32_t firstCell = 0;  // index of its first cell in the lowered resources

  Subresource cellSub(size_t m, size_t l) const {
    Subresource s;
    if (mips > 1) s.mipBegin = mipSpans[m].begin, s.mipCount = mipSpans[m].end - mipSpans[m].begin;
    if (layers > 1) s.layerBegin = layerSpans[l].begin, s.layerCount = layerSpans[l].end - layerSpans[l].begin;
    return s;
  }
  size_t cellCount() const { return mipSpans.size() * layerSpans.size(); }
};

std::vector<Span> spans(uint32_t count, const std::set<uint32_t>& cuts, bool perElement) {
  std::vector<Span> out;
  uint32_t at = 0;
  for (uint32_t i = 1; i <= count; ++i)
    if (i == count || perElement || cuts.count(i)) {
      out.push_back({at, i});
      at = i;
    }
  return out;
}

class Lowering {
 public:
  Lowering(const GraphDesc& d, const CompileOptions& o) : d_(d), o_(o) {}

  // False: no texture is cut (no slot binds a part of one, or every part was
  // refused: then `diagnostics` says why), so the graph compiles as it is.
  bool lower();
  Plan compileAndFold();
  Diagnostics diagnostics;

 private:
  void mapVersionsToResources();
  int resourceOf(const ResourceUse& u) const;
  bool resolveRange(const PassDecl& p, const ResourceUse& u, int r, Subresource& sub);
  void cut();
  void lowerPasses();
  std::string mangle(const std::string& name, uint32_t r, size_t m, size_t l) const;
  Diagnostic& error(std::string message, const PassDecl& p, const ResourceUse& u, std::string_view resource);

  const GraphDesc& d_;
  const CompileOptions& o_;
  std::unordered_map<std::string, int> versionRes_;  // version name -> declared resource
  std::map<uint32_t, Cutting> cut_;                  // resources bound in part
  std::vector<std::vector<Subresource>> ranges_;     // per pass, per use: the resolved range
  GraphDesc lowered_;
  CellUnits units_;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> useCells_;  // per pass, per use: lowered uses [b, e)
};

Diagnostic& Lowering::error(std::string message, const PassDecl& p, const ResourceUse& u,
                            std::string_view resource) {
  Diagnostic dg;
  dg.code = DiagCode::subresource_range;
  dg.message = std::move(message);
  dg.pass = p.name;
  dg.slot = u.slot;
  dg.resource = resource;
  dg.where = isWriteAccess(u.access) && locationSet(u.outputWhere) ? u.outputWhere : u.inputWhere;
  if (!locationSet(dg.where)) dg.where = p.where;
  diagnostics.push_back(std::move(dg));
  return diagnostics.back();
}

// Which declared resource each version name is of: a resource's name is its
// first version; an in-place write's output is of its input's resource.
// Names the compiler will refuse (unknown, duplicate) map to nothing or to
// the first mapping; it reports them.
void Lowering::mapVersionsToResources() {
  for (size_t r = 0; r < d_.resources.size(); ++r) versionRes_.emplace(d_.resources[r].name, static_cast<int>(r));
  for (bool changed = true; changed;) {
    changed = false;
    for (const PassDecl& p : d_.passes)
      for (const ResourceUse& u : p.uses) {
        if (u.input.empty() || u.output.empty() || !isWriteAccess(u.access) || versionRes_.count(u.output)) continue;
        if (auto it = versionRes_.find(u.input); it != versionRes_.end()) {
          versionRes_.emplace(u.output, it->second);
          changed = true;
        }
      }
  }
}

int Lowering::resourceOf(const ResourceUse& u) const {
  const std::string& name = !u.input.empty() ? u.input : u.output;
  auto it = versionRes_.find(name);
  return it == versionRes_.end() ? -1 : it->second;
}

// The use's range against its texture: counts resolved, indices checked.
bool Lowering::resolveRange(const PassDecl& pass, const ResourceUse& u, int r, Subresource& sub) {
  const ResourceDecl& rd = d_.resources[r];
  const std::string& name = !u.input.empty() ? u.input : u.output;
  const std::string label = subresourceLabel(name, u.sub, rd.texture.cube);
  if (rd.kind == ResourceKind::buffer) {
    error("slot " + q(u.slot) + " binds " + q(label) + ", a part of buffer " + q(rd.name) +
              "; buffers are bound whole (mip, layer and face name parts of textures)",
          pass, u, label);
    return false;
  }
  const uint32_t mips = mipLevels(rd.texture, resolveSize(rd.texture.size, o_.output));
  const uint32_t layers = std::max<uint32_t>(1, arrayLayers(rd.texture));
  sub = u.sub;
  auto check = [&](uint32_t& begin, uint32_t& count, uint32_t total, const char* what, const char* noun) {
    if (count == Subresource::kAll) count = begin < total ? total - begin : 0;
    if (count != 0 && begin < total && count <= total - begin) return true;
    const uint32_t last = count == 0 ? begin : begin + count - 1;
    const std::string valid = std::string(what) + "[0" + (total > 1 ? ".." + std::to_string(total - 1) : "") + "]";
    error("slot " + q(u.slot) + " binds " + q(label) + ", but " + q(rd.name) + " has " + std::to_string(total) + " " +
              noun + (total == 1 ? "" : "s") + " (" + valid + "): " + what + "[" + std::to_string(last) +
              "] is out of range",
          pass, u, label);
    return false;
  };
  const bool mipOk = check(sub.mipBegin, sub.mipCount, mips, "mip", "mip level");
  const bool layerOk = check(sub.layerBegin, sub.layerCount, layers, "layer", "array layer");
  if (!mipOk || !layerOk) return false;
  if (!rd.historyOf.empty()) {
    error("slot " + q(u.slot) + " binds " + q(label) + ", a part of history resource " + q(rd.name) +
              "; history resources are bound whole",
          pass, u, label);
    return false;
  }
  return true;
}

bool Lowering::lower() {
  bool any = false;
  for (const PassDecl& p : d_.passes)
    for (const ResourceUse& u : p.uses) any = any || !u.sub.whole();
  if (!any) return false;
  mapVersionsToResources();
  ranges_.resize(d_.passes.size());
  for (size_t pi = 0; pi < d_.passes.size(); ++pi) {
    const PassDecl& p = d_.passes[pi];
    ranges_[pi].resize(p.uses.size());
    for (size_t i = 0; i < p.uses.size(); ++i) {
      const ResourceUse& u = p.uses[i];
      if (u.sub.whole()) continue;
      const int r = resourceOf(u);
      if (r < 0) continue;  // an unknown name: the compiler reports it
      Subresource sub;
      if (!resolveRange(p, u, r, sub)) continue;
      ranges_[pi][i] = sub;
      Cutting& c = cut_[static_cast<uint32_t>(r)];
      c.mipCuts.insert({sub.mipBegin, sub.mipBegin + sub.mipCount});
      c.layerCuts.insert({sub.layerBegin, sub.layerBegin + sub.layerCount});
    }
  }
  if (cut_.empty()) return false;
  cut();
  lowerPasses();
  return true;
}

// Cells of each texture bound in part, and the lowered resources.
void Lowering::cut() {
  lowered_.resources.reserve(d_.resources.size() + cut_.size() * 8);
  for (uint32_t r = 0; r < d_.resources.size(); ++r) {
    const ResourceDecl& rd = d_.resources[r];
    const uint32_t unit = r;
    units_.rep.push_back(static_cast<uint32_t>(lowered_.resources.size()));
    auto it = cut_.find(r);
    if (it == cut_.end()) {
      units_.of.push_back(unit);
      units_.mip.push_back(0);
      lowered_.resources.push_back(rd);
      continue;
    }
    Cutting& c = it->second;
    c.mips = mipLevels(rd.texture, resolveSize(rd.texture.size, o_.output));
    c.layers = std::max<uint32_t>(1, arrayLayers(rd.texture));
    c.cube = rd.texture.cube;
    c.mipSpans = spans(c.mips, c.mipCuts, true);
    c.layerSpans = spans(c.layers, c.layerCuts, c.layers <= kLayerCells);
    c.firstCell = static_cast<uint32_t>(lowered_.resources.size());
    for (size_t m = 0; m < c.mipSpans.size(); ++m)
      for (size_t l = 0; l < c.layerSpans.size(); ++l) {
        ResourceDecl cell = rd;
        cell.name = subresourceLabel(rd.name, c.cellSub(m, l), c.cube);
        units_.of.push_back(unit);
        units_.mip.push_back(c.mipSpans[m].begin);
        lowered_.resources.push_back(std::move(cell));
      }
  }
}

std::string Lowering::mangle(const std::string& name, uint32_t r, size_t m, size_t l) const {
  if (name.empty()) return name;
  const Cutting& c = cut_.at(r);
  return subresourceLabel(name, c.cellSub(m, l), c.cube);
}

// One lowered use per cell a use covers; uses of textures not cut stay as they are.
void Lowering::lowerPasses() {
  lowered_.output = d_.output;
  lowered_.outputWhere = d_.outputWhere;
  const auto out = versionRes_.find(d_.output);
  if (out != versionRes_.end() && cut_.count(static_cast<uint32_t>(out->second)))
    lowered_.output = mangle(d_.output, static_cast<uint32_t>(out->second), 0, 0);  // level 0, layer 0 is the image
  lowered_.passes.reserve(d_.passes.size());
  useCells_.resize(d_.passes.size());
  for (size_t pi = 0; pi < d_.passes.size(); ++pi) {
    const PassDecl& p = d_.passes[pi];
    PassDecl& lp = lowered_.passes.emplace_back();
    lp.name = p.name, lp.type = p.type, lp.sideEffect = p.sideEffect, lp.enabled = p.enabled, lp.jitter = p.jitter;
    lp.where = p.where;
    for (size_t i = 0; i < p.uses.size(); ++i) {
      const ResourceUse& u = p.uses[i];
      const uint32_t begin = static_cast<uint32_t>(lp.uses.size());
      const int r = resourceOf(u);
      auto it = r < 0 ? cut_.end() : cut_.find(static_cast<uint32_t>(r));
      if (it == cut_.end()) {
        lp.uses.push_back(u);  // not cut (or refused: a buffer, an unknown name)
        lp.uses.back().sub = Subresource{};
      } else {
        const Cutting& c = it->second;
        Subresource s = ranges_[pi][i];
        if (s.mipCount == Subresource::kAll) s = {0, c.mips, 0, c.layers};  // whole, or a range refused
        for (size_t m = 0; m < c.mipSpans.size(); ++m) {
          if (c.mipSpans[m].begin < s.mipBegin || c.mipSpans[m].end > s.mipBegin + s.mipCount) continue;
          for (size_t l = 0; l < c.layerSpans.size(); ++l) {
            if (c.layerSpans[l].begin < s.layerBegin || c.layerSpans[l].end > s.layerBegin + s.layerCount) continue;
            ResourceUse cell = u;
            cell.sub = Subresource{};
            cell.input = mangle(u.input, static_cast<uint32_t>(r), m, l);
            cell.output = mangle(u.output, static_cast<uint32_t>(r), m, l);
            lp.uses.push_back(std::move(cell));
          }
        }
      }
      useCells_[pi].push_back({begin, static_cast<uint32_t>(lp.uses.size())});
    }
  }
}

// The lowered plan, with one resource and one binding per declared one.
Plan Lowering::compileAndFold() {
  Plan low;
  Compiler(lowered_, o_, low, &units_).run();
  Plan plan;
  plan.output = low.output;
  plan.passes = std::move(low.passes);
  plan.order = std::move(low.order);
  plan.physical = std::move(low.physical);  // lists units: the declared resources
  plan.naiveBytes = low.naiveBytes;
  plan.allocatedBytes = low.allocatedBytes;
  plan.peakLiveBytes = low.peakLiveBytes;
  plan.diagnostics = std::move(diagnostics);
  for (Diagnostic& dg : low.diagnostics) plan.diagnostics.push_back(std::move(dg));
  plan.outputVersion = low.outputVersion;
  if (low.outputResource.valid()) plan.outputResource = ResourceIndex(units_.of[low.outputResource.value()]);
  plan.resources.resize(d_.resources.size());
  for (uint32_t lr = 0; lr < low.resources.size(); ++lr) {
    const uint32_t r = units_.of[lr];
    PlannedResource& pr = plan.resources[r];
    PlannedResource& cell = low.resources[lr];
    const bool first = units_.rep[r] == lr;
    if (first) {
      pr = std::move(cell);
      pr.name = d_.resources[r].name;
      // A history's links are of lowered indices; histories are never cut, so the index maps 1:1.
      if (pr.historyOf.valid()) pr.historyOf = ResourceIndex(units_.of[pr.historyOf.value()]);
      if (pr.history.valid()) pr.history = ResourceIndex(units_.of[pr.history.value()]);
    } else {
      for (std::string& v : cell.versions) pr.versions.push_back(std::move(v));
    }
  }
  plan.bindings.resize(d_.passes.size());
  for (size_t pi = 0; pi < d_.passes.size(); ++pi) {
    const PassDecl& p = d_.passes[pi];
    for (size_t i = 0; i < p.uses.size(); ++i) {
      const ResourceUse& u = p.uses[i];
      const auto [b, e] = useCells_[pi][i];
      BoundUse bu{u.slot, u.access, ResourceIndex(), u.input, isWriteAccess(u.access) ? u.output : std::string(),
                  isWriteAccess(u.access) && u.input.empty()};
      for (uint32_t k = b; k < e && !bu.resource.valid(); ++k)
        if (const ResourceIndex lr = low.bindings[pi][k].resource; lr.valid())
          bu.resource = ResourceIndex(units_.of[lr.value()]);
      if (!u.sub.whole()) bu.sub = ranges_[pi][i];
      plan.bindings[pi].push_back(std::move(bu));
    }
  }
  return plan;
}

// Whole bindings of textures: every level and layer, counted.
void resolveWholeRanges(const GraphDesc& d, const CompileOptions& o, Plan& plan) {
  std::vector<Subresource> whole(d.resources.size());  // kAll: a buffer
  for (size_t r = 0; r < d.resources.size(); ++r) {
    const ResourceDecl& rd = d.resources[r];
    if (rd.kind == ResourceKind::texture)
      whole[r] = {0, mipLevels(rd.texture, resolveSize(rd.texture.size, o.output)), 0,
                  std::max<uint32_t>(1, arrayLayers(rd.texture))};
  }
  for (auto& uses : plan.bindings)
    for (BoundUse& bu : uses)
      if (bu.resource.valid() && bu.sub.mipCount == Subresource::kAll) bu.sub = whole[bu.resource.value()];
}

}  // namespace

Plan compileSubresources(const GraphDesc& desc, const CompileOptions& options) {
  Plan plan;
  Lowering lowering(desc, options);
  if (lowering.lower()) {
    plan = lowering.compileAndFold();
  } else {
    Compiler(desc, options, plan).run();
    // Parts refused before any texture was cut: the graph compiled whole.
    plan.diagnostics.insert(plan.diagnostics.begin(), lowering.diagnostics.begin(), lowering.diagnostics.end());
  }
  resolveWholeRanges(desc, options, plan);
  return plan;
}

}  // namespace rgraph::graph_detail
