// Exact-visibility oracle (issue 28): is a light visible from a point? A CPU
// ray caster in double precision over a scene's shadow-casting triangles
// (visibility_bvh.h), for the shadow tests ("hard shadows agree with exact
// visibility away from edges") and the shadows bench (each method's error).
// GL-free: library rgraph_visibility_oracle (tests/support/visibility_oracle.cmake),
// linkable by the test suites and by bench/.
//
// What it models:
//   - casters: every primitive Scene::castsShadows says casts (castShadows, else not blended), its mesh's triangles
//     under the primitive's static `transform` (local -> world). A primitive's
//     spin (transformAt) is ignored: the oracle sees the scene at time 0, as
//     does every static render. Back and front faces both block; a caster is
//     opaque (an alpha mask's cut-outs block too; a blended primitive casts
//     only when its castShadows says so, and then it blocks fully).
//   - lights: a point light is visible when the segment from the point to its
//     position crosses no caster; a directional light when the ray from the
//     point towards -direction (unbounded) crosses none. A spot light is
//     `outside` for points beyond its outer cone (angle from its direction >
//     outerConeDeg), whatever lies between. The lights' radius and
//     attenuation are not looked at: visibility is geometry only.
//   - self-intersection (the probed point lies on a surface): epsilon() =
//     kRelativeEpsilon * the diagonal of the casters' bounding box. Without a
//     normal, hits closer than epsilon() to the point are ignored (tMin);
//     with a normal, the ray starts at point + normal * epsilon() and every
//     hit counts. Either way a point light's segment stops epsilon() short of
//     the light, so that a light sitting on a surface is not blocked by it.
//     1e-5: a float-rounded G-buffer position on a flat floor (error up to
//     2^-24 of the coordinates, which are within the scene's box) is still
//     lit by a light 1 degree above the horizon (the ray leaves the floor
//     after error / sin(1 deg) ~ 3.4e-6 diagonals); the price is that a caster
//     closer than epsilon() to the point (a contact gap under 1e-5 of the
//     scene) is not seen. Translating a scene does not change epsilon().
#pragma once

#include <cstdint>
#include <vector>

#include <rgraph/scene.h>

#include "visibility_bvh.h"

namespace rgraph::oracle {

enum class Visibility : uint8_t {
  lit,       // nothing between the point and the light
  shadowed,  // a caster between them
  outside,   // a spot light's cone does not contain the point (never for point or directional lights)
};
const char* visibilityName(Visibility v);

// The world-space triangles of the scene's casters (see above), in double
// precision. Throws std::runtime_error when a primitive's mesh index is out of range.
std::vector<WorldTriangle> shadowCasterTriangles(const Scene& scene);

class VisibilityOracle {
 public:
  static constexpr double kRelativeEpsilon = 1e-5;

  // One probed point; a zero normal means "none" (the tMin form above).
  struct Probe {
    dvec3 point{0.0};
    dvec3 normal{0.0};
  };

  explicit VisibilityOracle(const Scene& scene);
  explicit VisibilityOracle(std::vector<WorldTriangle> triangles);

  Visibility classify(const dvec3& point, const PointLight& light) const { return classify(Probe{point}, light); }
  Visibility classify(const dvec3& point, const DirectionalLight& light) const {
    return classify(Probe{point}, light);
  }
  Visibility classify(const Probe& probe, const PointLight& light) const;
  Visibility classify(const Probe& probe, const DirectionalLight& light) const;
  bool visible(const dvec3& point, const PointLight& light) const { return classify(point, light) == Visibility::lit; }
  bool visible(const dvec3& point, const DirectionalLight& light) const {
    return classify(point, light) == Visibility::lit;
  }

  // Many points at once, on `threads` threads (0: std::thread::hardware_concurrency()).
  // The answers are the same as the single queries', in the probes' order.
  std::vector<Visibility> classify(const std::vector<Probe>& probes, const PointLight& light, int threads = 0) const;
  std::vector<Visibility> classify(const std::vector<Probe>& probes, const DirectionalLight& light,
                                   int threads = 0) const;

  // The point a G-buffer holds at window position (x, y) of a width x height
  // frame seen by `camera`: GL window coordinates (x from the left, y from the
  // bottom row, pixel centres at i + 0.5, as gl_FragCoord and glReadPixels), the
  // first caster the camera ray meets between the near and far planes, with its
  // face normal turned towards the camera. nullopt where it meets none. The
  // oracle holds only casters: a non-casting primitive is not seen.
  std::optional<Probe> probeAtPixel(const Camera& camera, int width, int height, double x, double y) const;

  // The surface a ray meets first (any triangle, tMin = epsilon()): for probes
  // placed by casting camera rays, without a G-buffer.
  std::optional<RayHit> closestHit(const dvec3& origin, const dvec3& direction) const;
  // The geometric (face) normal of a hit's triangle, unit, on the side the ray came from.
  dvec3 faceNormal(const RayHit& hit, const dvec3& rayDirection) const;

  double epsilon() const { return epsilon_; }
  const Bvh& bvh() const { return bvh_; }

 private:
  // The shadow ray of a probe towards a target at `toLight` (a direction from
  // the probe; for a point light, the vector to its position): origin, tMin and tMax set.
  Ray shadowRay(const Probe& probe, const dvec3& toLight, bool bounded) const;

  Bvh bvh_;
  double epsilon_ = kRelativeEpsilon;
};

}  // namespace rgraph::oracle
