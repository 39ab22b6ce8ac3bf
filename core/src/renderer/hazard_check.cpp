// The hazard harness (rgraph/hazard_check.h): the plain run's snapshots, each
// mode's run compared with them, the first differing pass named.
#include "rgraph/hazard_check.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "rgraph/error.h"
#include "rgraph/format.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/context_identity.h"
#include "rgraph/gl/executor.h"
#include "rgraph/testing.h"
#include "texture_snapshot.h"

namespace rgraph {

namespace {

using hazard_detail::Level;
using hazard_detail::Snapshot;
using hazard_detail::SnapshotReader;

bool sameValue(float a, float b, float tolerance) {
  if (std::memcmp(&a, &b, sizeof a) == 0) return true;
  return tolerance > 0.0f && std::isfinite(a) && std::isfinite(b) && std::fabs(a - b) <= tolerance;
}

struct Difference {
  size_t pixels = 0, compared = 0;
  uint32_t level = 0, layer = 0;  // of the first differing texel
};

Difference compare(const Snapshot& plain, const Snapshot& other, float tolerance) {
  Difference d;
  for (uint32_t l = 0; l < plain.size() && l < other.size(); ++l) {
    const Level& a = plain[l];
    const Level& b = other[l];
    const size_t texels = a.texels.size() / a.channels;
    d.compared += texels;
    if (a.texels.size() != b.texels.size()) {
      if (d.pixels == 0) d.level = l;
      d.pixels += texels;
      continue;
    }
    for (size_t t = 0; t < texels; ++t)
      for (uint32_t c = 0; c < a.channels; ++c)
        if (!sameValue(a.texels[t * a.channels + c], b.texels[t * a.channels + c], a.integer ? 0.0f : tolerance)) {
          if (d.pixels == 0) {
            d.level = l;
            d.layer = static_cast<uint32_t>(t / (size_t{a.width} * a.height));
          }
          ++d.pixels;
          break;
        }
  }
  return d;
}

// (frame, pass declaration index or kFrameEnd, resource index)
using Key = std::tuple<uint32_t, uint32_t, uint32_t>;
constexpr uint32_t kFrameEnd = UINT32_MAX;

// What one run saw: snapshots, or the error that stopped it.
struct RunResult {
  std::map<Key, Snapshot> snapshots;
  std::string error;
  PipelineConfig pipeline;  // as adapted
  Plan plan;
};

// The plain plan decides what is compared: after each pass, the textures
// live at its step (in that run's order only those it writes, for reorder);
// after each frame, those whose content outlives it.
struct Selection {
  std::vector<std::vector<uint32_t>> live, written;  // per pass declaration
  std::vector<uint32_t> kept;
};

Selection select(const Plan& plan, const PipelineConfig& pipeline) {
  Selection s;
  s.live.resize(plan.passes.size());
  s.written.resize(plan.passes.size());
  auto comparable = [&](uint32_t r) {  // multisampled ones too, sample by sample
    const PlannedResource& pr = plan.resources[r];
    return pr.kind == ResourceKind::texture && pr.firstPass.valid();
  };
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    if (!comparable(r)) continue;
    const PlannedResource& pr = plan.resources[r];
    for (uint32_t st = pr.firstPass.value(); st <= pr.lastPass.value() && st < plan.order.size(); ++st)
      s.live[plan.order[st].value()].push_back(r);
    if (pr.imported || pr.persistent || pr.history.valid() || ResourceIndex(r) == plan.outputResource)
      s.kept.push_back(r);
  }
  for (uint32_t p = 0; p < plan.passes.size(); ++p)
    for (const BoundUse& u : plan.bindings[p])
      if (isWriteAccess(u.access) && u.resource.valid() && comparable(u.resource.value()) &&
          std::find(s.written[p].begin(), s.written[p].end(), u.resource.value()) == s.written[p].end())
        s.written[p].push_back(u.resource.value());
  return s;
}

bool isDepthResource(const PipelineConfig& pipeline, uint32_t r) {
  return formatInfo(pipeline.graph.resources[r].texture.format).isDepth;
}

// One run: `modes` (none: the plain run, which also fixes `selection`).
RunResult run(const std::string& path, const HazardCheckOptions& options, const HazardModes& modes,
              const std::shared_ptr<RenderScene>& scene, std::optional<Selection>& selection,
              SnapshotReader& reader) {
  RunResult out;
  RendererOptions ro = options.renderer;
  ro.size = options.size;
  ro.hazards = modes;
  Diagnostics diags;
  std::unique_ptr<Renderer> renderer = Renderer::fromFile(path, ro, diags);
  if (!renderer) {
    for (const auto& d : diags)
      if (d.severity == Severity::error) out.error += (out.error.empty() ? "" : "\n") + formatDiagnostic(d);
    return out;
  }
  if (scene) renderer->setScene(scene);
  renderer->setSize(options.size);
  const bool reorder = modes.has(HazardMode::reorder);
  uint32_t frame = 0;
  renderer->setAfterPass([&](size_t step) {
    const Executor* exec = renderer->executor();
    const Plan& plan = exec->plan();
    // The plain run's first pass fixes what every run compares.
    if (!selection) selection = select(plan, renderer->pipeline());
    if (step >= plan.order.size()) return;
    const uint32_t p = plan.order[step].value();
    if (p >= selection->live.size()) return;
    for (uint32_t r : reorder ? selection->written[p] : selection->live[p]) {
      const uint32_t texture = exec->textureOf(plan.resources[r].name);
      if (texture) out.snapshots[{frame, p, r}] = reader.read(texture, isDepthResource(renderer->pipeline(), r));
    }
  });
  try {
    for (frame = 0; frame < std::max(1u, options.frames); ++frame) {
      renderer->render();
      if (frame == 0) {
        out.pipeline = renderer->pipeline();
        out.plan = renderer->executor()->plan();
      }
      if (!selection) break;  // no pass ran
      for (uint32_t r : selection->kept) {
        const uint32_t texture = renderer->executor()->textureOf(out.plan.resources[r].name);
        if (texture) out.snapshots[{frame, kFrameEnd, r}] = reader.read(texture, isDepthResource(out.pipeline, r));
      }
    }
  } catch (const RuntimeError& e) {
    out.error = e.what();
  }
  return out;
}

std::string locationPrefix(const SourceLocation& w, const std::string& fallback) {
  if (!w.known()) return fallback + ": ";
  return w.file + ":" + std::to_string(w.line) + ":" + std::to_string(w.column) + ": ";
}

std::string subresourceText(const std::string& name, const Snapshot& s, const Difference& d, bool cube) {
  std::string label = name;
  if (s.size() > 1) label += ".mip[" + std::to_string(d.level) + "]";
  if (d.level < s.size() && s[d.level].layers > 1) {
    static const char* faces[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    label += cube && s[d.level].layers == 6 ? std::string(".face[") + faces[d.layer] + "]"
                                             : ".layer[" + std::to_string(d.layer) + "]";
  }
  return label;
}

// The mode's run against the plain one: the first finding (in frame and
// plain step order) when a kept resource differs, or the run failed.
HazardModeRun judge(const std::string& path, const std::string& label, const RunResult& plain, const RunResult& mode,
                    float tolerance) {
  HazardModeRun result;
  result.mode = label;
  auto passFinding = [&](uint32_t p, HazardFinding f) {
    if (p < plain.pipeline.graph.passes.size()) {
      const PassDecl& pd = plain.pipeline.graph.passes[p];
      f.pass = pd.name, f.passType = pd.type, f.where = pd.where;
    }
    return f;
  };
  if (!mode.error.empty()) {
    HazardFinding f;
    f.mode = label;
    // "pass 'NAME'" in the executor's messages names the pass.
    if (const size_t at = mode.error.find("pass '"); at != std::string::npos) {
      const std::string name = mode.error.substr(at + 6, mode.error.find('\'', at + 6) - at - 6);
      for (uint32_t p = 0; p < plain.pipeline.graph.passes.size(); ++p)
        if (plain.pipeline.graph.passes[p].name == name) f = passFinding(p, f);
    }
    f.message = locationPrefix(f.where, path) + "error: hazard (" + label + "): the run failed: " + mode.error;
    result.findings.push_back(f);
    return result;
  }
  bool visible = false;
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, std::pair<Key, Difference>> differing;
  for (const auto& [key, snap] : mode.snapshots) {
    auto it = plain.snapshots.find(key);
    if (it == plain.snapshots.end()) continue;
    const Difference d = compare(it->second, snap, tolerance);
    result.comparedPixels += d.compared;
    if (d.pixels == 0) continue;
    const auto [frame, p, r] = key;
    visible = visible || p == kFrameEnd;
    // Ordered by frame, then the pass's step in the plain order (frame ends last).
    const uint32_t step = p == kFrameEnd ? UINT32_MAX : plain.plan.passes[p].order.value();
    differing[{frame, step, r}] = {key, d};
  }
  if (!visible) {
    result.hiddenDifferences = differing.size();
    return result;
  }
  const auto& [key, d] = differing.begin()->second;
  const auto [frame, p, r] = key;
  const Snapshot& snap = mode.snapshots.at(key);
  HazardFinding f;
  f.mode = label;
  f.frame = frame;
  if (p != kFrameEnd) f = passFinding(p, f);
  const ResourceDecl& rd = plain.pipeline.graph.resources[r];
  f.resource = subresourceText(rd.name, snap, d, rd.texture.cube);
  f.pixels = d.pixels;
  f.comparedPixels = d.level < snap.size() ? snap[d.level].texels.size() / snap[d.level].channels : 0;
  bool writes = false;
  if (p != kFrameEnd)
    for (const BoundUse& u : plain.plan.bindings[p])
      writes = writes || (isWriteAccess(u.access) && u.resource == ResourceIndex(r));
  f.declared = p == kFrameEnd || writes;
  std::ostringstream m;
  m << locationPrefix(f.where, path) << "error: hazard (" << label << ", frame " << frame << "): ";
  if (p == kFrameEnd)
    m << "after the last pass, ";
  else
    m << "after pass '" << f.pass << "' (type '" << f.passType << "'), ";
  m << "'" << f.resource << "' differs from the plain run in " << f.pixels << " of " << f.comparedPixels
    << " pixels";
  if (!f.declared) m << " (a resource the pass does not declare writing)";
  f.message = m.str();
  result.findings.push_back(f);
  return result;
}

}  // namespace

bool HazardReport::hazardFree() const { return error.empty() && findings().empty(); }

std::vector<HazardFinding> HazardReport::findings() const {
  std::vector<HazardFinding> all;
  for (const auto& r : runs) all.insert(all.end(), r.findings.begin(), r.findings.end());
  return all;
}

std::string HazardReport::describe() const {
  std::ostringstream s;
  s << "hazard check of " << pipeline << "\n";
  if (!error.empty()) s << "  the plain run failed: " << error << "\n";
  for (const auto& r : runs)
    s << "  " << r.mode << ": " << r.comparedPixels << " pixels compared, "
      << (r.findings.empty() ? std::string("no finding") : r.findings.front().message) << "\n";
  return s.str();
}

HazardReport checkHazards(const std::string& pipelinePath, const HazardCheckOptions& options) {
  HazardReport report;
  report.pipeline = pipelinePath;
  std::shared_ptr<RenderScene> scene;
  try {
    if (!options.scene.empty()) scene = RenderScene::load(options.scene);
  } catch (const RuntimeError& e) {
    report.error = e.what();
    return report;
  }
  std::optional<Selection> selection;
  SnapshotReader reader;
  const RunResult plain = run(pipelinePath, options, HazardModes{}, scene, selection, reader);
  if (!plain.error.empty()) {
    report.error = plain.error;
    return report;
  }
  for (HazardMode m : kHazardModes) {
    if (!options.modes.has(m)) continue;
    const uint32_t runs = m == HazardMode::reorder ? std::max(1u, options.modes.reorder) : 1u;
    for (uint32_t k = 1; k <= runs; ++k) {
      HazardModes modes = HazardModes::of(m);
      modes.reorder = k;
      const std::string label = hazardModesLabel(modes);
      const RunResult other = run(pipelinePath, options, modes, scene, selection, reader);
      report.runs.push_back(judge(pipelinePath, label, plain, other, options.floatTolerance));
    }
  }
  return report;
}

namespace testing {

HazardReport expectHazardFree(const std::string& path, const HazardCheckOptions& options) {
  std::unique_ptr<GlContext> own;
  if (gl::currentContext() == gl::ContextIdentity{}) own = GlContext::create();
  return checkHazards(path, options);
}

}  // namespace testing
}  // namespace rgraph
