#include "rgraph/gl/executor.h"

#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "memory_barriers.h"
#include "executor_internal.h"
#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/scene_program.h"

namespace rgraph {

using exec_detail::PassRun;
using exec_detail::ResourceObject;
using exec_detail::SlotBinding;

namespace {

float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

bool isSoftwareRenderer() {
  const GLubyte* r = glGetString(GL_RENDERER);
  std::string s = r ? reinterpret_cast<const char*>(r) : "";
  for (const char* n : {"llvmpipe", "softpipe", "swrast", "SWR", "Software Rasterizer"})
    if (s.find(n) != std::string::npos) return true;
  return false;
}

}  // namespace


exec_detail::SharedTexture Executor::Impl::takeTexture(Format format, Extent extent, uint32_t mips, uint32_t samples,
                                                       uint32_t layers, bool cube, bool reuse) {
  auto same = std::find_if(reusable.begin(), reusable.end(), [&](const SharedTexture& t) {
    return t.texture && t.format == format && t.extent == extent && t.mips == mips && t.samples == samples &&
           t.layers == layers && t.cube == cube;
  });
  if (reuse && same != reusable.end()) return std::exchange(*same, SharedTexture{});
  return SharedTexture{std::make_shared<gl::Texture>(gl::createTexture(format, extent, mips, samples, layers, cube)),
                       format, extent, mips, samples, layers, cube};
}

// The plan is ok: every resource a pass uses has a physical or is imported
// (rgraph/graph.h), and Plan::resources matches the config's resources.
void Executor::Impl::createResources() {
  physicalTextures.resize(plan.physical.size());
  physicalBuffers.resize(plan.physical.size());
  const std::vector<bool> kept = keptPhysicals(plan);
  const auto& decls = pipeline.graph.resources;
  for (size_t i = 0; i < plan.physical.size(); ++i) {
    const PhysicalTexture& p = plan.physical[i];
    if (p.kind == ResourceKind::texture) {
      // The shape: the physical's, or (a compiler that does not fill layers
      // and cube yet) its resources' declarations'.
      uint32_t layers = std::max<uint32_t>(1, p.layers);
      bool cube = p.cube;
      for (ResourceIndex r : p.resources) {
        layers = std::max(layers, decls[r.value()].texture.layers);
        cube = cube || decls[r.value()].texture.cube;
      }
      physicalTextures[i] = takeTexture(p.format, p.extent, p.mips, p.samples, layers, cube, !kept[i]);
    } else {
      physicalBuffers[i] = gl::createBuffer();
      glNamedBufferStorage(physicalBuffers[i].id(), static_cast<GLsizeiptr>(std::max<uint64_t>(p.bytes, 4)), nullptr,
                           GL_DYNAMIC_STORAGE_BIT);
    }
  }

  resources.resize(plan.resources.size());
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const PlannedResource& pr = plan.resources[r];
    const ResourceDecl& decl = decls[r];
    ResourceObject& obj = resources[r];
    byName[pr.name] = ResourceIndex(r);
    for (const auto& v : pr.versions) byName.emplace(v, ResourceIndex(r));
    if (pr.kind == ResourceKind::texture) {
      obj.extent = pr.extent;
      obj.format = decl.texture.format;
      obj.samples = std::max<uint32_t>(1, decl.texture.samples);
      obj.mips = decl.texture.mips;
      obj.layers = std::max<uint32_t>(1, decl.texture.layers);
      obj.cube = decl.texture.cube;
      if (pr.physical.valid()) {
        const PhysicalTexture& p = plan.physicalTexture(pr.physical);
        const SharedTexture& t = physicalTextures[pr.physical.value()];
        obj.texture = t.id();
        obj.layers = t.layers;
        obj.cube = t.cube;
        obj.format = p.format;
        obj.extent = p.extent;
        obj.samples = std::max<uint32_t>(1, p.samples);
        obj.mips = p.mips;
      } else if (pr.imported) {  // used or not; an unused transient gets nothing
        if (auto it = imports.find(pr.name); it != imports.end()) {
          const std::string mismatch = gl::checkImportedTexture(pr.name, declaredShape(ResourceIndex(r)), it->second);
          if (!mismatch.empty()) throw RuntimeError(mismatch);
          obj.texture = it->second;
        } else {
          obj.ownTexture = takeTexture(obj.format, obj.extent, obj.mips, obj.samples, obj.layers, obj.cube);
          obj.texture = obj.ownTexture.id();
        }
      }
      if (obj.mips == 0) obj.mips = gl::fullMipCount(obj.extent);
      if (obj.texture) {
        GLint levels = 1;
        if (obj.samples <= 1) glGetTextureParameteriv(obj.texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
        obj.mips = static_cast<uint32_t>(std::max(levels, 1));
      }
    } else {
      if (pr.physical.valid()) {
        obj.buffer = physicalBuffers[pr.physical.value()].id();
      } else if (pr.imported) {
        obj.ownBuffer = gl::createBuffer();
        glNamedBufferStorage(obj.ownBuffer.id(), static_cast<GLsizeiptr>(std::max<uint64_t>(pr.bytes, 4)), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        obj.buffer = obj.ownBuffer.id();
      }
    }
  }
}

std::unique_ptr<PassRun> Executor::Impl::createRun(PassIndex pass, Extent output) {
  const PassDecl& pd = pipeline.graph.passes[pass.value()];
  const PassTypeDesc* type = registry.find(pd.type);
  if (!type) throw RuntimeError("pass '" + pd.name + "': unknown pass type '" + pd.type + "'");

  auto run = std::make_unique<PassRun>();
  run->name = pd.name;
  run->type = type;
  run->typeName = pd.type;
  run->decl = pass;
  run->shaderLib = &shaders;
  run->scenePtr = scene;
  run->gpuScenePtr = gpuScene;
  run->historyHeld = &historyHeld;
  run->frameCounter = &frame;
  run->emptyVao = emptyVao.id();
  run->bindingRecord = &bound;
  run->cache = &cache;
  run->sampling = sampling;
  run->output = output;
  run->jitter = pd.jitter;
  // Writes persistent resources only (and at least one): skipped while they are valid.
  bool writes = false, onlyPersistent = true;
  for (const BoundUse& u : plan.uses(pass)) {
    if (!isWriteAccess(u.access)) continue;
    writes = true;
    onlyPersistent = onlyPersistent && u.resource.valid() && plan.resource(u.resource).persistent;
  }
  run->persistentOnly = writes && onlyPersistent;
  run->paramSet = defaultParams(type->params);
  if (pass.value() < pipeline.params.size())
    for (const auto& [k, v] : pipeline.params[pass.value()].values()) run->paramSet.set(k, v);

  auto slotOrder = [&](const std::string& slot) {
    for (size_t i = 0; i < type->slots.size(); ++i)
      if (type->slots[i].name == slot) return i;
    return type->slots.size();
  };

  for (const BoundUse& u : plan.uses(pass)) {
    const ResourceObject& obj = resources[u.resource.value()];
    SlotBinding b;
    b.slot = u.slot;
    b.access = u.access;
    b.resource = u.resource;
    b.loads = isWriteAccess(u.access) && !u.readVersion.empty();
    b.firstWrite = u.firstWrite;
    b.history = plan.resources[u.resource.value()].historyOf.valid();
    b.texture = obj.texture;
    b.buffer = obj.buffer;
    b.format = obj.format;
    b.textureExtent = b.extent = obj.extent;
    b.samples = obj.samples;
    b.mips = obj.mips;
    b.arrayLayers = obj.layers * (obj.cube ? 6 : 1);
    b.cube = obj.cube;
    b.target = gl::textureTarget(obj.samples, obj.layers, obj.cube);
    if (obj.texture) resolveSubresource(*run, b, u.sub);
    run->slots.push_back(std::move(b));
  }
  std::stable_sort(run->slots.begin(), run->slots.end(),
                   [&](const SlotBinding& a, const SlotBinding& b) { return slotOrder(a.slot) < slotOrder(b.slot); });
  for (size_t i = 0; i < run->slots.size(); ++i) {
    const ResourceDecl& decl = pipeline.graph.resources[run->slots[i].resource.value()];
    if (run->slots[i].firstWrite && decl.kind == ResourceKind::texture && decl.texture.clear)
      run->clearSlots.push_back(i);
  }

  attachPassFramebuffer(*run);
  bindSampledSubresources(*run);

  if (!type->create) throw RuntimeError("pass type '" + pd.type + "' has no factory");
  run->instance = type->create();
  if (!run->instance) throw RuntimeError("pass '" + pd.name + "': pass type '" + pd.type + "' created no instance");
  return run;
}

void Executor::Impl::build(Extent output) {
  context = gl::currentContext();
  CompileOptions opts;
  opts.output = output;
  // The device's own limit, so that a texture it cannot hold is a located
  // diagnostic here rather than a GL error later.
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  if (maxTexture > 0) {
    const GLubyte* renderer = glGetString(GL_RENDERER);
    opts.maxTextureSize = static_cast<uint32_t>(maxTexture);
    opts.maxTextureSizeOrigin = std::string("this device's GL_MAX_TEXTURE_SIZE") +
                                (renderer ? std::string(" (") + reinterpret_cast<const char*>(renderer) + ")" : "");
  }
  hazardCompileOptions(opts);
  plan = compile(pipeline.graph, opts);
  if (!plan.ok()) {
    std::string msg = "the render graph";
    if (!pipeline.file.empty()) msg += " of " + pipeline.file;
    msg += " has errors:";
    for (const auto& d : plan.diagnostics)
      if (d.severity == Severity::error) msg += "\n  " + formatDiagnostic(d);
    throw RuntimeError(msg);
  }
  for (const auto& d : plan.diagnostics)
    if (d.severity == Severity::warning) spdlog::warn("{}", formatDiagnostic(d));
  // What the pass types require of the passes that run (rgraph/pass_check.h),
  // before any texture or program exists.
  PassCheckOptions checkOptions;
  checkOptions.scenePresent = scene != nullptr;
  checkOptions.culledPasses = false;
  const Diagnostics refused = runPassChecks(pipeline, plan, registry, checkOptions);
  if (hasErrors(refused)) {
    std::string msg = "the render graph";
    if (!pipeline.file.empty()) msg += " of " + pipeline.file;
    msg += " cannot run:";
    for (const auto& d : refused) msg += "\n  " + formatDiagnostic(d);
    throw RuntimeError(msg);
  }

  if (scene && !gpuScene) {
    ownGpuScene = std::make_unique<GpuScene>(*scene);
    gpuScene = ownGpuScene.get();
  }
  size = output;
  createResources();
  reusable.clear();  // what was not taken is the previous executor's alone again
  createRuns();
  built = true;
}

// Framebuffers, pass instances and their programs over the resources as they
// are now (again after an import changes a texture).
void Executor::Impl::createRuns() {
  runs.clear();
  cache.clear();
  if (!emptyVao) emptyVao = gl::createVertexArray();
  builtPrograms.clear();
  slotUnits.clear();
  for (PassIndex pass : plan.order) runs.push_back(createRun(pass, size));
  timings.clear();
  for (const auto& run : runs) timings.push_back({run->name, 0.0, 0});
  timingsFrame.reset();
  queryRing.reset();  // pending results are of the previous runs
  assignMemoryBarriers();
  planHistory();
  planPoison();
  // Scene vertex shaders deform (skins, morph targets) only in scenes that need it.
  std::vector<std::string> sceneDefines;
  if (scene && GpuScene::sceneDeforms(*scene)) sceneDefines.push_back(kSceneAnimationDefine);
  for (auto& run : runs) {
    try {
      // The programs the type's spec names, before setup, so that a pass
      // takes them by index instead of building them itself.
      RequestRecorder record(shaders, builtPrograms, run->name);
      run->programs.build(run->name, *run->type, run->paramSet, shaders, sceneDefines);
      run->programs.resolveSlots(*run);
      run->programs.resolveSamplers(pipeline, run->decl.value(), *run->type, samplerCache);
      run->instance->setup(*run);
    } catch (const RuntimeError& e) {
      // Where the pass is in the config, when it came from one.
      std::string at;
      const SourceLocation& w = pipeline.graph.passes[run->decl.value()].where;
      if (w.known())
        at = " at " + w.file + ":" + std::to_string(w.line) + ":" + std::to_string(w.column) +
             (w.path.empty() ? "" : " (" + w.path + ")");
      std::string message = std::string(e.what()) + "\n  (in setup of pass '" + run->name + "' of type '" +
                            run->typeName + "'" + at + ")";
      if (dynamic_cast<const LocatedError*>(&e)) throw LocatedError(message);
      throw RuntimeError(message);
    }
    for (uint32_t unit : run->programs.units())
      if (std::find(slotUnits.begin(), slotUnits.end(), unit) == slotUnits.end()) slotUnits.push_back(unit);
  }
}

gl::TextureShape Executor::Impl::declaredShape(ResourceIndex r) const {
  return gl::declaredShape(pipeline.graph.resources[r.value()], plan.resources[r.value()].extent);
}

// What passes may rely on (docs/writing-a-pass.md, rgraph/pass.h's
// GlStateGroup), put back only where the state may differ: at the start of a
// frame everything, after a pass what its changedState() names. Bindings are
// not reset: a pass binds the framebuffer (and viewport), program and vertex
// array it draws with; binding 0 in between would only make the driver
// validate them again. What was bound through PassContext::bindings() is
// remembered (GlBindings) until a pass says it bound something itself.
void Executor::Impl::resetState(const PassRun& run) {
  const uint32_t d = dirtyState;
  if (d & kGlStateBlend) glDisable(GL_BLEND);
  if (d & kGlStateDepth) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  } else if (depthMaskOff) {
    glDepthMask(GL_TRUE);  // only the mask a read-only depth pass had
  }
  depthMaskOff = false;
  if (d & kGlStateStencil) {
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xFFu);
  }
  if (d & kGlStateCull) glDisable(GL_CULL_FACE);
  if (d & kGlStateScissor) glDisable(GL_SCISSOR_TEST);
  if (d & kGlStateColorMask) glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  if (d & kGlStateSrgb) glEnable(GL_FRAMEBUFFER_SRGB);
  if (d & kGlStateBindings) {
    bound.forget();
    if (gpuScene) gpuScene->forgetBindings();
  }
  dirtyState = 0;
  if (run.readOnlyDepth) {
    glDepthMask(GL_FALSE);
    depthMaskOff = true;
  }
}

// Derived once per plan, not searched per frame: which passes read what an
// earlier pass wrote through image or storage access.
void Executor::Impl::assignMemoryBarriers() {
  const MemoryBarrierPlan barriers = deriveMemoryBarriers(plan);
  for (size_t i = 0; i < runs.size() && i < barriers.beforePass.size(); ++i)
    runs[i]->memoryBarrier = barriers.beforePass[i];
  frameEndBarrier = barriers.afterFrame;
}

void Executor::Impl::applyClears(PassRun& run) {
  for (size_t slot : run.clearSlots) {
    const SlotBinding& s = run.slots[slot];
    const std::vector<float>& c = *pipeline.graph.resources[s.resource.value()].texture.clear;
    if (gl::isDepth(s.format)) {
      float d = c.empty() ? 1.0f : c[0];
      GLint stencil = c.size() > 1 ? static_cast<GLint>(c[1]) : 0;
      if (s.depthAttachment) {
        if (gl::hasStencil(s.format))
          glClearNamedFramebufferfi(run.fbo, GL_DEPTH_STENCIL, 0, d, stencil);
        else
          glClearNamedFramebufferfv(run.fbo, GL_DEPTH, 0, &d);
      } else {
        for (uint32_t level = 0; level < s.mips; ++level) {
          if (gl::hasStencil(s.format)) {
            struct {
              float depth;
              uint32_t stencil;
            } ds{d, static_cast<uint32_t>(stencil) & 0xFFu};
            glClearTexImage(s.texture, static_cast<GLint>(level), GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV,
                            &ds);
          } else {
            glClearTexImage(s.texture, static_cast<GLint>(level), GL_DEPTH_COMPONENT, GL_FLOAT, &d);
          }
        }
      }
    } else {
      float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      for (size_t i = 0; i < 4 && i < c.size(); ++i) v[i] = c[i];
      if (s.colorIndex >= 0) {
        glClearNamedFramebufferfv(run.fbo, GL_COLOR, s.colorIndex, v);
      } else {
        if (gl::isSrgb(s.format))
          for (int i = 0; i < 3; ++i) v[i] = linearToSrgb(v[i]);
        for (uint32_t level = 0; level < s.mips; ++level)
          glClearTexImage(s.texture, static_cast<GLint>(level), GL_RGBA, GL_FLOAT, v);
      }
    }
  }
}

// ------------------------------------------------------------------ Executor

Executor::Executor(const PipelineConfig& pipeline, const PassRegistry& registry, ShaderLibrary& shaders,
                   const Scene* scene)
    : impl_(std::make_unique<Impl>(pipeline, registry, shaders, scene)) {
  impl_->software = isSoftwareRenderer();
}

Executor::Executor(const PipelineConfig& pipeline, const PassRegistry& registry, ShaderLibrary& shaders,
                   GpuScene& gpuScene)
    : impl_(std::make_unique<Impl>(pipeline, registry, shaders, &gpuScene.scene())) {
  impl_->gpuScene = &gpuScene;
  impl_->software = isSoftwareRenderer();
}

void Executor::setCamera(const Camera& camera) { impl_->camera = camera; }
void Executor::setCpuPassTiming(bool on) { impl_->cpuPassTiming = on; }
void Executor::setGpuTimerQueries(bool on) {
  if (impl_->gpuTimerQueries == on) return;
  impl_->gpuTimerQueries = on;
  impl_->queryRing.reset();  // the clock changes: what was measured with the other one is not reported
  impl_->timingsFrame.reset();
}
void Executor::setStateChecks(bool on) { impl_->stateChecks = on; }
void Executor::setHazards(const HazardModes& modes) {
  if (impl_->hazards == modes) return;
  impl_->requireContext("Executor::setHazards");
  impl_->hazards = modes;
  impl_->teardown();  // the plan may change: built again at the next resize()
}
const HazardModes& Executor::hazards() const { return impl_->hazards; }
void Executor::setAfterPass(std::function<void(size_t)> callback) { impl_->afterPass = std::move(callback); }


Executor::~Executor() {
  if (impl_) impl_->teardown();
}

void Executor::resize(Extent output) {
  if (output.width == 0 || output.height == 0)
    throw RuntimeError("cannot render at " + std::to_string(output.width) + "x" + std::to_string(output.height));
  impl_->requireContext("Executor::resize");  // teardown would delete another context's objects
  if (impl_->built && impl_->size == output) return;
  impl_->teardown();
  try {
    impl_->build(output);
  } catch (...) {
    impl_->teardown();
    throw;
  }
}

void Executor::renderFrame() {
  Impl& im = *impl_;
  if (!im.built) throw RuntimeError("Executor::renderFrame: call resize() first");
  im.requireContext("Executor::renderFrame");
  if (im.gpuScene) im.gpuScene->requireUploadContext("Executor::renderFrame");
  im.checkImports();
  using Clock = std::chrono::steady_clock;
  im.updateFrameBlock();
  im.beginHistory();
  // Software renderers: CPU time around a glFinish per pass, only when asked
  // (setCpuPassTiming): each finish stalls the pipeline the driver keeps.
  // Otherwise timer queries, read frames later without waiting (timer_query_ring.h).
  const bool queries = im.queryTimed();
  const bool cpuTiming = !queries && im.cpuPassTiming;
  gl::TimerQueryRing* ring = nullptr;
  if (queries) {
    if (!im.queryRing) im.queryRing = std::make_unique<gl::TimerQueryRing>(im.runs.size());
    ring = im.queryRing.get();
    ring->beginFrame(im.frame);
    im.takeQueryTimes();
  } else {
    im.timingsFrame.reset();
    for (auto& t : im.timings) t.ms = 0.0;
  }
  im.dirtyState = kGlStateAll;  // whatever the caller left
  // The scene's draws keep the passes' binding record up to date (no
  // kGlStateBindings for a pass that draws the scene), this frame only.
  struct RecordScope {
    GpuScene* scene;
    ~RecordScope() {
      if (scene) scene->useBindingRecord(nullptr);
    }
  } recordScope{im.gpuScene};
  if (im.gpuScene) im.gpuScene->useBindingRecord(&im.bound);
  if (cpuTiming) glFinish();
  for (size_t i = 0; i < im.runs.size(); ++i) {
    PassRun& run = *im.runs[i];
    // What it writes is persistent and still valid: nothing to do this frame.
    if (run.persistentOnly && im.persistentHeld) {
      if (cpuTiming) im.timings[i].ms = 0.0;
      continue;
    }
    ++im.timings[i].executions;
    const Clock::time_point t0 = cpuTiming ? Clock::now() : Clock::time_point{};
    if (ring) ring->beginPass(i);
    if (run.memoryBarrier) glMemoryBarrier(run.memoryBarrier);
    if (im.hazards.any()) {  // the one test a plain frame pays (rgraph/hazards.h)
      if (im.hazards.has(HazardMode::stateScramble)) im.scrambleState();
      im.poison(run);
    }
    im.resetState(run);
    if (im.gpuScene) im.gpuScene->selectJitter(run.jitter);
    // The pass's framebuffer before its inputs: a pass usually reads what the
    // one before drew into, and binding that texture while its framebuffer is
    // still bound costs the driver a flush more.
    if (run.fbo && im.bound.drawFramebuffer != run.fbo) {
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, run.fbo);
      im.bound.drawFramebuffer = run.fbo;
    }
    im.applyClears(run);
    run.applyLevelRanges();
    run.programs.bindSlots();
    try {
      RequestRecorder record(im.shaders, im.builtPrograms, run.name);
      run.instance->execute(run);
      run.programs.unbindSamplers();
      run.restoreLevels();
      im.dirtyState |= run.instance->changedState();
      if (im.stateChecks || im.hazards.has(HazardMode::stateScramble)) im.checkState(run);
    } catch (const RuntimeError& e) {
      run.programs.unbindSamplers();
      run.restoreLevels();
      if (ring) ring->endPass(i);
      std::string message = std::string(e.what()) + "\n  (in pass '" + run.name + "' of type '" + run.typeName + "')";
      if (dynamic_cast<const LocatedError*>(&e)) throw LocatedError(message);
      throw RuntimeError(message);
    }
    if (ring) ring->endPass(i);
    if (cpuTiming) {
      glFinish();
      im.timings[i].ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    }
    if (im.afterPass) {
      im.afterPass(i);  // outside the pass's time
      im.dirtyState = kGlStateAll;
    }
  }
  if (im.frameEndBarrier) glMemoryBarrier(im.frameEndBarrier);
  if (ring) ring->endFrame();
  if (cpuTiming) im.timingsFrame = im.frame;
  im.endHistory();
  im.persistentHeld = true;
  ++im.frame;
  // Leave a neutral state for whoever draws next (e.g. a blit to the window:
  // sRGB encoding left on would encode the output a second time).
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(0);
  glBindVertexArray(0);
  for (uint32_t unit : im.slotUnits) glBindTextureUnit(unit, 0);
}

void Executor::Impl::takeQueryTimes() {
  if (!queryRing || queryRing->resultFrame() == timingsFrame) return;
  const std::vector<double>& ms = queryRing->resultMs();
  for (size_t i = 0; i < timings.size() && i < ms.size(); ++i) timings[i].ms = ms[i];
  timingsFrame = queryRing->resultFrame();
}

void Executor::collectTimings(bool wait) {
  Impl& im = *impl_;
  if (!im.queryRing) return;
  im.requireContext("Executor::collectTimings");
  if (wait) glFinish();  // asked for: the frames in flight finish, their queries are in
  im.queryRing->collect();
  im.takeQueryTimes();
}

const Plan& Executor::plan() const { return impl_->plan; }
const std::vector<Executor::BuiltProgram>& Executor::builtPrograms() const { return impl_->builtPrograms; }
std::vector<uint32_t> Executor::memoryBarriers() const {
  std::vector<uint32_t> bits;
  for (const auto& run : impl_->runs) bits.push_back(run->memoryBarrier);
  return bits;
}
uint32_t Executor::frameEndMemoryBarrier() const { return impl_->frameEndBarrier; }
GpuScene* Executor::gpuScene() const { return impl_->gpuScene; }
const std::vector<Executor::PassTiming>& Executor::timings() const { return impl_->timings; }
std::optional<uint64_t> Executor::timingsFrame() const { return impl_->timingsFrame; }
bool Executor::cpuTimed() const { return !impl_->queryTimed(); }

}  // namespace rgraph
