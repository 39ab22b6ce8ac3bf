// Pass checks before the GPU: what a pass type requires of its bindings
// beyond slot formats (equal sizes, a format a blit can copy, the slots a
// G-buffer layout needs, a scene...), stated once in its declaration
// (PassTypeDesc::check, PassTypeDesc::needsScene) and run on the compiled plan
// without a GL context: by `rgraph validate`, `plan`, `render` before any GL
// work, and by the executor before it creates a pass. Errors become
// diagnostics located at the slot's binding or the parameter in the config.
// No GL include.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/params.h"

namespace rgraph {

struct PipelineConfig;
class PassRegistry;

// One slot of a pass as the compiled plan binds it.
struct CheckedSlot {
  std::string slot;
  Access access = Access::sampled;
  std::string resource;          // the version the config names (for messages)
  std::optional<Format> format;  // unknown for a buffer or a binding the graph could not resolve
  ResourceKind kind = ResourceKind::texture;
  uint64_t bufferBytes = 0;      // a buffer's buffer_bytes (0: a texture or unresolved)
  Extent extent;                 // at the plan's output size, of the level bound; 0x0 when unknown
  uint32_t samples = 1;
  // The part of the texture bound (BoundUse::sub, resolved) and its shape.
  Subresource sub;
  uint32_t layers = 1;  // TextureDesc::layers
  bool cube = false;
  // Mip levels the binding covers: the texture's (TextureDesc::mips resolved
  // at the plan's size) from sub.mipBegin on, or the bound range's; 0 when unknown.
  uint32_t mips = 0;
  bool loads = false;    // a writing slot that also loads its previous version
  // A history resource (ResourceDecl::historyOf): the resource whose previous
  // frame it holds; empty for anything else.
  std::string historyOf;
  SourceLocation where;  // the binding in the config
};

// The slots pass `pass` binds, resolved through the compiled plan: formats
// and samples from the resource declarations, sizes from the plan (at its
// output size). What the pass checks see (and what the shader checks need).
std::vector<CheckedSlot> planSlots(const GraphDesc& graph, const Plan& plan, size_t pass);

// The pass that wrote the version a reading slot binds, for a check that
// spans two passes (a G-buffer reader's "layout" against its writer's:
// gbuffer_layout.h). Valid while the check runs.
struct SlotWriter {
  std::string pass;         // its name
  std::string type;         // its pass type
  std::string slot;         // the slot it wrote the version through
  const ParamSet* params = nullptr;  // its params, declared defaults filled in
  // Where one of its params is in the config (at the pass when the config
  // leaves it at its default): for messages that name both places.
  std::function<SourceLocation(const std::string& param)> paramWhere;
};

// What a check hook sees of one pass instance. GL-free.
class PassCheckContext {
 public:
  // Finds the writer of a slot's version (runPassChecks gives one; without
  // it, writer() finds none).
  using WriterLookup = std::function<std::optional<SlotWriter>(const CheckedSlot&)>;

  PassCheckContext(std::string passName, const ParamSet& params, std::vector<CheckedSlot> slots, Extent output,
                   std::optional<bool> scenePresent, WriterLookup writers = {})
      : passName_(std::move(passName)),
        params_(params),
        slots_(std::move(slots)),
        output_(output),
        scenePresent_(scenePresent),
        writers_(std::move(writers)) {}

  const std::string& passName() const { return passName_; }
  const ParamSet& params() const { return params_; }
  Extent outputExtent() const { return output_; }
  // Whether the pipeline runs with a scene; nullopt during a plain `validate`.
  std::optional<bool> scenePresent() const { return scenePresent_; }

  bool bound(std::string_view slot) const { return find(slot) != nullptr; }
  // nullptr when the slot is unbound.
  const CheckedSlot* find(std::string_view slot) const;
  // Unknown (nullopt / 0x0) when the slot is unbound or unresolved.
  std::optional<Format> format(std::string_view slot) const;
  Extent extent(std::string_view slot) const;
  uint32_t samples(std::string_view slot) const;
  bool loads(std::string_view slot) const;
  const std::vector<CheckedSlot>& slots() const { return slots_; }
  // The pass that wrote the version a reading slot binds; nullopt when the
  // slot is unbound or writes, or the version has no writer among the
  // pipeline's passes (an imported or history resource, or an error the
  // graph reports).
  std::optional<SlotWriter> writer(std::string_view slot) const;

 private:
  std::string passName_;
  const ParamSet& params_;
  std::vector<CheckedSlot> slots_;
  Extent output_;
  std::optional<bool> scenePresent_;
  WriterLookup writers_;
};

// Where a check hook reports. Messages say what is wrong and what to do;
// the framework adds the pass, its type and the location in the config.
class PassChecks {
 public:
  // At the slot's binding (at the pass's inputs/outputs when it is unbound).
  void slotError(std::string slot, std::string message);
  // At the parameter in the config (at the pass when it is left at its default).
  void paramError(std::string param, std::string message);
  // At the pass.
  void passError(std::string message);

  struct Entry {
    enum class Kind { slot, param, pass } kind = Kind::pass;
    std::string name;  // slot or parameter
    std::string message;
  };
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::vector<Entry> entries_;
};

// "WxH" for messages.
std::string extentText(Extent e);
// "FILE:LINE:COL" (or "FILE:LINE", or FILE) for a message that names a second
// place in the config; "" when the location is unknown.
std::string locationText(const SourceLocation& at);
// A common check: slots `a` and `b` (both bound, sizes known) have the same
// size; otherwise an error at `a` naming both sizes.
void checkSameSize(const PassCheckContext& ctx, PassChecks& checks, const std::string& a, const std::string& b);

// A requirement a pass type states once: `text` is the sentence `rgraph
// passes` prints (e.g. "hdr and output must have the same size"), `check` the
// code that validate, plan, render and the executor run to enforce it.
// PassTypeDesc::rules holds them; PassTypeDesc::check is for checks with no
// sentence of their own.
struct PassRule {
  std::string text;
  std::function<void(const PassCheckContext&, PassChecks&)> check;
};
// "A, B and C must have the same size": each slot but the last is checked
// against the last with checkSameSize (slots left unbound are not compared).
PassRule sameSizeRule(std::vector<std::string> slots);

struct PassCheckOptions {
  // Whether the pipeline will run with a scene; nullopt: unknown (a pass type
  // with needsScene is then not refused).
  std::optional<bool> scenePresent;
  // false: passes the plan culls are not checked (they do not run).
  bool culledPasses = true;
};

// Runs every enabled pass's needsScene and check hook on the compiled plan.
// Passes of unknown types are skipped (the config loader reported them). A
// parameter is located by reading the config file again (pipeline.file)
// when a hook reports one; when that fails the pass is the location.
Diagnostics runPassChecks(const PipelineConfig& pipeline, const Plan& plan, const PassRegistry& registry,
                          const PassCheckOptions& options = {});

}  // namespace rgraph
