// Scenes and reference answers shared by the visibility-oracle tests: a box
// over a floor, built from the library's meshes, and an analytic segment-box
// test written independently of the oracle's triangles and BVH.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <rgraph/scene.h>

#include "visibility_oracle.h"

namespace vistest {

using glm::dvec2;
using glm::dvec3;

// Appended piecewise: GCC 12 warns (-Warray-bounds, falsely) on string + literal + string here.
inline std::string asset(const std::string& rel) {
  std::string path(RGRAPH_ASSETS_DIR);
  path.append("/gltf/").append(rel);
  return path;
}

// A unit box (edge 1) centred at `boxCentre` above a floor plane y = 0 of half
// size `floorHalf`; primitives "box" (0) and "floor" (1).
inline rgraph::Scene boxOverFloor(glm::vec3 boxCentre = {0.0f, 2.0f, 0.0f}, float floorHalf = 50.0f,
                                  glm::vec3 offset = glm::vec3(0.0f)) {
  rgraph::Scene s;
  s.meshes.push_back(rgraph::makeCube(0.5f));
  s.meshes.push_back(rgraph::makePlane(floorHalf, floorHalf));
  s.materials.push_back({});
  rgraph::Primitive box;
  box.mesh = 0;
  box.material = 0;
  box.name = "box";
  box.transform = glm::translate(glm::mat4(1.0f), offset + boxCentre);
  rgraph::Primitive floor = box;
  floor.mesh = 1;
  floor.name = "floor";
  floor.transform = glm::translate(glm::mat4(1.0f), offset);
  s.primitives = {box, floor};
  return s;
}

// Does the segment from p to q (q = p + d * t, t in (t0, t1)) cross the box
// [lo, hi]? Analytic slab test, with the overlap length of the interval as a
// measure of how far from grazing the box it is.
inline double segmentBoxOverlap(const dvec3& p, const dvec3& d, double t0, double t1, const dvec3& lo,
                                const dvec3& hi) {
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (p[a] < lo[a] || p[a] > hi[a]) return -1.0;
      continue;
    }
    double ta = (lo[a] - p[a]) / d[a], tb = (hi[a] - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 - t0;
}

// The convex hull (counter-clockwise, x-z plane) of 2D points: Andrew's monotone chain.
inline std::vector<dvec2> convexHull(std::vector<dvec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const dvec2& a, const dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](const dvec2& o, const dvec2& a, const dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<dvec2> h(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// A double as a float G-buffer would hold it.
inline dvec3 floatRounded(const dvec3& p) { return dvec3(glm::vec3(p)); }

}  // namespace vistest
