// What a pass type is (its declaration) and what a pass instance does at run
// time. No GL include: GL object names travel as uint32_t.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/params.h"
#include "rgraph/pass_check.h"
#include "rgraph/sampler_state.h"
#include "rgraph/scene.h"  // Camera (SceneFeatures)

namespace rgraph {

struct Scene;          // defined by the scene module
class ShaderLibrary;   // defined by the GL backend
class GpuScene;        // the scene uploaded to the GPU (rgraph/gl/gpu_scene.h)

// How a slot may be bound in a config.
struct SlotDecl {
  std::string name;
  Access access = Access::sampled;
  bool required = true;
  // For writing slots: whether the config may (or must) also bind the slot in
  // "inputs" to load that version and produce its successor (blend into it).
  enum class Load { never, optional, required };
  Load load = Load::never;
  std::vector<Format> formats;  // accepted formats; empty accepts any
  bool acceptsMultisample = false;
  std::string description;
  // A G-buffer target: gbufferBytesPerPixel (rgraph plan --scene, rgraph
  // bench) counts the resources bound to such slots. Core knows no pass type
  // by name; the pass type says which of its slots hold the G-buffer.
  bool gbufferTarget = false;
  // Sampled slots: how the slot's texture is filtered, wrapped and compared
  // (rgraph/sampler_state.h). Unset: with the texture's own parameters
  // (linear, clamped to the edge, trilinear over a mip chain) through
  // sampler 0, as before sampler states existed. A pass in the config may
  // override it ("samplers": {"SLOT": {...}}, applied on top of this state,
  // or of SamplerState{} when unset). A depth slot sampled through a shadow
  // sampler (sampler2DShadow, ...) needs a state with a compare mode.
  std::optional<SamplerState> sampler;
};

class PassContext;

// One image of a framebuffer a pass asks for (PassContext::framebuffer): mip
// level `mip` of the texture bound to `slot`, and one array layer (a cube's
// face: 6 * cube + face, in +x -x +y -y +z -z order) or, with kAllLayers,
// every layer it binds (a layered attachment: the shader picks the layer with
// gl_Layer; a 2D texture's one image). Levels and layers count from the first
// the slot binds (a slot bound to "bloom.mip[2..4]" has mip 0 = level 2).
struct AttachmentRef {
  static constexpr uint32_t kAllLayers = Subresource::kAll;
  std::string_view slot;
  uint32_t mip = 0;
  uint32_t layer = kAllLayers;
};

// A framebuffer from the executor's cache and the extent to draw it with
// (the smallest of its attachments' at their levels).
struct PassFramebuffer {
  uint32_t id = 0;
  Extent extent;
};

// What a scene needs, so that a pipeline models no more than that: derived
// from the scene (rgraph::sceneFeatures) and handed to each pass type's
// `adapt` hook before the graph is compiled.
struct SceneFeatures {
  bool pointLights = true;
  bool blendMaterials = true;
  bool normalMaps = true;
  // The scene has an environment (Scene::environment): image-based lighting.
  bool environment = false;
  // false: every drawn material has the same metallic and roughness (no
  // texture), so no G-buffer target needs to carry them.
  bool metallicRoughnessVariation = true;
  float metallic = 1.0f, roughness = 1.0f;  // the shared values when there is no variation
  // Light markers (the forward pass): whether some point light asks for one
  // (PointLight::marker), and the largest half extent that keeps them small
  // beside the scene: kMarkerScale of its bounding radius (LearnOpenGL's
  // demo, radius 4.97, keeps its 0.125).
  bool lightMarkers = true;
  float markerSizeLimit = std::numeric_limits<float>::infinity();
  static constexpr float kMarkerScale = 1.0f / 32.0f;
  // Some drawn material emits light (Material::emits): the G-buffer carries
  // an emissive target.
  bool emissive = true;
  // Some drawn material has non-default reflectance (Material::nonDefaultReflectance):
  // the G-buffer carries a reflectance target.
  bool reflectance = true;

  // Shadows (passes/shadow_map): which lights a shadow pipeline should give
  // maps, from the scene's lights, its casters and the camera it is seen from.
  struct ShadowLight {
    enum class Kind { directional, spot, point };
    Kind kind = Kind::directional;
    uint32_t light = 0;  // index into Scene::directionalLights (directional) or Scene::pointLights
    bool operator==(const ShadowLight&) const = default;
  };
  struct UnshadowedLight {
    ShadowLight light;
    // Why it has no map, one short phrase: "does not cast" (its castShadows
    // is false, or unset on a point light), "outside the view" (its reach
    // misses the camera's frustum), "not shaded" (a directional light after
    // the first: the lighting passes shade only the first).
    std::string reason;
    bool operator==(const UnshadowedLight&) const = default;
  };
  // Some primitive casts (Scene::castsShadows).
  bool shadowCasters = false;
  // The casting lights that reach the view, most important first: the first
  // directional light, then spot and point lights by distance from the
  // camera to the light's reach (0 inside it), ties in scene order. Empty
  // without casters (every light then goes to unshadowedLights with "no
  // caster in the scene").
  std::vector<ShadowLight> shadowLights;
  std::vector<UnshadowedLight> unshadowedLights;  // every other light, in scene order (directional first)

  // What the facts above were derived from, for hooks that report on the
  // view (the shadow budget): the scene (valid while adaptToScene runs; not
  // compared when deciding to adapt again), its camera and the aspect.
  const Scene* scene = nullptr;
  Camera camera;
  float aspect = 16.0f / 9.0f;
};

// What a pass type's adapt hook may change in one pass for a scene.
//
// Expansion: a template pass may be replaced by instances generated from the
// scene (a shadow map per casting light and cascade). Each instance is the
// template with its own name, params and a subset of the template's
// bindings, each optionally narrowed to a part of its texture; instances
// keep the template's source location, so diagnostics about them point at
// the template. An empty `expand` removes the template (its resources may
// then have no writer: readers must be adapted too, from the same features).
struct ExpandedPass {
  std::string suffix;  // the instance is named "<template name>.<suffix>"
  ParamSet params;     // a copy of the template's params, as the hook changed them
  struct Binding {
    std::string slot;                  // a slot the template binds (its input and output alike)
    std::optional<Subresource> part;   // unset: what the template binds
  };
  std::vector<Binding> bindings;       // the template's other bindings are dropped
};

struct PassAdaptation {
  bool disable = false;                   // in-place writes become pass-throughs
  std::vector<std::string> unbindSlots;   // optional slots to drop (their resources may become unused)
  ParamSet params;                        // the pass's parameters, to modify
  std::vector<std::string> notes;         // why, one line each ("no point lights: ...")
  // A table the hook reports on the scene (the shadow budget), one line per
  // row: `rgraph plan --scene` prints it under the pass's name.
  std::vector<std::string> report;
  // Set: the pass is replaced by these, at its place, in this order (above).
  std::optional<std::vector<ExpandedPass>> expand;
  // The resource a template's slot binds, reshaped for its instances: a
  // texture's array layer count (a plain 2D array) and square size, a
  // buffer's bytes (0 leaves each as declared). Applied with expand.
  struct Reshape {
    std::string slot;
    uint32_t layers = 0;
    uint32_t size = 0;   // width = height, absolute
    uint64_t bytes = 0;  // buffers
  };
  std::vector<Reshape> reshape;
};

// A sampled slot and the sampler uniform a program reads it through.
struct SamplerSlot {
  std::string slot;     // the pass type's sampled slot
  std::string uniform;  // the sampler uniform in the shader
  // Texture unit (mandatory, >= 0). The executor sets the sampler uniform to
  // it once when it builds the program, and binds the slot's texture there
  // (texture 0 when the slot is unbound) before every execute(). A shader's
  // layout(binding) must name the same unit, or be left out.
  int unit = -1;
  // true: the pass tells the shader whether the slot is bound (e.g. a
  // u_hasAo flag), so a sampler read with the slot unbound is fine. false:
  // reading it unbound (texture 0) is an error.
  bool optional = false;
};

// One program a pass instance builds: what `rgraph validate` compiles and
// reflects without a GL context (see rgraph/shader_check.h), and what the
// executor builds for it (PassContext::program).
struct ShaderProgramSpec {
  std::string vert, frag;  // a vertex + fragment program (names as ShaderLibrary::program takes them)
  std::string comp;        // or a compute program
  std::vector<std::string> defines;
  // How the program's samplers map to the pass's sampled slots.
  std::vector<SamplerSlot> samplers;
  // Samplers the pass binds itself (scene material textures), not from slots.
  std::vector<std::string> ownSamplers;
  // false: skip the sampler checks (the pass binds samplers some other way).
  bool checkSamplers = true;
  // The fragment outputs go to the pass's colour attachments (in slot
  // declaration order, locations 0..N-1). false: skip the output checks.
  bool drawsToAttachments = true;
  // Drawn with source-alpha blending: the outputs' alpha must be written.
  bool blendsSourceAlpha = false;
};

// A vertex + fragment program: the common ShaderProgramSpec.
ShaderProgramSpec programSpec(std::string vert, std::string frag, std::vector<std::string> defines = {},
                              std::vector<SamplerSlot> samplers = {});

// One pass in a running pipeline. Created per pass per realized plan.
// The fixed-function state the executor puts back before a pass, by group
// (PassInstance::changedState), and the value each group starts a pass with.
enum GlStateGroup : uint32_t {
  kGlStateBlend = 1u << 0,      // GL_BLEND off
  kGlStateDepth = 1u << 1,      // GL_DEPTH_TEST off, depth function GL_LESS, depth writes on
  kGlStateStencil = 1u << 2,    // GL_STENCIL_TEST off, stencil write mask 0xFF
  kGlStateCull = 1u << 3,       // GL_CULL_FACE off
  kGlStateScissor = 1u << 4,    // GL_SCISSOR_TEST off
  kGlStateColorMask = 1u << 5,  // every channel written (draw buffer 0)
  kGlStateSrgb = 1u << 6,       // GL_FRAMEBUFFER_SRGB on
  // Not a value put back: the draw framebuffer, viewport, program or vertex
  // array were bound other than through PassContext::bindings() (the gl::
  // helpers in rgraph/gl/fullscreen.h), so the executor forgets its record.
  kGlStateBindings = 1u << 7,
  kGlStateAll = (1u << 8) - 1,
};

// What the executor knows is bound between passes: binds through it
// (gl::bindPassFramebuffer, gl::useProgram, gl::bindVertexArray) skip a
// bind already in place, so a chain of passes drawing with one program and
// one vertex array binds them once per frame, as hand-written GL would.
struct GlBindings {
  static constexpr uint32_t kUnknown = 0xFFFFFFFFu;
  uint32_t drawFramebuffer = kUnknown;
  uint32_t viewportWidth = kUnknown, viewportHeight = kUnknown;  // at (0, 0)
  uint32_t program = kUnknown;
  uint32_t vertexArray = kUnknown;
  void forget() { *this = GlBindings{}; }
};

class PassInstance {
 public:
  virtual ~PassInstance() = default;
  // After the plan's textures and framebuffers exist (again after a resize).
  // Throw rgraph::RuntimeError with a clear message on failure.
  virtual void setup(PassContext& /*ctx*/) {}
  // Record the pass's GL work. The executor has bound the sampled slots its
  // programs' specs name to their units (and nothing else): use
  // ctx.program(i), ctx.framebuffer() and ctx.texture(slot).
  virtual void execute(PassContext& ctx) = 0;
  // The GlStateGroup bits execute() may leave different from the values
  // above (after setup(), for every frame). The executor puts back only
  // these before the next pass, so a pass that sets none of them, or puts
  // back what it set, saves the next pass those calls by returning 0
  // (kGlStateBindings stays set if it binds framebuffers, programs or
  // vertex arrays with raw GL calls).
  // Executor::setStateChecks(true) verifies the answer after every pass.
  virtual uint32_t changedState() const { return kGlStateAll; }
};

struct PassTypeDesc {
  std::string name;          // the config's "type"
  std::string description;   // one line
  std::vector<SlotDecl> slots;
  std::vector<ParamDecl> params;
  bool sideEffect = false;
  // The one place a pass type names its programs: every variant an instance
  // with these params may use (e.g. with and without a scene-dependent
  // define), their defines and which sampled slot each sampler reads on which
  // unit. `rgraph validate` compiles and reflects exactly these; the executor
  // builds exactly these before PassInstance::setup (PassContext::program)
  // and binds the sampled slots to their units before every execute(). May
  // throw RuntimeError when the params name no usable shader. Unset: the
  // pass uses no programs.
  std::function<std::vector<ShaderProgramSpec>(const ParamSet&)> programs;
  std::function<std::unique_ptr<PassInstance>()> create;
  // Optional: drops what the scene does not need (see SceneFeatures).
  std::function<void(const SceneFeatures&, PassAdaptation&)> adapt;
  // Optional, GL-free: what the pass requires of its bindings beyond slot
  // formats (equal sizes, formats a blit can copy, slots a layout needs),
  // checked on the compiled plan by validate and before any GL work by render
  // and the executor, so setup() need not (see rgraph/pass_check.h).
  std::function<void(const PassCheckContext&, PassChecks&)> check;
  // Requirements stated as a sentence and a check (rgraph/pass_check.h):
  // run like `check`, and listed by `rgraph passes` (e.g. sameSizeRule).
  std::vector<PassRule> rules;
  // The pass draws or shades the scene: refused before any GL work when the
  // pipeline runs without one.
  bool needsScene = false;
  std::string origin = "built-in";  // or the plugin file it came from

  const SlotDecl* findSlot(std::string_view slot) const;
  const ParamDecl* findParam(std::string_view param) const;
  // The shader files of programs(default params), each once (for listings);
  // empty without programs or when the defaults name no usable shader.
  std::vector<std::string> shaderFiles() const;
};

// Per-frame data the executor gives to passes.
class PassContext {
 public:
  virtual ~PassContext() = default;
  virtual const std::string& passName() const = 0;
  virtual const ParamSet& params() const = 0;
  virtual Extent outputExtent() const = 0;

  // Slots: bound or not, GL texture name (0 for unbound or buffers), format,
  // size. A sampled slot bound to part of a texture (e.g. "bloom.mip[2]")
  // gives the name to sample that part through: a texture view whose level 0
  // and layer 0 are the part's first, or the texture itself with its base and
  // max level set to the part's levels while the pass runs (the executor
  // chooses; either way textureSize(s, 0) and texelFetch(s, p, 0) see the
  // part's first level). extent() is that first level's size.
  virtual bool bound(std::string_view slot) const = 0;
  virtual uint32_t texture(std::string_view slot) const = 0;
  // The texture bound to `slot`, only `sub` of it (levels and layers counted
  // from the first the slot binds; kAll: to its end), to sample in this pass:
  // for passes that sample some levels of a texture while drawing into
  // others (a mip chain reads level k, writes k + 1). A whole-texture `sub`
  // is texture(slot). Promises: what it returns samples `sub` alone, as
  // texture(slot) describes, until the pass's next texture(slot, ...) call for
  // the same slot (the executor may narrow the texture's own level range
  // rather than make a view: bind the name before the next call, and do not
  // keep it past execute()); views are made once per plan and never deleted
  // by the pass. 0 for an unbound or buffer slot. Throws RuntimeError naming
  // the pass and slot when `sub` leaves what the slot binds.
  virtual uint32_t texture(std::string_view /*slot*/, const Subresource& /*sub*/) { return 0; }
  virtual uint32_t buffer(std::string_view slot) const = 0;
  virtual Format format(std::string_view slot) const = 0;
  virtual Extent extent(std::string_view slot) const = 0;
  virtual uint32_t samples(std::string_view slot) const = 0;
  // True when a writing slot loads its previous version (do not clear it).
  virtual bool loads(std::string_view slot) const = 0;
  // A slot bound to a history resource (ResourceDecl::historyOf): whether its
  // texture holds the previous frame's content. false on the first frame,
  // after a resize, a reload or a camera cut (the texture is then cleared to
  // zero: do not blend with it), and for slots bound to anything else.
  virtual bool historyValid(std::string_view /*slot*/) const { return false; }
  // Frames this pass's executor has rendered before this one (0 on the first).
  virtual uint64_t frameIndex() const { return 0; }

  // The pass's framebuffer: colour attachments in slot-declaration order at
  // GL_COLOR_ATTACHMENT0.., plus the depth/stencil slot; draw buffers set.
  // 0 when the pass has no attachments. Its size is framebufferExtent().
  virtual uint32_t framebuffer() const = 0;
  virtual Extent framebufferExtent() const = 0;
  // A framebuffer attaching exactly these images, for a pass that draws into
  // several targets (or levels, or layers) in turn, or reads one (a blit's
  // source): colour ones in the order given at GL_COLOR_ATTACHMENT0.. with a
  // draw buffer each and the first as read buffer, a depth/stencil one at its
  // attachment point. Promises: every pass asking for the same images gets
  // the same framebuffer (the pass's own framebuffer() included), made and
  // checked the first time (in setup() or execute()) and kept until the plan
  // is rebuilt: never delete it, and ask again after a setup() rather than
  // keep it. Throws RuntimeError naming the pass: a slot not bound to a
  // texture, a level or layer outside what it binds, two depth images, an
  // incomplete framebuffer (its status by name, the attachments listed).
  // Bind it with gl::bindPassFramebuffer(ctx, {...}).
  virtual PassFramebuffer framebuffer(std::span<const AttachmentRef> /*attachments*/) { return {}; }
  PassFramebuffer framebuffer(std::initializer_list<AttachmentRef> attachments) {
    return framebuffer(std::span<const AttachmentRef>(attachments.begin(), attachments.size()));
  }

  // Program `index` of the pass type's programs(params), in their order,
  // built by the executor before setup(). Throws RuntimeError naming the pass
  // when there is no such program.
  virtual uint32_t program(size_t index) const = 0;
  virtual size_t programCount() const = 0;

  virtual ShaderLibrary& shaders() = 0;
  virtual const Scene* scene() const = 0;  // nullptr when the pipeline runs without a scene
  // The scene on the GPU, created once per executor; its Frame block is
  // updated for the output extent before the first pass of every frame.
  // nullptr without a scene.
  virtual GpuScene* gpuScene() { return nullptr; }
  // An empty vertex array the executor keeps for its passes (a fullscreen
  // triangle from gl_VertexID needs one bound): passes that share it spare
  // the driver revalidating vertex input between their draws. 0: none (make
  // your own).
  virtual uint32_t emptyVertexArray() const { return 0; }
  // The executor's record of what is bound (GlBindings), for the gl::
  // binding helpers; nullptr: no record, they always bind.
  virtual GlBindings* bindings() { return nullptr; }
};

}  // namespace rgraph
