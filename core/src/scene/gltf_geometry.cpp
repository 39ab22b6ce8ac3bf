// glTF geometry: accessors (checked against their buffer views and buffers
// before any byte is read), sparse substitution, indices, and meshes built
// from primitives (normals, tangents, UV sets). See gltf_internal.h.
#include <algorithm>
#include <climits>
#include <cstdint>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gltf_internal.h"
#include "rgraph/error.h"

namespace rgraph::gltf_detail {

namespace {

// Non-finite floats read as 0 (and set *nonFinite when given).
float readComponent(const unsigned char* p, int componentType, bool normalized, bool* nonFinite = nullptr) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      if (std::isfinite(f)) return f;
      if (nonFinite) *nonFinite = true;
      return 0.0f;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v = *p;
      return normalized ? float(v) / 255.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? float(double(v) / 4294967295.0) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default: return 0.0f;
  }
}

uint32_t readIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0;
  }
}

const char* componentTypeName(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return "unknown";
  }
}

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "unknown mode";
  }
}

}  // namespace

// A strip's or fan's vertex sequence as a triangle list, with the winding the
// glTF specification gives ("3.7.2.1 Topology Types"): strip triangle i is
// (v[i], v[i+1], v[i+2]) for even i and (v[i], v[i+2], v[i+1]) for odd i, so
// every triangle faces the way the first does; fan triangle i is
// (v[i+1], v[i+2], v[0]), the same winding as (v[0], v[i+1], v[i+2]).
// Triangles that repeat a vertex (zero area, as strips joined by repeated
// indices have) are dropped: they draw nothing and have no normal.
std::vector<uint32_t> trianglesFrom(int mode, const std::vector<uint32_t>& v) {
  std::vector<uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve((v.size() - 2) * 3);
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    uint32_t a, b, c;
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      a = v[i + 1], b = v[i + 2], c = v[0];
    } else if (i % 2 == 0) {
      a = v[i], b = v[i + 1], c = v[i + 2];
    } else {
      a = v[i], b = v[i + 2], c = v[i + 1];
    }
    if (a == b || b == c || a == c) continue;
    out.insert(out.end(), {a, b, c});
  }
  return out;
}

// Checks accessor `index` against its buffer view and buffer; `what` names it in errors.
AccessorInfo GltfLoader::checkAccessor(int index, const std::string& what, std::initializer_list<int> types,
                           std::initializer_list<int> componentTypes) const {
  if (index < 0 || size_t(index) >= model_.accessors.size())
    fail(what + ": accessor " + std::to_string(index) + " does not exist (" + std::to_string(model_.accessors.size()) +
         " accessors)");
  const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
  const std::string name = what + " (accessor " + std::to_string(index) + ")";
  if (std::find(types.begin(), types.end(), acc.type) == types.end())
    fail(name + ": unexpected type " + std::to_string(acc.type));
  if (std::find(componentTypes.begin(), componentTypes.end(), acc.componentType) == componentTypes.end())
    fail(name + ": unexpected component type " + componentTypeName(acc.componentType));
  AccessorInfo info;
  info.componentType = acc.componentType;
  info.components = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
  info.normalized = acc.normalized;
  info.count = acc.count;
  const int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
  if (info.components <= 0 || compSize <= 0) fail(name + ": invalid type");
  const size_t elemSize = size_t(info.components) * size_t(compSize);
  if (acc.count > kMaxElements) fail(name + ": count " + std::to_string(acc.count) + " is too large");

  if (acc.bufferView < 0) {
    if (acc.count > kMaxUnbackedElements) fail(name + ": count " + std::to_string(acc.count) + " is too large");
    info.stride = elemSize;
    return info;
  }
  const std::string bvDesc = checkBufferView(acc.bufferView, name);
  const tinygltf::BufferView& bv = model_.bufferViews[size_t(acc.bufferView)];
  info.stride = bv.byteStride ? bv.byteStride : elemSize;
  if (bv.byteStride != 0 && bv.byteStride < elemSize)
    fail(name + ": byteStride " + std::to_string(bv.byteStride) + " is smaller than the element size " + std::to_string(elemSize));
  if (bv.byteStride > 252) fail(name + ": byteStride " + std::to_string(bv.byteStride) + " exceeds 252");
  if (acc.byteOffset > bv.byteLength)
    fail(name + ": byteOffset " + std::to_string(acc.byteOffset) + " lies beyond " + bvDesc + " (" + std::to_string(bv.byteLength) +
         " bytes)");
  if (acc.count > 0) {
    // No overflow: byteOffset <= byteLength <= buffer size, count <= 2^26, stride <= 252.
    const uint64_t need = uint64_t(acc.byteOffset) + uint64_t(info.stride) * uint64_t(acc.count - 1) + uint64_t(elemSize);
    if (need > bv.byteLength)
      fail(name + ": " + std::to_string(acc.count) + " elements at byteOffset " + std::to_string(acc.byteOffset) +
           " with stride " + std::to_string(info.stride) + " need " + std::to_string(need) + " bytes but " + bvDesc + " has " +
           std::to_string(bv.byteLength));
  }
  const tinygltf::Buffer& buf = model_.buffers[size_t(bv.buffer)];
  info.data = buf.data.data() + bv.byteOffset + acc.byteOffset;
  return info;
}

// Checks buffer view `index` lies inside its buffer; returns a description for messages.
std::string GltfLoader::checkBufferView(int index, const std::string& what) const {
  if (index < 0 || size_t(index) >= model_.bufferViews.size())
    fail(what + ": buffer view " + std::to_string(index) + " does not exist (" + std::to_string(model_.bufferViews.size()) +
         " buffer views)");
  const tinygltf::BufferView& bv = model_.bufferViews[size_t(index)];
  const std::string desc = "buffer view " + std::to_string(index);
  if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
    fail(what + ": " + desc + " refers to buffer " + std::to_string(bv.buffer) + ", which does not exist");
  const size_t size = model_.buffers[size_t(bv.buffer)].data.size();
  if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
    fail(what + ": " + desc + " (byteOffset " + std::to_string(bv.byteOffset) + ", byteLength " + std::to_string(bv.byteLength) +
         ") exceeds buffer " + std::to_string(bv.buffer) + " of " + std::to_string(size) + " bytes");
  return desc;
}

// Reads a numeric accessor as floats (count * components), applying sparse substitution.
std::vector<float> GltfLoader::readFloats(int index, const std::string& what, std::initializer_list<int> types,
                              std::initializer_list<int> componentTypes, size_t* firstNonFinite) const {
  const AccessorInfo info = checkAccessor(index, what, types, componentTypes);
  const size_t nc = size_t(info.components);
  const int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(info.componentType));
  std::vector<float> out(info.count * nc, 0.0f);
  if (info.data) {
    for (size_t i = 0; i < info.count; ++i) {
      const unsigned char* e = info.data + i * info.stride;
      bool bad = false;
      for (size_t c = 0; c < nc; ++c)
        out[i * nc + c] = readComponent(e + c * size_t(compSize), info.componentType, info.normalized, &bad);
      if (bad && firstNonFinite && *firstNonFinite == SIZE_MAX) *firstNonFinite = i;
    }
  }
  const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
  if (acc.sparse.isSparse) applySparse(acc, what + " (accessor " + std::to_string(index) + ")", info, out, firstNonFinite);
  return out;
}

void GltfLoader::applySparse(const tinygltf::Accessor& acc, const std::string& name, const AccessorInfo& info, std::vector<float>& out,
                             size_t* firstNonFinite) const {
  const int n = acc.sparse.count;
  if (n <= 0 || size_t(n) > info.count) fail(name + ": sparse count " + std::to_string(n) + " out of range");
  const int it = acc.sparse.indices.componentType;
  if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(name + ": sparse indices have component type " + componentTypeName(it));
  const size_t is = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(it)));
  const size_t cs = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(info.componentType)));
  const size_t es = cs * size_t(info.components);
  auto region = [&](int bvIndex, int offset, size_t bytes, const char* what) -> const unsigned char* {
    const std::string desc = checkBufferView(bvIndex, name + " sparse " + what);
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(bvIndex)];
    if (offset < 0 || size_t(offset) > bv.byteLength || bytes > bv.byteLength - size_t(offset))
      fail(name + ": sparse " + what + " exceed " + desc);
    return model_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + size_t(offset);
  };
  const unsigned char* idx = region(acc.sparse.indices.bufferView, acc.sparse.indices.byteOffset, is * size_t(n), "indices");
  const unsigned char* val = region(acc.sparse.values.bufferView, acc.sparse.values.byteOffset, es * size_t(n), "values");
  const size_t nc = size_t(info.components);
  for (int i = 0; i < n; ++i) {
    const uint32_t target = readIndex(idx + size_t(i) * is, it);
    if (target >= info.count)
      fail(name + ": sparse index " + std::to_string(target) + " >= count " + std::to_string(info.count));
    bool bad = false;
    for (size_t c = 0; c < nc; ++c)
      out[size_t(target) * nc + c] = readComponent(val + size_t(i) * es + c * cs, info.componentType, info.normalized, &bad);
    if (bad && firstNonFinite) *firstNonFinite = std::min(*firstNonFinite, size_t(target));
  }
}

std::vector<uint32_t> GltfLoader::readIndices(int index, const std::string& what, size_t vertexCount) const {
  const AccessorInfo info = checkAccessor(
      index, what, {TINYGLTF_TYPE_SCALAR},
      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
  std::vector<uint32_t> out(info.count, 0);
  if (info.data)
    for (size_t i = 0; i < info.count; ++i) out[i] = readIndex(info.data + i * info.stride, info.componentType);
  const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
  if (acc.sparse.isSparse) {
    std::vector<float> tmp(out.begin(), out.end());  // exact for indices < 2^24; sparse indices are rare
    applySparse(acc, what + " (accessor " + std::to_string(index) + ")", info, tmp);
    for (size_t i = 0; i < out.size(); ++i) out[i] = uint32_t(tmp[i]);
  }
  for (size_t i = 0; i < out.size(); ++i)
    if (out[i] >= vertexCount)
      fail(what + " (accessor " + std::to_string(index) + "): index " + std::to_string(out[i]) + " at position " + std::to_string(i) +
           " is out of range (" + std::to_string(vertexCount) + " vertices)");
  return out;
}

// The component types core glTF and KHR_mesh_quantization allow together
// (the extension's table; it only adds to core): a combination outside it is
// refused at the attribute's JSON pointer. The file need not list the
// extension: what it asks for is read the same either way.
void GltfLoader::checkAttributeTypes(const tinygltf::Primitive& prim, const std::string& pointer) {
  constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE, UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                S = TINYGLTF_COMPONENT_TYPE_SHORT, US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  struct Rule {
    const char* attribute;
    std::vector<int> any;         // normalized or not
    std::vector<int> normalized;  // normalized only
    const char* allowed;
  };
  static const Rule rules[] = {
      {"POSITION", {F, B, UB, S, US}, {}, "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"},
      {"NORMAL", {F}, {B, S}, "FLOAT, or normalized BYTE or SHORT"},
      {"TANGENT", {F}, {B, S}, "FLOAT, or normalized BYTE or SHORT"},
      {"TEXCOORD_0", {F, B, UB, S, US}, {}, "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"},
      {"TEXCOORD_1", {F, B, UB, S, US}, {}, "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"},
      {"COLOR_0", {F}, {UB, US}, "FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT"},
  };
  for (const Rule& r : rules) {
    auto it = prim.attributes.find(r.attribute);
    if (it == prim.attributes.end() || it->second < 0 || size_t(it->second) >= model_.accessors.size()) continue;
    const tinygltf::Accessor& acc = model_.accessors[size_t(it->second)];
    const int t = acc.componentType;
    const bool ok = std::find(r.any.begin(), r.any.end(), t) != r.any.end() ||
                    (acc.normalized && std::find(r.normalized.begin(), r.normalized.end(), t) != r.normalized.end());
    if (!ok)
      failAt(pointer + "/attributes/" + r.attribute,
             "accessor " + std::to_string(it->second) + " is " + (acc.normalized ? "normalized " : "") + componentTypeName(t) +
                 (acc.normalized || t == F ? "" : " (not normalized)") + "; " + r.attribute + " may be " + r.allowed +
                 " (glTF with KHR_mesh_quantization)");
  }
}

// The scene mesh for glTF mesh `mi` primitive `pi`; -1 when skipped.
int GltfLoader::sceneMesh(int mi, size_t pi) {
  const auto key = std::make_pair(mi, pi);
  if (auto it = meshMap_.find(key); it != meshMap_.end()) return it->second;
  int id = -1;
  const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
  const tinygltf::Primitive& prim = gm.primitives[pi];
  const std::string what = "mesh " + std::to_string(mi) + (gm.name.empty() ? "" : " ('" + gm.name + "')") + " primitive " +
                           std::to_string(pi);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    warn(what + ": mode " + std::to_string(mode) + " (" + modeName(mode) + ") is not drawn: only triangles are; skipped");
  } else if (prim.attributes.find("POSITION") == prim.attributes.end()) {
    warn(what + ": no POSITION attribute; skipped");
  } else {
    const std::string pointer = "/meshes/" + std::to_string(mi) + "/primitives/" + std::to_string(pi);
    MeshData mesh = buildMesh(prim, what, pointer);
    if (mesh.indices.empty()) {
      warn(what + ": no triangles; skipped");
    } else {
      id = int(scene_.meshes.size());
      scene_.meshes.push_back(std::move(mesh));
      primMaterial_.push_back(resolvedMaterial_);
    }
  }
  meshMap_.emplace(key, id);
  return id;
}

MeshData GltfLoader::buildMesh(const tinygltf::Primitive& prim, const std::string& what, const std::string& pointer) {
  const std::initializer_list<int> quantized = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
  checkAttributeTypes(prim, pointer);
  MeshData mesh;
  mesh.name = what;

  // Material first: it decides whether tangents are needed.
  if (prim.material >= 0) {
    if (size_t(prim.material) >= model_.materials.size())
      fail(what + ": material " + std::to_string(prim.material) + " does not exist (" + std::to_string(model_.materials.size()) +
           " materials)");
    resolvedMaterial_ = prim.material;
  } else {
    resolvedMaterial_ = defaultMaterial();
  }
  const Material material = scene_.materials[size_t(resolvedMaterial_)];

  auto attr = [&](const char* name) -> int {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  std::vector<float> pos = readFloats(attr("POSITION"), what + " POSITION", {TINYGLTF_TYPE_VEC3}, quantized);
  const size_t n = pos.size() / 3;
  if (n > size_t(UINT32_MAX)) fail(what + ": too many vertices");
  mesh.positions.resize(n);
  for (size_t i = 0; i < n; ++i) mesh.positions[i] = glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);

  auto readSized = [&](const char* name, int type, size_t comps, std::initializer_list<int> cts) -> std::vector<float> {
    const int a = attr(name);
    if (a < 0) return {};
    std::vector<float> v = readFloats(a, what + " " + name, {type}, cts);
    if (v.size() / comps != n)
      fail(what + " " + name + " (accessor " + std::to_string(a) + "): count " + std::to_string(v.size() / comps) +
           " differs from the POSITION count " + std::to_string(n));
    return v;
  };
  std::vector<float> nrm = readSized("NORMAL", TINYGLTF_TYPE_VEC3, 3,
                                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});
  const std::initializer_list<int> uvTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                              TINYGLTF_COMPONENT_TYPE_SHORT};
  std::vector<float> uv0 = readSized("TEXCOORD_0", TINYGLTF_TYPE_VEC2, 2, uvTypes);
  std::vector<float> uv1 = readSized("TEXCOORD_1", TINYGLTF_TYPE_VEC2, 2, uvTypes);
  std::vector<float> tan = readSized("TANGENT", TINYGLTF_TYPE_VEC4, 4,
                                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});

  if (const int a = attr("COLOR_0"); a >= 0) {
    // vec3 or vec4 (readFloats checked the accessor, so its type is one of the two).
    std::vector<float> c = readFloats(a, what + " COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4},
                                      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    const size_t comps = model_.accessors[size_t(a)].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    if (c.size() / comps != n)
      fail(what + " COLOR_0 (accessor " + std::to_string(a) + "): count " + std::to_string(c.size() / comps) +
           " differs from the POSITION count " + std::to_string(n));
    mesh.colors.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const float* v = &c[comps * i];
      mesh.colors[i] = glm::clamp(glm::vec4(v[0], v[1], v[2], comps == 4 ? v[3] : 1.0f), 0.0f, 1.0f);
    }
  }

  readSkinAttributes(prim, mesh, what, pointer);
  readMorphTargets(prim, mesh, what, pointer);

  mesh.hasUv0 = !uv0.empty();
  mesh.uv0.assign(n, glm::vec2(0.0f));
  if (!uv0.empty())
    for (size_t i = 0; i < n; ++i) mesh.uv0[i] = glm::vec2(uv0[2 * i], uv0[2 * i + 1]);
  if (!uv1.empty()) {
    mesh.uv1.resize(n);
    for (size_t i = 0; i < n; ++i) mesh.uv1[i] = glm::vec2(uv1[2 * i], uv1[2 * i + 1]);
  }

  if (prim.indices >= 0) {
    mesh.indices = readIndices(prim.indices, what + " indices", n);
  } else {
    mesh.indices.resize(n);
    for (size_t i = 0; i < n; ++i) mesh.indices[i] = uint32_t(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    mesh.indices = trianglesFrom(prim.mode, mesh.indices);
  } else if (mesh.indices.size() % 3 != 0) {
    warn(what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3; extra indices dropped");
    mesh.indices.resize(mesh.indices.size() - mesh.indices.size() % 3);
  }

  const bool wantTangents = material.hasNormalMap();
  if (!nrm.empty()) {
    mesh.normals.resize(n);
    bool fixed = false;
    for (size_t i = 0; i < n; ++i) {
      glm::vec3 v(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
      const float len = glm::length(v);
      if (len > 1e-12f) {
        mesh.normals[i] = v / len;
      } else {
        mesh.normals[i] = glm::vec3(0.0f, 0.0f, 1.0f);
        fixed = true;
      }
    }
    if (fixed) warn(what + ": zero-length normals replaced");
    if (wantTangents && !tan.empty()) {
      mesh.tangents.resize(n);
      for (size_t i = 0; i < n; ++i) {
        glm::vec3 t(tan[4 * i], tan[4 * i + 1], tan[4 * i + 2]);
        const float len = glm::length(t);
        t = len > 1e-12f ? t / len : glm::vec3(1.0f, 0.0f, 0.0f);
        mesh.tangents[i] = glm::vec4(t, tan[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
      }
    }
  } else {
    // glTF: "When normals are not specified, client implementations MUST calculate flat normals."
    computeFlatNormals(mesh);  // unwelds; file tangents (if any) would no longer line up
  }
  // Morph deltas of attributes the file does not give are meaningless:
  // computed flat normals and generated tangents stay undeformed by them.
  const bool fileTangents = !mesh.tangents.empty();
  for (MorphTarget& t : mesh.morphTargets) {
    if (nrm.empty()) t.normals.clear();
    if (!fileTangents) t.tangents.clear();
  }
  if (wantTangents && mesh.tangents.empty()) {
    const bool useUv1 = material.normalTexture.texCoord == 1 && !mesh.uv1.empty();
    if (useUv1) std::swap(mesh.uv0, mesh.uv1);
    generateTangents(mesh);
    if (useUv1) std::swap(mesh.uv0, mesh.uv1);
  }
  mesh.updateBounds();
  return mesh;
}

// EXT_mesh_gpu_instancing: one local matrix per instance, translation *
// rotation * scale from the extension's per-instance accessors (each one
// optional, all of one count). nullopt: the node has no such extension.
std::optional<std::vector<glm::mat4>> GltfLoader::nodeInstances(int nodeIndex, const tinygltf::Node& node) {
  const auto it = node.extensions.find("EXT_mesh_gpu_instancing");
  if (it == node.extensions.end()) return std::nullopt;
  const std::string ptr = "/nodes/" + std::to_string(nodeIndex) + "/extensions/EXT_mesh_gpu_instancing";
  if (!it->second.IsObject() || !it->second.Get("attributes").IsObject())
    failAt(ptr, "expected {\"attributes\": {\"TRANSLATION\" | \"ROTATION\" | \"SCALE\": accessor}}");
  const tinygltf::Value& attributes = it->second.Get("attributes");
  constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE, UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                S = TINYGLTF_COMPONENT_TYPE_SHORT, US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  std::optional<size_t> count;
  auto read = [&](const char* name, int type, size_t comps, std::initializer_list<int> cts) -> std::vector<float> {
    const tinygltf::Value& v = attributes.Get(name);
    if (v.Type() == tinygltf::NULL_TYPE) return {};
    const std::string ap = ptr + "/attributes/" + name;
    if (!v.IsNumber() || v.GetNumberAsDouble() < 0.0 || v.GetNumberAsDouble() >= double(INT_MAX))
      failAt(ap, "expected an accessor index");
    std::vector<float> out = readFloats(int(v.GetNumberAsDouble()), "node " + std::to_string(nodeIndex) + " EXT_mesh_gpu_instancing " + name, {type}, cts);
    const size_t n = out.size() / comps;
    if (count && *count != n)
      failAt(ap, "has " + std::to_string(n) + " instances, another attribute " + std::to_string(*count));
    count = n;
    return out;
  };
  const std::vector<float> t = read("TRANSLATION", TINYGLTF_TYPE_VEC3, 3, {F, B, UB, S, US});
  const std::vector<float> r = read("ROTATION", TINYGLTF_TYPE_VEC4, 4, {F, B, S});
  const std::vector<float> s = read("SCALE", TINYGLTF_TYPE_VEC3, 3, {F, B, UB, S, US});
  if (!count) failAt(ptr + "/attributes", "names none of TRANSLATION, ROTATION and SCALE");
  if (*count > kMaxInstances)
    failAt(ptr, std::to_string(*count) + " instances: at most " + std::to_string(kMaxInstances) + " are drawn");
  std::vector<glm::mat4> instances(*count, glm::mat4(1.0f));
  for (size_t i = 0; i < *count; ++i) {
    glm::mat4& m = instances[i];
    if (!t.empty()) m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
    if (!r.empty()) {
      const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);  // w, x, y, z
      const float len = glm::length(q);
      if (len > 0.0f) m = m * glm::mat4_cast(q / len);
    }
    if (!s.empty()) m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
  }
  return instances;
}

}  // namespace rgraph::gltf_detail
