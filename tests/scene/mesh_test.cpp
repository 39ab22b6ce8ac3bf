// Procedural meshes, normals and tangents.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "rgraph/error.h"
#include "rgraph/scene.h"

using namespace rgraph;

namespace {

// Every triangle's geometric normal points away from the origin (closed convex
// meshes centred at the origin) and agrees with its vertex normals.
void expectOutwardWinding(const MeshData& m, bool checkVertexNormals = true) {
  size_t checked = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) < 1e-9f) continue;  // degenerate
    const glm::vec3 centre = (a + b + c) / 3.0f;
    ASSERT_GT(glm::dot(n, centre), 0.0f) << m.name << " triangle " << t;
    if (checkVertexNormals) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_GT(glm::dot(glm::normalize(n), m.normals[m.indices[3 * t + k]]), 0.0f) << m.name << " triangle " << t;
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

void expectOrthonormalTangents(const MeshData& m) {
  ASSERT_EQ(m.tangents.size(), m.vertexCount());
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    const glm::vec3 t(m.tangents[i]);
    ASSERT_NEAR(glm::length(t), 1.0f, 1e-4f) << m.name << " vertex " << i;
    ASSERT_NEAR(glm::dot(t, m.normals[i]), 0.0f, 1e-4f) << m.name << " vertex " << i;
    ASSERT_TRUE(m.tangents[i].w == 1.0f || m.tangents[i].w == -1.0f);
  }
}

}  // namespace

TEST(Mesh, IcosphereIsClosedAndOutward) {
  for (int sub = 0; sub <= 4; ++sub) {
    SCOPED_TRACE(sub);
    const MeshData m = makeIcosphere(sub);
    std::string why;
    ASSERT_TRUE(m.valid(&why)) << why;
    size_t pow4 = 1;
    for (int i = 0; i < sub; ++i) pow4 *= 4;
    EXPECT_EQ(m.triangleCount(), 20 * pow4);
    EXPECT_EQ(m.vertexCount(), 10 * pow4 + 2);  // shared vertices: no seams, no duplicates

    // Edge-manifold with consistent orientation: each directed edge appears once and
    // its reverse appears once, so every undirected edge is used by exactly two triangles.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < m.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
      ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeated";
      ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "edge " << edge.first << "-" << edge.second << " is open";
    }
    const size_t edges = directed.size() / 2;
    EXPECT_EQ(long(m.vertexCount()) - long(edges) + long(m.triangleCount()), 2);  // Euler characteristic of a sphere
    // No two vertices at the same place.
    std::set<std::tuple<long, long, long>> seen;
    for (const glm::vec3& p : m.positions) {
      ASSERT_NEAR(glm::length(p), 1.0f, 1e-5f);
      ASSERT_TRUE(seen.insert({std::lround(p.x * 1e5), std::lround(p.y * 1e5), std::lround(p.z * 1e5)}).second);
    }
    expectOutwardWinding(m);
  }
  EXPECT_THROW(makeIcosphere(-1), RuntimeError);
  EXPECT_THROW(makeIcosphere(8), RuntimeError);
}

// The inscribed icosphere is smaller than the sphere it approximates: a light volume
// must be scaled by at least 1/min(distance of a face from the centre) to cover the radius.
TEST(Mesh, IcosphereFaceDistance) {
  const MeshData m = makeIcosphere(2);
  float minDist = 1.0f;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
    minDist = std::min(minDist, glm::dot(glm::normalize(glm::cross(b - a, c - a)), a));
  }
  EXPECT_GT(minDist, 0.95f);
  EXPECT_LT(minDist, 1.0f);
}

TEST(Mesh, CubeHas24VerticesAndFaceNormals) {
  const MeshData m = makeCube(1.0f);
  EXPECT_EQ(m.vertexCount(), 24u);
  EXPECT_EQ(m.triangleCount(), 12u);
  EXPECT_TRUE(m.valid());
  std::set<std::tuple<int, int, int>> normals;
  for (const glm::vec3& n : m.normals) normals.insert({int(n.x), int(n.y), int(n.z)});
  EXPECT_EQ(normals.size(), 6u);
  expectOutwardWinding(m);
  EXPECT_EQ(m.bounds.min, glm::vec3(-1.0f));
  EXPECT_EQ(m.bounds.max, glm::vec3(1.0f));
}

TEST(Mesh, SphereAndPlane) {
  const MeshData s = makeUvSphere(2.0f, 16, 8);
  EXPECT_TRUE(s.valid());
  EXPECT_EQ(s.triangleCount(), size_t(16 * 8 * 2 - 2 * 16));
  for (size_t i = 0; i < s.vertexCount(); ++i) {
    ASSERT_NEAR(glm::length(s.positions[i]), 2.0f, 1e-5f);
    ASSERT_NEAR(glm::distance(s.normals[i], s.positions[i] / 2.0f), 0.0f, 1e-5f);
  }
  expectOutwardWinding(s);

  const MeshData p = makePlane(2.0f, 3.0f);
  EXPECT_EQ(p.triangleCount(), 2u);
  for (size_t t = 0; t < p.triangleCount(); ++t) {
    const glm::vec3 a = p.positions[p.indices[3 * t]], b = p.positions[p.indices[3 * t + 1]], c = p.positions[p.indices[3 * t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);  // CCW seen from above
  }
  EXPECT_EQ(p.bounds.max, glm::vec3(2, 0, 3));
}

TEST(Mesh, GeneratedTangentsAreOrthogonalUnitVectors) {
  for (MeshData m : {makeCube(), makeUvSphere(1.0f, 24, 12), makePlane(), makeIcosphere(1)}) {
    SCOPED_TRACE(m.name);
    generateTangents(m);  // the icosphere has no UVs: arbitrary orthogonal tangents
    expectOrthonormalTangents(m);
  }
  // On the cube's +Z face (u along +X, v downwards) the tangent is +X and the bitangent +Y.
  MeshData cube = makeCube();
  generateTangents(cube);
  for (size_t i = 0; i < cube.vertexCount(); ++i) {
    if (cube.normals[i] != glm::vec3(0, 0, 1)) continue;
    EXPECT_NEAR(glm::distance(glm::vec3(cube.tangents[i]), glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_EQ(cube.tangents[i].w, 1.0f);
  }
}

TEST(Mesh, MirroredUvsFlipHandedness) {
  MeshData m = makePlane();
  MeshData mirrored = m;
  for (glm::vec2& uv : mirrored.uv0) uv.x = 1.0f - uv.x;
  generateTangents(m);
  generateTangents(mirrored);
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    EXPECT_EQ(m.tangents[i].w, -mirrored.tangents[i].w);
    EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), glm::vec3(mirrored.tangents[i])), -1.0f, 1e-5f);
  }
}

TEST(Mesh, GramSchmidtAgainstTiltedNormals) {
  MeshData m = makePlane();
  for (glm::vec3& n : m.normals) n = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  generateTangents(m);
  expectOrthonormalTangents(m);
}

TEST(Mesh, DegenerateUvsStillGiveTangents) {
  MeshData m = makeCube();
  for (glm::vec2& uv : m.uv0) uv = glm::vec2(0.5f);
  generateTangents(m);
  expectOrthonormalTangents(m);
}

TEST(Mesh, SmoothAndFlatNormals) {
  MeshData ico = makeIcosphere(3);
  ico.normals.assign(ico.vertexCount(), glm::vec3(0.0f));
  computeSmoothNormals(ico);
  for (size_t i = 0; i < ico.vertexCount(); ++i) ASSERT_GT(glm::dot(ico.normals[i], ico.positions[i]), 0.99f);

  MeshData flat = makeIcosphere(1);
  computeFlatNormals(flat);
  EXPECT_EQ(flat.vertexCount(), flat.triangleCount() * 3);
  EXPECT_TRUE(flat.valid());
  expectOutwardWinding(flat);
  for (size_t t = 0; t < flat.triangleCount(); ++t) {
    EXPECT_EQ(flat.normals[3 * t], flat.normals[3 * t + 1]);
    EXPECT_EQ(flat.normals[3 * t], flat.normals[3 * t + 2]);
  }
}

TEST(Mesh, ValidAndInterleaved) {
  MeshData m = makeCube();
  generateTangents(m);
  const std::vector<MeshVertex> v = m.interleaved();
  ASSERT_EQ(v.size(), m.vertexCount());
  EXPECT_EQ(v[5].position, m.positions[5]);
  EXPECT_EQ(v[5].normal, m.normals[5]);
  EXPECT_EQ(v[5].uv, m.uv0[5]);
  EXPECT_EQ(v[5].tangent, m.tangents[5]);
  m.indices.push_back(99);
  std::string why;
  EXPECT_FALSE(m.valid(&why));
  EXPECT_NE(why.find("multiple of 3"), std::string::npos) << why;
  m.indices.push_back(0);
  m.indices.push_back(1);
  EXPECT_FALSE(m.valid(&why));
  EXPECT_NE(why.find("99"), std::string::npos) << why;
}

TEST(Mesh, BoundsTransform) {
  Bounds b;
  EXPECT_TRUE(b.empty());
  b.expand(glm::vec3(-1, -2, -3));
  b.expand(glm::vec3(1, 2, 3));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.center(), glm::vec3(0));
  EXPECT_EQ(b.size(), glm::vec3(2, 4, 6));
  glm::mat4 m(1.0f);
  m[3] = glm::vec4(10, 0, 0, 1);
  const Bounds t = b.transformed(m);
  EXPECT_EQ(t.min, glm::vec3(9, -2, -3));
  EXPECT_EQ(t.max, glm::vec3(11, 2, 3));
  EXPECT_TRUE(Bounds{}.transformed(m).empty());
}
