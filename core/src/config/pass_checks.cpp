// Runs the pass types' check hooks (rgraph/pass_check.h) on a compiled plan
// and turns what they report into located diagnostics.
#include <algorithm>
#include <memory>

#include "rgraph/config.h"
#include "rgraph/registry.h"

namespace rgraph {

const CheckedSlot* PassCheckContext::find(std::string_view slot) const {
  for (const auto& s : slots_)
    if (s.slot == slot) return &s;
  return nullptr;
}

std::optional<Format> PassCheckContext::format(std::string_view slot) const {
  const CheckedSlot* s = find(slot);
  return s ? s->format : std::nullopt;
}

Extent PassCheckContext::extent(std::string_view slot) const {
  const CheckedSlot* s = find(slot);
  return s ? s->extent : Extent{};
}

uint32_t PassCheckContext::samples(std::string_view slot) const {
  const CheckedSlot* s = find(slot);
  return s ? s->samples : 1;
}

bool PassCheckContext::loads(std::string_view slot) const {
  const CheckedSlot* s = find(slot);
  return s && s->loads;
}

std::optional<SlotWriter> PassCheckContext::writer(std::string_view slot) const {
  const CheckedSlot* s = find(slot);
  if (!s || !writers_ || isWriteAccess(s->access) || s->resource.empty()) return std::nullopt;
  return writers_(*s);
}

void PassChecks::slotError(std::string slot, std::string message) {
  entries_.push_back({Entry::Kind::slot, std::move(slot), std::move(message)});
}

void PassChecks::paramError(std::string param, std::string message) {
  entries_.push_back({Entry::Kind::param, std::move(param), std::move(message)});
}

void PassChecks::passError(std::string message) { entries_.push_back({Entry::Kind::pass, {}, std::move(message)}); }

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

std::string locationText(const SourceLocation& at) {
  if (at.file.empty()) return {};
  std::string out = at.file;
  if (at.line > 0) out += ":" + std::to_string(at.line);
  if (at.line > 0 && at.column > 0) out += ":" + std::to_string(at.column);
  return out;
}

void checkSameSize(const PassCheckContext& ctx, PassChecks& checks, const std::string& a, const std::string& b) {
  const Extent ea = ctx.extent(a), eb = ctx.extent(b);
  if (ea.width == 0 || eb.width == 0 || ea == eb) return;
  checks.slotError(
      a, "'" + a + "' (" + extentText(ea) + ") and '" + b + "' (" + extentText(eb) + ") must have the same size");
}

PassRule sameSizeRule(std::vector<std::string> slots) {
  std::string text;
  for (size_t i = 0; i < slots.size(); ++i)
    text += (i == 0 ? "" : i + 1 == slots.size() ? " and " : ", ") + slots[i];
  PassRule rule;
  rule.text = text + " must have the same size";
  rule.check = [slots = std::move(slots)](const PassCheckContext& ctx, PassChecks& checks) {
    for (size_t i = 0; i + 1 < slots.size(); ++i) checkSameSize(ctx, checks, slots[i], slots.back());
  };
  return rule;
}

std::vector<CheckedSlot> planSlots(const GraphDesc& g, const Plan& plan, size_t pass) {
  const PassDecl& pd = g.passes[pass];
  const std::vector<BoundUse>* uses = pass < plan.bindings.size() ? &plan.bindings[pass] : nullptr;
  std::vector<CheckedSlot> out;
  for (const ResourceUse& ru : pd.uses) {
    CheckedSlot s;
    s.slot = ru.slot;
    s.access = ru.access;
    const bool write = isWriteAccess(ru.access);
    s.resource = write ? ru.output : ru.input;
    s.loads = write && !ru.input.empty();
    s.where = write ? ru.outputWhere : ru.inputWhere;
    const BoundUse* bu = nullptr;
    if (uses)
      for (const auto& x : *uses)
        if (x.slot == ru.slot) bu = &x;
    // Plan::resources matches g.resources one to one (rgraph/graph.h), ok or not.
    if (bu && bu->resource.valid()) {
      const ResourceDecl& rd = g.resources[bu->resource.value()];
      s.historyOf = rd.historyOf;
      s.kind = rd.kind;
      if (rd.kind == ResourceKind::buffer) s.bufferBytes = rd.bufferBytes;
      if (rd.kind == ResourceKind::texture) {
        s.format = rd.texture.format;
        s.samples = std::max<uint32_t>(1, rd.texture.samples);
        const Extent e = plan.resource(bu->resource).extent;
        const uint32_t level = bu->sub.mipCount == Subresource::kAll ? 0 : bu->sub.mipBegin;
        s.extent = e.width == 0 ? e
                                : Extent{std::max<uint32_t>(1, e.width >> level), std::max<uint32_t>(1, e.height >> level)};
        s.sub = bu->sub;
        if (e.width != 0) {
          const uint32_t levels = mipLevels(rd.texture, e);
          const uint32_t rest = bu->sub.mipBegin < levels ? levels - bu->sub.mipBegin : 0;
          s.mips = bu->sub.mipCount == Subresource::kAll ? rest : std::min(rest, bu->sub.mipCount);
        }
        s.layers = rd.texture.layers;
        s.cube = rd.texture.cube;
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

namespace {

// Reads the config file again, once, only when a parameter must be located.
class DocLocator {
 public:
  explicit DocLocator(std::string file) : file_(std::move(file)) {}
  SourceLocation locate(const std::string& pointer, const SourceLocation& fallback) {
    if (!tried_) {
      tried_ = true;
      if (!file_.empty()) {
        Diagnostics ignored;
        auto doc = std::make_unique<ConfigDocument>(ConfigDocument::parseFile(file_, ignored));
        if (doc->ok()) doc_ = std::move(doc);
      }
    }
    if (!doc_) return fallback;
    SourceLocation at = doc_->locate(pointer);
    return at.known() ? at : fallback;
  }

 private:
  std::string file_;
  bool tried_ = false;
  std::unique_ptr<ConfigDocument> doc_;
};

SourceLocation slotLocation(const PassDecl& pd, const PassTypeDesc& type, const PassCheckContext& ctx,
                            const std::string& slot, DocLocator& doc) {
  if (const CheckedSlot* bound = ctx.find(slot); bound && bound->where.known()) return bound->where;
  // Unbound: the pass's inputs or outputs object, where it would be bound.
  if (pd.where.path.empty()) return pd.where;
  const SlotDecl* decl = type.findSlot(slot);
  const bool write = decl && isWriteAccess(decl->access);
  return doc.locate(pd.where.path + (write ? "/outputs" : "/inputs"), pd.where);
}

// Every pass's params with its type's declared defaults filled in, made once
// (a writer's params are looked at by each of its readers).
class FilledParams {
 public:
  FilledParams(const PipelineConfig& pipeline, const PassRegistry& registry)
      : pipeline_(pipeline), registry_(registry), params_(pipeline.graph.passes.size()) {}
  // nullptr for a pass of an unknown type.
  const ParamSet* of(size_t pass) {
    if (params_[pass]) return &*params_[pass];
    const PassTypeDesc* type = registry_.find(pipeline_.graph.passes[pass].type);
    if (!type) return nullptr;
    ParamSet params = defaultParams(type->params);
    if (pass < pipeline_.params.size())
      for (const auto& [k, v] : pipeline_.params[pass].values()) params.set(k, v);
    return &params_[pass].emplace(std::move(params));
  }

 private:
  const PipelineConfig& pipeline_;
  const PassRegistry& registry_;
  std::vector<std::optional<ParamSet>> params_;
};

// The enabled pass other than `reader` that writes the version `slot` reads
// (a version has one writer: two are the graph's duplicate_writer error).
std::optional<SlotWriter> findWriter(const GraphDesc& g, size_t reader, const CheckedSlot& slot, FilledParams& params,
                                     DocLocator& locator) {
  for (size_t q = 0; q < g.passes.size(); ++q) {
    const PassDecl& pd = g.passes[q];
    if (q == reader || !pd.enabled) continue;
    for (const ResourceUse& ru : pd.uses) {
      if (!isWriteAccess(ru.access) || ru.output != slot.resource) continue;
      const ParamSet* set = params.of(q);
      if (!set) return std::nullopt;
      SlotWriter w;
      w.pass = pd.name;
      w.type = pd.type;
      w.slot = ru.slot;
      w.params = set;
      w.paramWhere = [&locator, &pd](const std::string& param) {
        return locator.locate(pd.where.path + "/params/" + param, pd.where);
      };
      return w;
    }
  }
  return std::nullopt;
}

}  // namespace

Diagnostics runPassChecks(const PipelineConfig& pipeline, const Plan& plan, const PassRegistry& registry,
                          const PassCheckOptions& options) {
  Diagnostics out;
  const GraphDesc& g = pipeline.graph;
  DocLocator locator(pipeline.file);
  FilledParams filled(pipeline, registry);
  for (size_t p = 0; p < g.passes.size(); ++p) {
    const PassDecl& pd = g.passes[p];
    if (!pd.enabled) continue;
    if (!options.culledPasses && p < plan.passes.size() && plan.passes[p].culled) continue;
    const PassTypeDesc* type = registry.find(pd.type);
    if (!type) continue;
    const std::string who = pd.type + " pass '" + pd.name + "'";
    auto add = [&](DiagCode code, std::string message, SourceLocation where, std::string slot) {
      Diagnostic d;
      d.code = code;
      d.message = who + ": " + message;
      d.pass = pd.name;
      d.slot = std::move(slot);
      d.where = std::move(where);
      out.push_back(std::move(d));
    };
    if (type->needsScene && options.scenePresent == false)
      add(DiagCode::needs_scene, "needs a scene (rgraph render --scene ...)", pd.where, {});
    if (!type->check && type->rules.empty()) continue;

    const ParamSet& params = *filled.of(p);
    const PassCheckContext ctx(pd.name, params, planSlots(g, plan, p), plan.output, options.scenePresent,
                               [&, p](const CheckedSlot& s) { return findWriter(g, p, s, filled, locator); });
    PassChecks checks;
    if (type->check) type->check(ctx, checks);
    for (const PassRule& rule : type->rules) rule.check(ctx, checks);
    for (const auto& e : checks.entries()) {
      switch (e.kind) {
        case PassChecks::Entry::Kind::slot:
          add(DiagCode::pass_check, e.message, slotLocation(pd, *type, ctx, e.name, locator), e.name);
          break;
        case PassChecks::Entry::Kind::param:
          add(DiagCode::pass_check, e.message, locator.locate(pd.where.path + "/params/" + e.name, pd.where), {});
          break;
        case PassChecks::Entry::Kind::pass:
          add(DiagCode::pass_check, e.message, pd.where, {});
          break;
      }
    }
  }
  return out;
}

}  // namespace rgraph
