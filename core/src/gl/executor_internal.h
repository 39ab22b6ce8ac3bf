// The executor's insides, shared by its source files: executor.cpp
// (building the plan's GL objects, running frames), executor_resources.cpp
// (imports, readback, what tools query) and executor_history.cpp (what
// carries over from one frame to the next). Not installed.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imported_texture.h"
#include "pass_programs.h"
#include "rgraph/gl/framebuffer_cache.h"
#include "rgraph/gl/context_identity.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/hazards.h"
#include "rgraph/pass.h"
#include "rgraph/scene.h"
#include "timer_query_ring.h"

namespace rgraph {
namespace exec_detail {

// A texture the executor made, shared so that a pipeline rebuilt from this
// one (Executor::reuseTextures) takes over those whose descriptions did not change.
struct SharedTexture {
  std::shared_ptr<gl::Texture> texture;
  Format format = Format::rgba8;
  Extent extent;
  uint32_t mips = 1, samples = 1;
  uint32_t layers = 1;  // TextureDesc::layers (cubes when `cube`)
  bool cube = false;
  uint32_t id() const { return texture ? texture->id() : 0; }
  explicit operator bool() const { return texture != nullptr; }
};

// After each frame, `source`'s texture is copied into `history`'s (every mip
// level; multisampled ones sample for sample).
struct HistoryCopy {
  ResourceIndex source, history;
  uint32_t from = 0, to = 0;  // GL textures
  Format format = Format::rgba8;
  Extent extent;
  uint32_t mips = 1, samples = 1;
  unsigned target = 0;     // GL texture target
  uint32_t arrayLayers = 1;  // layers copied (6 per cube)
};

// How a sampled slot bound to part of a texture (and PassContext::texture(slot,
// sub)) shows the pass only that part: a texture view (made once per plan), or
// the texture itself with its base and max level set before the pass and put
// back after (levels only: a layer range is always a view). One switch for the
// executor, so that both can be measured on one pipeline (docs/performance.md).
enum class SubresourceSampling { views, levels };
// RGRAPH_SUBRESOURCE_SAMPLING=levels|views (unset: the default, views).
SubresourceSampling subresourceSamplingFromEnvironment();

// A texture whose base and max level a pass's sampling changed (levels mode):
// put back after the pass.
struct LevelRestore {
  uint32_t texture = 0;
  int base = 0, max = 1000;
};

struct SlotBinding {
  std::string slot;
  Access access = Access::sampled;
  ResourceIndex resource;
  uint32_t texture = 0, buffer = 0;
  Format format = Format::rgba8;
  Extent extent;         // of the bound part's first level (sub.mipBegin)
  Extent textureExtent;  // the texture's level 0
  uint32_t samples = 1;
  uint32_t mips = 1;     // the texture's levels
  uint32_t arrayLayers = 1;  // the texture's array layers (6 per cube)
  bool cube = false;
  unsigned target = 0;   // the texture's GL target
  // The part bound, resolved against the texture (counts never kAll; whole
  // when the plan says kAll).
  Subresource sub;
  // A sampled slot bound to part of a texture: what its unit gets (a view, or
  // the texture with `levels` set around the pass).
  uint32_t sampled = 0;
  bool levelRange = false;
  bool immutable = true;  // immutable storage: views can be made of it
  bool loads = false;
  bool firstWrite = false;
  bool history = false;  // bound to a history resource (ResourceDecl::historyOf)
  int colorIndex = -1;    // GL_COLOR_ATTACHMENT0 + colorIndex
  bool depthAttachment = false;
};

struct ResourceObject {
  SharedTexture ownTexture;  // an imported resource the caller gave no texture
  gl::Buffer ownBuffer;
  uint32_t texture = 0, buffer = 0;
  Format format = Format::rgba8;
  Extent extent;
  uint32_t samples = 1, mips = 1;
  uint32_t layers = 1;  // TextureDesc::layers (cubes when `cube`)
  bool cube = false;
};

class PassRun final : public PassContext {
 public:
  std::string name;
  std::string typeName;
  PassIndex decl;
  ParamSet paramSet;
  std::vector<SlotBinding> slots;
  std::vector<size_t> clearSlots;  // slots first written here whose resource has a clear value
  uint32_t fbo = 0;  // from the executor's cache: shared by passes with the same attachments
  Extent fbExtent;
  gl::FramebufferCache* cache = nullptr;  // Executor::Impl::cache
  SubresourceSampling sampling = SubresourceSampling::views;
  // Levels mode: what execute() changed, put back after it (restoreLevels).
  std::vector<LevelRestore> levelRestores;
  std::unique_ptr<PassInstance> instance;
  ShaderLibrary* shaderLib = nullptr;
  const Scene* scenePtr = nullptr;
  GpuScene* gpuScenePtr = nullptr;
  Extent output;
  bool readOnlyDepth = false;
  uint32_t memoryBarrier = 0;  // glMemoryBarrier bits before execute (memory_barriers.h)
  const PassTypeDesc* type = nullptr;
  PassPrograms programs;  // built from type->programs(paramSet) before setup
  // The executor's frame state, read through historyValid() and frameIndex().
  const bool* historyHeld = nullptr;
  const uint64_t* frameCounter = nullptr;
  uint32_t emptyVao = 0;  // Executor::Impl::emptyVao
  GlBindings* bindingRecord = nullptr;  // Executor::Impl::bound
  bool jitter = true;     // PassDecl::jitter
  bool persistentOnly = false;  // writes only persistent resources: runs while they are invalid
  std::vector<ResourceIndex> poisonAtStart;  // hazard mode poison: transients whose lifetime begins here

  const SlotBinding* find(std::string_view slot) const {
    for (const auto& s : slots)
      if (s.slot == slot) return &s;
    return nullptr;
  }
  // "pass 'NAME' (type 'TYPE')", how messages name the pass.
  std::string who() const { return "pass '" + name + "' (type '" + typeName + "')"; }
  // Levels mode: base and max level of `texture` set to [base, max], what
  // it had before recorded for restoreLevels().
  void setLevels(uint32_t texture, uint32_t base, uint32_t max);

  const std::string& passName() const override { return name; }
  const ParamSet& params() const override { return paramSet; }
  Extent outputExtent() const override { return output; }
  bool bound(std::string_view slot) const override { return find(slot) != nullptr; }
  uint32_t texture(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s ? (s->sampled ? s->sampled : s->texture) : 0;
  }
  uint32_t texture(std::string_view slot, const Subresource& sub) override;
  using PassContext::framebuffer;
  PassFramebuffer framebuffer(std::span<const AttachmentRef> attachments) override;
  // Sets each levels-mode sampled slot's base and max level (before
  // execute), and puts back what execute() and they changed (after).
  void applyLevelRanges();
  void restoreLevels();
  uint32_t buffer(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s ? s->buffer : 0;
  }
  Format format(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s ? s->format : Format::rgba8;
  }
  Extent extent(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s ? s->extent : Extent{};
  }
  uint32_t samples(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s ? s->samples : 0;
  }
  bool loads(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s && s->loads;
  }
  bool historyValid(std::string_view slot) const override {
    const SlotBinding* s = find(slot);
    return s && s->history && historyHeld && *historyHeld;
  }
  uint64_t frameIndex() const override { return frameCounter ? *frameCounter : 0; }
  uint32_t framebuffer() const override { return fbo; }
  Extent framebufferExtent() const override { return fbExtent; }
  ShaderLibrary& shaders() override { return *shaderLib; }
  const Scene* scene() const override { return scenePtr; }
  GpuScene* gpuScene() override { return gpuScenePtr; }
  uint32_t emptyVertexArray() const override { return emptyVao; }
  GlBindings* bindings() override { return bindingRecord; }
  uint32_t program(size_t index) const override { return programs.program(index, name); }
  size_t programCount() const override { return programs.count(); }
};

}  // namespace exec_detail

struct Executor::Impl {
  PipelineConfig pipeline;
  const PassRegistry& registry;
  ShaderLibrary& shaders;
  const Scene* scene;
  std::unique_ptr<GpuScene> ownGpuScene;  // created once per executor when there is a scene
  GpuScene* gpuScene = nullptr;           // ownGpuScene, or one shared with other executors
  std::optional<Camera> camera;           // none: the scene's
  std::function<void(size_t)> afterPass;  // Executor::setAfterPass
  bool cpuPassTiming = true;              // Executor::setCpuPassTiming
  bool gpuTimerQueries = false;           // Executor::setGpuTimerQueries
  bool stateChecks = false;               // Executor::setStateChecks
  HazardModes hazards;                    // Executor::setHazards (executor_hazards.cpp)
  // state-scramble's hostile bindings, made at its first pass.
  std::unique_ptr<gl::Texture> hostileTexture;
  gl::Framebuffer hostileFramebuffer;
  gl::VertexArray hostileVao;
  gl::Buffer hostileBuffer;  // bound at every uniform and storage buffer binding point scrambled
  uint32_t hostileBufferBindings = 0;
  uint32_t dirtyState = kGlStateAll;      // GlStateGroup bits resetState() puts back
  bool depthMaskOff = false;              // the last pass read depth only: its mask alone to put back
  GlBindings bound;                       // PassContext::bindings: forgotten with kGlStateBindings
  std::map<std::string, uint32_t, std::less<>> imports;  // resource name -> caller's texture
  bool software = false;

  bool built = false;
  gl::ContextIdentity context;  // where the built objects live (set by build)
  Extent size;
  Plan plan;
  using SharedTexture = exec_detail::SharedTexture;
  std::vector<SharedTexture> physicalTextures;
  std::vector<SharedTexture> reusable;  // offered by the executor this one replaces; used by the next build only
  std::vector<gl::Buffer> physicalBuffers;
  std::vector<exec_detail::ResourceObject> resources;
  std::map<std::string, ResourceIndex, std::less<>> byName;  // resource and version names
  std::vector<std::unique_ptr<exec_detail::PassRun>> runs;      // execution order
  // Every pass's framebuffers and texture views, by what they attach or show.
  gl::FramebufferCache cache;
  exec_detail::SubresourceSampling sampling = exec_detail::subresourceSamplingFromEnvironment();
  gl::VertexArray emptyVao;  // PassContext::emptyVertexArray, made with the runs
  std::vector<PassTiming> timings;  // named in createRuns(), timed per frame
  std::optional<uint64_t> timingsFrame;  // the frame `timings` belong to (Executor::timingsFrame)
  // Timing with queries: made at the first frame so timed, dropped with the
  // runs (resize, rebuild), so that no result lands on another pass list.
  std::unique_ptr<gl::TimerQueryRing> queryRing;
  std::vector<uint32_t> slotUnits;  // texture units passes' slots are bound to: cleared after a frame
  gl::SamplerCache samplerCache;    // the sampler objects of the slots' sampler states (sampler_cache.h)
  std::vector<BuiltProgram> builtPrograms;  // what passes asked the ShaderLibrary for, in order
  uint32_t frameEndBarrier = 0;  // glMemoryBarrier bits after the last pass

  // Frame state (executor_history.cpp). `frame` counts every renderFrame and
  // survives resize(); the rest starts again on a build, a resize and a cut.
  uint64_t frame = 0;
  bool historyHeld = false;  // history textures hold the previous frame's content
  bool persistentHeld = false;  // persistent resources hold their writers' content (invalidatePersistent)
  std::optional<glm::mat4> prevViewProj;  // the last frame's unjittered view-projection
  std::vector<exec_detail::HistoryCopy> historyCopies;

  Impl(const PipelineConfig& p, const PassRegistry& r, ShaderLibrary& s, const Scene* sc)
      : pipeline(p), registry(r), shaders(s), scene(sc) {}

  void teardown() {
    runs.clear();  // pass instances first: they may hold GL objects of their own
    cache.clear();
    emptyVao = {};
    resources.clear();
    physicalTextures.clear();
    physicalBuffers.clear();
    byName.clear();
    timings.clear();
    timingsFrame.reset();
    queryRing.reset();
    slotUnits.clear();
    samplerCache.clear();
    builtPrograms.clear();
    frameEndBarrier = 0;
    historyCopies.clear();
    hostileFramebuffer = {};
    hostileVao = {};
    hostileBuffer = {};
    hostileTexture.reset();
    historyHeld = false;
    persistentHeld = false;
    prevViewProj.reset();
    built = false;
  }

  void build(Extent output);
  void createRuns();
  // createRuns() on a built executor; on failure nothing is left half built.
  void rebuildRuns() {
    try {
      createRuns();
    } catch (...) {
      teardown();
      throw;
    }
  }
  void createResources();
  // Timing (executor.cpp): whether passes are timed with GL_TIME_ELAPSED
  // queries, and the ring's newest results copied into `timings`.
  bool queryTimed() const { return !software || gpuTimerQueries; }
  void takeQueryTimes();
  // A reusable texture of this description (unless !reuse), else a new one.
  SharedTexture takeTexture(Format format, Extent extent, uint32_t mips, uint32_t samples, uint32_t layers, bool cube,
                            bool reuse = true);
  // The slot's default framebuffer (createRun): every attachment slot at its bound level and layers.
  void attachPassFramebuffer(exec_detail::PassRun& run);
  // A slot's part of its texture: `sub` resolved (kAll counts to the end; a
  // part outside the texture throws), its first level's extent.
  void resolveSubresource(exec_detail::PassRun& run, exec_detail::SlotBinding& b, const Subresource& sub) const;
  // Sampled slots bound to part of a texture: a view, or a level range set around the pass.
  void bindSampledSubresources(exec_detail::PassRun& run);
  gl::TextureShape declaredShape(ResourceIndex r) const;
  // Before each frame: every caller's texture still a texture of its
  // declaration (not deleted or redefined since importTexture); throws
  // RuntimeError naming the resource.
  void checkImports() const;
  // Throws RuntimeError (starting with `who`) when a built executor is used
  // in a GL context other than the one its objects were made in.
  void requireContext(const char* who) const;
  std::unique_ptr<exec_detail::PassRun> createRun(PassIndex pass, Extent output);
  void applyClears(exec_detail::PassRun& run);
  void resetState(const exec_detail::PassRun& run);
  // Throws when the state differs from the reset values in a group the
  // pass's changedState() leaves out (executor_state_check.cpp).
  void checkState(const exec_detail::PassRun& run) const;
  void checkBindings(const exec_detail::PassRun& run) const;
  void checkSamplers(const exec_detail::PassRun& run) const;  // none left bound (executor_state_check.cpp)
  void assignMemoryBarriers();
  // Hazard modes (executor_hazards.cpp): the plan's options, what each run
  // poisons (after the runs exist), the poison before a pass and the hostile
  // state before resetState().
  void hazardCompileOptions(CompileOptions& options) const;
  void planPoison();
  void poison(const exec_detail::PassRun& run);
  void scrambleState();
  // History (executor_history.cpp): which textures are copied after a frame
  // (after createResources), which physicals must never be shared with
  // another executor, the Frame block's motion, the clear before a frame that
  // follows no previous one and the copy after every frame.
  void planHistory();
  static std::vector<bool> keptPhysicals(const Plan& plan);
  void updateFrameBlock();
  void beginHistory();
  void endHistory();

  ResourceIndex resourceIndex(std::string_view name) const {
    auto it = byName.find(name);
    return it == byName.end() ? ResourceIndex() : it->second;
  }
};

}  // namespace rgraph
