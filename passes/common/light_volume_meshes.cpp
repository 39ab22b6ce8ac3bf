#include "rgraph/passes/light_volume_meshes.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass.h"

namespace rgraph::light_volumes {

MeshData makeSpotVolume(int segments) {
  if (segments < 3 || segments > 1024)
    throw RuntimeError("makeSpotVolume: segments must be in 3..1024, got " + std::to_string(segments));
  MeshData m;
  m.name = "spot-volume";
  const uint32_t n = uint32_t(segments);
  // Vertices: the apex (0), ring 1 at z = 1 (1..n), ring 2 at z = 2 (n+1..2n),
  // the cap's centre (2n+1). Rings on the unit circle.
  m.positions.push_back(glm::vec3(0.0f));
  for (int z = 1; z <= 2; ++z)
    for (uint32_t i = 0; i < n; ++i) {
      const float a = 2.0f * glm::pi<float>() * float(i) / float(n);
      m.positions.push_back(glm::vec3(std::cos(a), std::sin(a), float(z)));
    }
  m.positions.push_back(glm::vec3(0.0f, 0.0f, 2.0f));
  const uint32_t apex = 0, cap = 2 * n + 1;
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    const uint32_t a1 = 1 + i, b1 = 1 + j, a2 = 1 + n + i, b2 = 1 + n + j;
    // Counter-clockwise seen from outside: the ring runs counter-clockwise
    // about +z, so the cone's side and the cylinder's face outward with
    // (apex, b1, a1) and (a1, b1, b2), (a1, b2, a2); the cap faces +z.
    m.indices.insert(m.indices.end(), {apex, b1, a1, a1, b1, b2, a1, b2, a2, a2, b2, cap});
  }
  m.normals.assign(m.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  m.uv0.assign(m.positions.size(), glm::vec2(0.0f));
  m.updateBounds();
  return m;
}

Meshes::Meshes() {
  // Light volumes: subdivision 1 (80 triangles, scaled by 1/inradius = 1.07 to
  // enclose the sphere). On llvmpipe, 1280 triangles (level 3) per light cost
  // 2-3x more in setup than the 14% extra area costs in fragments, which
  // light_volume.frag rejects by distance anyway (bench/render_methods.cpp).
  const MeshData sphere = makeIcosphere(1);
  float inradius = 1.0f;  // smallest distance from the centre to a face plane
  for (size_t t = 0; t + 2 < sphere.indices.size(); t += 3) {
    const glm::vec3 a = sphere.positions[sphere.indices[t]], b = sphere.positions[sphere.indices[t + 1]],
                    c = sphere.positions[sphere.indices[t + 2]];
    inradius = std::min(inradius, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
  }
  icosphereScale_ = 1.0f / inradius;
  icosphere_ = upload(sphere);
  cube_ = upload(makeCube(1.0f));
  // Spot volumes: 16 sides, scaled by 1/cos(pi/16) (4%) so that the flat
  // sides enclose the round cone.
  constexpr int kSpotSides = 16;
  spotVolume_ = upload(makeSpotVolume(kSpotSides));
  spotVolumeScale_ = 1.0f / std::cos(glm::pi<float>() / kSpotSides);
}

const Meshes& Meshes::of(GpuScene& scene) { return scene.extension<Meshes>(); }

Meshes::Mesh Meshes::upload(const MeshData& mesh) {
  Mesh g;
  g.vertices = gl::createBuffer();
  g.indices = gl::createBuffer();
  glNamedBufferStorage(g.vertices.id(), static_cast<GLsizeiptr>(std::max<size_t>(mesh.positions.size(), 1) * sizeof(glm::vec3)),
                       mesh.positions.empty() ? nullptr : mesh.positions.data(), 0);
  glNamedBufferStorage(g.indices.id(), static_cast<GLsizeiptr>(std::max<size_t>(mesh.indices.size(), 1) * sizeof(uint32_t)),
                       mesh.indices.empty() ? nullptr : mesh.indices.data(), 0);
  g.indexCount = static_cast<uint32_t>(mesh.indices.size());
  g.vao = gl::createVertexArray();
  const GLuint vao = g.vao.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(vao, g.indices.id());
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  return g;
}

void Meshes::draw(const Mesh& mesh, GlBindings* record, uint32_t instances) {
  if (instances == 0) return;
  glBindVertexArray(mesh.vao.id());
  glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(mesh.indexCount), GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(instances));
  glBindVertexArray(0);
  if (record) record->vertexArray = 0;
}

void Meshes::drawIcosphere(GlBindings* record, uint32_t instances) const { draw(icosphere_, record, instances); }
void Meshes::drawSpotVolume(GlBindings* record, uint32_t instances) const { draw(spotVolume_, record, instances); }
void Meshes::drawCube(GlBindings* record, uint32_t instances) const { draw(cube_, record, instances); }

}  // namespace rgraph::light_volumes
