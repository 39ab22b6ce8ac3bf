// Where each shadow map looks from, frame by frame: GL-free maths shared by
// the shadow_map passes (which draw the maps) and the lighting passes' shadow
// data (which sample them), so that both derive every matrix from the same
// inputs by the same function.
//
// A shadow pipeline's template pass is expanded at adapt time into one pass
// per atlas layer group: a directional light's cascades, a spot light's one
// map, a point light's six cube faces. Which light owns which layers is fixed
// then (an Assignment, carried in each instance's params as a string); the
// matrices are recomputed every frame from the camera and the lights, so that
// moving lights and cameras never rebuild the graph.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/pass.h"
#include "rgraph/scene.h"

namespace rgraph::shadows {

using LightKind = SceneFeatures::ShadowLight::Kind;

// One shadowed light and the atlas layers it owns.
struct ShadowedLight {
  LightKind kind = LightKind::directional;
  uint32_t light = 0;       // index into Scene::directionalLights (directional) or Scene::pointLights
  uint32_t firstLayer = 0;  // atlas layer of its first map
  uint32_t layers = 1;      // its cascades (directional), 1 (spot), 6 (point: +x -x +y -y +z -z)
  bool operator==(const ShadowedLight&) const = default;
};

// How the maps are fitted. Every instance of one template carries the same.
struct ShadowSettings {
  uint32_t cascades = 4;    // directional lights: 1..4
  float lambda = 0.75f;     // practical split scheme: 0 uniform, 1 logarithmic
  float maxDistance = 0.0f; // cascades cover view depths up to min(camera.far, this); 0: camera.far
  uint32_t resolution = 2048;  // texels per side of one atlas layer
  // Directional cascades: true fits each to its slice's bounding sphere and
  // snaps the light-space origin to whole texels (edges do not shimmer when
  // the camera moves or turns); false fits a tight box to the slice's
  // corners each frame (sharper, shimmers: the stability tests' baseline).
  bool stabilize = true;
};

// The view of one atlas layer in one frame.
struct ShadowView {
  glm::mat4 view{1.0f};  // world -> light view
  glm::mat4 proj{1.0f};  // light view -> clip (OpenGL clip space, depth -1..1)
  uint32_t layer = 0;    // atlas layer
  LightKind kind = LightKind::directional;
  uint32_t light = 0;    // as ShadowedLight::light
  uint32_t cascade = 0;  // directional: cascade index; point: face index (+x -x +y -y +z -z); spot: 0
  // Directional: the camera view depths (positive distances along the view
  // direction) the cascade covers, [splitNear, splitFar).
  float splitNear = 0.0f, splitFar = 0.0f;
  // World units one texel spans: directional, everywhere in the cascade;
  // spot and point, at distance 1 from the light (scales with distance).
  float texelWorld = 0.0f;
  // Spot and point: the light's position and the near and far planes of its
  // perspective projection (depth linearisation, normal-offset scale).
  glm::vec3 lightPosition{0.0f};
  float nearPlane = 0.0f, farPlane = 0.0f;
  // Directional: casters in front of the near plane must still write depth
  // (clamped to it): draw with GL_DEPTH_CLAMP.
  bool depthClamp = false;
};

// N + 1 view depths from `near` to `far` bounding the N cascades: the
// practical split scheme, lambda * logarithmic + (1 - lambda) * uniform.
std::vector<float> cascadeSplits(float near, float far, uint32_t cascades, float lambda);

// Every layer's view for this frame, for the lights in `lights` (layers in
// their firstLayer order), seen with `camera` at `aspect` (width / height).
// Directional maps cover the scene's casters between the light and the
// cascade (depth clamp catches the rest); spot maps the cone (fov = twice the
// outer angle) to the light's reach; point maps 90-degree faces to its reach.
// A light's reach: PointLight::radius when > 0, else lightRadius(light),
// capped at the farthest corner of the scene's bounds.
std::vector<ShadowView> shadowViews(const Scene& scene, const Camera& camera, float aspect,
                                    const ShadowSettings& settings, const std::vector<ShadowedLight>& lights);

// The assignment as one pass param string, and back: "d0:0+4 s1:4+1 p3:5+6"
// (kind letter, light index, first layer, layer count; space separated).
// decode throws RuntimeError naming the bad token.
std::string encode(const std::vector<ShadowedLight>& lights);
std::vector<ShadowedLight> decode(std::string_view text);

// World units one texel of `view`'s map spans at world point `p` (the shadow
// budget report: the footprint on the visible surfaces).
float texelFootprint(const ShadowView& view, const glm::vec3& p, uint32_t resolution);

}  // namespace rgraph::shadows
