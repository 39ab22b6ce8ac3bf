// Scene data: bounds, mesh helpers, lights, camera, scene queries and merging.
#include "rgraph/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "environment_problem.h"
#include "rgraph/error.h"

namespace rgraph {

// ---------------------------------------------------------------- Bounds

void Bounds::expand(const glm::vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

void Bounds::expand(const Bounds& b) {
  if (b.empty()) return;
  expand(b.min);
  expand(b.max);
}

Bounds Bounds::transformed(const glm::mat4& m) const {
  Bounds out;
  if (empty()) return out;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
    out.expand(glm::vec3(m * glm::vec4(c, 1.0f)));
  }
  return out;
}

// ---------------------------------------------------------------- MeshData

void MeshData::updateBounds() {
  bounds = Bounds{};
  for (const glm::vec3& p : positions) bounds.expand(p);
}

bool MeshData::valid(std::string* why) const {
  auto fail = [&](const std::string& msg) {
    if (why) *why = msg;
    return false;
  };
  const size_t n = positions.size();
  if (normals.size() != n) return fail("normals count " + std::to_string(normals.size()) + " != vertex count " + std::to_string(n));
  if (uv0.size() != n) return fail("uv0 count " + std::to_string(uv0.size()) + " != vertex count " + std::to_string(n));
  if (!uv1.empty() && uv1.size() != n) return fail("uv1 count " + std::to_string(uv1.size()) + " != vertex count " + std::to_string(n));
  if (!tangents.empty() && tangents.size() != n)
    return fail("tangent count " + std::to_string(tangents.size()) + " != vertex count " + std::to_string(n));
  if (!colors.empty() && colors.size() != n)
    return fail("color count " + std::to_string(colors.size()) + " != vertex count " + std::to_string(n));
  for (size_t k = 0; k < influences.size(); ++k)
    if (influences[k].joints.size() != n || influences[k].weights.size() != n)
      return fail("influence set " + std::to_string(k) + " count != vertex count " + std::to_string(n));
  for (size_t k = 0; k < morphTargets.size(); ++k) {
    const MorphTarget& t = morphTargets[k];
    if ((!t.positions.empty() && t.positions.size() != n) || (!t.normals.empty() && t.normals.size() != n) ||
        (!t.tangents.empty() && t.tangents.size() != n))
      return fail("morph target " + std::to_string(k) + " count != vertex count " + std::to_string(n));
  }
  if (indices.size() % 3 != 0) return fail("index count " + std::to_string(indices.size()) + " is not a multiple of 3");
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= n)
      return fail("index " + std::to_string(indices[i]) + " at position " + std::to_string(i) + " >= vertex count " + std::to_string(n));
  return true;
}

std::vector<MeshVertex> MeshData::interleaved() const {
  std::vector<MeshVertex> out(positions.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].position = positions[i];
    out[i].normal = i < normals.size() ? normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
    out[i].uv = i < uv0.size() ? uv0[i] : glm::vec2(0.0f);
    out[i].tangent = i < tangents.size() ? tangents[i] : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  }
  return out;
}

// ---------------------------------------------------------------- materials

const char* alphaModeName(AlphaMode m) {
  switch (m) {
    case AlphaMode::opaque: return "OPAQUE";
    case AlphaMode::mask: return "MASK";
    case AlphaMode::blend: return "BLEND";
  }
  return "?";
}

bool SamplerDesc::usesMipmaps() const {
  return minFilter == kNearestMipmapNearest || minFilter == kLinearMipmapNearest || minFilter == kNearestMipmapLinear ||
         minFilter == kLinearMipmapLinear;
}

glm::mat3x2 TextureRef::uvTransform() const {
  // KHR_texture_transform: translation * rotation * scale, its rotation matrix
  // (row-major) being [cos sin; -sin cos].
  const float c = std::cos(rotation), s = std::sin(rotation);
  return glm::mat3x2(glm::vec2(c * scale.x, -s * scale.x), glm::vec2(s * scale.y, c * scale.y), offset);
}

Bounds Primitive::worldBounds(const Bounds& local) const {
  if (instances.empty()) return local.transformed(transform);
  Bounds b;
  for (const glm::mat4& instance : instances) b.expand(local.transformed(transform * instance));
  return b;
}

bool Material::usesUv1() const {
  for (const TextureRef* t : textures())
    if (t->valid() && t->texCoord == 1) return true;
  return false;
}

// ---------------------------------------------------------------- lights

float lightRadius(const PointLight& light, float threshold) {
  const float c = std::max(light.constant, 0.0f);
  const float l = std::max(light.linear, 0.0f);
  const float q = std::max(light.quadratic, 0.0f);
  const float brightest = std::max({light.color.r, light.color.g, light.color.b}) * std::max(light.intensity, 0.0f);
  if (!(threshold > 0.0f)) return std::numeric_limits<float>::infinity();
  const double k = double(brightest) / double(threshold);  // attenuation at which the light reaches the threshold
  if (k <= c) return 0.0f;                                 // never as bright as the threshold
  if (q > 0.0f) {
    const double disc = double(l) * l - 4.0 * q * (c - k);  // > l^2 since c < k
    return float((-double(l) + std::sqrt(disc)) / (2.0 * q));
  }
  if (l > 0.0f) return float((k - c) / l);
  return std::numeric_limits<float>::infinity();
}

// ---------------------------------------------------------------- camera

glm::vec3 Camera::forward() const {
  glm::vec3 d = target - position;
  float len = glm::length(d);
  return len > 0.0f ? d / len : glm::vec3(0.0f, 0.0f, -1.0f);
}

glm::vec3 Camera::validUp() const {
  const glm::vec3 f = forward();
  // lookAt degenerates when up is parallel to the view direction (or zero).
  const float len = glm::length(up);
  if (len > 0.0f && glm::length(glm::cross(f, up)) >= 1e-6f * len) return up;
  return std::abs(f.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
}

// The rotation from the direction alone, then the translation: lookAt(position,
// position + forward()) loses the direction once a unit step vanishes in the
// position's float precision (beyond ~1e7 units the view came out NaN).
glm::mat4 Camera::view() const {
  return glm::lookAt(glm::vec3(0.0f), forward(), validUp()) * glm::translate(glm::mat4(1.0f), -position);
}

glm::mat4 Camera::projection(float aspect) const {
  float a = aspect > 0.0f ? aspect : 1.0f;
  float n = near > 0.0f ? near : 0.1f;
  float f = far > n ? far : n * 1000.0f;
  return glm::perspective(glm::radians(fovY), a, n, f);
}

namespace {
// Calls f with every world-space point the default camera must see: each
// vertex of a plain primitive; for an instanced one (EXT_mesh_gpu_instancing,
// up to 2^20 instances) the 8 corners of its mesh's box under each instance.
template <typename F>
void forEachDrawnPoint(const Scene& scene, F&& f) {
  for (const Primitive& p : scene.primitives) {
    if (p.mesh < 0 || static_cast<size_t>(p.mesh) >= scene.meshes.size()) continue;
    const MeshData& mesh = scene.meshes[static_cast<size_t>(p.mesh)];
    if (p.instances.empty()) {
      for (const glm::vec3& v : mesh.positions) f(glm::vec3(p.transform * glm::vec4(v, 1.0f)));
      continue;
    }
    if (mesh.bounds.empty()) continue;
    for (const glm::mat4& instance : p.instances) {
      const glm::mat4 m = p.transform * instance;
      for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? mesh.bounds.max.x : mesh.bounds.min.x,
                               (i & 2) ? mesh.bounds.max.y : mesh.bounds.min.y,
                               (i & 4) ? mesh.bounds.max.z : mesh.bounds.min.z);
        f(glm::vec3(m * glm::vec4(corner, 1.0f)));
      }
    }
  }
}
}  // namespace

Camera frameBounds(const Bounds& bounds, float fovY) {
  if (bounds.empty()) {
    Camera cam;
    cam.fovY = fovY;
    return cam;
  }
  return frameSphere(bounds.center(), bounds.radius(), fovY);
}

Camera frameSphere(const glm::vec3& c, float radius, float fovY) {
  Camera cam;
  cam.fovY = fovY;
  const float r = std::max(radius, 1e-3f);
  const float halfFov = glm::radians(fovY) * 0.5f;
  const float dist = r / std::sin(halfFov) * 1.05f;
  const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));  // +Z side, slightly above
  cam.position = c + dir * dist;
  cam.target = c;
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.near = std::max(dist - r * 1.5f, dist * 0.01f);
  cam.near = std::max(cam.near, 1e-3f);
  cam.far = dist + r * 2.0f;
  return cam;
}

Camera frameScene(const Scene& scene, float fovY) {
  const Scene::Sphere sphere = scene.boundingSphere();
  Camera cam = frameSphere(sphere.center, sphere.radius, fovY);
  if (scene.bounds().empty()) return cam;
  // In the camera's basis a vertex p has x = (p-c).right, y = (p-c).up and
  // a = (p-c).dir (dir: from the centre c towards the camera), none of which
  // depends on the distance d; its depth is d - a. It lies within the margin
  // m of the field of view when max(|x|, |y|) <= m tan(fov/2) (d - a): the
  // closest d that keeps every vertex in is the largest a + max(|x|,|y|) / (m tan).
  const glm::vec3 dir = glm::normalize(cam.position - sphere.center);
  const glm::vec3 right = glm::normalize(glm::cross(cam.up, dir));
  const glm::vec3 up = glm::cross(dir, right);
  const float reach = 0.95f * std::tan(glm::radians(fovY) * 0.5f);
  const float r = std::max(sphere.radius, 1e-3f);
  float dist = 0.0f, nearest = 0.0f;  // nearest: the largest a (the vertex closest to the camera)
  bool any = false;
  forEachDrawnPoint(scene, [&](const glm::vec3& world) {
    const glm::vec3 d = world - sphere.center;
    const float a = glm::dot(d, dir);
    dist = std::max(dist, a + std::max(std::abs(glm::dot(d, right)), std::abs(glm::dot(d, up))) / reach);
    nearest = any ? std::max(nearest, a) : a;
    any = true;
  });
  if (!any) return cam;
  dist = std::max(dist, nearest + 0.05f * r);  // never at or past a vertex
  cam.position = sphere.center + dir * dist;
  cam.near = std::max((dist - nearest) * 0.5f, 1e-3f);
  cam.far = dist + r * 2.0f;
  return cam;
}

Camera orbitCamera(const Camera& camera, float degrees) {
  Camera c = camera;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(camera.validUp()));
  c.position = camera.target + glm::vec3(turn * glm::vec4(camera.position - camera.target, 0.0f));
  return c;
}

// ---------------------------------------------------------------- Scene queries

namespace {
std::vector<const Material*> usedMaterials(const Scene& s) {
  std::set<int> ids;
  for (const Primitive& p : s.primitives)
    if (p.material >= 0 && size_t(p.material) < s.materials.size()) ids.insert(p.material);
  std::vector<const Material*> out;
  for (int i : ids) out.push_back(&s.materials[size_t(i)]);
  return out;
}
}  // namespace

bool Scene::hasBlendMaterials() const {
  for (const Material* m : usedMaterials(*this))
    if (m->alphaMode == AlphaMode::blend) return true;
  return false;
}

bool Scene::hasMaskMaterials() const {
  for (const Material* m : usedMaterials(*this))
    if (m->alphaMode == AlphaMode::mask) return true;
  return false;
}

bool Scene::hasNormalMaps() const {
  for (const Material* m : usedMaterials(*this))
    if (m->hasNormalMap()) return true;
  return false;
}

bool Scene::hasVertexColors() const {
  for (const Primitive& p : primitives)
    if (p.mesh >= 0 && size_t(p.mesh) < meshes.size() && meshes[size_t(p.mesh)].hasColors()) return true;
  return false;
}

bool Scene::hasInstancing() const {
  return std::any_of(primitives.begin(), primitives.end(), [](const Primitive& p) { return !p.instances.empty(); });
}

bool Scene::hasTextures() const {
  for (const Material* m : usedMaterials(*this))
    if (m->baseColorTexture.valid() || m->metallicRoughnessTexture.valid() || m->normalTexture.valid() ||
        m->occlusionTexture.valid() || m->emissiveTexture.valid() || m->specularTexture.valid() ||
        m->specularColorTexture.valid())
      return true;
  return false;
}

bool Scene::hasMetallicRoughnessVariation() const {
  std::vector<const Material*> used = usedMaterials(*this);
  for (const Material* m : used)
    if (m->metallicRoughnessTexture.valid()) return true;
  for (const Material* m : used)
    if (m->metallicFactor != used.front()->metallicFactor || m->roughnessFactor != used.front()->roughnessFactor) return true;
  return false;
}

bool Scene::castsShadows(const Primitive& p) const {
  if (p.castShadows) return *p.castShadows;
  const bool blend = p.material >= 0 && size_t(p.material) < materials.size() &&
                     materials[size_t(p.material)].alphaMode == AlphaMode::blend;
  return !blend;
}

bool Scene::hasShadowCasters() const {
  return std::any_of(primitives.begin(), primitives.end(), [&](const Primitive& p) { return castsShadows(p); });
}

bool Scene::hasShadowCastingLights() const {
  return std::any_of(pointLights.begin(), pointLights.end(), [](const PointLight& l) { return l.castsShadows(); }) ||
         std::any_of(directionalLights.begin(), directionalLights.end(),
                     [](const DirectionalLight& l) { return l.castShadows; });
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Primitive& p : primitives)
    if (p.mesh >= 0 && size_t(p.mesh) < meshes.size())
      n += meshes[size_t(p.mesh)].triangleCount() * std::max<size_t>(p.instances.size(), 1);
  return n;
}

size_t Scene::vertexCount() const {
  size_t n = 0;
  for (const Primitive& p : primitives)
    if (p.mesh >= 0 && size_t(p.mesh) < meshes.size())
      n += meshes[size_t(p.mesh)].vertexCount() * std::max<size_t>(p.instances.size(), 1);
  return n;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const Primitive& p : primitives) b.expand(p.bounds);
  return b;
}

Scene::Sphere Scene::boundingSphere() const {
  Sphere s;
  const Bounds b = bounds();
  if (b.empty()) return s;
  s.center = b.center();
  // Squared distances, one square root at the end; the box's radius caps it
  // (a primitive's vertices lie inside its bounds).
  float r2 = 0.0f;
  forEachDrawnPoint(*this, [&](const glm::vec3& world) {
    const glm::vec3 d = world - s.center;
    r2 = std::max(r2, glm::dot(d, d));
  });
  s.radius = std::min(std::sqrt(r2), b.radius());
  return s;
}

namespace {
bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// False for NaN and infinity too.
bool inWorld(const glm::vec3& v) {
  return std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
         std::abs(v.z) <= kMaxWorldCoordinate;
}
std::string vecText(const glm::vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return b;
}
std::string limitText() {
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", double(kMaxWorldCoordinate));
  return limit;
}

// Finite inputs can still overflow on the way (a large vertex under a large
// scale): checked on the results, which is what the renderer reads.
void validateNumbers(const Scene& s) {
  const std::string where = s.source.empty() ? std::string("scene") : s.source;
  auto fail = [&](const std::string& msg) { throw RuntimeError(where + ": " + msg); };
  const std::string limit = limitText();
  const Bounds none;
  for (size_t i = 0; i < s.primitives.size(); ++i) {
    const glm::mat4& m = s.primitives[i].transform;
    for (int c = 0; c < 4; ++c)
      if (!finiteVec(glm::vec3(m[c])) || !std::isfinite(m[c].w))
        fail("primitive " + std::to_string(i) + " ('" + s.primitives[i].name +
             "'): its world transform is not finite (node transforms that overflow together?)");
    const Bounds& b = s.primitives[i].bounds;
    if (b.min == none.min && b.max == none.max) continue;  // no vertices
    if (!inWorld(b.min) || !inWorld(b.max))
      fail("primitive " + std::to_string(i) + " ('" + s.primitives[i].name + "'): world-space bounds " + vecText(b.min) +
           " to " + vecText(b.max) + " exceed +-" + limit +
           " units (the most supported; a huge vertex position or transform?)");
  }
  for (size_t i = 0; i < s.pointLights.size(); ++i) validatePointLight(s.pointLights[i], i, where);
  for (size_t i = 0; i < s.directionalLights.size(); ++i) validateDirectionalLight(s.directionalLights[i], i, where);
  validateAmbient(s.ambient, where);
  if (!s.hasCamera) return;  // the caller frames the scene: finite within the bounds above
  validateCamera(s.camera, where);
}
}  // namespace

namespace {
std::string numberText(float v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(v));
  return b;
}
SceneValueProblem problem(std::string key, std::string message) { return {std::move(key), std::move(message)}; }
// NaN first (it compares false with every bound), then the world's extent
// (an infinity, or a file's 1e39 read as a float, exceeds it).
std::optional<SceneValueProblem> positionProblem(const char* key, const glm::vec3& v) {
  if (std::isnan(v.x) || std::isnan(v.y) || std::isnan(v.z)) return problem(key, vecText(v) + " is not a finite number");
  if (!inWorld(v)) return problem(key, vecText(v) + " exceeds +-" + limitText() + " units");
  return std::nullopt;
}
std::optional<SceneValueProblem> colorProblem(const glm::vec3& color, float intensity) {
  if (!finiteVec(color)) return problem("color", vecText(color) + " is not a finite number");
  if (color.x < 0.0f || color.y < 0.0f || color.z < 0.0f) return problem("color", "values must be >= 0, got " + vecText(color));
  if (!std::isfinite(intensity)) return problem("intensity", "is not a finite number");
  if (intensity < 0.0f) return problem("intensity", "must be >= 0, got " + numberText(intensity));
  return std::nullopt;
}
}  // namespace

// The ranges scene files and the API share, stated here once (scenes/README.md
// lists them for files). Keys are the scene file's.
std::optional<SceneValueProblem> pointLightProblem(const PointLight& l) {
  if (auto p = positionProblem("position", l.position)) return p;
  if (auto p = colorProblem(l.color, l.intensity)) return p;
  const std::pair<const char*, float> terms[] = {{"constant", l.constant}, {"linear", l.linear}, {"quadratic", l.quadratic}};
  for (const auto& [key, v] : terms) {
    if (!std::isfinite(v)) return problem(key, "is not a finite number");
    if (v < 0.0f) return problem(key, "must be >= 0, got " + numberText(v));
  }
  if (l.constant + l.linear + l.quadratic <= 0.0f) return problem("", "constant, linear and quadratic cannot all be 0");
  // (An infinite radius is a light without falloff: callers cap it, see
  // lightRadius; 0 is one that never reaches the cut-off.)
  if (std::isnan(l.radius)) return problem("radius", "is not a number");
  if (l.radius < 0.0f) return problem("radius", "must be >= 0, got " + numberText(l.radius));
  if (!l.spot) return std::nullopt;
  const float len = finiteVec(l.direction) ? glm::length(l.direction) : 0.0f;
  if (!(std::abs(len - 1.0f) < 1e-3f)) return problem("direction", vecText(l.direction) + " is not a unit vector");
  // The ranges of glTF's KHR_lights_punctual (in degrees): a cone wider than a
  // half-space has no light volume of this shape, and inner >= outer no ramp.
  if (!(l.outerConeDeg > 0.0f && l.outerConeDeg <= 90.0f))
    return problem("outer_cone_deg", "must be in (0, 90] degrees (a half-angle from the axis), got " + numberText(l.outerConeDeg));
  if (!(l.innerConeDeg >= 0.0f && l.innerConeDeg < l.outerConeDeg))
    return problem("inner_cone_deg", "must be >= 0 and less than outer_cone_deg (" + numberText(l.outerConeDeg) +
                                         "), got " + numberText(l.innerConeDeg));
  return std::nullopt;
}

std::optional<SceneValueProblem> directionalLightProblem(const DirectionalLight& l) {
  if (!finiteVec(l.direction)) return problem("direction", vecText(l.direction) + " is not a finite number");
  // Scaled by its largest component first: the length of (1e38, 1e38, 0) overflows a float.
  const float largest = std::max({std::abs(l.direction.x), std::abs(l.direction.y), std::abs(l.direction.z)});
  if (!(largest > 0.0f)) return problem("direction", "must not be the zero vector");
  return colorProblem(l.color, l.intensity);
}

std::optional<SceneValueProblem> cameraProblem(const Camera& c) {
  if (auto p = positionProblem("position", c.position)) return p;
  if (auto p = positionProblem("target", c.target)) return p;
  if (c.target == c.position) return problem("target", "must differ from the position");
  if (!finiteVec(c.up) || glm::length(c.up) == 0.0f) return problem("up", "must be a finite, non-zero vector");
  if (!(c.fovY > 0.0f && c.fovY < 180.0f)) return problem("fov", "must be in (0, 180) degrees, got " + numberText(c.fovY));
  if (!(c.near > 0.0f && std::isfinite(c.near))) return problem("near", "must be > 0, got " + numberText(c.near));
  if (!(c.far > c.near && std::isfinite(c.far)))
    return problem("far", "must be greater than near (" + numberText(c.near) + "), got " + numberText(c.far));
  return std::nullopt;
}

std::optional<SceneValueProblem> ambientProblem(const glm::vec3& ambient) {
  if (!finiteVec(ambient)) return problem("ambient", vecText(ambient) + " is not a finite number");
  if (ambient.x < 0.0f || ambient.y < 0.0f || ambient.z < 0.0f)
    return problem("ambient", "values must be >= 0, got " + vecText(ambient));
  return std::nullopt;
}

namespace {
std::string problemText(const SceneValueProblem& p) { return p.key.empty() ? p.message : p.key + ": " + p.message; }
}  // namespace

void validatePointLight(const PointLight& l, size_t index, const std::string& where) {
  if (auto p = pointLightProblem(l))
    throw RuntimeError(where + ": point light " + std::to_string(index) + ": " + problemText(*p));
}

void validateDirectionalLight(const DirectionalLight& l, size_t index, const std::string& where) {
  if (auto p = directionalLightProblem(l))
    throw RuntimeError(where + ": directional light " + std::to_string(index) + ": " + problemText(*p));
}

void validateCamera(const Camera& camera, const std::string& where) {
  auto fail = [&](const std::string& msg) { throw RuntimeError(where + ": " + msg); };
  if (auto p = cameraProblem(camera)) fail("camera " + problemText(*p));
  const glm::mat4 vp = camera.viewProjection(1.0f);
  for (int c = 0; c < 4; ++c)
    if (!finiteVec(glm::vec3(vp[c])) || !std::isfinite(vp[c].w))
      fail("camera: its view and projection are not finite (near " + std::to_string(camera.near) + ", far " +
           std::to_string(camera.far) + ", fov " + std::to_string(camera.fovY) + ")");
}

void validateAmbient(const glm::vec3& ambient, const std::string& where) {
  if (auto p = ambientProblem(ambient)) throw RuntimeError(where + ": " + problemText(*p));
}

void Scene::validate() const {
  const std::string where = source.empty() ? std::string("scene") : source;
  auto fail = [&](const std::string& msg) { throw RuntimeError(where + ": " + msg); };
  if (environment)
    if (const auto problem = environmentProblem(*environment)) fail(*problem);
  for (size_t i = 0; i < meshes.size(); ++i) {
    std::string why;
    if (!meshes[i].valid(&why)) fail("mesh " + std::to_string(i) + " ('" + meshes[i].name + "'): " + why);
  }
  for (size_t i = 0; i < primitives.size(); ++i) {
    const Primitive& p = primitives[i];
    if (p.mesh < 0 || size_t(p.mesh) >= meshes.size()) fail("primitive " + std::to_string(i) + ": mesh index out of range");
    if (p.material < 0 || size_t(p.material) >= materials.size())
      fail("primitive " + std::to_string(i) + ": material index out of range");
    if (materials[size_t(p.material)].hasNormalMap() && !meshes[size_t(p.mesh)].hasTangents())
      fail("primitive " + std::to_string(i) + ": normal-mapped material on a mesh without tangents");
    if (p.node >= 0 && size_t(p.node) >= animation.nodes.size())
      fail("primitive " + std::to_string(i) + ": node index out of range");
    if (p.node >= 0 && animation.nodes[size_t(p.node)].weights.size() != meshes[size_t(p.mesh)].morphTargets.size())
      fail("primitive " + std::to_string(i) + ": its node's morph weights do not match its mesh's morph targets");
  }
  auto checkRef = [&](const TextureRef& r, size_t mi, const char* what) {
    if (r.texture >= 0 && size_t(r.texture) >= textures.size())
      fail("material " + std::to_string(mi) + ": " + what + " texture index out of range");
  };
  for (size_t i = 0; i < materials.size(); ++i) {
    const Material& m = materials[i];
    checkRef(m.baseColorTexture, i, "baseColor");
    checkRef(m.metallicRoughnessTexture, i, "metallicRoughness");
    checkRef(m.normalTexture, i, "normal");
    checkRef(m.occlusionTexture, i, "occlusion");
    checkRef(m.emissiveTexture, i, "emissive");
    checkRef(m.specularTexture, i, "specular");
    checkRef(m.specularColorTexture, i, "specular colour");
  }
  for (size_t i = 0; i < textures.size(); ++i)
    if (textures[i].image < 0 || size_t(textures[i].image) >= images.size())
      fail("texture " + std::to_string(i) + ": image index out of range");
  for (size_t i = 0; i < images.size(); ++i) {
    const ImageData& im = images[i];
    if (im.width <= 0 || im.height <= 0 || im.rgba.size() != size_t(im.width) * size_t(im.height) * 4)
      fail("image " + std::to_string(i) + " ('" + im.name + "'): pixel data does not match its size");
  }
  validateNumbers(*this);
}

// ---------------------------------------------------------------- merging and defaults

void appendScene(Scene& dst, Scene src, const glm::mat4& transform) {
  const int meshBase = int(dst.meshes.size());
  const int materialBase = int(dst.materials.size());
  const int textureBase = int(dst.textures.size());
  const int imageBase = int(dst.images.size());

  for (MeshData& m : src.meshes) dst.meshes.push_back(std::move(m));
  auto rebase = [&](TextureRef& r) {
    if (r.texture >= 0) r.texture += textureBase;
  };
  for (Material& m : src.materials) {
    rebase(m.baseColorTexture);
    rebase(m.metallicRoughnessTexture);
    rebase(m.normalTexture);
    rebase(m.occlusionTexture);
    rebase(m.emissiveTexture);
    rebase(m.specularTexture);
    rebase(m.specularColorTexture);
    dst.materials.push_back(std::move(m));
  }
  for (SceneTexture& t : src.textures) {
    if (t.image >= 0) t.image += imageBase;
    dst.textures.push_back(t);
  }
  for (ImageData& im : src.images) dst.images.push_back(std::move(im));
  for (std::string& w : src.warnings) dst.warnings.push_back(std::move(w));
  const int nodeBase = int(dst.animation.nodes.size());
  appendAnimation(dst.animation, std::move(src.animation), transform);
  for (Primitive& p : src.primitives) {
    if (p.node >= 0) p.node += nodeBase;
    p.mesh += meshBase;
    p.material += materialBase;
    p.transform = transform * p.transform;
    p.bounds = p.worldBounds(dst.meshes[size_t(p.mesh)].bounds);
    dst.primitives.push_back(std::move(p));
  }
  const glm::mat3 dirXf(transform);
  for (PointLight l : src.pointLights) {
    l.position = glm::vec3(transform * glm::vec4(l.position, 1.0f));
    const glm::vec3 d = dirXf * l.direction;
    if (l.spot && glm::length(d) > 0.0f) l.direction = glm::normalize(d);
    dst.pointLights.push_back(l);
  }
  for (DirectionalLight l : src.directionalLights) {
    glm::vec3 d = dirXf * l.direction;
    if (glm::length(d) > 0.0f) l.direction = glm::normalize(d);
    dst.directionalLights.push_back(l);
  }
  if (!dst.hasCamera && src.hasCamera) {
    Camera c = src.camera;
    c.position = glm::vec3(transform * glm::vec4(c.position, 1.0f));
    c.target = glm::vec3(transform * glm::vec4(src.camera.target, 1.0f));
    glm::vec3 u = dirXf * c.up;
    if (glm::length(u) > 0.0f) c.up = glm::normalize(u);
    dst.camera = c;
    dst.hasCamera = true;
  }
}

void applySceneDefaults(Scene& scene) {
  if (!scene.hasCamera) {
    scene.camera = frameScene(scene);
    scene.hasCamera = true;
  }
  if (scene.pointLights.empty() && scene.directionalLights.empty()) {
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
    sun.color = glm::vec3(1.0f);
    sun.intensity = 1.0f;
    scene.directionalLights.push_back(sun);
  }
}

}  // namespace rgraph
