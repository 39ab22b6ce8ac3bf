// Renderer: a pipeline from a config file run in the caller's GL context
// (rgraph/renderer.h). It owns the pipeline as loaded, adapts it to the scene,
// and keeps one Executor, rebuilt only when something the GL objects depend
// on changes (size, scene features, imports, the pipeline itself).
#include "rgraph/renderer.h"

#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "../gl/device_memory.h"
#include "../gl/imported_texture.h"
#include "object_ids.h"
#include "scene_depth.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/gl_state.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass.h"
#include "rgraph/pipeline_check.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"

namespace rgraph {

namespace {

std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }

// What the adapt hooks act on. unshadowedLights only explains the rest (its
// reasons): adding a light that casts nothing must not rebuild the pipeline.
// The casting lights in view as a set: lights that move and swap their
// distance order keep their maps (no rebuild for an order alone; a budget
// then keeps its earlier choice until the set itself changes).
std::vector<std::pair<int, uint32_t>> shadowSet(const SceneFeatures& f) {
  std::vector<std::pair<int, uint32_t>> set;
  for (const auto& l : f.shadowLights) set.emplace_back(static_cast<int>(l.kind), l.light);
  std::sort(set.begin(), set.end());
  return set;
}

bool sameFeatures(const SceneFeatures& a, const SceneFeatures& b) {
  return a.pointLights == b.pointLights && a.blendMaterials == b.blendMaterials && a.normalMaps == b.normalMaps &&
         a.environment == b.environment &&
         a.metallicRoughnessVariation == b.metallicRoughnessVariation && a.metallic == b.metallic &&
         a.roughness == b.roughness && a.lightMarkers == b.lightMarkers &&
         // (The markers' size follows the scene's bounds: an object added beyond them matters only with markers.)
         (!a.lightMarkers || a.markerSizeLimit == b.markerSizeLimit) &&
         a.emissive == b.emissive && a.reflectance == b.reflectance && a.shadowCasters == b.shadowCasters &&
         shadowSet(a) == shadowSet(b);
}

}  // namespace

struct Renderer::Impl {
  RendererOptions options;
  // This renderer's pass types: a copy of options.registry (or of the
  // built-ins) with the plugins its pipelines load; never shared, so that
  // nothing another renderer or a test loads is seen here. Executors keep a
  // reference: the address stays (unique_ptr) and types are only added.
  std::unique_ptr<PassRegistry> registry;
  std::unique_ptr<PluginLoader> loader;

  // A pipeline's origin: a file (`path`), or JSON text with the name its
  // messages use; plugin paths relative to `baseDir`.
  struct Source {
    std::string path;  // empty: JSON text
    std::string json, name, baseDir;
  };
  // Where the pipeline came from: reload() re-reads the file (reloadJson does not forget it), or takes
  // `json` again (a renderer made from text, or the last text reloadJson took).
  Source bound;

  PipelineConfig source;   // as loaded
  PipelineConfig adapted;  // as adapted to the scene (what runs)
  AdaptReport report;  // the last adaptation's notes and tables
  std::optional<SceneFeatures> adaptedFor;

  std::shared_ptr<RenderScene> scene;
  uint64_t sceneVersionSeen = 0;
  uint64_t environmentSeen = 0;  // RenderScene::environmentVersion at the last frame
  uint64_t instancesSeen = 0;    // RenderScene::instancesVersion at the last frame
  Camera camera;
  Extent size;
  std::map<std::string, uint32_t> imports;
  std::function<void(size_t)> afterPass;
  bool cpuPassTiming = true;

  SceneDepthCopy depth;                        // options.keepDepth: the scene's depth of the last frame
  PickReader pick;                             // requestPick: one pixel of the object ids, a frame late
  bool pickHooked = false;                     // the executor's after-pass callback serves `pick`
  ShaderLibrary shaders;                       // kept across rebuilds: unchanged programs are reused
  std::shared_ptr<RenderScene> executorScene;  // what `executor` draws: alive as long as it is
  std::unique_ptr<Executor> executor;
  uint64_t framesBefore = 0;  // frames drawn by the executors before `executor` (Renderer::frameIndex)
  bool rebuild = true;       // the executor must be made again before the next frame
  bool sizeRefused = false;  // the last build failed on the size itself: the graph there, or its memory
  uint64_t builds = 0;
  mutable std::optional<Plan> planBeforeFrame;
  gl::Framebuffer readFramebuffer;  // the output, for blits into the caller's framebuffer
  uint32_t readAttached = 0;

  // True while render() runs: its setAfterPass callback may read (the
  // read-backs, plan, timings) but not change the renderer (refuseInFrame).
  bool rendering = false;
  class FrameScope;
  void refuseInFrame(const char* call) const;

  class CallerState;
  void makeRegistry();
  static Source fileSource(const std::string& path) {
    std::error_code ec;
    return {path, {}, path, std::filesystem::absolute(path, ec).parent_path().string()};
  }
  static Source textSource(std::string_view json, const std::string& name, const std::string& baseDir) {
    return {{}, std::string(json), name.empty() ? std::string("<json>") : name, baseDir};
  }
  // Loads and checks a pipeline (the file, or the text): nullopt with diags
  // when validate would refuse it.
  std::optional<PipelineConfig> load(const Source& from, Diagnostics& diags) const;
  // Makes `next` the pipeline: at once when a frame was drawn (building its
  // GL objects now, so that a failure leaves the last good pipeline running),
  // else at the first frame. false, with a device_error naming `from` in
  // diags, on failure.
  bool replace(PipelineConfig next, const Source& from, Diagnostics& diags);
  void adapt();
  // The scene's features seen with this renderer's camera at its output's aspect.
  SceneFeatures features() const;
  CompileOptions compileOptions() const;
  // Why a plan's textures may not be allocated (both figures: over options.maxMemoryBytes, or over what
  // the device says it has free); "" when they fit.
  std::string memoryRefusal(const Plan& plan) const;
  // A new executor for the current pipeline, scene, size and imports; the old
  // one is kept until the new one is built.
  void buildExecutor();
  // The executor's after-pass callback: the depth copy and the caller's
  // callback, or none at all when neither is wanted (a callback costs state
  // resets after every pass).
  void installAfterPass(Executor& e);
  void prepareFrame();
  // One frame of the executor, with the pick reader's before and after.
  void renderFrame();
  void blitOutput(uint32_t framebuffer, const Viewport& viewport);
};

// A change in the middle of a frame would free or rebind what the running
// executor is using (reload: the executor itself; setAfterPass: the callback
// running): refused, so that the frame ends as it began.
void Renderer::Impl::refuseInFrame(const char* call) const {
  if (rendering)
    throw RuntimeError(std::string("Renderer::") + call +
                       " called from inside a render() callback (setAfterPass): a frame is running; only the "
                       "read-backs and queries may be used there. Make the call after render() returns");
}

class Renderer::Impl::FrameScope {
 public:
  explicit FrameScope(Impl& im) : im_(im) {
    im_.refuseInFrame("render");
    im_.rendering = true;
  }
  ~FrameScope() { im_.rendering = false; }
  FrameScope(const FrameScope&) = delete;
  FrameScope& operator=(const FrameScope&) = delete;

 private:
  Impl& im_;
};

void Renderer::Impl::makeRegistry() {
  registry = std::make_unique<PassRegistry>(options.registry ? *options.registry : PassRegistry::builtins());
  loader = std::make_unique<PluginLoader>(*registry);
  for (const auto& dir : options.pluginDirectories) loader->addSearchDirectory(dir);
}

std::optional<PipelineConfig> Renderer::Impl::load(const Source& from, Diagnostics& diags) const {
  PipelineLoadOptions loadOptions;
  loadOptions.registry = registry.get();
  loadOptions.loader = loader.get();
  std::optional<PipelineConfig> loaded = from.path.empty()
                                             ? loadPipelineText(from.json, from.name, from.baseDir, loadOptions, diags)
                                             : loadPipelineFile(from.path, loadOptions, diags);
  if (!loaded) return std::nullopt;
  // What validate checks, before any GL work: a config it refuses never runs.
  CompileOptions compile;
  compile.output = options.size;
  compile.maxTextureSize = options.maxTextureSize;
  if (options.maxTextureSize > 0)
    compile.maxTextureSizeOrigin = options.maxTextureSizeOrigin.empty() ? std::string("RendererOptions::maxTextureSize")
                                                                        : options.maxTextureSizeOrigin;
  PipelineCheckOptions checks;
  checks.registry = registry.get();
  checks.passChecks = options.runChecks;
  checks.shaders = options.runChecks ? ShaderCheckMode::cached : ShaderCheckMode::skip;
  checks.shaderDirectories = options.shaderDirectories;
  Diagnostics found;
  checkPipeline(*loaded, compile, checks, found);
  diags.insert(diags.end(), found.begin(), found.end());
  if (hasErrors(found)) return std::nullopt;
  return loaded;
}

bool Renderer::Impl::replace(PipelineConfig next, const Source& from, Diagnostics& diags) {
  // Programs whose shader files changed are compiled again; the others are reused.
  if (const size_t retired = shaders.retireChanged())
    spdlog::info("{} program(s) built from changed shader files will be compiled again", retired);
  PipelineConfig previous = std::move(source);
  // A rebuild pending before (setSize, setScene, an import) stays pending on
  // failure: the next frame builds the last good pipeline for it.
  const bool pendingRebuild = rebuild;
  source = std::move(next);
  rebuild = true;
  planBeforeFrame.reset();
  if (!executor) {
    shaders.releaseRetired();
    return true;
  }
  try {
    buildExecutor();
    shaders.releaseRetired();
    return true;
  } catch (const RuntimeError& e) {
    source = std::move(previous);
    shaders.restoreRetired();
    adapt();
    rebuild = pendingRebuild;
    Diagnostic d;
    d.code = DiagCode::device_error;
    d.message = e.what();
    d.where.file = from.path.empty() ? from.name : from.path;
    diags.push_back(std::move(d));
    return false;
  }
}

// "Model no more than a scene needs", from the pipeline as loaded each time.
void Renderer::Impl::adapt() {
  adapted = source;
  report = {};
  if (scene && options.adaptToScene) {
    const SceneFeatures now = features();
    report = adaptToScene(adapted, *registry, now);
    adaptedFor = now;
  } else {
    adaptedFor.reset();
  }
  if (options.picking)
    for (const std::string& pass : addObjectIds(adapted, *registry))
      report.notes.push_back("pass '" + pass + "': writes object ids into an 'object_id' output (RendererOptions::picking)");
}

SceneFeatures Renderer::Impl::features() const {
  const float aspect = size.width > 0 && size.height > 0 ? float(size.width) / float(size.height) : 16.0f / 9.0f;
  return sceneFeatures(scene->scene(), camera, aspect);
}

CompileOptions Renderer::Impl::compileOptions() const {
  CompileOptions compile;
  compile.output = size;
  compile.maxTextureSize = options.maxTextureSize;
  applyHazardModes(options.hazards, compile);
  return compile;
}

std::string Renderer::Impl::memoryRefusal(const Plan& plan) const {
  const uint64_t need = plan.allocatedBytes;
  const std::string needs = "the pipeline at " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                            " needs " + std::to_string(need) + " bytes of textures (" + mib(need) +
                            ", Plan::allocatedBytes)";
  if (options.maxMemoryBytes > 0 && need > options.maxMemoryBytes) {
    const std::string origin =
        options.maxMemoryOrigin.empty() ? "RendererOptions::maxMemoryBytes" : options.maxMemoryOrigin;
    return needs + ", more than the " + std::to_string(options.maxMemoryBytes) + " bytes (" +
           mib(options.maxMemoryBytes) + ") " + origin + " allows";
  }
  if (const std::optional<gl::DeviceMemory> device = gl::freeDeviceMemory()) {
    // The running executor's textures are given back (or reused) once the new one is built.
    const uint64_t held = executor ? executor->plan().allocatedBytes : 0;
    if (need > device->freeBytes + held)
      return needs + ", more than the device has free: " + std::to_string(device->freeBytes + held) + " bytes (" +
             mib(device->freeBytes + held) + ", " + device->source + ")";
  }
  return {};
}

void Renderer::Impl::prepareFrame() {
  if (size.width == 0 || size.height == 0) throw RuntimeError("Renderer::render: no output size (call setSize first)");
  // Light edits change the pipeline only when they change what the scene needs
  // (its first point light, or its last one removed, or the set of shadowed
  // lights). Camera moves alone do not re-adapt.
  // Object edits likewise (their first blended or emissive material, say); moves never.
  if (scene && (scene->lightsVersion() != sceneVersionSeen || scene->instancesVersion() != instancesSeen)) {
    sceneVersionSeen = scene->lightsVersion();
    instancesSeen = scene->instancesVersion();
    if (options.adaptToScene && adaptedFor && !sameFeatures(*adaptedFor, features())) {
      spdlog::info("the scene's lights or objects changed what it needs: adapting the pipeline again");
      rebuild = true;
    }
  }
  // A new environment: pre-filtered again (persistent resources), or a
  // pipeline adapted again when the scene gains or loses one.
  if (scene && scene->environmentVersion() != environmentSeen) {
    environmentSeen = scene->environmentVersion();
    if (options.adaptToScene && adaptedFor && !sameFeatures(*adaptedFor, features()))
      rebuild = true;
    else if (executor)
      executor->invalidatePersistent();
  }
  if (rebuild || !executor) {
    try {
      buildExecutor();
    } catch (const RuntimeError&) {
      // A size refused: the last good executor keeps running at its size, and size() says so (renderer.h,
      // setSize). Other failures (an import of the old size) keep the size asked for, to be fixed at it.
      if (sizeRefused && executor && executor->plan().output != size) {
        size = executor->plan().output;
        planBeforeFrame.reset();
      }
      throw;
    }
  }
  executor->setCamera(camera);
}

void Renderer::Impl::buildExecutor() {
  adapt();
  for (const auto& note : report.notes) spdlog::debug("{}", note);
  const Plan plan = rgraph::compile(adapted.graph, compileOptions());
  const std::string overBudget = plan.ok() ? memoryRefusal(plan) : std::string();
  sizeRefused = !plan.ok() || !overBudget.empty();  // a graph with errors: the executor throws, with its messages
  if (!overBudget.empty()) throw RuntimeError(overBudget);
  auto next = scene ? std::make_unique<Executor>(adapted, *registry, shaders, scene->gpu())
                    : std::make_unique<Executor>(adapted, *registry, shaders);
  for (const auto& [name, texture] : imports) next->importTexture(name, texture);
  next->setCpuPassTiming(cpuPassTiming);
  next->setGpuTimerQueries(options.gpuTimerQueries);
  next->setHazards(options.hazards);
  if (executor) next->reuseTextures(*executor);  // what did not change is kept
  next->resize(size);
  std::optional<SceneDepthSource> depthSource;
  if (options.keepDepth) {
    depthSource = findSceneDepth(next->plan(), *registry, options.depthResource);
    if (!depthSource && !options.depthResource.empty())
      throw RuntimeError("RendererOptions::depthResource '" + options.depthResource +
                         "': no pass that runs attaches it as depth");
    if (!depthSource) spdlog::warn("RendererOptions::keepDepth: the pipeline has no scene depth to keep");
  }
  // Nothing below throws: the new executor and its depth source replace the old ones together.
  depth.setSource(depthSource);
  pick.setSource(findObjectIds(next->plan()));
  installAfterPass(*next);
  if (executor) framesBefore += executor->frameIndex();
  executor = std::move(next);
  executorScene = scene;
  rebuild = false;
  planBeforeFrame.reset();
  ++builds;
}

void Renderer::Impl::installAfterPass(Executor& e) {
  // Picking hooks in only for frames with a request: other frames pay nothing.
  pickHooked = pick.wantsFrame();
  if (!depth.active() && !afterPass && !pickHooked) return e.setAfterPass({});
  e.setAfterPass([this, &e](size_t step) {
    depth.afterPass(step, e);
    if (pickHooked)
      pick.afterPass(step, e, framesBefore + e.frameIndex(), [this] {
        return executorScene ? executorScene->instances() : std::vector<InstanceId>{};
      });
    if (afterPass) afterPass(step);
  });
}

void Renderer::Impl::renderFrame() {
  pick.poll(false, [this](InstanceId id) { return scene && scene->contains(id); });
  if (pick.wantsFrame() != pickHooked) installAfterPass(*executor);
  executor->renderFrame();
  pick.endFrame(framesBefore + executor->frameIndex() - 1);
}

void Renderer::Impl::blitOutput(uint32_t framebuffer, const Viewport& viewport) {
  const uint32_t texture = executor->outputTexture();
  const Extent out = executor->outputExtent();
  if (!readFramebuffer) readFramebuffer = gl::createFramebuffer();
  if (readAttached != texture) {
    glNamedFramebufferTexture(readFramebuffer.id(), GL_COLOR_ATTACHMENT0, texture, 0);
    glNamedFramebufferReadBuffer(readFramebuffer.id(), GL_COLOR_ATTACHMENT0);
    readAttached = texture;
  }
  const GLint w = static_cast<GLint>(viewport.width ? viewport.width : size.width);
  const GLint h = static_cast<GLint>(viewport.height ? viewport.height : size.height);
  const bool scaled = static_cast<uint32_t>(w) != out.width || static_cast<uint32_t>(h) != out.height;
  // Stored values are copied: no sRGB encoding on the way, no scissor.
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBlitNamedFramebuffer(readFramebuffer.id(), framebuffer, 0, 0, static_cast<GLint>(out.width),
                         static_cast<GLint>(out.height), viewport.x, viewport.y, viewport.x + w, viewport.y + h,
                         GL_COLOR_BUFFER_BIT, scaled ? GL_LINEAR : GL_NEAREST);
}

// ------------------------------------------------------------------ Renderer

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

std::unique_ptr<Renderer> Renderer::fromFile(const std::string& pipelinePath, const RendererOptions& options,
                                             Diagnostics& diags) {
  std::unique_ptr<Renderer> r(new Renderer());
  r->impl_->options = options;
  r->impl_->makeRegistry();
  r->impl_->bound = Impl::fileSource(pipelinePath);
  r->impl_->size = options.size;
  for (const auto& dir : options.shaderDirectories) addShaderSearchDirectory(dir);
  std::optional<PipelineConfig> loaded = r->impl_->load(r->impl_->bound, diags);
  if (!loaded) return nullptr;
  r->impl_->source = std::move(*loaded);
  return r;
}

std::unique_ptr<Renderer> Renderer::fromJson(std::string_view json, const std::string& nameForMessages,
                                             const RendererOptions& options, Diagnostics& diags,
                                             const std::string& baseDir) {
  std::unique_ptr<Renderer> r(new Renderer());
  r->impl_->options = options;
  r->impl_->makeRegistry();
  r->impl_->bound = Impl::textSource(json, nameForMessages, baseDir);
  r->impl_->size = options.size;
  for (const auto& dir : options.shaderDirectories) addShaderSearchDirectory(dir);
  std::optional<PipelineConfig> loaded = r->impl_->load(r->impl_->bound, diags);
  if (!loaded) return nullptr;
  r->impl_->source = std::move(*loaded);
  return r;
}

void Renderer::setScene(std::shared_ptr<RenderScene> scene) {
  impl_->refuseInFrame("setScene");
  impl_->scene = std::move(scene);
  impl_->sceneVersionSeen = impl_->scene ? impl_->scene->lightsVersion() : 0;
  impl_->environmentSeen = impl_->scene ? impl_->scene->environmentVersion() : 0;
  impl_->instancesSeen = impl_->scene ? impl_->scene->instancesVersion() : 0;
  impl_->camera = impl_->scene ? impl_->scene->scene().camera : Camera{};
  impl_->rebuild = true;
  impl_->planBeforeFrame.reset();
  impl_->pick.cancel();  // its ids would be the old scene's: InstanceIds are per scene
}

const std::shared_ptr<RenderScene>& Renderer::scene() const { return impl_->scene; }

void Renderer::setCamera(const Camera& camera) {
  impl_->refuseInFrame("setCamera");
  validateCamera(camera, "Renderer::setCamera");
  impl_->camera = camera;
}

const Camera& Renderer::camera() const { return impl_->camera; }

// A rebuild pending (new scene, size or pipeline) makes a new executor,
// which starts without history on its own.
void Renderer::cameraCut() {
  impl_->refuseInFrame("cameraCut");
  if (impl_->executor) impl_->executor->cameraCut();
}

void Renderer::setSize(Extent size) {
  impl_->refuseInFrame("setSize");
  if (size.width == 0 || size.height == 0)
    throw RuntimeError("Renderer::setSize: cannot render at " + std::to_string(size.width) + "x" +
                       std::to_string(size.height));
  if (size == impl_->size) return;
  impl_->size = size;
  // Every texture of the plan changes size: the next frame builds anew
  // (programs are kept), with the imports given for the new size.
  impl_->rebuild = true;
  impl_->planBeforeFrame.reset();
}

Extent Renderer::size() const { return impl_->size; }

void Renderer::importTexture(const std::string& resource, uint32_t glTexture) {
  impl_->refuseInFrame("importTexture");
  Impl& im = *impl_;
  if (std::string refusal = gl::checkImportName(im.source.graph, resource); !refusal.empty())
    throw RuntimeError(refusal);
  if (im.executor && !im.rebuild) {
    im.executor->importTexture(resource, glTexture);  // checks, and rebinds at once
  } else {
    // Checked now against the declaration at size(), although it is bound
    // when the next frame builds.
    const Plan& p = plan();
    const auto& decls = im.source.graph.resources;
    for (size_t r = 0; r < decls.size() && r < p.resources.size(); ++r) {
      if (decls[r].name != resource) continue;
      const std::string mismatch =
          gl::checkImportedTexture(resource, gl::declaredShape(decls[r], p.resources[r].extent), glTexture);
      if (!mismatch.empty()) throw RuntimeError(mismatch);
    }
  }
  im.imports[resource] = glTexture;
}

void Renderer::releaseTexture(const std::string& resource) {
  impl_->refuseInFrame("releaseTexture");
  if (impl_->imports.erase(resource) && impl_->executor && !impl_->rebuild) impl_->executor->releaseTexture(resource);
}

std::vector<std::string> Renderer::importableResources() const {
  std::vector<std::string> names;
  for (const auto& r : impl_->source.graph.resources)
    if (r.imported) names.push_back(r.name);  // the output's resource is imported too
  return names;
}

// The GL state contract (renderer.h): the caller's state is saved (unless
// asked not to), then what rgraph relies on and a caller may have changed
// (polygon mode, pixel store, clip control, ...) is reset for its own work.
class Renderer::Impl::CallerState {
 public:
  explicit CallerState(bool restore) {
    if (restore) guard_.emplace();
    gl::applyRendererDefaults();
  }

 private:
  std::optional<gl::GlStateGuard> guard_;
};

void Renderer::render() {
  Impl::FrameScope frame(*impl_);
  Impl::CallerState state(impl_->options.restoreGlState);
  impl_->prepareFrame();
  impl_->renderFrame();
}

void Renderer::render(uint32_t framebuffer, const Viewport& viewport) {
  Impl::FrameScope frame(*impl_);
  Impl::CallerState state(impl_->options.restoreGlState);
  impl_->prepareFrame();
  impl_->renderFrame();
  impl_->blitOutput(framebuffer, viewport);
}

void Renderer::present(uint32_t framebuffer, const Viewport& viewport) {
  if (!impl_->executor || !impl_->executor->outputTexture()) return;
  Impl::CallerState state(impl_->options.restoreGlState);
  impl_->blitOutput(framebuffer, viewport);
}

bool Renderer::reload(Diagnostics& diags) {
  impl_->refuseInFrame("reload");
  std::optional<PipelineConfig> loaded = impl_->load(impl_->bound, diags);
  return loaded && impl_->replace(std::move(*loaded), impl_->bound, diags);
}

bool Renderer::reloadJson(std::string_view json, Diagnostics& diags, const std::string& nameForMessages) {
  impl_->refuseInFrame("reloadJson");
  // Plugin paths stay relative to the folder of what the renderer is bound to.
  const Impl::Source text = Impl::textSource(json, nameForMessages, impl_->bound.baseDir);
  std::optional<PipelineConfig> loaded = impl_->load(text, diags);
  if (!loaded || !impl_->replace(std::move(*loaded), text, diags)) return false;
  // A renderer made from a file keeps its path (watched, re-read by reload()).
  impl_->bound.json = text.json;
  impl_->bound.name = text.name;
  return true;
}

bool Renderer::load(const std::string& pipelinePath, Diagnostics& diags) {
  impl_->refuseInFrame("load");
  const Impl::Source file = Impl::fileSource(pipelinePath);
  std::optional<PipelineConfig> loaded = impl_->load(file, diags);
  if (!loaded || !impl_->replace(std::move(*loaded), file, diags)) return false;
  impl_->bound = file;  // reload() and watchedFiles() follow the new file
  return true;
}

const PassRegistry& Renderer::passTypes() const { return *impl_->registry; }

std::vector<std::string> Renderer::loadedPlugins() const {
  std::vector<std::string> paths;
  for (const auto& plugin : impl_->loader->loaded()) paths.push_back(plugin.path);
  return paths;
}

std::vector<std::string> Renderer::watchedFiles() const {
  std::vector<std::string> files;
  if (!impl_->bound.path.empty()) files.push_back(impl_->bound.path);
  for (auto& f : impl_->shaders.files())
    if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(std::move(f));
  return files;
}

const PipelineConfig& Renderer::pipeline() const {
  return impl_->executor && !impl_->rebuild ? impl_->adapted : impl_->source;
}

const std::vector<std::string>& Renderer::adaptNotes() const { return impl_->report.notes; }
const std::vector<AdaptReport::Table>& Renderer::adaptTables() const { return impl_->report.tables; }

const Plan& Renderer::plan() const {
  if (impl_->executor && !impl_->rebuild && impl_->executor->plan().output == impl_->size)
    return impl_->executor->plan();
  if (!impl_->planBeforeFrame) {
    const PipelineConfig& p = impl_->executor && !impl_->rebuild ? impl_->adapted : impl_->source;
    impl_->planBeforeFrame = rgraph::compile(p.graph, impl_->compileOptions());
  }
  return *impl_->planBeforeFrame;
}

std::vector<Renderer::PassTiming> Renderer::timings() const {
  std::vector<PassTiming> out;
  if (!impl_->executor) return out;
  for (const auto& t : impl_->executor->timings()) out.push_back({t.name, t.ms, t.executions});
  return out;
}

std::optional<uint64_t> Renderer::timingsFrame() const {
  if (!impl_->executor) return std::nullopt;
  const std::optional<uint64_t> f = impl_->executor->timingsFrame();
  return f ? std::optional<uint64_t>(impl_->framesBefore + *f) : std::nullopt;
}

uint64_t Renderer::frameIndex() const {
  return impl_->framesBefore + (impl_->executor ? impl_->executor->frameIndex() : 0);
}

void Renderer::collectTimings(bool wait) {
  impl_->refuseInFrame("collectTimings");
  if (impl_->executor) impl_->executor->collectTimings(wait);
}

bool Renderer::cpuTimed() const { return impl_->executor && impl_->executor->cpuTimed(); }
uint32_t Renderer::outputTexture() const { return impl_->executor ? impl_->executor->outputTexture() : 0; }
Extent Renderer::outputExtent() const { return impl_->executor ? impl_->executor->outputExtent() : Extent{}; }

std::vector<uint8_t> Renderer::readOutputRGBA8() const {
  if (!impl_->executor) throw RuntimeError("Renderer::readOutputRGBA8: nothing rendered yet");
  Impl::CallerState state(impl_->options.restoreGlState);  // the caller's pack state must not apply
  return impl_->executor->readOutputRGBA8();
}

std::vector<float> Renderer::readResourceRGBA32F(const std::string& name) const {
  if (!impl_->executor) throw RuntimeError("Renderer::readResourceRGBA32F: nothing rendered yet");
  Impl::CallerState state(impl_->options.restoreGlState);
  return impl_->executor->readTextureRGBA32F(name);
}

void Renderer::setCpuPassTiming(bool on) {
  impl_->refuseInFrame("setCpuPassTiming");
  impl_->cpuPassTiming = on;
  if (impl_->executor) impl_->executor->setCpuPassTiming(on);
}

bool Renderer::cpuPassTiming() const { return impl_->cpuPassTiming; }

void Renderer::setAfterPass(std::function<void(size_t)> callback) {
  impl_->refuseInFrame("setAfterPass");
  impl_->afterPass = std::move(callback);
  if (impl_->executor) impl_->installAfterPass(*impl_->executor);
}

void Renderer::requestPick(uint32_t x, uint32_t y) {
  impl_->refuseInFrame("requestPick");
  const Extent size = impl_->size;
  if (x >= size.width || y >= size.height)
    throw RuntimeError("Renderer::requestPick: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                       ") is outside the output (" + std::to_string(size.width) + "x" + std::to_string(size.height) +
                       ", counted from its top-left corner)");
  impl_->pick.request(x, y, size);
}

std::optional<PickResult> Renderer::pickResult(bool wait) {
  impl_->refuseInFrame("pickResult");
  impl_->pick.poll(wait, [this](InstanceId id) { return impl_->scene && impl_->scene->contains(id); });
  return impl_->pick.answer();
}

uint32_t Renderer::outputDepthTexture() const { return impl_->executor ? impl_->depth.texture() : 0; }
uint32_t Renderer::outputDepthFormat() const { return outputDepthTexture() ? impl_->depth.internalFormat() : 0; }
Extent Renderer::outputDepthExtent() const { return outputDepthTexture() ? impl_->depth.extent() : Extent{}; }
std::string Renderer::outputDepthResource() const {
  return impl_->executor && impl_->depth.source() ? impl_->depth.source()->resource : std::string();
}

uint64_t Renderer::builds() const { return impl_->builds; }
Executor* Renderer::executor() { return impl_->executor.get(); }

}  // namespace rgraph
