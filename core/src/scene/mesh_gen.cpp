// Procedural meshes and per-vertex attribute generation (normals, tangents).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <glm/gtc/constants.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

glm::vec3 anyOrthogonal(const glm::vec3& n) {
  glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::vec3 t = glm::cross(a, n);
  float len = glm::length(t);
  return len > 0.0f ? t / len : glm::vec3(1, 0, 0);
}

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
  float len = glm::length(v);
  return (len > 1e-20f && std::isfinite(len)) ? v / len : fallback;
}

}  // namespace

// ---------------------------------------------------------------- normals and tangents

void computeSmoothNormals(MeshData& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<glm::vec3> acc(n, glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    if (i0 >= n || i1 >= n || i2 >= n) continue;
    glm::vec3 fn = glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]);
    acc[i0] += fn;
    acc[i1] += fn;
    acc[i2] += fn;
  }
  mesh.normals.resize(n);
  for (size_t i = 0; i < n; ++i) mesh.normals[i] = safeNormalize(acc[i], glm::vec3(0.0f, 0.0f, 1.0f));
}

void computeFlatNormals(MeshData& mesh) {
  const size_t n = mesh.positions.size();
  const size_t triCount = mesh.indices.size() / 3;
  MeshData out;
  out.name = mesh.name;
  out.hasUv0 = mesh.hasUv0;
  out.positions.reserve(triCount * 3);
  out.normals.reserve(triCount * 3);
  out.uv0.reserve(triCount * 3);
  const bool uv0 = mesh.uv0.size() == n, uv1 = !mesh.uv1.empty() && mesh.uv1.size() == n;
  const bool tan = !mesh.tangents.empty() && mesh.tangents.size() == n;
  const bool colors = !mesh.colors.empty() && mesh.colors.size() == n;
  // Skin influences and morph deltas follow their vertices.
  out.influences.resize(mesh.influences.size());
  out.morphTargets.resize(mesh.morphTargets.size());
  auto carry = [n](auto& to, const auto& from, uint32_t i) {
    if (from.size() == n) to.push_back(from[i]);
  };
  for (size_t t = 0; t < triCount; ++t) {
    uint32_t idx[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
    if (idx[0] >= n || idx[1] >= n || idx[2] >= n) continue;
    glm::vec3 fn = safeNormalize(glm::cross(mesh.positions[idx[1]] - mesh.positions[idx[0]],
                                            mesh.positions[idx[2]] - mesh.positions[idx[0]]),
                                 glm::vec3(0.0f, 0.0f, 1.0f));
    for (uint32_t i : idx) {
      out.indices.push_back(uint32_t(out.positions.size()));
      out.positions.push_back(mesh.positions[i]);
      out.normals.push_back(fn);
      out.uv0.push_back(uv0 ? mesh.uv0[i] : glm::vec2(0.0f));
      if (uv1) out.uv1.push_back(mesh.uv1[i]);
      if (tan) out.tangents.push_back(mesh.tangents[i]);
      if (colors) out.colors.push_back(mesh.colors[i]);
      for (size_t k = 0; k < mesh.influences.size(); ++k) {
        carry(out.influences[k].joints, mesh.influences[k].joints, i);
        carry(out.influences[k].weights, mesh.influences[k].weights, i);
      }
      for (size_t k = 0; k < mesh.morphTargets.size(); ++k) {
        carry(out.morphTargets[k].positions, mesh.morphTargets[k].positions, i);
        carry(out.morphTargets[k].normals, mesh.morphTargets[k].normals, i);
        carry(out.morphTargets[k].tangents, mesh.morphTargets[k].tangents, i);
      }
    }
  }
  out.bounds = mesh.bounds;
  mesh = std::move(out);
}

// Lengyel's per-triangle accumulation. glTF's UV origin is the image's top-left
// corner (v grows downwards) while normal maps store +Y = "up in the image", so
// the bitangent cross(N, T) * w must point along -dP/dv: that decides w.
void generateTangents(MeshData& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<glm::vec3> tan1(n, glm::vec3(0.0f)), tan2(n, glm::vec3(0.0f));
  const bool haveUv = mesh.uv0.size() == n;
  if (haveUv) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
      if (i0 >= n || i1 >= n || i2 >= n) continue;
      const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
      const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
      const glm::vec2 d1 = mesh.uv0[i1] - mesh.uv0[i0];
      const glm::vec2 d2 = mesh.uv0[i2] - mesh.uv0[i0];
      const float det = d1.x * d2.y - d2.x * d1.y;
      if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) continue;
      const float r = 1.0f / det;
      const glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;  // dP/du
      const glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;  // dP/dv
      if (!std::isfinite(sdir.x + sdir.y + sdir.z + tdir.x + tdir.y + tdir.z)) continue;
      for (uint32_t i : {i0, i1, i2}) {
        tan1[i] += sdir;
        tan2[i] += tdir;
      }
    }
  }
  mesh.tangents.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 nrm = i < mesh.normals.size() ? safeNormalize(mesh.normals[i], glm::vec3(0, 0, 1)) : glm::vec3(0, 0, 1);
    glm::vec3 t = tan1[i] - nrm * glm::dot(nrm, tan1[i]);  // Gram-Schmidt
    float len = glm::length(t);
    glm::vec3 tu;
    if (len > 1e-12f * std::max(1.0f, glm::length(tan1[i])) && std::isfinite(len)) {
      tu = t / len;
    } else {
      // No u gradient: derive it from the v gradient if there is one, else anything orthogonal.
      glm::vec3 b = tan2[i] - nrm * glm::dot(nrm, tan2[i]);
      tu = glm::length(b) > 1e-20f ? glm::normalize(glm::cross(-b, nrm)) : anyOrthogonal(nrm);
    }
    const float w = glm::dot(glm::cross(nrm, tu), tan2[i]) > 0.0f ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(tu, w);
  }
}

// ---------------------------------------------------------------- procedural meshes

MeshData makeCube(float h) {
  MeshData m;
  m.name = "cube";
  m.hasUv0 = true;
  struct Face {
    glm::vec3 n, r, u;  // normal, right, up; cross(r, u) == n
  };
  const Face faces[6] = {
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},  {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
  };
  for (const Face& f : faces) {
    const uint32_t base = uint32_t(m.positions.size());
    const glm::vec3 c = f.n * h;
    const glm::vec3 corners[4] = {c - f.r * h - f.u * h, c + f.r * h - f.u * h, c + f.r * h + f.u * h, c - f.r * h + f.u * h};
    const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};  // glTF: v = 0 at the top
    for (int i = 0; i < 4; ++i) {
      m.positions.push_back(corners[i]);
      m.normals.push_back(f.n);
      m.uv0.push_back(uvs[i]);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
  m.updateBounds();
  return m;
}

MeshData makeUvSphere(float radius, int segments, int rings) {
  segments = std::max(segments, 3);
  rings = std::max(rings, 2);
  MeshData m;
  m.name = "sphere";
  m.hasUv0 = true;
  const float pi = glm::pi<float>();
  for (int i = 0; i <= rings; ++i) {
    const float theta = pi * float(i) / float(rings);  // 0 at +Y
    for (int j = 0; j <= segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);  // 0 at +Z, growing towards +X
      glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      if (i == 0) n = glm::vec3(0, 1, 0);
      if (i == rings) n = glm::vec3(0, -1, 0);
      m.positions.push_back(n * radius);
      m.normals.push_back(n);
      m.uv0.push_back(glm::vec2(float(j) / float(segments), float(i) / float(rings)));
    }
  }
  const uint32_t row = uint32_t(segments + 1);
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + row, c = b + 1, d = a + 1;
      if (i != 0) m.indices.insert(m.indices.end(), {a, b, d});
      if (i != rings - 1) m.indices.insert(m.indices.end(), {d, b, c});
    }
  }
  m.updateBounds();
  return m;
}

MeshData makePlane(float hx, float hz, float uvScale) {
  MeshData m;
  m.name = "plane";
  m.hasUv0 = true;
  m.positions = {{-hx, 0, hz}, {hx, 0, hz}, {hx, 0, -hz}, {-hx, 0, -hz}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.uv0 = {{0, uvScale}, {uvScale, uvScale}, {uvScale, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.updateBounds();
  return m;
}

MeshData makeIcosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 7)
    throw RuntimeError("makeIcosphere: subdivisions must be in 0..7, got " + std::to_string(subdivisions));
  MeshData m;
  m.name = "icosphere";
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  std::vector<uint32_t> idx = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                               3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<uint64_t, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const uint32_t id = uint32_t(v.size());
      v.push_back(glm::normalize(v[a] + v[b]));
      mid.emplace(key, id);
      return id;
    };
    std::vector<uint32_t> next;
    next.reserve(idx.size() * 4);
    for (size_t i = 0; i < idx.size(); i += 3) {
      const uint32_t a = idx[i], b = idx[i + 1], c = idx[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    idx = std::move(next);
  }
  m.positions = v;
  m.normals = v;
  m.uv0.assign(v.size(), glm::vec2(0.0f));
  m.indices = std::move(idx);
  m.updateBounds();
  return m;
}

}  // namespace rgraph
