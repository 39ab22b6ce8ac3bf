// RenderScene's objects (rgraph/renderer.h): instances added, removed, moved,
// recoloured and hidden between frames, and the meshes and materials made in
// code that they draw. Every edit is checked before anything changes, so a
// call that throws leaves the scene as it was.
//
// An object is a Scene::primitives entry: GpuScene::updateFrame writes the
// matrices that changed into its Objects buffer each frame, with the previous
// frame's transform from its motion path, and the draws read the material
// from the Scene. Nothing here uploads but a new mesh (GpuScene::meshAdded).
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "render_scene_impl.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/renderer.h"

namespace rgraph {
namespace {

std::string num(float v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(v));
  return b;
}

std::string vecText(const glm::vec3& v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }
std::string vecText(const glm::vec4& v) {
  return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ", " + num(v.w) + ")";
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool inWorld(const glm::vec3& v) {
  return finite(v) && std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
         std::abs(v.z) <= kMaxWorldCoordinate;
}

// Why `m` cannot place an object drawing a mesh with local bounds `local`
// (and EXT_mesh_gpu_instancing `instances`), or "" when it can.
std::string transformProblem(const glm::mat4& m, const Primitive& p, const Bounds& local) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return "transform: column " + std::to_string(c) + " " + vecText(m[c]) + " is not finite";
  const float det = glm::determinant(glm::mat3(m));
  if (!std::isnormal(det))
    return "transform: its 3x3 part has determinant " + num(det) +
           " (it flattens the object, and its normals are undefined): hide it with setVisible(false) instead";
  Bounds b;  // Primitive::worldBounds with `m` for its transform
  if (p.instances.empty()) b = local.transformed(m);
  for (const glm::mat4& instance : p.instances) b.expand(local.transformed(m * instance));
  if (!b.empty() && (!inWorld(b.min) || !inWorld(b.max)))
    return "transform: world-space bounds " + vecText(b.min) + " to " + vecText(b.max) + " exceed +-" +
           num(kMaxWorldCoordinate) + " units";
  return {};
}

std::string factorsProblem(const glm::vec4& base, float metallic, float roughness, const glm::vec3& emissive) {
  for (int i = 0; i < 4; ++i)
    if (!(base[i] >= 0.0f && base[i] <= 1.0f))
      return "baseColorFactor: " + vecText(base) + " must be in 0..1";
  if (!(metallic >= 0.0f && metallic <= 1.0f)) return "metallicFactor: " + num(metallic) + " must be in 0..1";
  if (!(roughness >= 0.0f && roughness <= 1.0f)) return "roughnessFactor: " + num(roughness) + " must be in 0..1";
  if (!finite(emissive) || emissive.x < 0.0f || emissive.y < 0.0f || emissive.z < 0.0f)
    return "emissiveFactor: " + vecText(emissive) + " must be finite and >= 0";
  return {};
}

// Why `mesh` (made in code) cannot be drawn, or ""; fills in what may be
// left out (normals, uv0) first.
std::string meshProblem(MeshData& mesh) {
  const size_t n = mesh.positions.size();
  if (n == 0) return "no positions";
  if (mesh.indices.empty()) return "no indices (no triangle to draw)";
  for (size_t i = 0; i < n; ++i)
    if (!inWorld(mesh.positions[i]))
      return "positions[" + std::to_string(i) + "]: " + vecText(mesh.positions[i]) + " is not finite or exceeds +-" +
             num(kMaxWorldCoordinate) + " units";
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    return "normals: " + std::to_string(mesh.normals.size()) + " for " + std::to_string(n) +
           " positions (give one per position, or none: smooth normals are computed)";
  if (!mesh.uv0.empty() && mesh.uv0.size() != n)
    return "uv0: " + std::to_string(mesh.uv0.size()) + " for " + std::to_string(n) + " positions (one per position, or none)";
  if (mesh.indices.size() % 3 != 0)
    return "indices: " + std::to_string(mesh.indices.size()) + " is not a multiple of 3 (triangles)";
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      return "indices[" + std::to_string(i) + "]: " + std::to_string(mesh.indices[i]) + " is not below the " +
             std::to_string(n) + " positions";
  for (size_t i = 0; i < mesh.normals.size(); ++i)
    if (!finite(mesh.normals[i])) return "normals[" + std::to_string(i) + "]: " + vecText(mesh.normals[i]) + " is not finite";
  mesh.hasUv0 = !mesh.uv0.empty();
  if (!mesh.hasUv0) mesh.uv0.assign(n, glm::vec2(0.0f));
  if (mesh.normals.empty()) computeSmoothNormals(mesh);
  // Tangents for any material it may be drawn with (a normal map needs them).
  if (!mesh.hasTangents()) generateTangents(mesh);
  std::string why;
  if (!mesh.valid(&why)) return why;  // tangents, uv1 or colours of another size
  mesh.updateBounds();
  return {};
}

}  // namespace

// ---------------------------------------------------------------- bookkeeping

void RenderScene::Impl::numberPrimitives() {
  ids.clear();
  indexOf.clear();
  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    ids.push_back(nextId);
    indexOf[nextId++] = i;
  }
  hidden.assign(scene.primitives.size(), false);
}

size_t RenderScene::Impl::find(InstanceId id, const char* call) const {
  const auto it = indexOf.find(id.value);
  if (it == indexOf.end())
    throw RuntimeError(where() + ": RenderScene::" + call + ": no instance " + std::to_string(id.value) +
                       " (removed, or never added; the scene has " + std::to_string(ids.size()) + " instances)");
  return it->second;
}

std::string RenderScene::Impl::describe(size_t primitive) const {
  const std::string& name = scene.primitives[primitive].name;
  return "instance " + std::to_string(ids[primitive]) + (name.empty() ? std::string() : " ('" + name + "')");
}

// ---------------------------------------------------------------- meshes and materials

size_t RenderScene::addMesh(MeshData mesh) {
  Impl& d = *impl_;
  const size_t index = d.scene.meshes.size();
  const std::string name = mesh.name.empty() ? "mesh " + std::to_string(index) : "mesh '" + mesh.name + "'";
  if (const std::string why = meshProblem(mesh); !why.empty())
    throw RuntimeError(d.where() + ": RenderScene::addMesh: " + name + ": " + why);
  if (d.gpu) d.gpu->requireUploadContext("RenderScene::addMesh");
  d.scene.meshes.push_back(std::move(mesh));
  if (d.gpu) {
    try {
      d.gpu->meshAdded();
    } catch (...) {
      d.scene.meshes.pop_back();
      throw;
    }
  }
  return index;
}

size_t RenderScene::addMaterial(Material material) {
  Impl& d = *impl_;
  const size_t index = d.scene.materials.size();
  auto fail = [&](const std::string& why) {
    throw RuntimeError(d.where() + ": RenderScene::addMaterial: material " + std::to_string(index) +
                       (material.name.empty() ? std::string() : " ('" + material.name + "')") + ": " + why);
  };
  if (const std::string why = factorsProblem(material.baseColorFactor, material.metallicFactor,
                                             material.roughnessFactor, material.emissiveFactor);
      !why.empty())
    fail(why);
  if (!(material.alphaCutoff >= 0.0f) || !std::isfinite(material.alphaCutoff))
    fail("alphaCutoff: " + num(material.alphaCutoff) + " must be finite and >= 0");
  for (const TextureRef* t : material.textures()) {
    if (t->texture >= 0 && static_cast<size_t>(t->texture) >= d.scene.textures.size())
      fail("texture " + std::to_string(t->texture) + " is out of range (the scene has " +
           std::to_string(d.scene.textures.size()) + ")");
    if (t->texCoord != 0 && t->texCoord != 1) fail("texCoord " + std::to_string(t->texCoord) + " must be 0 or 1");
  }
  if (material.hasNormalMap() && d.gpu && !d.gpu->hasTangents())
    fail("a normal map in a scene uploaded without normal maps (its vertex buffers carry no tangents)");
  d.scene.materials.push_back(std::move(material));
  return index;
}

// ---------------------------------------------------------------- instances

InstanceId RenderScene::addInstance(size_t mesh, size_t material, const glm::mat4& transform, std::string name) {
  Impl& d = *impl_;
  Scene& s = d.scene;
  const std::string who = d.where() + ": RenderScene::addInstance: instance " + std::to_string(d.nextId) +
                          (name.empty() ? std::string() : " ('" + name + "')") + ": ";
  if (mesh >= s.meshes.size())
    throw RuntimeError(who + "mesh " + std::to_string(mesh) + " is out of range (the scene has " +
                       std::to_string(s.meshes.size()) + ")");
  if (material >= s.materials.size())
    throw RuntimeError(who + "material " + std::to_string(material) + " is out of range (the scene has " +
                       std::to_string(s.materials.size()) + ")");
  if (s.materials[material].hasNormalMap() && !s.meshes[mesh].hasTangents())
    throw RuntimeError(who + "material " + std::to_string(material) + " has a normal map and mesh " +
                       std::to_string(mesh) + " no tangents");
  Primitive p;
  p.mesh = static_cast<int>(mesh);
  p.material = static_cast<int>(material);
  p.name = std::move(name);
  if (const std::string why = transformProblem(transform, p, s.meshes[mesh].bounds); !why.empty())
    throw RuntimeError(who + why);
  p.transform = transform;
  p.bounds = p.worldBounds(s.meshes[mesh].bounds);
  s.primitives.push_back(std::move(p));
  const uint64_t id = d.nextId++;
  d.ids.push_back(id);
  d.hidden.push_back(false);
  d.indexOf[id] = s.primitives.size() - 1;
  if (d.gpu) d.gpu->primitiveAdded();
  ++d.instancesVersion;
  return InstanceId{id};
}

void RenderScene::removeInstance(InstanceId id) {
  Impl& d = *impl_;
  const size_t i = d.find(id, "removeInstance");
  d.scene.primitives.erase(d.scene.primitives.begin() + static_cast<std::ptrdiff_t>(i));
  d.ids.erase(d.ids.begin() + static_cast<std::ptrdiff_t>(i));
  d.hidden.erase(d.hidden.begin() + static_cast<std::ptrdiff_t>(i));
  d.indexOf.erase(id.value);
  for (size_t k = i; k < d.ids.size(); ++k) d.indexOf[d.ids[k]] = k;
  if (const auto own = d.ownMaterial.find(id.value); own != d.ownMaterial.end()) {
    d.freeMaterials.push_back(own->second);
    d.ownMaterial.erase(own);
  }
  if (d.gpu) d.gpu->primitiveRemoved(i);
  ++d.instancesVersion;
}

void RenderScene::setTransform(InstanceId id, const glm::mat4& transform) {
  Impl& d = *impl_;
  const size_t i = d.find(id, "setTransform");
  Primitive& p = d.scene.primitives[i];
  const Bounds& local = d.scene.meshes[static_cast<size_t>(p.mesh)].bounds;
  if (const std::string why = transformProblem(transform, p, local); !why.empty())
    throw RuntimeError(d.where() + ": RenderScene::setTransform: " + d.describe(i) + ": " + why);
  p.transform = transform;
  p.bounds = p.worldBounds(local);  // back-to-front order and shadow fitting read them
}

const glm::mat4& RenderScene::transform(InstanceId id) const {
  return impl_->scene.primitives[impl_->find(id, "transform")].transform;
}

void RenderScene::setMaterial(InstanceId id, size_t material) {
  Impl& d = *impl_;
  const size_t i = d.find(id, "setMaterial");
  Primitive& p = d.scene.primitives[i];
  const std::string who = d.where() + ": RenderScene::setMaterial: " + d.describe(i) + ": ";
  if (material >= d.scene.materials.size())
    throw RuntimeError(who + "material " + std::to_string(material) + " is out of range (the scene has " +
                       std::to_string(d.scene.materials.size()) + ")");
  if (d.scene.materials[material].hasNormalMap() && !d.scene.meshes[static_cast<size_t>(p.mesh)].hasTangents())
    throw RuntimeError(who + "material " + std::to_string(material) + " has a normal map and its mesh no tangents");
  if (const auto own = d.ownMaterial.find(id.value); own != d.ownMaterial.end() && own->second != material) {
    d.freeMaterials.push_back(own->second);
    d.ownMaterial.erase(own);
  }
  p.material = static_cast<int>(material);
  ++d.instancesVersion;
}

void RenderScene::setMaterialParameters(InstanceId id, const MaterialParameters& v) {
  Impl& d = *impl_;
  const size_t i = d.find(id, "setMaterialParameters");
  if (const std::string why = factorsProblem(v.baseColorFactor, v.metallicFactor, v.roughnessFactor, v.emissiveFactor);
      !why.empty())
    throw RuntimeError(d.where() + ": RenderScene::setMaterialParameters: " + d.describe(i) + ": " + why);
  Primitive& p = d.scene.primitives[i];
  auto own = d.ownMaterial.find(id.value);
  if (own == d.ownMaterial.end()) {
    // The object's own copy of what it draws with: a free slot, else a new one.
    Material copy = d.scene.materials[static_cast<size_t>(p.material)];
    size_t slot = d.scene.materials.size();
    // (A free slot some object was pointed at since, with setMaterial, is its material now: not reused.)
    while (!d.freeMaterials.empty() && slot == d.scene.materials.size()) {
      const size_t candidate = d.freeMaterials.back();
      d.freeMaterials.pop_back();
      bool used = false;
      for (const Primitive& q : d.scene.primitives) used = used || q.material == static_cast<int>(candidate);
      if (!used) slot = candidate;
    }
    if (slot < d.scene.materials.size()) {
      d.scene.materials[slot] = std::move(copy);
    } else {
      d.scene.materials.push_back(std::move(copy));
    }
    own = d.ownMaterial.emplace(id.value, slot).first;
    p.material = static_cast<int>(slot);
  }
  Material& m = d.scene.materials[own->second];
  m.baseColorFactor = v.baseColorFactor;
  m.metallicFactor = v.metallicFactor;
  m.roughnessFactor = v.roughnessFactor;
  m.emissiveFactor = v.emissiveFactor;
  ++d.instancesVersion;
}

MaterialParameters RenderScene::materialParameters(InstanceId id) const {
  const Impl& d = *impl_;
  const Material& m = d.scene.materials[static_cast<size_t>(d.scene.primitives[d.find(id, "materialParameters")].material)];
  return MaterialParameters{m.baseColorFactor, m.metallicFactor, m.roughnessFactor, m.emissiveFactor};
}

void RenderScene::setVisible(InstanceId id, bool visible) {
  Impl& d = *impl_;
  const size_t i = d.find(id, "setVisible");
  d.hidden[i] = !visible;
  if (d.gpu) d.gpu->setVisible(i, visible);
}

bool RenderScene::visible(InstanceId id) const { return !impl_->hidden[impl_->find(id, "visible")]; }

std::vector<InstanceId> RenderScene::instances() const {
  std::vector<InstanceId> out;
  out.reserve(impl_->ids.size());
  for (uint64_t id : impl_->ids) out.push_back(InstanceId{id});
  return out;
}

bool RenderScene::contains(InstanceId id) const { return impl_->indexOf.count(id.value) != 0; }
size_t RenderScene::primitiveIndex(InstanceId id) const { return impl_->find(id, "primitiveIndex"); }

InstanceId RenderScene::instanceAt(size_t primitive) const {
  if (primitive >= impl_->ids.size())
    throw RuntimeError(impl_->where() + ": RenderScene::instanceAt: no primitive " + std::to_string(primitive) +
                       " (the scene has " + std::to_string(impl_->ids.size()) + ")");
  return InstanceId{impl_->ids[primitive]};
}

uint64_t RenderScene::instancesVersion() const { return impl_->instancesVersion; }

}  // namespace rgraph
