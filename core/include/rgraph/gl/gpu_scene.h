// A Scene uploaded to the GPU: one vertex/index buffer pair per mesh, textures
// with their samplers, the per-frame uniform block and point-light buffers.
// Scene passes share one GpuScene through PassContext::gpuScene().
//
// Shader conventions (see shaders/include/frame.glsl and scene.vert):
//   vertex attributes  0 position, 1 normal, 2 uv0, 3 tangent (MeshVertex)
//   uniform block 0    Frame (camera, viewport, ambient, directional light, counts)
//   storage buffer 0   PointLight[]: point, then spot lights (bindPointLights)
//   per draw           u_model, u_normalMatrix, u_prevModel (the previous frame's
//                      u_model, for motion vectors; equal to u_model without
//                      motion), material uniforms u_baseColorFactor,
//                      u_metallicFactor, u_roughnessFactor, u_specular, u_normalScale,
//                      u_occlusionStrength, u_alphaCutoff, u_alphaMode (0 opaque,
//                      1 mask, 2 blend), u_emissive, u_hasBaseColorTex,
//                      u_hasMetallicRoughnessTex, u_hasNormalTex, u_hasOcclusionTex
//   texture units      0 base colour, 1 metallic-roughness, 2 normal, 3 occlusion, 4 emissive
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/gl/context_identity.h"
#include "rgraph/gl/objects.h"
#include "rgraph/graph.h"

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
  // The scene's lights or ambient changed (same Scene object): light buffers
  // are rewritten in place at their next use, grown only past their capacity
  // (a power of two), so that moving, recolouring, adding and removing lights
  // creates no GL object in the common case.
  void lightsChanged() { ++lightsVersion_; }
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

  // Point and spot lights with radii solved for `threshold` (LearnOpenGL: 5/256 of the
  // brightest channel) and capped at the distance beyond which the scene has
  // no geometry. threshold <= 0: no cut-off (radius -1). Cached for the
  // kLightBufferCacheSize thresholds used last (passes with different
  // thresholds, renderers sharing the scene), so that a threshold dragged
  // through many values holds no more buffers than that.
  // The buffer holds the point lights first, then the spot lights (its last
  // spotLightCount() entries), each in scene order.
  // Binds the buffer at shader storage binding 0, unless this scene's record
  // says it is bound there already (forgetBindings).
  void bindPointLights(float threshold);
  uint32_t pointLightBuffer(float threshold);
  uint32_t pointLightCount() const;  // every light in the buffer, spot lights included
  uint32_t spotLightCount() const;
  // The radius each light gets for a threshold, in scene order.
  std::vector<float> pointLightRadii(float threshold) const;

  enum class Filter { opaque, blend, all };  // opaque includes alpha-mask materials
  struct DrawOptions {
    Filter filter = Filter::opaque;
    bool backToFront = false;    // sort by distance of bounds centre (blended surfaces)
    bool cullBackFaces = true;   // per material: double-sided materials are never culled
  };
  // Draws every matching primitive with `program` (already in use or not):
  // sets per-draw and material uniforms, binds textures and samplers.
  void drawPrimitives(uint32_t program, const DrawOptions& options) const;
  size_t primitiveCount(Filter filter) const;
  // Whether vertex buffers carry tangents (only when the scene has normal maps).
  bool hasTangents() const { return hasTangents_; }

  // Closed unit icosphere (light volumes) and unit cube (light markers), drawn
  // `instances` times; vertex attribute 0 is the position.
  void drawIcosphere(uint32_t instances) const;
  // The icosphere's flat faces lie inside the unit sphere; scaling a light's
  // volume by radius * icosphereScale() makes the mesh enclose the whole sphere.
  float icosphereScale() const { return icosphereScale_; }
  void drawCube(uint32_t instances) const;
  // makeSpotVolume(16), drawn `instances` times (light_volume.vert bends it
  // to each spot light's cone); scaling its radius by spotVolumeScale() makes
  // its flat sides enclose the round cone.
  void drawSpotVolume(uint32_t instances) const;
  float spotVolumeScale() const { return spotVolumeScale_; }

 private:
  struct GpuMesh {
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    uint32_t indexCount = 0;
  };
  struct Locations;
  GpuMesh upload(const struct MeshData& mesh, bool tangents) const;
  const Locations& locations(uint32_t program) const;
  void bindMaterial(uint32_t program, int material) const;

  const Scene& scene_;
  gl::ContextIdentity uploadedIn_;
  std::vector<GpuMesh> meshes_;
  GpuMesh icosphere_, cube_, spotVolume_;
  float icosphereScale_ = 1.0f, spotVolumeScale_ = 1.0f;
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
  void bindProgram(uint32_t program) const;
  void bindVertexArray(uint32_t vertexArray) const;
  // Model matrices of the last updateFrame with motion (empty: draw with each
  // Primitive::transform, previous = current): this frame's, the previous
  // frame's, and the frame number they belong to.
  std::vector<glm::mat4> models_, prevModels_;
  std::optional<uint64_t> modelsFrame_;
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
};

}  // namespace rgraph
