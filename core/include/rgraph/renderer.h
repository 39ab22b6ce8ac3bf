// rgraph inside your own OpenGL program: run a pipeline from a config file in
// the GL context you made current, into your framebuffer or your textures.
// rgraph creates no context and no window on this path.
//
//   rgraph::Diagnostics diags;
//   auto renderer = rgraph::Renderer::fromFile("pipelines/default.json", {}, diags);
//   if (!renderer) { for (auto& d : diags) std::cerr << rgraph::formatDiagnostic(d) << "\n"; return 1; }
//   auto scene = rgraph::RenderScene::load("learnopengl:overview");
//   renderer->setScene(scene);
//   renderer->setSize({1280, 720});
//   while (running) {
//     renderer->setCamera(myCamera);                    // every frame, no rebuild
//     scene->setPointLight(0, movedLight);              // lights too
//     scene->setTransform(crate, crateMatrix);          // and objects (addInstance)
//     renderer->render(/*framebuffer=*/0);              // 0 = the window
//     ... your own drawing; your GL state is as you left it ...
//   }
//
// Imported targets: a resource the config declares with "imported": true can
// be given one of your GL textures (importTexture); rgraph reads and writes it
// in place, never aliases it, and never culls a pass that writes it.
//
// Several renderers in one context (a main view and an inset, say) may share
// one RenderScene: the scene is uploaded to the GPU once, lights edited once.
//
// Contexts. A renderer and a RenderScene belong to the GL context current
// when they first draw (the scene: when it is uploaded). Drawing either in
// another context throws RuntimeError saying so, and draws nothing: also in a
// context sharing objects with the first, since GL never shares the vertex
// arrays and framebuffers they hold. Each context needs its own renderers and
// its own RenderScene (RenderScene::load again). The context is told apart by
// the window system's name for it (EGL, GLX) and, where neither knows it, by
// whether the scene's buffer is a buffer there.
//
// Re-entry. While render() runs, its setAfterPass callback may use the
// read-backs (readResourceRGBA32F, readOutputRGBA8) and the const queries;
// any other Renderer call from inside it (reload, reloadJson, load, setSize,
// setScene, setCamera, importTexture, render itself, ...) throws RuntimeError
// naming the call ("called from inside a render() callback") and changes
// nothing: nothing is deferred to the end of the frame.
//
// Errors. Config problems (JSON, graph, pass checks, shader checks) are
// Diagnostics with file:line:col and the JSON path, never exceptions: the
// factories return nullptr, reload() returns false and keeps the last good
// pipeline. What can only fail on the device (a framebuffer the driver calls
// incomplete, a shader the driver refuses, a texture over its size limit) and
// misuse (an imported texture that does not match its declaration, an unknown
// resource name, a light or camera outside the ranges of scene files) throw
// rgraph::RuntimeError with one clear message. A call that throws or returns
// false changes nothing: what size(), scene(), pipeline() and the next frame
// see is the state after the last call that succeeded (setSize and setScene
// succeed at once; the next frame builds for them, even after a failed reload).
//
// GL state contract. render() (and the read-backs) change GL state while they run and, with
// RendererOptions::restoreGlState (the default), put back everything they may touch before they return: the draw and
// read framebuffers, the current program, the vertex array, the buffers bound to GL_ARRAY_BUFFER, GL_UNIFORM_BUFFER,
// GL_SHADER_STORAGE_BUFFER, GL_PIXEL_PACK_BUFFER and GL_PIXEL_UNPACK_BUFFER, the viewport and scissor box (index 0),
// the enables (blend per draw buffer, depth test, stencil test, cull face, scissor test, framebuffer sRGB, polygon
// offset fill, multisample, depth clamp, rasterizer discard, colour logic op, primitive restart, sample alpha to
// coverage, sample coverage, sample mask), the blend functions, blend equations and colour mask of draw buffers 0-7,
// the blend colour, depth function, depth mask, stencil functions, masks and operations (front and back), cull face
// mode, front face, polygon mode, clip control, the active texture unit, the textures (every target) and sampler
// bound on units 0-15, uniform and shader storage buffer bindings 0-7 with their ranges, image unit bindings 0-7,
// and the pixel pack and unpack parameters (alignment, row length, image height, skips). For its own work it first
// resets what a caller may have changed and rgraph relies on (always, restoreGlState or not): polygon mode fill,
// multisample on, no polygon offset, rasterizer discard, logic op, primitive restart or sample coverage, the default
// clip control and pixel store, no pixel pack or unpack buffer, no sampler object on units 0-15. Not restored: the
// contents of rgraph's own objects, viewports and scissor boxes past index 0, draw buffers 8 and up; rgraph never
// changes clear values, depth range, polygon offset factors, the logic op, the primitive restart index or the sample
// coverage value. A program the caller deleted while it was current is not made current again. See docs/embedding.md.
//
// Threading: use a renderer on the thread whose context is current, and
// destroy renderers and scenes while that context is still current.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/diagnostics.h"
#include "rgraph/graph.h"
#include "rgraph/hazards.h"
#include "rgraph/scene.h"

namespace rgraph {

class Executor;
class GpuScene;
class PassRegistry;

// A scene object's handle (RenderScene::addInstance, instances()): stays
// valid until that object is removed, whatever else is added or removed;
// never reused within one RenderScene. 0 is no object.
struct InstanceId {
  uint64_t value = 0;
  explicit operator bool() const { return value != 0; }
  auto operator<=>(const InstanceId&) const = default;
};

// The material values an object may change per frame (RenderScene::
// setMaterialParameters), in the ranges of glTF: colour factors in 0..1,
// metallic and roughness in 0..1, emissive finite and >= 0.
struct MaterialParameters {
  glm::vec4 baseColorFactor{1.0f};
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  glm::vec3 emissiveFactor{0.0f};
};

// A scene that renderers draw: the CPU data, edits to its lights, and one GPU
// upload shared by every renderer that draws it, all in the one GL context
// it was uploaded in (Contexts, top of this file).
class RenderScene {
 public:
  // A scene file (.json), a glTF (.gltf/.glb) or a procedural name
  // (learnopengl:overview, many-lights:N, ...), as `rgraph render --scene`.
  // Throws RuntimeError naming the file and the problem.
  static std::shared_ptr<RenderScene> load(const std::string& spec);
  // A scene built in code. Throws RuntimeError when it breaks Scene::validate().
  // After validating it derives what loaders fill in and code may leave out
  // (what is given is kept): a MeshData::bounds left empty from the mesh's
  // positions (MeshData::updateBounds), a Primitive::bounds left empty from
  // its mesh's bounds, transform and instances (Primitive::worldBounds), and
  // a point or spot light's radius left 0 from its attenuation (lightRadius
  // at kLightThreshold; 0 again for a light too dim to reach it). The camera,
  // materials and everything else are taken as given. load() goes through
  // here too (its loaders fill these in already).
  static std::shared_ptr<RenderScene> fromScene(Scene scene);
  ~RenderScene();
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;

  const Scene& scene() const;

  // Light edits take effect at the next frame of every renderer drawing the
  // scene, without rebuilding pipelines; the light buffers are rewritten in
  // place (they grow only past a power of two). Exception: when the scene
  // gains its first point light or loses its last one, renderers adapt their
  // pipeline to it again (no point lights: no light volumes) at their next
  // frame. A light or ambient outside the ranges scene files have (negative
  // colour, intensity, attenuation or radius, a spot's cone, a zero
  // directional light, a position not finite or beyond +-1e15: rgraph/scene.h
  // pointLightProblem and the others, scenes/README.md) throws RuntimeError
  // naming the light and the value, and changes nothing.
  size_t pointLightCount() const;
  const PointLight& pointLight(size_t index) const;
  void setPointLight(size_t index, const PointLight& light);
  size_t addPointLight(const PointLight& light);  // returns its index
  void removePointLight(size_t index);             // later lights move down by one
  void setPointLights(std::vector<PointLight> lights);
  void setDirectionalLights(std::vector<DirectionalLight> lights);
  void setAmbient(const glm::vec3& ambient);
  // Increases with every light or ambient edit.
  uint64_t lightsVersion() const;
  // The image-based lighting environment (nullopt: none). Renderers
  // pre-filter it again at their next frame (their persistent IBL resources
  // are invalidated); gaining or losing one adapts their pipeline again. An
  // hdr environment with no pixels, or a negative or non-finite value, throws
  // RuntimeError and changes nothing.
  void setEnvironment(std::optional<Environment> environment);
  // Increases with every setEnvironment.
  uint64_t environmentVersion() const;

  // ---- Objects (instances): what an editor or a game moves.
  // Every primitive of the scene is an object with an InstanceId (a loaded
  // scene's primitives too, in scene().primitives order). Edits take effect
  // at the next frame of every renderer drawing the scene, with no pipeline
  // rebuild, no history reset and no upload but that of a new mesh and the
  // moved objects' entries of the scene's per-object buffer (GpuScene's
  // Objects); a moved object's previous transform goes into the velocity target
  // (renderers with motion vectors: TAA follows the object, not a cut).
  // Exception, as for lights: an edit that changes what the scene needs
  // (its first blended, emissive or normal-mapped object, metallic or
  // roughness that now differ between objects, its last shadow caster gone,
  // an object added beyond its bounds where lights draw markers) adapts
  // renderers' pipelines again at their next frame; transform and
  // visibility edits never do. A call a caller gets wrong (an unknown or
  // removed id, a transform that is not finite or flattens the object, a
  // mesh or material index out of range, a value outside the ranges of
  // glTF, a mesh whose arrays disagree) throws RuntimeError naming the
  // object ("instance 7 ('crate')") and the value, and changes nothing.
  //
  // A mesh made in code (positions, normals, uv0, indices; normals may be
  // empty: smooth ones are computed, uv0 too: zeros; tangents are made from
  // the UVs): returns its index in scene().meshes. Uploaded once, now when
  // the scene is on the GPU (else with it), and shared by every object
  // drawing it; uploadCount() does not change.
  size_t addMesh(MeshData mesh);
  // A material made in code (textures index scene().textures): its index.
  // A normal-mapped one only in a scene whose upload had normal maps.
  size_t addMaterial(Material material);
  // A new object drawing scene().meshes[mesh] with scene().materials[material]
  // at `transform` (local -> world). Drawn from the next frame on; no motion
  // on its first frame.
  InstanceId addInstance(size_t mesh, size_t material, const glm::mat4& transform, std::string name = {});
  // The object is gone from the next frame; every other id stays valid.
  void removeInstance(InstanceId id);
  void setTransform(InstanceId id, const glm::mat4& transform);
  const glm::mat4& transform(InstanceId id) const;
  // Draws the object with another material of the scene.
  void setMaterial(InstanceId id, size_t material);
  // The object's own material values: the first call gives the object a
  // material of its own (a copy of the one it draws with, added to
  // scene().materials); later calls rewrite that copy. Other objects
  // sharing its former material are unchanged.
  void setMaterialParameters(InstanceId id, const MaterialParameters& parameters);
  MaterialParameters materialParameters(InstanceId id) const;
  // Hidden objects are not drawn (not into shadow maps either) but keep
  // their id, transform and material; the scene's bounds still count them.
  void setVisible(InstanceId id, bool visible);
  bool visible(InstanceId id) const;
  // Every object, in scene().primitives order; whether `id` is one.
  std::vector<InstanceId> instances() const;
  bool contains(InstanceId id) const;
  // Where the object's Primitive is in scene().primitives now (removals
  // move later ones down), and the object at a primitive index.
  size_t primitiveIndex(InstanceId id) const;
  InstanceId instanceAt(size_t primitive) const;
  // Increases with every edit that may change what the scene needs (adding,
  // removing, a material or material values; not transforms or visibility).
  uint64_t instancesVersion() const;

  // ---- Animation (glTF animations, skins and morph targets; rgraph/animation.h).
  // The scene's clock is the caller's: setTime(seconds) poses the scene at
  // that time, playing `animation` (an index into scene().animation's
  // animations; kAllAnimations: every one at once, each looping on its own
  // duration; kRestPose: none). Animations loop (loopTime). From the next
  // frame: objects drawn by animated glTF nodes move (as setTransform moves
  // them, the previous transform into the velocity target; an object whose
  // node did not move since the last setTime keeps a transform the caller
  // gave it), skinned objects follow their joints (the skinned node's own
  // transform is ignored, as glTF says) and morphed ones their weights (the
  // mesh's default weights where not animated); motion vectors include
  // skinning and morphing (the previous frame's joints and weights). Only
  // the joint matrices and weights that changed are uploaded. Bounds
  // (Primitive::bounds, culling and shadow fitting) cover the pose: a
  // skinned object's box is the union of its local box (morphed) under
  // each of its skin's joint matrices, which holds every vertex whose
  // weights sum to 1 (glTF requires it); a morphed one's local box grows by
  // each target's deltas times its weight. Before any setTime the scene is
  // at rest (kRestPose). Throws RuntimeError (changing nothing) for a
  // non-finite time or an animation index the scene does not have. A scene
  // without animation ignores the clock.
  void setTime(double seconds, int animation = kAllAnimations);
  double time() const;  // the last setTime's seconds (0 before any)

  // The GPU copy, uploaded on first use (a GL context must be current; later
  // calls throw RuntimeError in any other context, see Contexts above).
  GpuScene& gpu();
  // How many times the geometry, textures and materials were uploaded: 1 once
  // any renderer has drawn the scene, however many renderers share it.
  uint64_t uploadCount() const;

 private:
  RenderScene();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct RendererOptions {
  // The pass types pipelines may name; nullptr: PassRegistry::builtins().
  // Pass types of the application's own code: a copy of the built-ins with
  // yours added (rgraph/registry.h, docs/embedding.md). The renderer copies
  // it when it is made (later changes to yours are not seen) and loads the
  // plugins its pipelines name into its copy: each renderer has its own
  // types, and nothing it loads reaches another renderer or the built-ins.
  const PassRegistry* registry = nullptr;
  // Folders searched for the plugins the config names, before
  // $RGRAPH_PLUGIN_PATH and rgraph's own plugin folder (rgraph/plugin.h).
  std::vector<std::string> pluginDirectories;
  // Folders searched for shader files before the built-in shaders.
  std::vector<std::string> shaderDirectories;
  // The output size the factories check the graph at (setSize changes it).
  Extent size{1280, 720};
  // At creation and reload: what `rgraph validate` checks (graph at `size`,
  // the pass types' checks, the glslang shader checks, cached on disk as
  // `rgraph render` caches them). false skips the pass and shader checks.
  bool runChecks = true;
  // The texture size limit the checks assume; 0: none before the device's own
  // GL_MAX_TEXTURE_SIZE, checked when the pipeline is built.
  uint32_t maxTextureSize = 0;
  // How messages name that limit (default "RendererOptions::maxTextureSize").
  std::string maxTextureSizeOrigin;
  // A budget for the pipeline's textures (Plan::allocatedBytes at the size being built), in bytes; 0: none.
  // Whatever the budget, a build is also refused when the device says it has less free memory than the plan
  // needs (GL_NVX_gpu_memory_info, GL_ATI_meminfo; Mesa llvmpipe says nothing). Either refusal is a
  // RuntimeError from render() giving both figures, before any texture is allocated (see setSize).
  uint64_t maxMemoryBytes = 0;
  // How messages name that budget (default "RendererOptions::maxMemoryBytes").
  std::string maxMemoryOrigin;
  // "Model no more than a scene needs": adapt the pipeline to the scene (no
  // point lights: no light volumes, ...). Notes go to adaptNotes().
  bool adaptToScene = true;
  // The GL state contract (top of this file).
  bool restoreGlState = true;
  // Keep the scene's depth of every frame for the caller's own drawing over
  // the output with a depth test (Renderer::outputDepthTexture): one depth
  // blit per frame, right after the pass that last writes it (later passes
  // may reuse its memory). Off: no copy, and outputDepthTexture() is 0.
  bool keepDepth = false;
  // The resource keepDepth copies; empty: found in the plan, the last depth
  // attachment at the output's size (one layer) of a pass that draws the
  // scene (forwardDepth in default.json, depth in forward.json). A name no
  // pass that runs attaches as depth makes render() throw RuntimeError.
  std::string depthResource;
  // Picking (Renderer::requestPick): every pass of the pipeline that can
  // write object ids and is not asked to (the geometry pass: an "object_id"
  // output slot and a boolean "object_id" parameter) is asked to, into a
  // resource "object_id" (rg32ui, the output's size) the renderer declares:
  // 8 bytes per pixel and one more G-buffer attachment. Off (the default):
  // none of it, unless the pipeline file asks itself (docs/pipeline-format.md).
  bool picking = false;
  // Time passes with GL_TIME_ELAPSED queries on a software renderer too
  // (Executor::setGpuTimerQueries; a GPU always uses them). For tests of the
  // query path: llvmpipe's query values are poor.
  bool gpuTimerQueries = false;
  // Hazard modes (rgraph/hazards.h; docs/testing.md): run the pipeline with
  // what its graph does not promise changed (poisoned transients, another
  // aliasing or order, hostile GL state, culled passes run), to see whether a
  // pass relies on it. None by default. `rgraph check-hazards` and
  // testing::expectHazardFree compare such runs with a plain one.
  HazardModes hazards;
};

// A rectangle of a framebuffer, in pixels from its lower-left corner.
struct Viewport {
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;  // 0: the renderer's size
};

// The answer to a Renderer::requestPick.
struct PickResult {
  uint32_t x = 0, y = 0;  // the pixel asked about, from the output's top-left corner
  uint64_t frame = 0;     // the frame it was read from (frameIndex() counting; 0 when none was read)
  // The object drawn there by a pass that writes object ids (the geometry
  // pass: opaque and alpha-masked surfaces; blended surfaces drawn by forward
  // passes are not in the ids, the surface behind them is); 0: nothing there
  // (the background), an object removed since that frame, or no answer
  // (`problem`).
  InstanceId instance;
  // The triangle of the object's mesh under the pixel (gl_PrimitiveID: its
  // first index is 3 x triangle in the mesh's indices); 0 without an instance.
  uint32_t triangle = 0;
  // Why there is no answer: the pipeline writes no object ids. Empty when
  // the ids were read.
  std::string problem;
};

class Renderer {
 public:
  // nullptr when the config has errors (all in diags, warnings too).
  static std::unique_ptr<Renderer> fromFile(const std::string& pipelinePath, const RendererOptions& options,
                                            Diagnostics& diags);
  // From JSON text; messages name `nameForMessages`; plugin paths in it are
  // relative to `baseDir` ("" = the working directory).
  static std::unique_ptr<Renderer> fromJson(std::string_view json, const std::string& nameForMessages,
                                            const RendererOptions& options, Diagnostics& diags,
                                            const std::string& baseDir = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The scene to draw (nullptr: none; scene passes then refuse to run). The
  // camera becomes the scene's camera. Adapts the pipeline at the next frame.
  void setScene(std::shared_ptr<RenderScene> scene);
  const std::shared_ptr<RenderScene>& scene() const;
  // Per frame; no rebuild. Each renderer has its own camera. Held to the
  // scene files' ranges (0 < fov < 180 degrees, 0 < near < far, position and
  // target finite and apart): RuntimeError otherwise, the camera unchanged.
  void setCamera(const Camera& camera);
  const Camera& camera() const;
  // The next frame follows no previous one (a cut, a teleport): history
  // resources start again from a cleared, invalid state and motion vectors
  // are zero (Executor::cameraCut). Setting a new scene or size, or a reload,
  // does the same on its own.
  void cameraCut();

  // Output size. Textures are re-created at the next frame when it changes.
  // When that build refuses the size itself (RuntimeError from render(): the
  // graph has errors at it, a fixed-size resource beside "output" ones, or
  // its textures exceed the memory budget), the last good pipeline keeps its
  // textures and its size, and size() is that size again: the next render()
  // draws the last good frame instead of retrying the refused size. Other
  // failures (an import of the old size, below) keep the size asked for.
  void setSize(Extent size);
  Extent size() const;

  // Gives the resource `resource` (declared "imported": true, or the output's)
  // your texture, from the next frame on. Refused at once with RuntimeError,
  // naming the resource and both descriptions, when the texture's target,
  // format, size, sample count (or mip levels, for an immutable texture of a
  // resource with mips > 1) differs from the declaration at size(); and when
  // the resource is unknown, not imported, or a buffer. After setSize, import
  // textures of the new size (one of the old size makes the next render()
  // throw). Kept across reload() while the reloaded declaration still matches
  // (else the next frame throws). Checked again at every render(): a texture
  // deleted or redefined (glTextureStorage on a new name, a new size) since
  // makes render() throw RuntimeError naming the resource, before drawing.
  // A texture without storage (glCreateTextures alone) is refused as such.
  void importTexture(const std::string& resource, uint32_t glTexture);
  // Back to a texture rgraph owns.
  void releaseTexture(const std::string& resource);
  // Names of the resources the config declares imported (the output included).
  std::vector<std::string> importableResources() const;

  // Runs the pipeline once. The output stays in outputTexture() (or your
  // imported texture). Throws RuntimeError on device failures (see top).
  void render();
  // The same, then copies the output into `viewport` of `framebuffer`
  // (0 = the window's), scaled with linear filtering when the sizes differ.
  // Stored values are copied (an sRGB output's encoded bytes, as a PNG holds).
  void render(uint32_t framebuffer, const Viewport& viewport = {});
  // Copies the output as it stands into `viewport` of `framebuffer` again, as
  // render(framebuffer) does, without rendering: after a render() that threw,
  // the last good frame stays on screen. Does nothing before the first frame.
  void present(uint32_t framebuffer, const Viewport& viewport = {});

  // Re-reads the pipeline file (or takes new JSON text: its messages name
  // `nameForMessages`, "<json>" when empty, and plugin paths stay relative to
  // the folder of the renderer's file, or fromJson's baseDir) and the shader
  // files that changed on disk, checks it as the factories do and, when
  // nothing is wrong, replaces the pipeline. Once a frame was drawn the new
  // pipeline is built at once, so that even what only
  // the device refuses (a device_error diagnostic) leaves the last good
  // pipeline running. Programs whose shader files did not change are reused.
  // On errors returns false, diags says why, and nothing changed.
  // A renderer made from a file stays bound to it after reloadJson: the file
  // is still in watchedFiles(), and reload() reads the file again (replacing
  // what reloadJson gave: an editor's unsaved edits give way to the file's
  // next change). A renderer made from text: reload() takes the last text
  // (fromJson's, or the last reloadJson accepted) again.
  bool reload(Diagnostics& diags);
  bool reloadJson(std::string_view json, Diagnostics& diags, const std::string& nameForMessages = "<json>");
  // Another pipeline file, taken as reload() takes one (checked first, built
  // at once when a frame was drawn; on errors false, diags naming
  // `pipelinePath`, and the old pipeline keeps running, still bound to its
  // file). On success the renderer is bound to the new file: reload() reads
  // it, watchedFiles() lists it instead of the old one, plugin paths in it
  // are relative to its folder, and imports are kept as reload() keeps them.
  bool load(const std::string& pipelinePath, Diagnostics& diags);
  // This renderer's pass types: RendererOptions::registry's (or the
  // built-ins), plus those of the plugins its pipelines loaded.
  const PassRegistry& passTypes() const;
  // The plugin libraries its pipelines loaded (absolute paths), in load order.
  std::vector<std::string> loadedPlugins() const;
  // The files whose changes reload() picks up: the pipeline file (when the
  // renderer came from one) and every shader file its programs were compiled
  // from, includes too (known once a frame was drawn), and, for a shader
  // name found in a later shader folder, where it would be in each earlier
  // one (an override that appears there, or comes back after being deleted,
  // takes its place at the next reload). For live reload: a missing file is
  // listed as the path that would be read.
  std::vector<std::string> watchedFiles() const;

  // The pipeline as adapted to the scene, and the notes the adaptation made.
  const PipelineConfig& pipeline() const;
  const std::vector<std::string>& adaptNotes() const;
  // The tables pass types reported while adapting (AdaptReport::tables: a
  // shadow_map template's shadow budget), as `rgraph plan --scene` prints
  // them; empty without a scene or with adaptToScene off.
  const std::vector<AdaptReport::Table>& adaptTables() const;
  // The compiled plan of the last frame (before the first frame: compiled
  // now at size(), GL-free). Memory: Plan::naiveBytes / allocatedBytes.
  const Plan& plan() const;
  struct PassTiming {
    std::string name;
    double ms = 0.0;
    uint64_t executions = 0;  // Executor::PassTiming::executions
  };
  // Per executed pass, in execution order, of the frame timingsFrame() names
  // (ms 0 while it names none). With GL_TIME_ELAPSED queries (GPUs) that is
  // a frame 1-3 frames back: render() never waits for the GPU to time a
  // frame; with CPU timing (software renderers) the frame just rendered.
  // Executor::timings says more.
  std::vector<PassTiming> timings() const;
  // Which frame timings() belong to, counted as frameIndex() counts (the
  // frame just rendered is frameIndex() - 1); nullopt while none is known
  // (before the first frame, CPU pass timing off, and after a rebuild until a
  // frame of the rebuilt pipeline is in: no result is attributed across it).
  std::optional<uint64_t> timingsFrame() const;
  // Frames this renderer has drawn (render() calls that completed), across rebuilds.
  uint64_t frameIndex() const;
  // Takes the timer query results that are in now, without waiting (render()
  // does so at its start). wait: waits for the GPU first (glFinish), so that
  // the last frame's times are in: at the end of a run, never per frame.
  void collectTimings(bool wait = false);
  // true: timings are CPU time around a glFinish per pass (software renderers,
  // whose timer queries are not trustworthy); false: GL_TIME_ELAPSED queries.
  bool cpuTimed() const;
  // With CPU timing: time each pass (a glFinish after each, the default) or
  // not (timings() then all 0, frames without the stalls). Kept across rebuilds.
  void setCpuPassTiming(bool on);
  bool cpuPassTiming() const;

  uint32_t outputTexture() const;
  Extent outputExtent() const;
  // The scene's depth of the last frame, for drawing over the output with a
  // depth test (RendererOptions::keepDepth; docs/embedding.md, "Drawing over
  // the frame"): a GL_TEXTURE_2D the renderer owns, one sample (a
  // multisampled depth is resolved by the blit), of the depth resource's
  // format (outputDepthFormat: GL_DEPTH24_STENCIL8 or GL_DEPTH_COMPONENT32F
  // in the shipped pipelines) and size (outputDepthExtent: the output's
  // unless depthResource names another), holding window-space depth (0 near,
  // 1 far) of camera().projection(aspect) * camera().view(), jittered when
  // the pipeline jitters. Sample it, or blit it into a depth buffer of the
  // same format. 0 when keepDepth is off, before the first frame, and for a
  // pipeline with no scene depth. Rewritten by every render(); a new texture
  // when its size or format changes.
  uint32_t outputDepthTexture() const;
  uint32_t outputDepthFormat() const;  // its GL internal format, 0 without one
  Extent outputDepthExtent() const;
  // The resource it is copied from ("" without one).
  std::string outputDepthResource() const;
  // The output as RGBA8, rows top-down (stored bytes of an sRGB output; a
  // one-channel output is grey).
  std::vector<uint8_t> readOutputRGBA8() const;
  // Any resource or version as RGBA32F, rows top-down (see Executor).
  std::vector<float> readResourceRGBA32F(const std::string& name) const;

  // Picking: which object is under a pixel, answered a frame late without
  // waiting for the GPU. requestPick(x, y) asks about pixel (x, y) of the
  // output, counted from its top-left corner as window coordinates are
  // (0 <= x < size().width, 0 <= y < size().height; outside: RuntimeError,
  // nothing asked). The next render() copies that pixel of the object ids
  // (RendererOptions::picking, or a pipeline whose geometry pass writes
  // "object_id") into a pixel buffer right after the pass that writes them,
  // with a fence; a later render() or pickResult() takes it once the fence
  // says it is in (usually the next frame). A newer request replaces one not
  // yet read. pickResult(): the answer to the last request once it is in;
  // nullopt before any request and while it is pending (no frame yet, the
  // copy not done). wait: waits for the GPU (glClientWaitSync) when the read
  // is queued: for tests and tools, never per frame. The objects are those
  // of the frame that was read: an object moved since is found where it was
  // drawn then; one removed since is reported as nothing. setScene forgets
  // the request and its answer (InstanceIds are per scene).
  void requestPick(uint32_t x, uint32_t y);
  std::optional<PickResult> pickResult(bool wait = false);

  // Called after each pass of every frame with its step in plan().order
  // (GL work recorded, before the next pass): copy a resource out as it was
  // right after a pass wrote it. Kept across rebuilds and reloads. The
  // callback may not change the renderer (Re-entry, top of this file).
  void setAfterPass(std::function<void(size_t step)> callback);

  // How many times GL objects were (re)built for this renderer: the first
  // frame, size, scene-feature, import and pipeline changes. Camera and light
  // changes never add one.
  uint64_t builds() const;
  // The engine underneath, for tools and tests (nullptr before the first frame).
  Executor* executor();

 private:
  Renderer();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgraph
