// Runs a compiled render graph on the current GL context.
//
//   ShaderLibrary shaders;
//   Executor exec(pipeline, PassRegistry::builtins(), shaders, scene);
//   exec.resize({1280, 720});   // compile + create textures, framebuffers, pass instances
//   exec.renderFrame();          // every frame
//   auto rgba = exec.readOutputRGBA8();
//
// One GL texture per Plan::physical entry (aliased resources share it), one
// per imported or un-aliased resource, one framebuffer per pass with
// attachments. All of it is created in resize() and reused every frame.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/graph.h"
#include "rgraph/hazards.h"
#include "rgraph/pass.h"

namespace rgraph {

class PassRegistry;
class GpuScene;
struct Camera;

class Executor {
 public:
  // Keeps a copy of the pipeline and references to registry and shaders
  // (they must outlive the executor). Needs a current GL 4.5 context.
  Executor(const PipelineConfig& pipeline, const PassRegistry& registry, ShaderLibrary& shaders,
           const Scene* scene = nullptr);
  // Draws a scene already uploaded (shared with other executors: each writes
  // its own camera into the scene's Frame block at the start of its frame).
  // `gpuScene` must outlive the executor.
  Executor(const PipelineConfig& pipeline, const PassRegistry& registry, ShaderLibrary& shaders,
           GpuScene& gpuScene);
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  // Compiles the plan for this output size and (re)creates GL objects and pass
  // instances. A no-op when the size is unchanged. Throws RuntimeError when the
  // plan has errors (one formatDiagnostic line each), a pass type is unknown, a
  // framebuffer is incomplete (names the pass and status) or a pass's setup fails.
  void resize(Extent output);
  // Executes every planned pass in order (clears first-written resources that
  // have a clear value, then Pass::execute). Times each pass (timings()).
  // Never waits for the GPU, except with CPU pass timing (below).
  void renderFrame();

  // The camera of the following frames (default: the scene's own camera).
  void setCamera(const Camera& camera);
  // The next frame follows no previous one (a cut in an edit, a teleport):
  // history resources are cleared and PassContext::historyValid is false for
  // it, and motion vectors are zero (previous camera and models = current).
  void cameraCut();
  // Frames rendered since this executor was built (resize() keeps counting;
  // it resets history like a cut).
  uint64_t frameIndex() const;
  // Persistent resources (ResourceDecl::persistent) no longer hold what their
  // writers would write (the scene's environment changed): those writers run
  // again at the next frame, once. A build or resize invalidates them too.
  void invalidatePersistent();

  // The caller's GL texture for a resource declared imported (rgraph/renderer.h):
  // used from now on instead of a texture the executor creates. Throws
  // RuntimeError when the resource is unknown, not imported, or not a texture,
  // and when the texture does not match the declaration at the current size
  // (checked now when built, else at resize(); the message names the resource
  // and both descriptions). Rebuilds framebuffers and pass instances when
  // built (programs and other textures are kept).
  void importTexture(const std::string& resource, uint32_t texture);
  // Offers `previous`'s transient textures to this executor's next resize():
  // a physical texture of the same format, size, mips and samples is shared
  // instead of created (a rebuilt pipeline keeps what did not change). Both
  // may hold them until `previous` is destroyed; contents are not kept
  // meaningful (transients are written before they are read each frame).
  // History resources and their sources are neither offered nor taken: this
  // executor's history starts cleared and invalid all the same.
  void reuseTextures(const Executor& previous);

  // Back to a texture the executor owns (no-op when none was imported).
  void releaseTexture(const std::string& resource);

  // Called after each executed pass with its step (execution-order index,
  // as timings()), GL work recorded, before the next pass: for tools that copy
  // a resource out as it was right after a pass wrote it (rgraph view's
  // inspector). Empty: none. Kept across resize().
  void setAfterPass(std::function<void(size_t step)> callback);

  const Plan& plan() const;
  // Every program a pass asked the ShaderLibrary for (each once per pass, in
  // order): those the executor built from the pass type's programs(params)
  // before setup(), and any the pass built itself. The same specs are what
  // `rgraph validate` checks (ShaderChecker::checkedPrograms).
  struct BuiltProgram {
    std::string pass;
    ProgramRequest program;
    bool operator==(const BuiltProgram&) const = default;
  };
  const std::vector<BuiltProgram>& builtPrograms() const;
  // The glMemoryBarrier bits issued before each executed pass (execution
  // order, as timings()), 0 for none, and after the last pass: derived in
  // resize() from declared access, so that what a pass wrote through image or
  // storage access is visible to whoever touches it next (no pass issues
  // barriers itself). For tests and tools.
  std::vector<uint32_t> memoryBarriers() const;
  uint32_t frameEndMemoryBarrier() const;
  // The scene uploaded to the GPU (created by the first resize() when a scene
  // was given; its Frame block is updated for the output extent at the start
  // of every frame). nullptr without a scene.
  GpuScene* gpuScene() const;
  struct PassTiming {
    std::string name;
    double ms = 0.0;
    // Frames that ran the pass since the passes were built (resize, import):
    // a pass that writes only persistent resources runs only while they are
    // invalid, so steady frames leave its count (and its ms at 0) alone.
    uint64_t executions = 0;
  };
  // Per executed pass, in execution order, of the frame timingsFrame() names
  // (ms 0 while it names none). Two clocks:
  // - GL_TIME_ELAPSED queries (GPUs; any renderer with setGpuTimerQueries):
  //   each frame's queries are read without waiting, once the GPU says they
  //   are in, at the start of a later frame (or collectTimings()): timings
  //   are those of a frame 1-3 frames back. A frame that finds the queries
  //   of the 3 frames before it all still in flight is not timed (it never
  //   waits for them).
  // - CPU time around a glFinish per pass (software renderers, whose timer
  //   queries are not trustworthy; setCpuPassTiming): the frame just rendered.
  const std::vector<PassTiming>& timings() const;
  // The frame timings() belong to: frameIndex() as it was while that frame
  // ran (the frame just rendered is frameIndex() - 1). nullopt while no
  // frame's times are known: before the first, with CPU pass timing off, and
  // after resize(), an import or a clock change until a frame timed since is in
  // (results of the GL objects before are dropped, never given to the new ones).
  std::optional<uint64_t> timingsFrame() const;
  // Takes the query results that are in now, without waiting (renderFrame
  // does so at its start). wait: first waits for the GPU to finish (a
  // glFinish), so that the last frame's times are in: for a tool at the end
  // of a run or after its own glFinish, never per frame. No-op with CPU timing.
  void collectTimings(bool wait = false);
  // Whether timings come from the CPU clock around glFinish (software renderers)
  // rather than GL_TIME_ELAPSED queries.
  bool cpuTimed() const;
  // Software renderers only: whether each pass is timed with a glFinish after
  // it (default true). Off, passes are not timed (their ms stay 0) and the
  // frame runs without the stalls. GPU timer queries are unaffected.
  void setCpuPassTiming(bool on);
  // Times passes with GL_TIME_ELAPSED queries on a software renderer too
  // (default false: the CPU clock there; a GPU always uses queries). For tests
  // of the query path: llvmpipe supports the queries, but its values are
  // poor. From the next frame on; what the other clock measured is dropped.
  void setGpuTimerQueries(bool on);
  // After every pass, reads back the state groups its changedState() says
  // it leaves alone (rgraph/pass.h) and throws RuntimeError naming the pass
  // and the state when one differs. For tests of pass types; off by default
  // (the reads cost a GL query each).
  void setStateChecks(bool on);
  // Hazard modes (rgraph/hazards.h, docs/testing.md): poison, no-alias,
  // alias-shuffle, reorder, state-scramble (which turns the state checks above
  // on), no-cull. A change drops what was built: call resize() again. None
  // by default: a plain frame.
  void setHazards(const HazardModes& modes);
  const HazardModes& hazards() const;

  uint32_t outputTexture() const;
  Extent outputExtent() const;
  Format outputFormat() const;
  // Output image as RGBA8, rows top-down, 4 bytes per pixel (stored bytes:
  // an srgb8_alpha8 output gives its encoded values; a one-channel output,
  // e.g. r8, is grey: its value in R, G and B).
  std::vector<uint8_t> readOutputRGBA8() const;
  // Any resource (or one of its version names) as RGBA32F, rows top-down, 4
  // floats per pixel; depth formats give depth in R (G = B = 0, A = 1). Level 0.
  // With aliasing, a resource whose lifetime ended may have been overwritten.
  std::vector<float> readTextureRGBA32F(const std::string& resourceOrVersionName) const;
  // GL texture (or buffer) name of a resource or version; 0 when it has none.
  uint32_t textureOf(const std::string& resourceOrVersionName) const;
  uint32_t bufferOf(const std::string& resourceOrVersionName) const;

  // GL objects this executor owns right now (textures + buffers + framebuffers + queries;
  // the timer queries are made at the first frame timed with them).
  size_t ownedObjects() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgraph
