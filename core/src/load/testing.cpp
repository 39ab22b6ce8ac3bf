#include "rgraph/testing.h"

#include <algorithm>
#include <cstdio>

#include "rgraph/adapt.h"
#include "rgraph/pass_check.h"
#include "rgraph/pipeline_check.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"

namespace rgraph::testing {

// Loads, adapts and checks; the one place that fills a CompiledPipeline in.
struct CompiledPipelineBuilder {
  static CompiledPipeline finish(std::string source, std::optional<PipelineConfig> loaded, Diagnostics diags,
                                 const Options& options, const PassRegistry& registry) {
    CompiledPipeline r;
    r.source_ = std::move(source);
    r.diagnostics_ = std::move(diags);
    if (!loaded) return r;
    r.loaded_ = true;
    r.pipeline_ = std::move(*loaded);
    if (options.scene) r.adaptNotes_ = adaptToScene(r.pipeline_, registry, *options.scene).notes;
    CompileOptions compile;
    compile.output = options.size;
    compile.alias = options.alias;
    compile.maxTextureSize = options.maxTextureSize;
    if (options.maxTextureSize != CompileOptions{}.maxTextureSize)
      compile.maxTextureSizeOrigin = "the limit rgraph::testing::Options::maxTextureSize sets";
    PipelineCheckOptions checks;
    checks.passChecks = options.passChecks;
    checks.shaders = options.shaderChecks ? ShaderCheckMode::run : ShaderCheckMode::skip;
    checks.scenePresent = options.scenePresent;
    checks.registry = &registry;
    checks.shaderDirectories = options.shaderDirectories;
    r.plan_ = checkPipeline(r.pipeline_, compile, checks, r.diagnostics_);
    return r;
  }
};

namespace {

// The pass types of one compile: a copy of the caller's registry (or of the
// built-in types) with the config's plugins loaded into it and dropped with
// it, so that no compile sees what another loaded or added (each test its own).
struct CompileTypes {
  PassRegistry registry;
  PluginLoader loader{registry};
  explicit CompileTypes(const Options& options)
      : registry(options.registry ? *options.registry : PassRegistry::builtins()) {}
  CompileTypes(const CompileTypes&) = delete;
  CompileTypes& operator=(const CompileTypes&) = delete;

  PipelineLoadOptions loadOptions(const Options& options) {
    PipelineLoadOptions lo;
    lo.pluginDirectories = options.pluginDirectories;
    lo.registry = &registry;
    lo.loader = &loader;
    return lo;
  }
};

std::string q(std::string_view s) { return "'" + std::string(s) + "'"; }

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string out;
  for (const auto& s : items) {
    if (!out.empty()) out += sep;
    out += s;
  }
  return out;
}

std::string bytesText(uint64_t bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return std::string(buf) + " (" + std::to_string(bytes) + " bytes)";
}

}  // namespace

CompiledPipeline compileFile(const std::string& path, const Options& options) {
  Diagnostics diags;
  CompileTypes types(options);
  std::optional<PipelineConfig> p = loadPipelineFile(path, types.loadOptions(options), diags);
  return CompiledPipelineBuilder::finish(path, std::move(p), std::move(diags), options, types.registry);
}

CompiledPipeline compileText(std::string_view json, const Options& options, const std::string& nameForMessages,
                             const std::string& baseDir) {
  Diagnostics diags;
  CompileTypes types(options);
  std::optional<PipelineConfig> p = loadPipelineText(json, nameForMessages, baseDir, types.loadOptions(options), diags);
  return CompiledPipelineBuilder::finish(nameForMessages, std::move(p), std::move(diags), options, types.registry);
}

// ---------------------------------------------------------------- diagnostics

Diagnostics CompiledPipeline::errors() const {
  Diagnostics out;
  for (const auto& d : diagnostics_)
    if (d.severity == Severity::error) out.push_back(d);
  return out;
}

Diagnostics CompiledPipeline::warnings() const {
  Diagnostics out;
  for (const auto& d : diagnostics_)
    if (d.severity == Severity::warning) out.push_back(d);
  return out;
}

bool CompiledPipeline::hasError(DiagCode code) const {
  return std::any_of(diagnostics_.begin(), diagnostics_.end(),
                     [&](const Diagnostic& d) { return d.code == code && d.severity == Severity::error; });
}

bool CompiledPipeline::hasDiagnostic(DiagCode code) const { return find(code) != nullptr; }

bool CompiledPipeline::hasMessage(std::string_view text) const {
  return std::any_of(diagnostics_.begin(), diagnostics_.end(),
                     [&](const Diagnostic& d) { return d.message.find(text) != std::string::npos; });
}

const Diagnostic* CompiledPipeline::find(DiagCode code) const {
  for (const auto& d : diagnostics_)
    if (d.code == code) return &d;
  return nullptr;
}

std::vector<std::string> CompiledPipeline::diagnosticLines() const {
  std::vector<std::string> out;
  for (const auto& d : diagnostics_) out.push_back(formatDiagnostic(d));
  return out;
}

// ---------------------------------------------------------------- passes

const PlannedPass* CompiledPipeline::findPass(std::string_view pass) const {
  for (const auto& p : plan_.passes)
    if (p.name == pass) return &p;
  return nullptr;
}

std::vector<std::string> CompiledPipeline::passes() const {
  std::vector<std::string> out;
  for (const auto& p : plan_.passes) out.push_back(p.name);
  return out;
}

bool CompiledPipeline::hasPass(std::string_view pass) const { return findPass(pass) != nullptr; }

std::vector<std::string> CompiledPipeline::order() const {
  std::vector<std::string> out;
  for (PassIndex i : plan_.order)
    if (i.valid() && i.value() < plan_.passes.size()) out.push_back(plan_.pass(i).name);
  return out;
}

std::optional<size_t> CompiledPipeline::step(std::string_view pass) const {
  const PlannedPass* p = findPass(pass);
  if (!p || p->culled || !p->order.valid() || p->order.value() >= plan_.order.size()) return std::nullopt;
  return p->order.value();
}

bool CompiledPipeline::runsBefore(std::string_view a, std::string_view b) const {
  const auto sa = step(a), sb = step(b);
  return sa && sb && *sa < *sb;
}

bool CompiledPipeline::runs(std::string_view pass) const { return step(pass).has_value(); }

bool CompiledPipeline::culled(std::string_view pass) const {
  const PlannedPass* p = findPass(pass);
  return p && p->culled;
}

std::string CompiledPipeline::cullReason(std::string_view pass) const {
  const PlannedPass* p = findPass(pass);
  return p && p->culled ? p->reason : std::string();
}

std::vector<std::string> CompiledPipeline::culledPasses() const {
  std::vector<std::string> out;
  for (const auto& p : plan_.passes)
    if (p.culled) out.push_back(p.name);
  return out;
}

std::vector<Binding> CompiledPipeline::bindings(std::string_view pass) const {
  std::vector<Binding> out;
  const PlannedPass* p = findPass(pass);
  if (!p || p->decl.value() >= plan_.bindings.size()) return out;
  for (const BoundUse& u : plan_.uses(p->decl)) {
    Binding b;
    b.slot = u.slot;
    b.access = u.access;
    if (u.resource.valid() && u.resource.value() < plan_.resources.size()) b.resource = plan_.resource(u.resource).name;
    b.readVersion = u.readVersion;
    b.writeVersion = u.writeVersion;
    b.sub = u.sub;
    out.push_back(std::move(b));
  }
  return out;
}

std::optional<Binding> CompiledPipeline::binding(std::string_view pass, std::string_view slot) const {
  for (auto& b : bindings(pass))
    if (b.slot == slot) return b;
  return std::nullopt;
}

// ---------------------------------------------------------------- resources

const PlannedResource* CompiledPipeline::findResource(std::string_view name) const {
  for (const auto& r : plan_.resources)
    if (r.name == name || std::find(r.versions.begin(), r.versions.end(), name) != r.versions.end()) return &r;
  return nullptr;
}

bool CompiledPipeline::hasResource(std::string_view name) const { return findResource(name) != nullptr; }

std::string CompiledPipeline::resourceOf(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r ? r->name : std::string();
}

std::vector<std::string> CompiledPipeline::versions(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r ? r->versions : std::vector<std::string>{};
}

bool CompiledPipeline::imported(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r && r->imported;
}

bool CompiledPipeline::used(std::string_view name) const { return lifetime(name).has_value(); }

Extent CompiledPipeline::extent(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r ? r->extent : Extent{};
}

uint64_t CompiledPipeline::bytes(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r ? r->bytes : 0;
}

std::optional<Lifetime> CompiledPipeline::lifetime(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  if (!r || !r->firstPass.valid() || !r->lastPass.valid()) return std::nullopt;
  const size_t n = plan_.order.size();
  if (r->firstPass.value() >= n || r->lastPass.value() >= n) return std::nullopt;  // a plan with errors
  Lifetime l;
  l.first = r->firstPass.value();
  l.last = r->lastPass.value();
  l.firstPass = plan_.pass(plan_.step(r->firstPass)).name;
  l.lastPass = plan_.pass(plan_.step(r->lastPass)).name;
  return l;
}

std::optional<TextureInfo> CompiledPipeline::textureAt(PhysicalIndex i) const {
  if (!i.valid() || i.value() >= plan_.physical.size()) return std::nullopt;
  const PhysicalTexture& t = plan_.physicalTexture(i);
  TextureInfo info;
  info.index = i.value();
  info.format = t.format;
  info.extent = t.extent;
  info.mips = t.mips;
  info.samples = t.samples;
  info.bytes = t.bytes;
  for (ResourceIndex r : t.resources)
    if (r.valid() && r.value() < plan_.resources.size()) info.resources.push_back(plan_.resource(r).name);
  return info;
}

std::optional<TextureInfo> CompiledPipeline::texture(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  return r ? textureAt(r->physical) : std::nullopt;
}

std::vector<std::string> CompiledPipeline::sharing(std::string_view name) const {
  std::optional<TextureInfo> t = texture(name);
  return t ? t->resources : std::vector<std::string>{};
}

bool CompiledPipeline::aliased(std::string_view a, std::string_view b) const {
  const PlannedResource* ra = findResource(a);
  const PlannedResource* rb = findResource(b);
  if (!ra || !rb || ra == rb) return false;
  const auto ta = textureAt(ra->physical);
  return ta && ra->physical == rb->physical;
}

std::vector<TextureInfo> CompiledPipeline::textures() const {
  std::vector<TextureInfo> out;
  for (uint32_t i = 0; i < plan_.physical.size(); ++i) out.push_back(*textureAt(PhysicalIndex(i)));
  return out;
}

std::vector<std::vector<std::string>> CompiledPipeline::aliasGroups() const {
  std::vector<std::vector<std::string>> out;
  for (auto& t : textures())
    if (t.resources.size() > 1) out.push_back(std::move(t.resources));
  return out;
}

// ---------------------------------------------------------------- output, memory

std::string CompiledPipeline::outputResource() const {
  const ResourceIndex o = plan_.outputResource;
  return o.valid() && o.value() < plan_.resources.size() ? plan_.resource(o).name : std::string();
}

std::string CompiledPipeline::outputVersion() const {
  return outputResource().empty() ? std::string() : plan_.outputVersion;
}

uint64_t CompiledPipeline::naiveBytes() const { return plan_.naiveBytes; }
uint64_t CompiledPipeline::allocatedBytes() const { return plan_.allocatedBytes; }
uint64_t CompiledPipeline::peakLiveBytes() const { return plan_.peakLiveBytes; }

// ---------------------------------------------------------------- summaries

std::string CompiledPipeline::describePass(std::string_view pass) const {
  const PlannedPass* p = findPass(pass);
  if (!p) {
    if (!loaded_) return "no pass named " + q(pass) + ": " + source_ + " did not load (see its diagnostics)";
    return "no pass named " + q(pass) + " (passes: " + join(passes(), ", ") + ")";
  }
  if (p->culled) return "pass " + q(pass) + " (type " + p->type + ") is culled: " + p->reason;
  const auto s = step(pass);
  if (!s) return "pass " + q(pass) + " (type " + p->type + ") has no place in the order (the graph has errors)";
  return "pass " + q(pass) + " (type " + p->type + ") runs at step " + std::to_string(*s) + " of " +
         std::to_string(plan_.order.size());
}

std::string CompiledPipeline::describeResource(std::string_view name) const {
  const PlannedResource* r = findResource(name);
  if (!r) {
    if (!loaded_) return "no resource named " + q(name) + ": " + source_ + " did not load (see its diagnostics)";
    std::vector<std::string> names;
    for (const auto& res : plan_.resources) names.push_back(res.name);
    return "no resource or version named " + q(name) + " (resources: " + join(names, ", ") + ")";
  }
  std::string out = "resource " + q(r->name);
  if (r->name != name) out += " (version " + q(name) + ")";
  out += r->kind == ResourceKind::buffer ? ", buffer" : ", " + extentText(r->extent);
  if (r->imported) out += ", imported";
  if (r->historyOf.valid()) out += ", history of " + q(plan_.resource(r->historyOf).name) + " (kept across frames)";
  if (r->history.valid()) out += ", kept across frames in " + q(plan_.resource(r->history).name);
  const auto l = lifetime(name);
  if (!l) return out + ", unused";
  out += ", used from step " + std::to_string(l->first) + " (" + l->firstPass + ") to step " + std::to_string(l->last) +
         " (" + l->lastPass + ")";
  if (const auto t = texture(name)) {
    out += ", texture #" + std::to_string(t->index);
    if (t->resources.size() > 1) out += " shared with " + join(t->resources, ", ");
  }
  return out + ", " + bytesText(r->bytes);
}

std::string CompiledPipeline::describe() const {
  std::string out = "pipeline " + source_ + (loaded_ ? " at " + extentText(plan_.output) : std::string()) + ": ";
  const size_t nErrors = errors().size(), nWarnings = warnings().size();
  if (!loaded_)
    out += "not loaded";
  else
    out += ok() ? "ok" : "has errors";
  out += " (" + std::to_string(nErrors) + " errors, " + std::to_string(nWarnings) + " warnings)\n";
  for (const auto& line : diagnosticLines()) out += "  " + line + "\n";
  if (!loaded_) return out;
  for (const auto& note : adaptNotes_) out += "  adapted: " + note + "\n";
  out += "order: " + join(order(), " -> ") + "\n";
  for (const auto& p : plan_.passes)
    if (p.culled) out += "culled: " + p.name + ": " + p.reason + "\n";
  for (const auto& p : plan_.passes)  // runs only for the next frame (a history's source)
    if (!p.culled && !p.reason.empty()) {
      const std::string_view why = std::string_view(p.reason).substr(p.reason.rfind("kept: ", 0) == 0 ? 6 : 0);
      out += "kept: " + p.name + ": " + std::string(why) + "\n";
    }
  for (const auto& r : plan_.resources)
    if (r.historyOf.valid())
      out += "history: " + r.name + " holds the previous frame of " + plan_.resource(r.historyOf).name + "\n";
  for (const auto& t : textures())
    out += "texture #" + std::to_string(t.index) + " " + std::string(formatName(t.format)) + " " +
           extentText(t.extent) + ": " + join(t.resources, ", ") + "\n";
  out += "output: " + (outputResource().empty() ? std::string("none") : outputVersion()) + "\n";
  out += "memory: naive " + bytesText(naiveBytes()) + ", allocated " + bytesText(allocatedBytes()) + ", peak live " +
         bytesText(peakLiveBytes()) + "\n";
  return out;
}

}  // namespace rgraph::testing
