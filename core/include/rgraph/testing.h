// Unit-testing your own pipelines: compile a pipeline config (a file or JSON
// text) the way `rgraph validate` does, without a GL context, and ask the
// result simple questions by name: which passes run and in what order, which
// are culled and why, which texture each resource lives in and which share
// one, lifetimes, memory, diagnostics. Works with any test framework (this
// header includes none):
//
//   #include "rgraph/testing.h"
//   namespace rt = rgraph::testing;
//
//   TEST(MyPipeline, Compiles) {
//     rt::Options options;
//     options.pluginDirectories = {"build/lib/rgraph/plugins"};
//     rt::CompiledPipeline p = rt::compileFile("my.json", options);
//     ASSERT_TRUE(p.ok()) << p.describe();
//     EXPECT_EQ(p.order(), (std::vector<std::string>{"gbuffer", "lighting", "tonemap", "my_pass"}));
//     EXPECT_FALSE(p.culled("my_pass")) << p.cullReason("my_pass");
//     EXPECT_LT(p.allocatedBytes(), p.naiveBytes());
//   }
//
// Pass types: the built-in ones (PassRegistry::builtins(), filled in by
// librgraph: link rgraph::rgraph), or Options::registry, plus the plugins the
// config's "plugins" array names, found in Options::pluginDirectories first.
// Every compile has its own copy of those types, with its own plugins: no
// compile sees what an earlier one loaded. A program linked only to the
// GL-free libraries passes its own registry.
//
// Nothing here throws for a bad config, and no query crashes on a name the
// pipeline does not have: each says what it returns then (false, an empty
// list, nullopt). describe() is meant for a test's failure message.
//
// The namespace is rgraph::testing: code inside namespace rgraph that names
// GoogleTest's namespace writes ::testing (e.g. ::testing::Test).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/diagnostics.h"
#include "rgraph/graph.h"
#include "rgraph/hazard_check.h"
#include "rgraph/pass.h"

namespace rgraph {

class PassRegistry;

namespace testing {

struct Options {
  // The output size the graph is compiled at (sizes of "output"- and
  // scale-sized resources, hence memory).
  Extent size{1280, 720};
  // Folders searched for the plugins the config names, before
  // $RGRAPH_PLUGIN_PATH and rgraph's own plugin folder (rgraph/plugin.h).
  std::vector<std::string> pluginDirectories;
  // "Model no more than a scene needs": when set, the pipeline is adapted to
  // a scene with these features before it is compiled (rgraph/adapt.h), as
  // `rgraph render` does; adaptNotes() says what changed.
  std::optional<SceneFeatures> scene;
  // Whether the pipeline will run with a scene (pass types that draw one are
  // refused without). nullopt: unknown, not checked (as `rgraph validate`).
  std::optional<bool> scenePresent;
  // The pass types' own checks (equal sizes, G-buffer slots...: rgraph/pass_check.h).
  bool passChecks = true;
  // The glslang shader checks (rgraph/shader_check.h): compile and reflect
  // every enabled pass's programs against its bindings. Off by default: they
  // take tens of milliseconds per distinct program.
  bool shaderChecks = false;
  // Shader folders searched before the built-in ones (shaderChecks only).
  std::vector<std::string> shaderDirectories;
  // false: every transient texture gets its own memory (no aliasing).
  bool alias = true;
  // Largest texture side allowed (0: no limit); 16384 is the OpenGL 4.5 minimum.
  uint32_t maxTextureSize = 16384;
  // The pass types the pipeline may name (nullptr: PassRegistry::builtins()):
  // your own, registered in-process, beside or instead of the built-in ones.
  // Each compile copies it and loads the config's plugins into the copy, then
  // drops the copy: nothing a compile loads stays registered for the next, so
  // tests pass in any order (a type of yours and a plugin's of the same name
  // clash only within one compile).
  const PassRegistry* registry = nullptr;
};

// A texture the plan allocates, and the resources that live in it.
struct TextureInfo {
  uint32_t index = 0;  // its number in the plan (Plan::physical)
  Format format = Format::rgba8;
  Extent extent;
  uint32_t mips = 1, samples = 1;
  uint64_t bytes = 0;
  std::vector<std::string> resources;  // in first-use order; more than one: aliased
};

// When a resource is alive: the steps (positions in order()) of the first
// and last pass that runs and uses it, and those passes' names.
struct Lifetime {
  size_t first = 0, last = 0;
  std::string firstPass, lastPass;
};

// One slot of a pass as the plan binds it.
struct Binding {
  std::string slot;
  Access access = Access::sampled;
  std::string resource;      // the declared resource
  std::string readVersion;   // the version read ("" for a fresh write)
  std::string writeVersion;  // the version written ("" for a read)
  Subresource sub;           // the levels and layers bound, resolved (every one for a whole texture)
};

// A compiled pipeline (or one that failed to load), and the questions a test
// asks of it. A value: copy it, keep it, compare queries across two of them.
class CompiledPipeline {
 public:
  CompiledPipeline() = default;

  // ---- status
  // The config parsed and every pass type, slot and parameter was known
  // (with its plugins loaded): the plan below exists. false: only the
  // diagnostics say anything; every other query answers "nothing".
  bool loaded() const { return loaded_; }
  // Loaded, and no diagnostic (graph, pass checks, shaders) is an error.
  // Warnings do not count: see warnings().
  bool ok() const { return loaded_ && !hasErrors(diagnostics_); }
  // The file name messages use (the path, or the name given for text).
  const std::string& source() const { return source_; }

  // ---- diagnostics, in the order they were found (load, graph, pass
  // checks, shaders)
  const Diagnostics& diagnostics() const { return diagnostics_; }
  Diagnostics errors() const;
  Diagnostics warnings() const;
  // Whether any error has this code (hasDiagnostic: of any severity).
  bool hasError(DiagCode code) const;
  bool hasDiagnostic(DiagCode code) const;
  // Whether any diagnostic's message contains `text` (case-sensitive; "" matches any).
  bool hasMessage(std::string_view text) const;
  // The first diagnostic with this code, nullptr when none.
  const Diagnostic* find(DiagCode code) const;
  // Each diagnostic as the command line prints it:
  // `FILE:LINE:COL: error: /json/path: message`.
  std::vector<std::string> diagnosticLines() const;

  // ---- passes (by the names the config gives them)
  // Every pass the config declares, in config order (culled ones too).
  std::vector<std::string> passes() const;
  bool hasPass(std::string_view pass) const;
  // The passes that run, in execution order.
  std::vector<std::string> order() const;
  // A pass's position in order(); nullopt when it is culled or unknown.
  std::optional<size_t> step(std::string_view pass) const;
  // Whether `a` runs before `b` (false when either does not run).
  bool runsBefore(std::string_view a, std::string_view b) const;
  // Declared and not culled.
  bool runs(std::string_view pass) const;
  // Declared and culled (disabled, or nothing that reaches the output reads
  // its outputs). false for an unknown pass: check hasPass() too.
  bool culled(std::string_view pass) const;
  // Why the compiler culled it ("disabled", "its outputs (x) are never read
  // by a pass that reaches the output", ...); "" when it runs or is unknown.
  std::string cullReason(std::string_view pass) const;
  // The culled passes, in config order.
  std::vector<std::string> culledPasses() const;
  // The slots of a pass as the plan binds them (the config's inputs and
  // outputs, a slot that loads and writes counted once); empty for an unknown pass.
  std::vector<Binding> bindings(std::string_view pass) const;
  // One slot; nullopt when the pass is unknown or leaves the slot unbound.
  std::optional<Binding> binding(std::string_view pass, std::string_view slot) const;

  // ---- resources. A name is a declared resource or any version of one
  // ("hdr_lit" answers for "hdr").
  bool hasResource(std::string_view name) const;
  // The declared resource a resource or version name belongs to; "" when unknown.
  std::string resourceOf(std::string_view name) const;
  // Its versions in write order (the first is the resource's own name).
  std::vector<std::string> versions(std::string_view name) const;
  bool imported(std::string_view name) const;
  // Used by a pass that runs.
  bool used(std::string_view name) const;
  // Resolved size at Options::size; 0x0 when unknown.
  Extent extent(std::string_view name) const;
  // Bytes it would need on its own; 0 when unknown.
  uint64_t bytes(std::string_view name) const;
  // The steps and passes of its first and last use; nullopt when it is
  // unused or unknown.
  std::optional<Lifetime> lifetime(std::string_view name) const;
  // The texture it lives in; nullopt when it is imported, unused, a buffer
  // with no memory of the plan's, or unknown.
  std::optional<TextureInfo> texture(std::string_view name) const;
  // The resources sharing its texture, itself included, in first-use order;
  // empty when it has none (see texture()).
  std::vector<std::string> sharing(std::string_view name) const;
  // Whether two different resources live in the same texture.
  bool aliased(std::string_view a, std::string_view b) const;
  // Every texture (and buffer) the plan allocates.
  std::vector<TextureInfo> textures() const;
  // The groups of resources that share a texture (only groups of two or more).
  std::vector<std::vector<std::string>> aliasGroups() const;

  // ---- output and memory
  // The resource that becomes the image, and the version of it shown; ""
  // when there is none (not loaded, or an output error).
  std::string outputResource() const;
  std::string outputVersion() const;
  // Every used transient on its own, after aliasing, and the most live at one
  // pass (Plan::naiveBytes, Plan::allocatedBytes, Plan::peakLiveBytes); 0
  // when not loaded.
  uint64_t naiveBytes() const;
  uint64_t allocatedBytes() const;
  uint64_t peakLiveBytes() const;

  // ---- adaptation (Options::scene)
  // One line per change adaptToScene made ("pass 'x': ..."); empty without a scene.
  const std::vector<std::string>& adaptNotes() const { return adaptNotes_; }

  // ---- the raw results, for what the queries above do not ask
  // The plan (Plan{} when not loaded; check ok() before relying on its order
  // and textures, as graph.h's contract says).
  const Plan& plan() const { return plan_; }
  // The pipeline as loaded (and adapted); PipelineConfig{} when not loaded.
  const PipelineConfig& pipeline() const { return pipeline_; }

  // A summary for a failure message: the source and size, every diagnostic
  // line, the execution order, each culled pass with its reason, each
  // texture with its resources, the output and the memory.
  std::string describe() const;
  // One pass or resource in a line: "pass 'x' runs at step 2 (type t)",
  // "pass 'x' is culled: <reason>", or "no pass named 'x' (passes: ...)";
  // for a resource, its texture, lifetime and bytes, or the names there are.
  std::string describePass(std::string_view pass) const;
  std::string describeResource(std::string_view name) const;

 private:
  friend struct CompiledPipelineBuilder;  // compileFile and compileText fill it in

  const PlannedPass* findPass(std::string_view pass) const;
  const PlannedResource* findResource(std::string_view name) const;
  std::optional<TextureInfo> textureAt(PhysicalIndex i) const;

  std::string source_;
  bool loaded_ = false;
  Diagnostics diagnostics_;
  PipelineConfig pipeline_;
  Plan plan_;
  std::vector<std::string> adaptNotes_;
};

// Loads the pipeline in `path` (plugin paths in it relative to its folder),
// loads its plugins, adapts it to Options::scene when set, compiles it at
// Options::size and runs the checks Options asks for. A missing file or a
// config error is a diagnostic (file_not_found, json_syntax, ...), never an
// exception.
CompiledPipeline compileFile(const std::string& path, const Options& options = {});
// The same from JSON text. Messages name `nameForMessages`; plugin paths are
// relative to `baseDir` ("" = the working directory).
CompiledPipeline compileText(std::string_view json, const Options& options = {},
                             const std::string& nameForMessages = "<inline>", const std::string& baseDir = "");

// The hazard harness (rgraph/hazard_check.h) on a pipeline file, as
// `rgraph check-hazards` runs it: plain, then under each hazard mode, every
// kept resource compared. Renders (link rgraph::rgraph): in the GL context
// current, or in a headless one made for the call when none is.
//
//   rgraph::HazardCheckOptions o;
//   o.renderer.pluginDirectories = {"build/lib/rgraph/plugins"};
//   const rgraph::HazardReport r = rt::expectHazardFree("my.json", o);
//   EXPECT_TRUE(r.hazardFree()) << r.describe();
HazardReport expectHazardFree(const std::string& path, const HazardCheckOptions& options = {});

}  // namespace testing
}  // namespace rgraph
