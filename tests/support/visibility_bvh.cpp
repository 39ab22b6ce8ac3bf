#include "visibility_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace rgraph::oracle {

namespace {

bool finite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double halfArea(const dvec3& mn, const dvec3& mx) {
  const dvec3 e = glm::max(mx - mn, dvec3(0.0));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// gamma(3) of Pharr, Jakob and Humphreys (3 * eps / (1 - 3 * eps), eps the
// double's unit roundoff): the bound on the relative error of the slab
// distances, so that widening the far distance by 1 + 2 * gamma(3) keeps the
// test conservative.
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() * 0.5;
constexpr double kGamma3 = 3.0 * kUnitRoundoff / (1.0 - 3.0 * kUnitRoundoff);
constexpr double kFarWiden = 1.0 + 2.0 * kGamma3;

// A ray with what every slab test needs precomputed.
struct SlabRay {
  dvec3 origin, inverse;
  std::array<bool, 3> parallel;  // direction component exactly 0: no division
  explicit SlabRay(const Ray& r) : origin(r.origin) {
    for (int a = 0; a < 3; ++a) {
      parallel[a] = r.direction[a] == 0.0;
      inverse[a] = parallel[a] ? 0.0 : 1.0 / r.direction[a];
    }
  }
};

// The entry distance when the ray meets the box within [lo, hi], else -1 (no NaN:
// parallel axes are tested by position instead of dividing by 0).
double slabEntry(const Bvh::Node& n, const SlabRay& r, double lo, double hi) {
  for (int a = 0; a < 3; ++a) {
    if (r.parallel[a]) {
      if (r.origin[a] < n.min[a] || r.origin[a] > n.max[a]) return -1.0;
      continue;
    }
    double t0 = (n.min[a] - r.origin[a]) * r.inverse[a];
    double t1 = (n.max[a] - r.origin[a]) * r.inverse[a];
    if (t0 > t1) std::swap(t0, t1);
    t1 = t1 > 0.0 ? t1 * kFarWiden : t1 / kFarWiden;
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (!(lo <= hi)) return -1.0;
  }
  return std::max(lo, 0.0);
}

}  // namespace

std::optional<RayHit> intersectTriangle(const WorldTriangle& tri, const Ray& ray) {
  const dvec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const dvec3 p = glm::cross(ray.direction, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0 || !std::isfinite(det)) return std::nullopt;
  const double inv = 1.0 / det;
  const dvec3 s = ray.origin - tri.a;
  const double u = glm::dot(s, p) * inv;
  if (!(u >= 0.0 && u <= 1.0)) return std::nullopt;
  const dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(ray.direction, q) * inv;
  if (!(v >= 0.0 && u + v <= 1.0)) return std::nullopt;
  const double t = glm::dot(e2, q) * inv;
  if (!(t > ray.tMin && t < ray.tMax)) return std::nullopt;
  return RayHit{t, -1, u, v};
}

bool usableTriangle(const WorldTriangle& t) {
  if (!finite(t.a) || !finite(t.b) || !finite(t.c)) return false;
  const dvec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const double n2 = glm::dot(glm::cross(e1, e2), glm::cross(e1, e2));
  const double limit = kMinEdgeSine * kMinEdgeSine * glm::dot(e1, e1) * glm::dot(e2, e2);
  return n2 > limit && std::isfinite(n2);
}

struct Bvh::BuildItem {
  dvec3 min, max, centroid;
  uint32_t triangle;
};

Bvh::Bvh(std::vector<WorldTriangle> triangles) {
  std::vector<BuildItem> items;
  items.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const WorldTriangle& t = triangles[i];
    if (!usableTriangle(t)) {
      ++(finite(t.a) && finite(t.b) && finite(t.c) ? stats_.droppedDegenerate : stats_.droppedNonFinite);
      continue;
    }
    const dvec3 mn = glm::min(t.a, glm::min(t.b, t.c)), mx = glm::max(t.a, glm::max(t.b, t.c));
    items.push_back({mn, mx, mn * 0.5 + mx * 0.5, static_cast<uint32_t>(i)});  // no overflow near DBL_MAX
  }
  stats_.triangles = items.size();
  if (items.empty()) return;
  nodes_.reserve(2 * items.size() / kMaxLeafTriangles + 1);
  build(items, 0, static_cast<uint32_t>(items.size()), 0);
  triangles_.reserve(items.size());
  for (const BuildItem& it : items) triangles_.push_back(triangles[it.triangle]);
  stats_.nodes = nodes_.size();
  const double rootArea = halfArea(nodes_[0].min, nodes_[0].max);
  for (const Node& n : nodes_) {
    const double share = rootArea > 0.0 ? halfArea(n.min, n.max) / rootArea : 1.0;
    stats_.sahCost += share * (n.count > 0 ? n.count : 1.0);
  }
}

// Binned SAH: for each axis of the centroids' box, bin the centroids and
// sweep the kSahBins - 1 boundaries; the cheapest (sum of child half-areas
// times triangle counts) wins. axis -1 when no boundary separates the items.
Bvh::SahSplit Bvh::bestSahSplit(const std::vector<BuildItem>& items, uint32_t begin, uint32_t end, const dvec3& cmin,
                                const dvec3& cmax) {
  SahSplit best;
  const uint32_t count = end - begin;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = cmax[axis] - cmin[axis];
    if (!(extent > 0.0)) continue;
    struct Bin {
      dvec3 min{std::numeric_limits<double>::infinity()}, max{-std::numeric_limits<double>::infinity()};
      uint32_t count = 0;
    };
    std::array<Bin, kSahBins> bins{};
    const double scale = kSahBins / extent;
    for (uint32_t i = begin; i < end; ++i) {
      const int b = std::min(kSahBins - 1, static_cast<int>((items[i].centroid[axis] - cmin[axis]) * scale));
      bins[b].min = glm::min(bins[b].min, items[i].min);
      bins[b].max = glm::max(bins[b].max, items[i].max);
      ++bins[b].count;
    }
    std::array<double, kSahBins> rightCost{};
    Bin acc;
    for (int b = kSahBins - 1; b > 0; --b) {
      acc.min = glm::min(acc.min, bins[b].min);
      acc.max = glm::max(acc.max, bins[b].max);
      acc.count += bins[b].count;
      rightCost[b] = acc.count ? halfArea(acc.min, acc.max) * acc.count : 0.0;
    }
    acc = Bin{};
    for (int b = 0; b < kSahBins - 1; ++b) {
      acc.min = glm::min(acc.min, bins[b].min);
      acc.max = glm::max(acc.max, bins[b].max);
      acc.count += bins[b].count;
      if (acc.count == 0 || acc.count == count) continue;
      const double cost = halfArea(acc.min, acc.max) * acc.count + rightCost[b + 1];
      if (cost < best.cost) best = {axis, b, cost};
    }
  }
  return best;
}

// Builds the subtree of items[begin, end) and returns its node's index. The
// split: the cheapest of kSahBins - 1 bin boundaries on each axis of the
// centroids' box; an object-median split on the widest axis when binning
// cannot separate the items (equal centroids) but they are too many for a leaf.
uint32_t Bvh::build(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  dvec3 mn(std::numeric_limits<double>::infinity()), mx(-std::numeric_limits<double>::infinity());
  dvec3 cmin = mn, cmax = mx;
  for (uint32_t i = begin; i < end; ++i) {
    mn = glm::min(mn, items[i].min);
    mx = glm::max(mx, items[i].max);
    cmin = glm::min(cmin, items[i].centroid);
    cmax = glm::max(cmax, items[i].centroid);
  }
  nodes_[index].min = mn;
  nodes_[index].max = mx;
  stats_.maxDepth = std::max(stats_.maxDepth, depth);
  const uint32_t count = end - begin;
  auto makeLeaf = [&] {
    nodes_[index].first = begin;
    nodes_[index].count = count;
    ++stats_.leaves;
    stats_.maxLeafSize = std::max<size_t>(stats_.maxLeafSize, count);
    return index;
  };
  if (count <= static_cast<uint32_t>(kMaxLeafTriangles) || depth >= kMaxDepth) return makeLeaf();

  const SahSplit best = bestSahSplit(items, begin, end, cmin, cmax);
  const int bestAxis = best.axis, bestSplit = best.bin;
  const double bestCost = best.cost;

  uint32_t mid = begin;
  if (bestAxis >= 0) {
    const double area = halfArea(mn, mx);
    // Traversal cost 1, triangle cost 1: a leaf is cheaper when the split's
    // expected cost is no better (the count limit still applies below 4x).
    if (area > 0.0 && 1.0 + bestCost / area >= count && count <= 4u * kMaxLeafTriangles) return makeLeaf();
    const double scale = kSahBins / (cmax[bestAxis] - cmin[bestAxis]);
    auto it = std::partition(items.begin() + begin, items.begin() + end, [&](const BuildItem& item) {
      return std::min(kSahBins - 1, static_cast<int>((item.centroid[bestAxis] - cmin[bestAxis]) * scale)) <=
             bestSplit;
    });
    mid = static_cast<uint32_t>(it - items.begin());
  }
  if (mid == begin || mid == end) {  // no separating boundary: object median
    const dvec3 e = mx - mn;
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    mid = begin + count / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                     [axis](const BuildItem& l, const BuildItem& r) { return l.centroid[axis] < r.centroid[axis]; });
  }
  build(items, begin, mid, depth + 1);
  const uint32_t right = build(items, mid, end, depth + 1);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

bool Bvh::anyHit(const Ray& ray) const {
  if (nodes_.empty()) return false;
  const SlabRay slab(ray);
  std::array<uint32_t, 2 * kMaxDepth + 4> stack;
  size_t top = 0;
  if (slabEntry(nodes_[0], slab, ray.tMin, ray.tMax) < 0.0) return false;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i)
        if (intersectTriangle(triangles_[i], ray)) return true;
      continue;
    }
    const uint32_t left = static_cast<uint32_t>(&n - nodes_.data()) + 1, right = n.first;
    if (slabEntry(nodes_[right], slab, ray.tMin, ray.tMax) >= 0.0) stack[top++] = right;
    if (slabEntry(nodes_[left], slab, ray.tMin, ray.tMax) >= 0.0) stack[top++] = left;
  }
  return false;
}

std::optional<RayHit> Bvh::closestHit(const Ray& ray) const {
  if (nodes_.empty()) return std::nullopt;
  const SlabRay slab(ray);
  Ray r = ray;
  std::optional<RayHit> best;
  std::array<uint32_t, 2 * kMaxDepth + 4> stack;
  size_t top = 0;
  if (slabEntry(nodes_[0], slab, r.tMin, r.tMax) < 0.0) return std::nullopt;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (slabEntry(n, slab, r.tMin, r.tMax) < 0.0) continue;  // farther than the best hit found since
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        if (auto hit = intersectTriangle(triangles_[i], r)) {
          hit->triangle = static_cast<int>(i);
          best = hit;
          r.tMax = hit->t;
        }
      }
      continue;
    }
    const uint32_t left = static_cast<uint32_t>(&n - nodes_.data()) + 1, right = n.first;
    const double tl = slabEntry(nodes_[left], slab, r.tMin, r.tMax);
    const double tr = slabEntry(nodes_[right], slab, r.tMin, r.tMax);
    // Nearer child on top of the stack: its hits shorten the ray for the other.
    if (tl >= 0.0 && tr >= 0.0) {
      stack[top++] = tl <= tr ? right : left;
      stack[top++] = tl <= tr ? left : right;
    } else if (tl >= 0.0) {
      stack[top++] = left;
    } else if (tr >= 0.0) {
      stack[top++] = right;
    }
  }
  return best;
}

bool bruteForceAnyHit(const std::vector<WorldTriangle>& triangles, const Ray& ray) {
  for (const WorldTriangle& t : triangles)
    if (usableTriangle(t) && intersectTriangle(t, ray)) return true;
  return false;
}

std::optional<RayHit> bruteForceClosestHit(const std::vector<WorldTriangle>& triangles, const Ray& ray) {
  Ray r = ray;
  std::optional<RayHit> best;
  for (size_t i = 0; i < triangles.size(); ++i) {
    if (!usableTriangle(triangles[i])) continue;
    if (auto hit = intersectTriangle(triangles[i], r)) {
      hit->triangle = static_cast<int>(i);
      best = hit;
      r.tMax = hit->t;
    }
  }
  return best;
}

}  // namespace rgraph::oracle
