#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass.h"
#include "frame_block.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "frame_block.h"
#include "rgraph/error.h"
#include "rgraph/jitter.h"
#include "rgraph/scene.h"

namespace rgraph {
namespace {

// The std140 mirror of shaders/include/frame.glsl (frame_block.h: a test holds
// every member's offset and type to glslang's reflection of the GLSL block).
using detail::FrameBlock;

// std430 mirror of PointLight in frame.glsl (the meaning of each member is
// documented there).
struct GpuPointLight {
  glm::vec4 positionRadius;
  glm::vec4 color;
  glm::vec4 attenuation;  // w: the cone scale
  glm::vec4 spot;         // xyz: cone direction, w: cos(outer cone angle)
};
static_assert(sizeof(GpuPointLight) == 64, "GpuPointLight must match the std430 layout");

// glTF KHR_lights_punctual's form of the cone: the shader's factor is
// clamp((cos(angle to the axis) - cos(outer)) * scale, 0, 1)^2 with
// scale = 1 / max(cos(inner) - cos(outer), 0.001). A point light's
// cos(outer) = -2 and scale 1 make it 1 in every direction.
GpuPointLight gpuLight(const PointLight& l, float radius) {
  GpuPointLight g{glm::vec4(l.position, radius), glm::vec4(l.color * l.intensity, 1.0f),
                  glm::vec4(l.constant, l.linear, l.quadratic, 1.0f), glm::vec4(0.0f, 0.0f, 0.0f, -2.0f)};
  if (l.spot) {
    const float cosOuter = std::cos(glm::radians(l.outerConeDeg)), cosInner = std::cos(glm::radians(l.innerConeDeg));
    g.attenuation.w = 1.0f / std::max(cosInner - cosOuter, 1e-3f);
    g.spot = glm::vec4(glm::normalize(l.direction), cosOuter);
  }
  return g;
}

gl::Texture solidTexture(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), 1, GL_RGBA8, 1, 1);
  const uint8_t px[4] = {r, g, b, a};
  glTextureSubImage2D(t.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
  return t;
}

int mipLevels(int w, int h) {
  int levels = 1;
  while ((w | h) >> levels) ++levels;
  return levels;
}

}  // namespace

void detail::fillSceneMembers(FrameBlock& f, const Scene& scene) {
  f.ambient = glm::vec4(scene.ambient, 0.0f);
  if (!scene.directionalLights.empty()) {
    const DirectionalLight& d = scene.directionalLights.front();
    f.dirLightDir = glm::vec4(glm::normalize(d.direction), 1.0f);
    f.dirLightColor = glm::vec4(d.color * d.intensity, 0.0f);
  }
  f.counts = glm::ivec4(static_cast<int>(scene.pointLights.size()), 0, 0, 0);
}

struct GpuScene::Locations {
  int model, prevModel, normalMatrix, baseColorFactor, metallicFactor, roughnessFactor, specular, normalScale,
      occlusionStrength, alphaCutoff, alphaMode, emissive, hasBaseColorTex, hasMetallicRoughnessTex, hasNormalTex,
      hasOcclusionTex, specularColorFactor, specularFactor, unlit, specularTextures, hasVertexColors, uvTransform, uvSet, instanceRange,
      object, skin, morph, poseStride;
};

GpuScene::GpuScene(const Scene& scene) : scene_(scene), uploadedIn_(gl::currentContext()) {
  static std::atomic<uint64_t> scenes{0};
  serial_ = ++scenes;
  scene_.validate();
  meshes_.reserve(scene.meshes.size());
  hasTangents_ = scene.hasNormalMaps();
  // The second UV set only where a material drawing the mesh samples it.
  std::vector<bool> uv1(scene.meshes.size(), false);
  for (const Primitive& p : scene.primitives)
    if (p.mesh >= 0 && static_cast<size_t>(p.mesh) < uv1.size() && scene.materials[p.material].usesUv1())
      uv1[p.mesh] = true;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    meshes_.push_back(upload(scene.meshes[i], hasTangents_ && scene.meshes[i].hasTangents(), uv1[i]));
    geometryBytes_ += meshes_.back().bytes;
  }
  uploadInstances();
  uploadDeformation();
  hasVertexColors_ = scene.hasVertexColors();
  for (const Material& m : scene.materials) reflectancePerDraw_ = reflectancePerDraw_ || m.nonDefaultReflectance();
  // Per-draw texture coordinates only where some texture is transformed or samples a second UV set.
  for (const Material& m : scene.materials)
    for (const TextureRef* t : m.textures())
      if (t->valid() && (t->texCoord != 0 || t->uvTransform() != glm::mat3x2(1.0f))) texCoordsPerDraw_ = true;

  images_.reserve(scene.images.size());
  for (const auto& img : scene.images) {
    gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
    const int w = std::max(img.width, 1), h = std::max(img.height, 1);
    glTextureStorage2D(t.id(), mipLevels(w, h), img.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, w, h);
    if (img.rgba.size() >= static_cast<size_t>(w) * h * 4) {
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTextureSubImage2D(t.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
      glGenerateTextureMipmap(t.id());
    }
    images_.push_back(std::move(t));
  }
  samplers_.reserve(scene.textures.size());
  for (const auto& tex : scene.textures) {
    gl::Sampler s = gl::createSampler();
    glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_S, tex.sampler.wrapS);
    glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_T, tex.sampler.wrapT);
    glSamplerParameteri(s.id(), GL_TEXTURE_MIN_FILTER, tex.sampler.minFilter);
    glSamplerParameteri(s.id(), GL_TEXTURE_MAG_FILTER, tex.sampler.magFilter);
    samplers_.push_back(std::move(s));
  }
  white_ = solidTexture(255, 255, 255, 255);
  flatNormal_ = solidTexture(128, 128, 255, 255);
  defaultSampler_ = gl::createSampler();
  glSamplerParameteri(defaultSampler_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(defaultSampler_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  frame_ = gl::createBuffer();
  glNamedBufferStorage(frame_.id(), sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
  frameUnjittered_ = gl::createBuffer();
  glNamedBufferStorage(frameUnjittered_.id(), sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

GpuScene::~GpuScene() = default;

void GpuScene::requireUploadContext(const std::string& who) const {
  // The window system's name for the context where it knows one; in any case
  // the Frame block must be a buffer here (one glIsBuffer: a context that
  // shares nothing with the upload's has no such buffer, or another one).
  if (gl::currentContext() == uploadedIn_ && glIsBuffer(frame_.id())) return;
  throw RuntimeError(who + ": the scene '" + (scene_.source.empty() ? std::string("(built in code)") : scene_.source) +
                     "' was uploaded to the GPU in another GL context: a RenderScene draws only in the context it was "
                     "first drawn in (not in another one, even one sharing objects with it: GL never shares vertex "
                     "arrays). Make that context current, or make a RenderScene for this context");
}

GpuScene::GpuMesh GpuScene::upload(const MeshData& mesh, bool tangents, bool uv1) const {
  GpuMesh g;
  // Model no more than the scene needs: without normal maps no tangent is
  // uploaded (32 bytes per vertex instead of 48) and attribute 3 stays off,
  // reading the constant (0, 0, 0, 1).
  struct VertexNoTangent {
    glm::vec3 position, normal;
    glm::vec2 uv;
  };
  std::vector<MeshVertex> full;
  std::vector<VertexNoTangent> compact;
  const void* data = nullptr;
  size_t bytes = 0, stride = 0;
  if (tangents) {
    full = mesh.interleaved();
    data = full.data();
    bytes = full.size() * sizeof(MeshVertex);
    stride = sizeof(MeshVertex);
  } else {
    compact.reserve(mesh.vertexCount());
    for (size_t i = 0; i < mesh.vertexCount(); ++i)
      compact.push_back({mesh.positions[i], mesh.normals[i], i < mesh.uv0.size() ? mesh.uv0[i] : glm::vec2(0.0f)});
    data = compact.data();
    bytes = compact.size() * sizeof(VertexNoTangent);
    stride = sizeof(VertexNoTangent);
  }
  g.vertices = gl::createBuffer();
  g.indices = gl::createBuffer();
  glNamedBufferStorage(g.vertices.id(), std::max<size_t>(bytes, 1), bytes ? data : nullptr, 0);
  glNamedBufferStorage(g.indices.id(), std::max<size_t>(mesh.indices.size() * sizeof(uint32_t), 1),
                       mesh.indices.empty() ? nullptr : mesh.indices.data(), 0);
  g.indexCount = static_cast<uint32_t>(mesh.indices.size());
  g.bytes = bytes + mesh.indices.size() * sizeof(uint32_t);
  g.vao = gl::createVertexArray();
  const GLuint vao = g.vao.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, static_cast<GLsizei>(stride));
  glVertexArrayElementBuffer(vao, g.indices.id());
  auto attrib = [&](GLuint loc, GLint size, size_t offset) {
    glEnableVertexArrayAttrib(vao, loc);
    glVertexArrayAttribFormat(vao, loc, size, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao, loc, 0);
  };
  if (tangents) {
    attrib(0, 3, offsetof(MeshVertex, position));
    attrib(1, 3, offsetof(MeshVertex, normal));
    attrib(2, 2, offsetof(MeshVertex, uv));
    attrib(3, 4, offsetof(MeshVertex, tangent));
  } else {
    attrib(0, 3, offsetof(VertexNoTangent, position));
    attrib(1, 3, offsetof(VertexNoTangent, normal));
    attrib(2, 2, offsetof(VertexNoTangent, uv));
  }
  // COLOR_0 (attribute 4) and TEXCOORD_1 (attribute 5) in a buffer of their
  // own, only for meshes that have them (and uv1 only where it is sampled):
  // the main vertex layout stays what it is without them.
  g.colors = mesh.hasColors();
  g.uv1 = uv1 && mesh.hasUv1();
  if (g.colors || g.uv1) {
    const size_t colorBytes = g.colors ? mesh.colors.size() * sizeof(glm::vec4) : 0;
    const size_t uvBytes = g.uv1 ? mesh.uv1.size() * sizeof(glm::vec2) : 0;
    std::vector<uint8_t> extra(colorBytes + uvBytes);
    if (colorBytes) std::memcpy(extra.data(), mesh.colors.data(), colorBytes);
    if (uvBytes) std::memcpy(extra.data() + colorBytes, mesh.uv1.data(), uvBytes);
    g.extra = gl::createBuffer();
    glNamedBufferStorage(g.extra.id(), static_cast<GLsizeiptr>(std::max<size_t>(extra.size(), 1)), extra.data(), 0);
    g.bytes += extra.size();
    auto stream = [&](GLuint loc, GLint size, size_t offset, size_t stride) {
      glVertexArrayVertexBuffer(vao, loc - 3, g.extra.id(), static_cast<GLintptr>(offset), static_cast<GLsizei>(stride));
      glEnableVertexArrayAttrib(vao, loc);
      glVertexArrayAttribFormat(vao, loc, size, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vao, loc, loc - 3);
    };
    if (g.colors) stream(4, 4, 0, sizeof(glm::vec4));
    if (g.uv1) stream(5, 2, colorBytes, sizeof(glm::vec2));
  }
  return g;
}

void GpuScene::uploadInstances() {
  // Per instance: its local matrix and that matrix's normal matrix (a mat3 in
  // a mat4's columns, std430), scene.vert's Instances block.
  std::vector<glm::mat4> data;
  instanceRanges_.assign(scene_.primitives.size(), InstanceRange{});
  for (size_t i = 0; i < scene_.primitives.size(); ++i) {
    const Primitive& p = scene_.primitives[i];
    if (p.instances.empty()) continue;
    instanceRanges_[i] = {static_cast<uint32_t>(data.size() / 2), static_cast<uint32_t>(p.instances.size())};
    for (const glm::mat4& m : p.instances) {
      data.push_back(m);
      data.push_back(glm::mat4(glm::transpose(glm::inverse(glm::mat3(m)))));
    }
  }
  if (data.empty()) return;
  instances_ = gl::createBuffer();
  glNamedBufferStorage(instances_.id(), static_cast<GLsizeiptr>(data.size() * sizeof(glm::mat4)), data.data(), 0);
}

void GpuScene::meshAdded() {
  if (meshes_.size() + 1 != scene_.meshes.size())
    throw RuntimeError("GpuScene::meshAdded: the scene has " + std::to_string(scene_.meshes.size()) +
                       " meshes, the GPU " + std::to_string(meshes_.size()) + ": one new mesh at a time");
  const MeshData& mesh = scene_.meshes.back();
  // Tangents only where the upload carries them (a scene with normal maps);
  // the second UV set where the mesh has one (no material samples it yet).
  meshes_.push_back(upload(mesh, hasTangents_ && mesh.hasTangents(), mesh.hasUv1()));
  geometryBytes_ += meshes_.back().bytes;
  hasVertexColors_ = hasVertexColors_ || mesh.hasColors();
}

void GpuScene::primitiveAdded() {
  const size_t index = scene_.primitives.size() - 1;
  const glm::mat4& m = scene_.primitives.back().transform;
  // Matrices of the last frame with motion: the new one's is its own (no
  // motion on its first frame, addedPrimitives_), the others keep theirs.
  if (!models_.empty()) {
    models_.push_back(m);
    prevModels_.push_back(m);
    addedPrimitives_.push_back(index);
  }
  if (!instanceRanges_.empty()) instanceRanges_.push_back(InstanceRange{});  // not instanced
  const Material& material = scene_.materials.at(static_cast<size_t>(scene_.primitives.back().material));
  reflectancePerDraw_ = reflectancePerDraw_ || material.nonDefaultReflectance();
  for (const TextureRef* t : material.textures())
    if (t->valid() && (t->texCoord != 0 || t->uvTransform() != glm::mat3x2(1.0f))) texCoordsPerDraw_ = true;
}

void GpuScene::primitiveRemoved(size_t index) {
  auto erase = [index](auto& v) {
    if (index < v.size()) v.erase(v.begin() + static_cast<std::ptrdiff_t>(index));
  };
  erase(models_);
  erase(prevModels_);
  erase(instanceRanges_);
  erase(hidden_);
  std::vector<size_t> added;
  for (size_t i : addedPrimitives_)
    if (i != index) added.push_back(i > index ? i - 1 : i);
  addedPrimitives_ = std::move(added);
}

void GpuScene::setVisible(size_t primitive, bool visible) {
  if (primitive >= scene_.primitives.size())
    throw RuntimeError("GpuScene::setVisible: no primitive " + std::to_string(primitive) + " (the scene has " +
                       std::to_string(scene_.primitives.size()) + ")");
  if (hidden_.size() <= primitive) {
    if (visible) return;
    hidden_.resize(primitive + 1, false);
  }
  hidden_[primitive] = !visible;
}

void GpuScene::updateFrame(Extent viewport) { updateFrame(viewport, scene_.camera); }

void GpuScene::updateFrame(Extent viewport, const Camera& cam) {
  // No motion: every primitive draws with its transform, previous = current.
  models_.clear();
  prevModels_.clear();
  modelsFrame_.reset();
  addedPrimitives_.clear();
  writeObjects();
  writePose(std::nullopt, true);
  writeFrame(viewport, cam, nullptr);
}

glm::mat4 GpuScene::updateFrame(Extent viewport, const Camera& cam, const FrameMotion& motion) {
  // Model matrices at this frame's animation time, from each primitive's
  // current transform (an API that moves a primitive between frames moves it).
  const double seconds = static_cast<double>(motion.frame) / 60.0;
  std::vector<glm::mat4> current;
  current.reserve(scene_.primitives.size());
  for (const Primitive& p : scene_.primitives) current.push_back(p.transformAt(seconds));
  const bool sameShape = models_.size() == current.size();
  if (!motion.prevViewProj) {
    prevModels_ = current;  // first frame or camera cut: no motion
  } else if (sameShape && modelsFrame_ && *modelsFrame_ + 1 == motion.frame) {
    prevModels_ = models_;  // the last frame's matrices
    // Primitives added since were not drawn then: no motion on their first frame.
    for (size_t i : addedPrimitives_)
      if (i < current.size()) prevModels_[i] = current[i];
  } else if (sameShape && modelsFrame_ && *modelsFrame_ == motion.frame) {
    // The same frame again (a second renderer sharing this scene): keep its previous matrices.
  } else {
    // Frames skipped (or the scene changed shape): the animation one frame
    // back, from today's transforms.
    prevModels_.clear();
    const double before = motion.frame > 0 ? static_cast<double>(motion.frame - 1) / 60.0 : seconds;
    for (const Primitive& p : scene_.primitives) prevModels_.push_back(p.transformAt(before));
  }
  models_ = std::move(current);
  modelsFrame_ = motion.frame;
  addedPrimitives_.clear();
  writeObjects();
  writePose(motion.frame, !motion.prevViewProj);
  return writeFrame(viewport, cam, &motion);
}

void GpuScene::writeObjects() const {
  const size_t n = scene_.primitives.size();
  const bool moving = models_.size() == n;
  std::vector<ObjectRecord> next(n);
  for (size_t i = 0; i < n; ++i) {
    ObjectRecord& o = next[i];
    o.model = moving ? models_[i] : scene_.primitives[i].transform;
    o.prevModel = moving ? prevModels_[i] : o.model;
    // The normal matrix only where the model matrix changed (an inverse each).
    const bool same = i < objects_.size() && objects_[i].model == o.model;
    o.normal = same ? objects_[i].normal : glm::mat4(glm::transpose(glm::inverse(glm::mat3(o.model))));
  }
  if (!objectBuffer_ || objectCapacity_ < std::max<size_t>(n, 1)) {
    // Room for growth, so that objects added now and then reuse the buffer.
    size_t capacity = 16;
    while (capacity < n) capacity *= 2;
    objectBuffer_ = gl::createBuffer();
    glNamedBufferStorage(objectBuffer_.id(), static_cast<GLsizeiptr>(capacity * sizeof(ObjectRecord)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    objectCapacity_ = capacity;
    objects_.clear();  // nothing in it yet: every entry is written
  }
  // One range, from the first entry that changed to the last.
  size_t first = n, last = 0;
  for (size_t i = 0; i < n; ++i)
    if (i >= objects_.size() || std::memcmp(&next[i], &objects_[i], sizeof(ObjectRecord)) != 0) {
      first = std::min(first, i);
      last = i + 1;
    }
  if (first < last) {
    const size_t bytes = (last - first) * sizeof(ObjectRecord);
    glNamedBufferSubData(objectBuffer_.id(), static_cast<GLintptr>(first * sizeof(ObjectRecord)),
                         static_cast<GLsizeiptr>(bytes), &next[first]);
    objectBytes_ += bytes;
  }
  objects_ = std::move(next);
}

glm::mat4 GpuScene::writeFrame(Extent viewport, const Camera& cam, const FrameMotion* motion) {
  const float w = static_cast<float>(std::max(viewport.width, 1u));
  const float h = static_cast<float>(std::max(viewport.height, 1u));
  eye_ = cam.position;
  camera_ = cam;
  viewport_ = viewport;
  FrameBlock f{};
  f.view = cam.view();
  f.proj = cam.projection(w / h);
  f.viewProj = f.proj * f.view;
  f.invView = glm::inverse(f.view);
  f.invProj = glm::inverse(f.proj);
  f.cameraPos = glm::vec4(cam.position, 1.0f);
  f.viewport = glm::vec4(w, h, 1.0f / w, 1.0f / h);
  detail::fillSceneMembers(f, scene_);
  const glm::mat4 unjittered = f.viewProj;
  f.viewProjNoJitter = unjittered;
  f.prevViewProj = motion && motion->prevViewProj ? *motion->prevViewProj : unjittered;
  if (motion)
    f.frame = glm::ivec4(static_cast<int>(motion->frame & 0x7fffffffu), static_cast<int>(motion->jitterPhases), 0, 0);
  frameIndex_ = f.frame;  // what views drawn this frame carry (drawView)
  glNamedBufferSubData(frameUnjittered_.id(), 0, sizeof(FrameBlock), &f);

  const glm::vec2 pixels = motion ? jitterPixels(motion->frame, motion->jitterPhases) : glm::vec2(0.0f);
  if (pixels != glm::vec2(0.0f)) {
    // clip.xy += ndc * clip.w: the whole image moves by `pixels`; the inverse
    // projection follows, so positions rebuilt from this frame's depth match.
    const glm::vec2 ndc = 2.0f * pixels / glm::vec2(w, h);
    f.jitter = glm::vec4(pixels, ndc);
    f.proj = glm::translate(glm::mat4(1.0f), glm::vec3(ndc, 0.0f)) * f.proj;
    f.viewProj = f.proj * f.view;
    f.invProj = glm::inverse(f.proj);
  }
  glNamedBufferSubData(frame_.id(), 0, sizeof(FrameBlock), &f);
  forgetBindings();  // a new frame: whatever the caller bound since the last one
  bindFrame();
  return unjittered;
}

void GpuScene::selectJitter(bool jittered) {
  jittered_ = jittered;
  if (boundFrame_ != (jittered_ ? frame_.id() : frameUnjittered_.id())) bindFrame();
}

void GpuScene::bindFrame() const {
  const uint32_t block = jittered_ ? frame_.id() : frameUnjittered_.id();
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, block);
  boundFrame_ = block;
}

uint32_t GpuScene::pointLightBuffer(float key, const LightRadii& radiiOf) {
  if (lightBuffers_.size() >= kLightBufferCacheSize && !lightBuffers_.count(key)) {
    // A new threshold (a slider dragged, a param edited): the least recently
    // used one's buffer goes (its last draws are already recorded).
    auto oldest = std::min_element(lightBuffers_.begin(), lightBuffers_.end(),
                                   [](const auto& a, const auto& b) { return a.second.lastUse < b.second.lastUse; });
    lightBuffers_.erase(oldest);
    boundLights_ = 0;  // a deleted buffer's name may come back for a new one
  }
  LightBuffer& slot = lightBuffers_[key];
  slot.lastUse = ++lightBufferUses_;
  if (slot.buffer && slot.version == lightsVersion_) return slot.buffer.id();
  std::vector<float> radii = radiiOf();
  if (radii.size() != scene_.pointLights.size())
    throw RuntimeError("GpuScene::pointLightBuffer: " + std::to_string(radii.size()) + " radii for " +
                       std::to_string(scene_.pointLights.size()) + " lights");
  std::vector<GpuPointLight> lights;
  lights.reserve(std::max<size_t>(radii.size(), 1));
  // Point lights first, then spot lights (scene order within each): light
  // volumes draw each kind's mesh over its own range of the buffer.
  for (int spots = 0; spots < 2; ++spots)
    for (size_t i = 0; i < radii.size(); ++i)
      if (scene_.pointLights[i].spot == (spots == 1)) lights.push_back(gpuLight(scene_.pointLights[i], radii[i]));
  // An empty SSBO binding is an error in GL: keep at least one (unused) light.
  if (lights.empty()) lights.push_back(GpuPointLight{});
  if (!slot.buffer || slot.capacity < lights.size()) {
    // Room for growth, so that adding a light now and then reuses the buffer.
    size_t capacity = 16;
    while (capacity <= lights.size()) capacity *= 2;  // always room for one more
    slot.buffer = gl::createBuffer();  // (the one it replaces is deleted: its name may come back)
    boundLights_ = 0;
    slot.capacity = capacity;
    glNamedBufferStorage(slot.buffer.id(), static_cast<GLsizeiptr>(capacity * sizeof(GpuPointLight)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  }
  glNamedBufferSubData(slot.buffer.id(), 0, static_cast<GLsizeiptr>(lights.size() * sizeof(GpuPointLight)),
                       lights.data());
  slot.version = lightsVersion_;
  return slot.buffer.id();
}

void GpuScene::bindPointLights(float key, const LightRadii& radii) {
  const uint32_t buffer = pointLightBuffer(key, radii);
  if (boundLights_ == buffer) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  boundLights_ = buffer;
}

uint32_t GpuScene::pointLightCount() const { return static_cast<uint32_t>(scene_.pointLights.size()); }

uint32_t GpuScene::spotLightCount() const {
  return static_cast<uint32_t>(
      std::count_if(scene_.pointLights.begin(), scene_.pointLights.end(), [](const PointLight& l) { return l.spot; }));
}

const GpuScene::Locations& GpuScene::locations(uint32_t program) const {
  auto it = locations_.find(program);
  if (it != locations_.end()) return *it->second;
  auto loc = std::make_unique<Locations>();
  auto get = [&](const char* name) { return glGetUniformLocation(program, name); };
  // clang-format off
  *loc = Locations{get("u_model"),           get("u_prevModel"),        get("u_normalMatrix"),
                   get("u_baseColorFactor"), get("u_metallicFactor"),   get("u_roughnessFactor"), get("u_specular"),
                   get("u_normalScale"),     get("u_occlusionStrength"), get("u_alphaCutoff"),
                   get("u_alphaMode"),       get("u_emissive"),         get("u_hasBaseColorTex"),
                   get("u_hasMetallicRoughnessTex"), get("u_hasNormalTex"), get("u_hasOcclusionTex"),
                   get("u_specularColorFactor"), get("u_specularFactor"), get("u_unlit"), get("u_specularTextures"),
                   get("u_hasVertexColors"), get("u_uvTransform"), get("u_uvSet"), get("u_instanceRange"),
                   get("u_object"), get("u_skin"), get("u_morph"), get("u_poseStride")};
  // clang-format on
  return *locations_.emplace(program, std::move(loc)).first->second;
}

void GpuScene::claimGeometryUniforms(uint32_t program, const Locations& loc) const {
  // Which GpuScene (by serial) last set a program's geometry uniforms: a
  // scene without vertex colours, texture transforms or instances sets them
  // per draw only when another scene has drawn with the program since (a
  // frame of such a scene sets none), so that what the other scene left
  // never shows here.
  static std::mutex mutex;
  static std::unordered_map<uint32_t, uint64_t> writers;
  {
    std::lock_guard<std::mutex> lock(mutex);
    uint64_t& writer = writers[program];
    if (writer == serial_) return;
    writer = serial_;
  }
  std::array<glm::mat3x2, kMaterialTextureUnits> identity;
  identity.fill(glm::mat3x2(1.0f));
  const std::array<int, kMaterialTextureUnits> uv0{};
  if (loc.uvTransform >= 0)
    glProgramUniformMatrix3x2fv(program, loc.uvTransform, kMaterialTextureUnits, GL_FALSE, glm::value_ptr(identity[0]));
  if (loc.uvSet >= 0) glProgramUniform1iv(program, loc.uvSet, kMaterialTextureUnits, uv0.data());
  if (loc.hasVertexColors >= 0) glProgramUniform1i(program, loc.hasVertexColors, 0);
  // KHR_materials_specular's defaults (F0 0.04, F90 1, no textures), lit.
  const glm::vec3 one(1.0f);
  glProgramUniform3fv(program, loc.specularColorFactor, 1, glm::value_ptr(one));
  glProgramUniform1f(program, loc.specularFactor, 1.0f);
  glProgramUniform1i(program, loc.unlit, 0);
  glProgramUniform1i(program, loc.specularTextures, 0);
  if (loc.instanceRange >= 0) glProgramUniform2i(program, loc.instanceRange, 0, 0);
}

void GpuScene::bindMaterial(uint32_t program, int materialIndex, bool meshHasUv1) const {
  const Locations& loc = locations(program);
  const Material& m = scene_.materials.at(static_cast<size_t>(materialIndex));
  glProgramUniform4fv(program, loc.baseColorFactor, 1, glm::value_ptr(m.baseColorFactor));
  glProgramUniform1f(program, loc.metallicFactor, m.metallicFactor);
  glProgramUniform1f(program, loc.roughnessFactor, m.roughnessFactor);
  glProgramUniform1f(program, loc.specular, m.specular);
  glProgramUniform1f(program, loc.normalScale, m.normalScale);
  glProgramUniform1f(program, loc.occlusionStrength, m.occlusionStrength);
  glProgramUniform1f(program, loc.alphaCutoff, m.alphaCutoff);
  glProgramUniform1i(program, loc.alphaMode, static_cast<int>(m.alphaMode));
  glProgramUniform3fv(program, loc.emissive, 1, glm::value_ptr(m.emissiveFactor));
  // (drawUniformBytes: the factors above, the four texture flags, and what follows where the scene has it.)
  drawUniformBytes_ += sizeof(glm::vec4) + 7 * sizeof(float) + sizeof(glm::vec3) + 4 * sizeof(int);
  if (reflectancePerDraw_) drawUniformBytes_ += sizeof(glm::vec3) + sizeof(float) + 2 * sizeof(int);
  if (texCoordsPerDraw_) drawUniformBytes_ += kMaterialTextureUnits * (sizeof(glm::mat3x2) + sizeof(int));
  if (reflectancePerDraw_) {
    glProgramUniform3fv(program, loc.specularColorFactor, 1, glm::value_ptr(m.specularColorFactor));
    glProgramUniform1f(program, loc.specularFactor, m.specularFactor);
    glProgramUniform1i(program, loc.unlit, m.unlit ? 1 : 0);
  }

  // Per texture unit: its KHR_texture_transform matrix and UV set
  // (material_uv.glsl); units without a texture keep identity and set 0.
  std::array<glm::mat3x2, kMaterialTextureUnits> uvTransforms;
  std::array<int, kMaterialTextureUnits> uvSets{};
  uvTransforms.fill(glm::mat3x2(1.0f));
  auto bind = [&](GLuint unit, const TextureRef& ref, int hasLocation, const gl::Texture& fallback) {
    if (ref.valid()) {
      uvTransforms[unit] = ref.uvTransform();
      uvSets[unit] = ref.texCoord == 1 && meshHasUv1 ? 1 : 0;  // a mesh without TEXCOORD_1 samples uv0
    }
    const bool has = ref.valid() && static_cast<size_t>(ref.texture) < scene_.textures.size() &&
                     scene_.textures[ref.texture].image >= 0 &&
                     static_cast<size_t>(scene_.textures[ref.texture].image) < images_.size();
    if (has) {
      glBindTextureUnit(unit, images_[scene_.textures[ref.texture].image].id());
      glBindSampler(unit, samplers_[ref.texture].id());
    } else {
      glBindTextureUnit(unit, fallback.id());
      glBindSampler(unit, defaultSampler_.id());
    }
    if (hasLocation >= 0) glProgramUniform1i(program, hasLocation, has ? 1 : 0);
  };
  bind(0, m.baseColorTexture, loc.hasBaseColorTex, white_);
  bind(1, m.metallicRoughnessTexture, loc.hasMetallicRoughnessTex, white_);
  bind(2, m.normalTexture, loc.hasNormalTex, flatNormal_);
  bind(3, m.occlusionTexture, loc.hasOcclusionTex, white_);
  bind(4, m.emissiveTexture, -1, white_);
  // Units 5..10 are the lighting passes' (include/gbuffer_read.glsl, shadows.glsl).
  if (reflectancePerDraw_) {
    bind(11, m.specularTexture, -1, white_);
    bind(12, m.specularColorTexture, -1, white_);
    glProgramUniform1i(program, loc.specularTextures,
                       (m.specularTexture.valid() ? 1 : 0) | (m.specularColorTexture.valid() ? 2 : 0));
  }
  if (!texCoordsPerDraw_) return;  // identity and uv0 everywhere, as claimGeometryUniforms left them
  if (loc.uvTransform >= 0)
    glProgramUniformMatrix3x2fv(program, loc.uvTransform, kMaterialTextureUnits, GL_FALSE, glm::value_ptr(uvTransforms[0]));
  if (loc.uvSet >= 0) glProgramUniform1iv(program, loc.uvSet, kMaterialTextureUnits, uvSets.data());
}

size_t GpuScene::primitiveCount(Filter filter) const {
  size_t n = 0;
  for (size_t i = 0; i < scene_.primitives.size(); ++i) n += selects(filter, i);
  return n;
}

void GpuScene::drawPrimitives(uint32_t program, const DrawOptions& options) const {
  drawList(program, select(options.filter, options.backToFront, eye_), options.cullBackFaces ? Cull::back : Cull::none,
           1);
}

void GpuScene::drawList(uint32_t program, const std::vector<size_t>& order, Cull cull, uint32_t views) const {
  const Locations& loc = locations(program);
  bindProgram(program);
  claimGeometryUniforms(program, loc);
  if (instances_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, instances_.id());
  // The objects' matrices (scene.vert's Objects): written by updateFrame; a
  // scene changed since (or drawn before any updateFrame) has them written now.
  if (!order.empty() && objects_.size() != scene_.primitives.size()) writeObjects();
  const bool objects = loc.object >= 0 && !order.empty();
  if (objects) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBinding, objectBuffer_.id());
  // Skins and morphs: only programs compiled with SCENE_ANIMATION read them.
  const bool deform = deforms_ && !order.empty() && (loc.skin >= 0 || loc.morph >= 0);
  if (deform) bindDeformation(program, loc.poseStride);
  for (size_t i : order) {
    const Primitive& p = scene_.primitives[i];
    const Material& m = scene_.materials[p.material];
    const GpuMesh& mesh = meshes_[p.mesh];
    if (mesh.indexCount == 0) continue;
    if (loc.object >= 0) {
      glProgramUniform1i(program, loc.object, static_cast<GLint>(i));
      drawUniformBytes_ += sizeof(int);
    } else {
      // A vertex shader of its own: the matrices as uniforms (the Objects entry's values).
      const ObjectRecord o = i < objects_.size() ? objects_[i]
                                                 : ObjectRecord{p.transform, p.transform, glm::mat4(p.normalMatrix())};
      glProgramUniformMatrix4fv(program, loc.model, 1, GL_FALSE, glm::value_ptr(o.model));
      if (loc.prevModel >= 0) glProgramUniformMatrix4fv(program, loc.prevModel, 1, GL_FALSE, glm::value_ptr(o.prevModel));
      const glm::mat3 nm(o.normal);
      glProgramUniformMatrix3fv(program, loc.normalMatrix, 1, GL_FALSE, glm::value_ptr(nm));
      drawUniformBytes_ += sizeof(glm::mat4) * (loc.prevModel >= 0 ? 2 : 1) + sizeof(glm::mat3);
    }
    bindMaterial(program, p.material, mesh.uv1);
    if (deform) setDeformation(program, loc.skin, loc.morph, i);
    // (Both 0 until set: scenes without vertex colours or instances set nothing per draw.)
    if (hasVertexColors_ && loc.hasVertexColors >= 0) glProgramUniform1i(program, loc.hasVertexColors, mesh.colors ? 1 : 0);
    // Instanced primitives: instance j of view v is GL instance j * views + v
    // (scene.vert), one draw for all of them.
    // (Instances are uploaded with the scene: primitives added since draw one instance.)
    const InstanceRange range = instances_ && i < instanceRanges_.size() ? instanceRanges_[i] : InstanceRange{};
    if (instances_ && loc.instanceRange >= 0)
      glProgramUniform2i(program, loc.instanceRange, static_cast<GLint>(range.count), static_cast<GLint>(range.first));
    const uint32_t instances = views * std::max<uint32_t>(range.count, 1);
    if (cull != Cull::none && !m.doubleSided) {
      glEnable(GL_CULL_FACE);
      glCullFace(cull == Cull::front ? GL_FRONT : GL_BACK);
    } else {
      glDisable(GL_CULL_FACE);
    }
    glFrontFace(p.mirrored() ? GL_CW : GL_CCW);
    bindVertexArray(mesh.vao.id());
    if (instances <= 1)
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indexCount), GL_UNSIGNED_INT, nullptr);
    else
      glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(mesh.indexCount), GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(instances));
  }
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  for (GLuint unit = 0; unit < 5; ++unit) glBindSampler(unit, 0);
  if (reflectancePerDraw_)  // the specular units bound above: no sampler object left for a later pass
    for (GLuint unit = 11; unit < 13; ++unit) glBindSampler(unit, 0);
  if (instances_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, 0);  // left as found
  if (objects) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBinding, 0);
  if (deform) unbindDeformation();
  bindVertexArray(0);
}

void GpuScene::bindProgram(uint32_t program) const {
  glUseProgram(program);
  if (record_) record_->program = program;
}

void GpuScene::bindVertexArray(uint32_t vertexArray) const {
  glBindVertexArray(vertexArray);
  if (record_) record_->vertexArray = vertexArray;
}

}  // namespace rgraph
