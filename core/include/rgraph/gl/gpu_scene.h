// A Scene uploaded to the GPU: one vertex/index buffer pair per mesh, textures
// with their samplers, the per-frame uniform block and point-light buffers.
// Scene passes share one GpuScene through PassContext::gpuScene().
//
// Shader conventions (see shaders/include/frame.glsl and scene.vert):
//   vertex attributes  0 position, 1 normal, 2 uv0, 3 tangent (MeshVertex);
//                      4 COLOR_0, 5 TEXCOORD_1, from a second buffer, only in
//                      meshes that have them (uv1 only where a texture samples it)
//   uniform block 0    Frame (camera, viewport, ambient, directional light, counts)
//   storage buffer 0   PointLight[]: point, then spot lights (bindPointLights)
//   storage buffer 5   Objects: per primitive its model matrix, the previous
//                      frame's (for motion vectors; equal to the model matrix
//                      without motion) and its normal matrix (scene.vert's
//                      u_model, u_prevModel, u_normalMatrix), rewritten by
//                      updateFrame only where they changed; bound for scene draws
//   per draw           u_object (the draw's entry in Objects); a program
//                      without u_object (a vertex shader of its own) gets
//                      u_model, u_normalMatrix and u_prevModel as uniforms;
//                      material uniforms u_baseColorFactor,
//                      u_metallicFactor, u_roughnessFactor, u_specular, u_normalScale,
//                      u_occlusionStrength, u_alphaCutoff, u_alphaMode (0 opaque,
//                      1 mask, 2 blend), u_emissive, u_hasBaseColorTex,
//                      u_hasMetallicRoughnessTex, u_hasNormalTex, u_hasOcclusionTex,
//                      u_hasVertexColors (the mesh has COLOR_0; else white),
//                      u_uvTransform[unit] / u_uvSet[unit] (KHR_texture_transform
//                      and texCoord of each texture unit's texture: material_uv.glsl),
//                      u_instanceRange (instance count, 0: not instanced; first
//                      entry of the Instances buffer)
//   storage buffer 7   Instances: per instance of EXT_mesh_gpu_instancing
//                      primitives its local matrix and normal matrix (scene.vert;
//                      written at upload: Primitive::instances edited later are not
//                      seen, a primitive's transform is), bound for scene draws only
//                      in scenes with instances
//   storage buffers    only in scenes with skins or morph targets
//   8, 9, 10, 11       (sceneDeforms; scene.vert's SCENE_ANIMATION):
//                      8 Joints (every skin's joint matrices, this frame's then
//                      the previous frame's), 9 MorphWeights (likewise), 10
//                      Influences (per vertex of skinned meshes: records of 4
//                      joints + weights, any number of sets), 11 MorphDeltas
//                      (per vertex and target: position, normal, tangent
//                      deltas); per draw u_skin, u_morph, per list u_poseStride
//   texture units      0 base colour, 1 metallic-roughness, 2 normal, 3 occlusion, 4 emissive
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/gl/context_identity.h"
#include "rgraph/gl/objects.h"
#include "rgraph/graph.h"
#include "rgraph/scene.h"  // Camera, held by value (camera())

namespace rgraph {

struct GlBindings;  // rgraph/pass.h

struct Scene;
struct Camera;

// What a frame needs beyond its camera: motion vectors and sub-pixel jitter
// (the executor keeps it per pipeline; rgraph/jitter.h).
struct FrameMotion {
  // The executor's frame number: the jitter phase, and the animation time of
  // models that move (frame / 60 seconds).
  uint64_t frame = 0;
  uint32_t jitterPhases = 0;  // Halton(2,3) phases; 0: no jitter
  // The previous frame's unjittered view-projection; none on the first frame
  // and after a camera cut, where motion is zero (previous = current, for the
  // models' matrices too).
  std::optional<glm::mat4> prevViewProj;
};

class GpuScene {
 public:
  static constexpr size_t kLightBufferCacheSize = 4;
  // Texture units whose UV transform and set bindMaterial sets (u_uvTransform's size in material_uv.glsl).
  static constexpr int kMaterialTextureUnits = 13;
  // Storage buffer binding of the per-instance matrices (scene.vert's Instances).
  static constexpr uint32_t kInstanceBinding = 7;
  // Storage buffer binding of the per-object matrices (scene.vert's Objects).
  static constexpr uint32_t kObjectBinding = 5;
  // Storage buffer bindings of skinning and morphing (scene.vert's SCENE_ANIMATION blocks).
  static constexpr uint32_t kJointBinding = 8, kMorphWeightBinding = 9, kInfluenceBinding = 10,
                            kMorphDeltaBinding = 11;
  explicit GpuScene(const Scene& scene);  // uploads; needs a current GL context
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  const Scene& scene() const { return scene_; }

  // Throws RuntimeError (starting with `who`) unless the current GL context
  // is the one the scene was uploaded in. Its vertex arrays exist only there
  // (GL never shares them, not even between contexts of one share group), and
  // its buffers and textures only there and in its share group.
  void requireUploadContext(const std::string& who) const;

  // Fills the Frame block for this viewport (camera aspect) and binds it at 0:
  // the scene's camera, or `camera` (renderers sharing one GpuScene each have
  // their own; the block is rewritten at the start of each one's frame).
  void updateFrame(Extent viewport);
  void updateFrame(Extent viewport, const Camera& camera);
  // The same with motion and jitter: fills the previous view-projection, the
  // jitter and the models' previous matrices (u_prevModel per draw). Returns
  // this frame's unjittered view-projection (the next frame's prevViewProj).
  glm::mat4 updateFrame(Extent viewport, const Camera& camera, const FrameMotion& motion);
  // The camera and viewport of the last updateFrame (unjittered): what passes
  // that fit something to the view (shadow cascades) fit it to.
  const Camera& camera() const { return camera_; }
  Extent viewport() const { return viewport_; }
  // The scene's lights or ambient changed (same Scene object): light buffers
  // are rewritten in place at their next use, grown only past their capacity
  // (a power of two), so that moving, recolouring, adding and removing lights
  // creates no GL object in the common case.
  void lightsChanged() { ++lightsVersion_; }
  // The scene's objects were edited between frames (RenderScene's instances,
  // rgraph/renderer.h). Transforms, materials and visibility need no call:
  // draws read them from the Scene each frame. These keep the GPU side in
  // step with a scene that changed shape, creating GL objects only for a
  // new mesh:
  //   meshAdded         the last of Scene::meshes is new: uploaded now, once
  //                     (every primitive drawing it shares the upload);
  //   primitiveAdded    the last of Scene::primitives is new: drawn from the
  //                     next frame, with no motion on its first frame;
  //   primitiveRemoved  primitive `index` was erased: the others keep their
  //                     previous frame's matrices (their motion vectors).
  void meshAdded();
  void primitiveAdded();
  void primitiveRemoved(size_t index);
  // Hidden primitives are not drawn (no filter selects them); all are shown
  // at first. RenderScene::setVisible.
  void setVisible(size_t primitive, bool visible);
  bool visible(size_t primitive) const { return primitive >= hidden_.size() || !hidden_[primitive]; }
  // Bytes of geometry (vertex and index buffers) uploaded since the scene
  // was made: the upload's, plus each meshAdded's. Never grows per frame.
  uint64_t geometryBytes() const { return geometryBytes_; }
  // Bytes of per-draw data the scene's draws have set since it was made:
  // each drawn primitive's model, previous model and normal matrices and its
  // material's uniforms (factors, flags; texture transforms where the scene
  // has them), the per-instance data of a frame's draws.
  uint64_t drawUniformBytes() const { return drawUniformBytes_; }
  // Bytes written into the Objects buffer since the scene was made: every
  // entry at the first frame, then only those that changed (a moved
  // object's, and its previous matrix the frame after it stopped).
  uint64_t objectBytes() const { return objectBytes_; }
  // Binds the Frame block at 0: the frame's jittered camera, or the same
  // camera without jitter while the executor runs a pass whose
  // PassDecl::jitter is false (selectJitter).
  // The executor has bound it before every pass: a pass calls this only to
  // get it back after binding another buffer there itself.
  void bindFrame() const;
  // The executor, before each pass: which block bindFrame() binds, and binds
  // it unless this scene's record says it is bound there already.
  void selectJitter(bool jittered);
  // Uniform buffer 0 and storage buffer 0 may hold something else now (a
  // pass bound them with raw GL calls, the caller ran between frames): the
  // next bindFrame / bindPointLights binds again. updateFrame forgets too; the
  // executor calls it after a pass whose changedState() has kGlStateBindings.
  void forgetBindings() const { boundFrame_ = boundLights_ = 0; }
  // The buffers the record says are bound at uniform buffer 0 and storage
  // buffer 0 (0: not known), for Executor::setStateChecks.
  uint32_t recordedFrameBinding() const { return boundFrame_; }
  uint32_t recordedLightBinding() const { return boundLights_; }
  // The executor, for the length of a frame: the record its passes bind
  // through (PassContext::bindings). The draws below bind their program and
  // vertex arrays with the same calls as without one and write them into it,
  // so that a pass drawing the scene need not declare kGlStateBindings.
  // nullptr (the default): no record.
  void useBindingRecord(GlBindings* record) const { record_ = record; }

  // The light buffer (frame.glsl's PointLight[]): the point lights first,
  // then the spot lights (its last spotLightCount() entries), each in scene
  // order, with the cut-off radius `radii()` gives each light (in scene
  // order; negative: no cut-off). The lighting passes' radii are
  // rgraph/passes/light_radii.h's, keyed by their threshold. Buffers are
  // cached by `key` for the kLightBufferCacheSize keys used last (passes
  // with different thresholds, renderers sharing the scene), so that a
  // threshold dragged through many values holds no more buffers than that;
  // radii() is called only when the key's buffer is (re)written: the first
  // time, and after lightsChanged(). The same key must always mean the same
  // radii.
  using LightRadii = std::function<std::vector<float>()>;
  // Binds the buffer at shader storage binding 0, unless this scene's record
  // says it is bound there already (forgetBindings).
  void bindPointLights(float key, const LightRadii& radii);
  uint32_t pointLightBuffer(float key, const LightRadii& radii);
  uint32_t pointLightCount() const;  // every light in the buffer, spot lights included
  uint32_t spotLightCount() const;

  // What a pass library keeps with this upload, made once for every
  // renderer sharing the scene (light volumes' meshes, say): the T of this
  // scene, made with T() at the first call (in the upload context: check
  // requireUploadContext first where that may not hold), deleted with the
  // scene. One object per type.
  template <class T>
  T& extension() {
    std::shared_ptr<void>& slot = extensions_[std::type_index(typeid(T))];
    if (!slot) slot = std::make_shared<T>();
    return *static_cast<T*>(slot.get());
  }

  // Which primitives a draw takes. opaque includes alpha-mask materials;
  // shadowCasters: those Scene::castsShadows says cast (a primitive's
  // castShadows, else every one but the blended ones).
  enum class Filter { opaque, blend, all, shadowCasters };
  struct DrawOptions {
    Filter filter = Filter::opaque;
    bool backToFront = false;    // sort by distance of bounds centre (blended surfaces)
    bool cullBackFaces = true;   // per material: double-sided materials are never culled
  };
  // Draws every matching primitive with `program` (already in use or not):
  // sets per-draw and material uniforms, binds textures and samplers. It
  // draws with whatever Frame block is bound at uniform buffer 0: the
  // camera's, which the executor binds before every pass.
  void drawPrimitives(uint32_t program, const DrawOptions& options) const;
  size_t primitiveCount(Filter filter) const;

  // ---- Drawing from another view (a light, a cube-map face, a mirror)
  //
  // The camera's Frame block stays the default view: these calls write the
  // view's own Frame block (same layout, frame.glsl) into a buffer of its own,
  // bind it at uniform buffer 0 for their draws, and bind the camera's block
  // back before they return (recordedFrameBinding() says so), so later draws
  // of the pass and later passes see the camera as before. A pass calling
  // them binds nothing it must declare: programs and vertex arrays go
  // through the binding record, the viewport too (below).
  enum class Cull { none, back, front };  // per material: double-sided materials are never culled
  struct Viewport {
    int32_t x = 0, y = 0;
    uint32_t width = 0, height = 0;
  };
  struct View {
    glm::mat4 view{1.0f};  // world -> view
    glm::mat4 proj{1.0f};  // view -> clip (OpenGL clip space, depth -1..1)
    // Set with glViewport for the draw (and left set, recorded in the binding
    // record); none: the viewport already set (the bound framebuffer's, as
    // gl::bindPassFramebuffer sets it), read back for u_viewport.
    std::optional<Viewport> viewport;
    Cull cull = Cull::back;
    Filter filter = Filter::opaque;
    bool backToFront = false;  // sort by distance of bounds centre to this view's eye
    // The view's position (u_cameraPos, back-to-front sorting); none: the
    // translation of inverse(view), which can differ from the position the
    // view was made from in the last bits (give it to match a camera's block).
    std::optional<glm::vec3> eye;
  };
  // Draws the `view.filter` primitives as drawPrimitives does, from `view`:
  // the Frame block its shaders read has u_view, u_proj, their product and
  // inverses, u_cameraPos (view.eye) and u_viewport of this view;
  // no jitter and no camera motion (u_prevViewProj = u_viewProjNoJitter =
  // u_viewProj, u_jitter 0); ambient, lights and u_frame are the frame's.
  // Model matrices (and u_prevModel) are the frame's, as in drawPrimitives.
  // Depth test, blending and the framebuffer are the caller's; face culling
  // is set per material and left off, as drawPrimitives leaves it.
  void drawView(uint32_t program, const View& view);
  // Whether drawLayered works here: gl_Layer can be written from the vertex
  // shader (GL_ARB_shader_viewport_layer_array or GL_AMD_vertex_shader_layer;
  // llvmpipe, NVIDIA, AMD and Intel's Mesa drivers have one).
  bool supportsLayeredDraw() const;
  // One instanced draw per primitive writing views.size() layers of a layered
  // framebuffer (a 2D array or cube map attached whole, depth too): instance
  // i draws views[i] into layer firstLayer + i (a cube map's layers are its
  // faces, +X -X +Y -Y +Z -Z). `program` must be scene.vert compiled with
  // LAYERED (it reads each layer's view-projection from the LayerViews block,
  // include/layer_views.glsl, uniform buffer 1, and sets gl_Layer); its
  // fragment shader sees views[0]'s Frame block. Every view must have the
  // first one's viewport, cull, filter and backToFront (else RuntimeError).
  // RuntimeError without supportsLayeredDraw(). More than 32 views: one draw
  // per primitive per 32. Uniform buffer 1 is left unbound.
  void drawLayered(uint32_t program, const std::vector<View>& views, uint32_t firstLayer = 0);
  // The same without gl_Layer, one draw per layer: for each i, bindLayer(i)
  // (the caller attaches layer i and binds the framebuffer, e.g. with
  // glNamedFramebufferTextureLayer), then drawView(program, views[i]). Works
  // on any device, with any scene.vert program (not LAYERED).
  void drawEachLayer(uint32_t program, const std::vector<View>& views, const std::function<void(size_t)>& bindLayer);

  // ---- Skins and morph targets (gpu_scene_animation.cpp)
  //
  // Only in a scene where sceneDeforms(): its skinned meshes'
  // influences and morphed meshes' deltas are uploaded with it (meshes added
  // later are drawn undeformed), and the pose starts as the rest pose
  // (evaluatePose with kRestPose: default morph weights). Other scenes
  // upload, bind and set nothing of this.
  bool deforms() const { return deforms_; }
  // Whether `scene` has something to deform on the GPU: a primitive whose
  // glTF node has a skin and whose mesh JOINTS/WEIGHTS, or whose mesh has
  // morph targets and its node weights. Scene vertex shaders get
  // SCENE_ANIMATION only then (the executor adds it).
  static bool sceneDeforms(const Scene& scene);
  // The pose to draw from the next updateFrame on (RenderScene::setTime):
  // joint matrices and morph weights as rgraph::Pose lays them out (sizes
  // SceneAnimation::jointCount and weightCount, else RuntimeError). Motion
  // vectors use the previous frame's pose, as they use previous models.
  void setPose(const std::vector<glm::mat4>& joints, const std::vector<float>& weights);
  // Bytes written into the Joints and MorphWeights buffers since the upload:
  // only the ranges that changed each frame (a still pose writes none).
  uint64_t poseBytes() const { return poseBytes_; }
  // Bytes of influences and morph deltas uploaded (once, with the scene).
  uint64_t deformationBytes() const { return deformationBytes_; }

  // Whether vertex buffers carry tangents (only when the scene has normal maps).
  bool hasTangents() const { return hasTangents_; }

 private:
  struct GpuMesh {
    // Skinning and morphing (gpu_scene_animation.cpp): first record and
    // records per vertex in Influences (0: none), first vec4 in MorphDeltas,
    // targets (0: none) and which attributes each target has (bits).
    int32_t firstInfluence = 0, influenceSets = 0, firstDelta = 0, morphTargets = 0, morphAttributes = 0;
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    gl::Buffer extra;  // COLOR_0 then TEXCOORD_1, where the mesh has them (else none)
    uint32_t indexCount = 0;
    bool colors = false, uv1 = false;
    uint64_t bytes = 0;  // uploaded into its buffers
  };
  struct Locations;
  GpuMesh upload(const struct MeshData& mesh, bool tangents, bool uv1) const;
  // Writes every instanced primitive's matrices into instances_.
  void uploadInstances();
  struct InstanceRange {
    uint32_t first = 0, count = 0;  // in instances_; count 0: not instanced
  };
  std::vector<InstanceRange> instanceRanges_;  // per primitive (empty: none instanced)
  gl::Buffer instances_;                       // none: no primitive is instanced
  // Whether draws set u_hasVertexColors, and u_uvTransform / u_uvSet (else
  // they keep 0 and the identity / uv0 every program starts with).
  bool hasVertexColors_ = false, texCoordsPerDraw_ = false;
  // Some material has KHR_materials_specular values or is unlit: bindMaterial
  // sets them per draw (else claimGeometryUniforms's defaults stand).
  bool reflectancePerDraw_ = false;
  uint64_t serial_ = 0;  // this GpuScene among all made (claimGeometryUniforms)
  // Sets `program`'s geometry uniforms to their defaults (no vertex colours,
  // uv0 untransformed, not instanced) unless this scene set them last.
  void claimGeometryUniforms(uint32_t program, const Locations& loc) const;
  // The primitives a filter takes, in scene order or back to front from `eye`.
  bool selects(Filter filter, size_t primitive) const;
  std::vector<size_t> select(Filter filter, bool backToFront, glm::vec3 eye) const;
  // Draws `order` with `program` (drawPrimitives' loop), each primitive
  // `views` times (drawLayered: GL instance = instance * views + view).
  void drawList(uint32_t program, const std::vector<size_t>& order, Cull cull, uint32_t views) const;
  void ensureViewBuffers();
  Viewport applyViewport(const View& view) const;
  // Writes the next slot of views_ for `view` and binds it at uniform buffer 0.
  void bindViewBlock(const View& view, Viewport viewport);
  const Locations& locations(uint32_t program) const;
  void bindMaterial(uint32_t program, int material, bool meshHasUv1) const;

  // Skins and morph targets (gpu_scene_animation.cpp).
  bool deforms_ = false;
  gl::Buffer influences_, morphDeltas_, joints_, morphWeights_;
  uint32_t jointCount_ = 0, weightCount_ = 0;  // per frame (the buffers hold two frames)
  // The pose to draw (setPose), what the buffers hold (this frame's, the
  // previous frame's), and the frame the drawn pose belongs to.
  std::vector<glm::mat4> pose_, gpuJoints_;
  std::vector<float> poseWeights_, gpuWeights_;
  std::optional<uint64_t> poseFrame_;
  uint64_t poseBytes_ = 0, deformationBytes_ = 0;
  // Uploads influences and deltas, makes the pose buffers (the constructor).
  void uploadDeformation();
  // Writes this frame's pose and the previous frame's into the buffers,
  // only the ranges that differ. `frame` nullopt (no motion) or a first
  // frame / camera cut (`cut`): the previous pose is this one.
  void writePose(std::optional<uint64_t> frame, bool cut);
  // Binds the four buffers and sets u_poseStride (drawList, where the
  // program reads them); per draw, u_skin and u_morph of primitive `i`.
  void bindDeformation(uint32_t program, int poseStrideLocation) const;
  void setDeformation(uint32_t program, int skinLocation, int morphLocation, size_t primitive) const;
  void unbindDeformation() const;

  const Scene& scene_;
  gl::ContextIdentity uploadedIn_;
  std::vector<GpuMesh> meshes_;
  bool hasTangents_ = false;
  std::vector<gl::Texture> images_;
  std::vector<gl::Sampler> samplers_;  // one per SceneTexture
  gl::Texture white_, flatNormal_;
  gl::Sampler defaultSampler_;
  gl::Buffer frame_;            // the Frame block with jitter (what passes see by default)
  gl::Buffer frameUnjittered_;  // the same frame without jitter (passes with jitter: false)
  bool jittered_ = true;        // which of the two bindFrame() binds (selectJitter)
  // What this scene last bound at uniform buffer 0 and storage buffer 0 (0:
  // unknown): passes ask for both and the executor for the Frame block before
  // each pass, so a frame binds each once, as hand-written GL would.
  mutable uint32_t boundFrame_ = 0, boundLights_ = 0;
  mutable GlBindings* record_ = nullptr;  // useBindingRecord
  // Views' Frame blocks and LayerViews blocks: rings of slots (drawView,
  // drawLayered), made at the first such draw; u_frame of the last updateFrame.
  gl::Buffer views_, layerViews_;
  uint32_t viewStride_ = 0, layerStride_ = 0, nextView_ = 0, nextLayerSlot_ = 0;
  glm::ivec4 frameIndex_{0};
  Camera camera_;     // of the last updateFrame
  Extent viewport_;
  mutable std::optional<bool> layeredSupport_;
  void bindProgram(uint32_t program) const;
  void bindVertexArray(uint32_t vertexArray) const;
  // Model matrices of the last updateFrame with motion (empty: draw with each
  // Primitive::transform, previous = current): this frame's, the previous
  // frame's, and the frame number they belong to.
  std::vector<glm::mat4> models_, prevModels_;
  std::optional<uint64_t> modelsFrame_;
  // Primitives added since the last updateFrame (primitiveAdded): their
  // previous matrix is their current one on their first frame.
  std::vector<size_t> addedPrimitives_;
  std::vector<bool> hidden_;  // per primitive (shorter: the rest are shown)
  // The Objects buffer (scene.vert) and what it holds, one entry per primitive.
  struct ObjectRecord {
    glm::mat4 model, prevModel, normal;  // normal: a mat3 in a mat4's columns (std430)
  };
  mutable std::vector<ObjectRecord> objects_;
  mutable gl::Buffer objectBuffer_;
  mutable size_t objectCapacity_ = 0;
  mutable uint64_t objectBytes_ = 0;
  // Brings the Objects buffer up to date with this frame's matrices (models_
  // and prevModels_, else each Primitive::transform): writes the one range
  // of entries that changed; a new buffer only past its capacity.
  void writeObjects() const;
  uint64_t geometryBytes_ = 0;
  mutable uint64_t drawUniformBytes_ = 0;
  glm::mat4 writeFrame(Extent viewport, const Camera& camera, const FrameMotion* motion);
  struct LightBuffer {
    gl::Buffer buffer;
    size_t capacity = 0;  // lights it can hold
    uint64_t version = 0;
    uint64_t lastUse = 0;  // lightBufferUses_ at its last use
  };
  std::map<float, LightBuffer> lightBuffers_;  // at most kLightBufferCacheSize
  uint64_t lightBufferUses_ = 0;  // a clock for evicting the least recently used
  uint64_t lightsVersion_ = 0;
  glm::vec3 eye_{0.0f};  // the camera of the current frame (back-to-front sorting)
  mutable std::map<uint32_t, std::unique_ptr<Locations>> locations_;
  std::map<std::type_index, std::shared_ptr<void>> extensions_;  // extension<T>()
};

}  // namespace rgraph
