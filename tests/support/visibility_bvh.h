// The exact-visibility oracle's ray caster (issue 28): world-space triangles in
// double precision, a bounding volume hierarchy over them, any-hit and
// closest-hit ray queries, and the same queries by brute force (every triangle
// tested) for the property tests and the benchmark's ratio. GL-free.
//
// BVH: binned SAH (kSahBins bins per axis, all three axes tried), leaves of at
// most kMaxLeafTriangles triangles, nodes flattened depth-first (left child
// right after its parent). Binned rather than full-sweep SAH: the build is
// O(n log n) with a small constant and the trees come within a few percent of
// a full sweep's cost, which is all an oracle needs.
//
// Robustness: a ray's slab test widens its far distance by 1 + 2*gamma(3)
// (Ize, "Robust BVH ray traversal", JCGT 2013) so that rounding never culls a
// box the ray touches; flat boxes (axis-aligned triangles) and zero direction
// components are handled without NaNs. Unusable triangles (usableTriangle():
// a non-finite vertex, or zero area up to rounding) are dropped at build time
// and skipped by brute force.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace rgraph::oracle {

using glm::dvec3;

struct WorldTriangle {
  dvec3 a, b, c;
  int primitive = -1;  // index into Scene::primitives (-1: not from a scene)
};

// origin + t * direction for tMin < t < tMax. `direction` need not be unit
// length; t is in units of its length.
struct Ray {
  dvec3 origin{0.0};
  dvec3 direction{0.0, 0.0, 1.0};
  double tMin = 0.0;
  double tMax = 1e300;
};

struct RayHit {
  double t = 0.0;
  int triangle = -1;  // index into the triangles searched: Bvh::triangles() (its own order) or brute force's
  double u = 0.0, v = 0.0;  // barycentrics of b and c
};

// Moller-Trumbore in double precision: the hit's t when the ray crosses the
// triangle's inside or edges strictly within (tMin, tMax). Rays in the
// triangle's plane never hit. Expects a usable triangle (below): on a sliver
// whose edges are collinear up to rounding it may report a hit anywhere along them.
std::optional<RayHit> intersectTriangle(const WorldTriangle& tri, const Ray& ray);

// Finite vertices and an area above rounding: the sine of the angle between
// two edges above kMinEdgeSine. Collinear vertices computed in double (a point
// a quarter along an edge) leave a normal of ~1e-16 relative length that
// Moller-Trumbore would turn into spurious hits; real meshes (float vertices)
// have no angle anywhere near 1e-12 radians.
inline constexpr double kMinEdgeSine = 1e-12;
bool usableTriangle(const WorldTriangle& tri);

struct BvhStats {
  size_t triangles = 0;       // kept (finite) triangles
  size_t droppedNonFinite = 0;
  size_t droppedDegenerate = 0;  // finite, but zero area (up to kMinEdgeSine)
  size_t nodes = 0;
  size_t leaves = 0;
  int maxDepth = 0;
  size_t maxLeafSize = 0;
  double sahCost = 0.0;       // expected cost per ray, traversal 1, triangle 1
};

class Bvh {
 public:
  static constexpr int kSahBins = 16;
  static constexpr int kMaxLeafTriangles = 4;
  static constexpr int kMaxDepth = 64;  // a leaf is forced below this depth (degenerate inputs)

  Bvh() = default;
  explicit Bvh(std::vector<WorldTriangle> triangles);

  bool anyHit(const Ray& ray) const;
  std::optional<RayHit> closestHit(const Ray& ray) const;

  const std::vector<WorldTriangle>& triangles() const { return triangles_; }
  const BvhStats& stats() const { return stats_; }
  // The box around every kept triangle (empty scene: min > max).
  dvec3 boundsMin() const { return nodes_.empty() ? dvec3(1.0) : nodes_[0].min; }
  dvec3 boundsMax() const { return nodes_.empty() ? dvec3(-1.0) : nodes_[0].max; }

  struct Node {
    dvec3 min, max;
    uint32_t first = 0;  // leaf: first triangle; inner: index of the right child
    uint32_t count = 0;  // leaf: triangle count (> 0); inner: 0
  };

 private:
  struct BuildItem;
  struct SahSplit {
    int axis = -1;  // -1: none
    int bin = 0;    // the left child takes bins 0..bin
    double cost = std::numeric_limits<double>::infinity();
  };
  static SahSplit bestSahSplit(const std::vector<BuildItem>& items, uint32_t begin, uint32_t end, const dvec3& cmin,
                               const dvec3& cmax);
  uint32_t build(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth);

  std::vector<WorldTriangle> triangles_;  // reordered so that each leaf's are contiguous
  std::vector<Node> nodes_;
  BvhStats stats_;
};

// Every usable triangle tested, no hierarchy: the reference the BVH must agree with.
bool bruteForceAnyHit(const std::vector<WorldTriangle>& triangles, const Ray& ray);
std::optional<RayHit> bruteForceClosestHit(const std::vector<WorldTriangle>& triangles, const Ray& ray);

}  // namespace rgraph::oracle
