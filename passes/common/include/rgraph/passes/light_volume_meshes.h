// The meshes the light_volumes pass draws each light with (a closed
// icosphere per point light, a cone per spot light) and the forward pass's
// light markers (a unit cube), kept with the scene's upload
// (GpuScene::extension) so that renderers sharing one scene share them too.
// Core draws scenes; what a light volume is lives here.
#pragma once

#include <cstdint>

#include "rgraph/gl/objects.h"
#include "rgraph/scene.h"

namespace rgraph {
class GpuScene;
struct GlBindings;
}  // namespace rgraph

namespace rgraph::light_volumes {

// A closed convex mesh for spot-light volumes, before light_volume.vert bends
// it to each light's cone: a unit cone (apex at the origin, `segments` vertices
// on the unit circle at z = 1) on a unit cylinder (z = 1..2) closed by a cap
// at z = 2; outward CCW winding. The shader maps z = 1 to the distance
// r cos(outer) along the axis at radius r sin(outer), and z = 2 to r, so that
// the mesh holds the part of the light's sphere r within its cone. Normals
// are placeholders. Valid range 3..1024 (else RuntimeError).
MeshData makeSpotVolume(int segments);

// Vertex attribute 0 is the position; each draw binds its vertex array,
// draws `instances` instances and binds 0, writing both binds into `record`
// (PassContext::bindings(); nullptr: none).
class Meshes {
 public:
  Meshes();  // uploads; needs a current GL context
  // The scene's meshes, uploaded at the first call in its upload context.
  static const Meshes& of(GpuScene& scene);

  // Closed unit icosphere (subdivision 1). Its flat faces lie inside the
  // unit sphere: scaling a light's volume by radius * icosphereScale()
  // makes the mesh enclose the whole sphere.
  void drawIcosphere(GlBindings* record, uint32_t instances) const;
  float icosphereScale() const { return icosphereScale_; }
  // makeSpotVolume(16) (light_volume.vert bends it to each spot light's
  // cone); scaling its radius by spotVolumeScale() makes its flat sides
  // enclose the round cone.
  void drawSpotVolume(GlBindings* record, uint32_t instances) const;
  float spotVolumeScale() const { return spotVolumeScale_; }
  // makeCube(1): the light markers.
  void drawCube(GlBindings* record, uint32_t instances) const;

 private:
  struct Mesh {
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    uint32_t indexCount = 0;
  };
  static Mesh upload(const MeshData& mesh);
  static void draw(const Mesh& mesh, GlBindings* record, uint32_t instances);
  Mesh icosphere_, spotVolume_, cube_;
  float icosphereScale_ = 1.0f, spotVolumeScale_ = 1.0f;
};

}  // namespace rgraph::light_volumes
