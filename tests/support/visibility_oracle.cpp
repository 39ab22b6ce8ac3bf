#include "visibility_oracle.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace rgraph::oracle {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool isZero(const dvec3& v) { return v.x == 0.0 && v.y == 0.0 && v.z == 0.0; }

// Runs answer(i) for i in [0, n) on `threads` threads, each over one contiguous range.
template <typename F>
void parallelFor(size_t n, int threads, F answer) {
  size_t count = threads > 0 ? static_cast<size_t>(threads) : std::max(1u, std::thread::hardware_concurrency());
  count = std::min(count, std::max<size_t>(1, n / 256));  // small batches are not worth a thread
  if (count <= 1) {
    for (size_t i = 0; i < n; ++i) answer(i);
    return;
  }
  std::vector<std::thread> pool;
  for (size_t k = 0; k < count; ++k) {
    pool.emplace_back([=, &answer] {
      for (size_t i = n * k / count; i < n * (k + 1) / count; ++i) answer(i);
    });
  }
  for (std::thread& t : pool) t.join();
}

}  // namespace

const char* visibilityName(Visibility v) {
  switch (v) {
    case Visibility::lit: return "lit";
    case Visibility::shadowed: return "shadowed";
    case Visibility::outside: return "outside";
  }
  return "?";
}

std::vector<WorldTriangle> shadowCasterTriangles(const Scene& scene) {
  std::vector<WorldTriangle> out;
  for (size_t p = 0; p < scene.primitives.size(); ++p) {
    const Primitive& prim = scene.primitives[p];
    if (!scene.castsShadows(prim)) continue;  // its castShadows, else not when it blends
    if (prim.mesh < 0 || static_cast<size_t>(prim.mesh) >= scene.meshes.size())
      throw std::runtime_error("visibility oracle: primitive " + std::to_string(p) + " ('" + prim.name +
                               "'): mesh " + std::to_string(prim.mesh) + " out of range (" +
                               std::to_string(scene.meshes.size()) + " meshes)");
    const MeshData& mesh = scene.meshes[prim.mesh];
    // The static transform, in double: the products are exact to double
    // rounding whatever the float matrix holds.
    const glm::dmat4 m(prim.transform);
    auto world = [&](uint32_t index) -> dvec3 {
      if (index >= mesh.positions.size())
        throw std::runtime_error("visibility oracle: mesh '" + mesh.name + "': index " + std::to_string(index) +
                                 " out of range");
      return dvec3(m * glm::dvec4(dvec3(mesh.positions[index]), 1.0));
    };
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      out.push_back({world(mesh.indices[t]), world(mesh.indices[t + 1]), world(mesh.indices[t + 2]),
                     static_cast<int>(p)});
  }
  return out;
}

VisibilityOracle::VisibilityOracle(const Scene& scene) : VisibilityOracle(shadowCasterTriangles(scene)) {}

VisibilityOracle::VisibilityOracle(std::vector<WorldTriangle> triangles) : bvh_(std::move(triangles)) {
  const dvec3 extent = bvh_.boundsMax() - bvh_.boundsMin();
  const double diagonal = bvh_.stats().triangles > 0 ? glm::length(extent) : 0.0;
  // An empty or point-sized scene blocks nothing; any positive epsilon does.
  epsilon_ = kRelativeEpsilon * (diagonal > 0.0 && std::isfinite(diagonal) ? diagonal : 1.0);
}

Ray VisibilityOracle::shadowRay(const Probe& probe, const dvec3& toLight, bool bounded) const {
  Ray ray;
  const bool hasNormal = !isZero(probe.normal);
  ray.origin = hasNormal ? probe.point + glm::normalize(probe.normal) * epsilon_ : probe.point;
  if (bounded) {
    // Segment to the light: t in [0, 1] spans it; stop epsilon short of the light.
    ray.direction = (probe.point + toLight) - ray.origin;
    const double length = glm::length(ray.direction);
    ray.tMin = hasNormal ? 0.0 : epsilon_ / length;
    ray.tMax = 1.0 - epsilon_ / length;
  } else {
    ray.direction = glm::normalize(toLight);
    ray.tMin = hasNormal ? 0.0 : epsilon_;
    ray.tMax = std::numeric_limits<double>::infinity();
  }
  return ray;
}

Visibility VisibilityOracle::classify(const Probe& probe, const PointLight& light) const {
  const dvec3 toLight = dvec3(light.position) - probe.point;
  const double distance = glm::length(toLight);
  if (light.spot) {
    // The cone of half-angle outerConeDeg about `direction`; a point at the
    // light itself has no direction from it: outside.
    if (!(distance > 0.0)) return Visibility::outside;
    const double cosAngle = glm::dot(-toLight / distance, glm::normalize(dvec3(light.direction)));
    if (cosAngle < std::cos(double(light.outerConeDeg) * kPi / 180.0)) return Visibility::outside;
  }
  if (distance <= epsilon_) return Visibility::lit;  // nothing fits between
  return bvh_.anyHit(shadowRay(probe, toLight, true)) ? Visibility::shadowed : Visibility::lit;
}

Visibility VisibilityOracle::classify(const Probe& probe, const DirectionalLight& light) const {
  const dvec3 toLight = -dvec3(light.direction);
  if (isZero(toLight)) return Visibility::outside;  // refused by validate(); no direction to cast towards
  return bvh_.anyHit(shadowRay(probe, toLight, false)) ? Visibility::shadowed : Visibility::lit;
}

std::vector<Visibility> VisibilityOracle::classify(const std::vector<Probe>& probes, const PointLight& light,
                                                   int threads) const {
  std::vector<Visibility> out(probes.size());
  parallelFor(probes.size(), threads, [&](size_t i) { out[i] = classify(probes[i], light); });
  return out;
}

std::vector<Visibility> VisibilityOracle::classify(const std::vector<Probe>& probes, const DirectionalLight& light,
                                                   int threads) const {
  std::vector<Visibility> out(probes.size());
  parallelFor(probes.size(), threads, [&](size_t i) { out[i] = classify(probes[i], light); });
  return out;
}

std::optional<RayHit> VisibilityOracle::closestHit(const dvec3& origin, const dvec3& direction) const {
  Ray ray;
  ray.origin = origin;
  ray.direction = glm::normalize(direction);
  ray.tMin = epsilon_;
  ray.tMax = std::numeric_limits<double>::infinity();
  return bvh_.closestHit(ray);
}

std::optional<VisibilityOracle::Probe> VisibilityOracle::probeAtPixel(const Camera& camera, int width, int height,
                                                                     double x, double y) const {
  if (width <= 0 || height <= 0) return std::nullopt;
  // The camera's frame as Camera::view() and projection() build it (glm::lookAt,
  // glm::perspective), in double. The ray's direction has unit length along
  // the view axis, so that its t is the view depth, clipped as GL clips.
  const dvec3 eye(camera.position), forward = glm::normalize(dvec3(camera.target) - eye);
  const dvec3 right = glm::normalize(glm::cross(forward, dvec3(camera.validUp())));
  const dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(double(camera.fovY) * kPi / 360.0), aspect = double(width) / double(height);
  const double ndcX = 2.0 * x / width - 1.0, ndcY = 2.0 * y / height - 1.0;
  Ray ray;
  ray.origin = eye;
  ray.direction = forward + right * (ndcX * tanHalf * aspect) + up * (ndcY * tanHalf);
  ray.tMin = camera.near > 0.0f ? double(camera.near) : 0.1;
  ray.tMax = camera.far > camera.near ? double(camera.far) : ray.tMin * 1000.0;
  const auto hit = bvh_.closestHit(ray);
  if (!hit) return std::nullopt;
  return Probe{ray.origin + ray.direction * hit->t, faceNormal(*hit, ray.direction)};
}

dvec3 VisibilityOracle::faceNormal(const RayHit& hit, const dvec3& rayDirection) const {
  const WorldTriangle& t = bvh_.triangles().at(static_cast<size_t>(hit.triangle));
  const dvec3 n = glm::cross(t.b - t.a, t.c - t.a);
  const double length = glm::length(n);
  if (!(length > 0.0)) return dvec3(0.0);
  return glm::dot(n, rayDirection) > 0.0 ? -n / length : n / length;
}

}  // namespace rgraph::oracle
