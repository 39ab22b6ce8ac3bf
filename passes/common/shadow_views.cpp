#include "rgraph/passes/shadow_views.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"

// The maths is done in double and rounded to float once, at the end: the
// snapping below expresses the world origin in texels of a cascade, which for
// a 2048-texel map of a 10-unit cascade 1e4 units from the origin is ~1e6
// texels, where a float's step (0.06) would already be visible shimmer.

namespace rgraph::shadows {

namespace {

using dvec3 = glm::dvec3;
using dmat4 = glm::dmat4;

// Spot maps leave this many texels between the cone's rim and the map's edge,
// so that a filter kernel (pcf 7: 3 texels either side) near the rim reads
// inside the map.
constexpr double kSpotMarginTexels = 4.0;
// A spot map's half-angle stays below 85 degrees: the perspective matrix
// degenerates at 90, and a wider cone (outer_cone_deg up to 90 is valid)
// loses its rim, not its centre.
constexpr double kMaxSpotHalfAngleDeg = 85.0;
// Perspective maps' near plane as a share of their far plane. Depth precision
// is set by far / near (24-bit depth resolves ~z^2 / (near * 2^24) at
// distance z: far * 6e-5 at the far plane with this ratio), and casters closer
// to the light than `near` are not drawn: 1/1000 of the reach is inside any
// real lamp's bulb. A ratio, not an absolute floor such as 0.02 units, so
// that a 1e-3-unit scene keeps its casters and a 1e4-unit one its precision.
constexpr double kNearOverFar = 1e-3;

// An up vector that is not parallel to `dir` (unit), fixed for a given
// direction so that a light's view does not turn with the camera.
dvec3 safeUp(const dvec3& dir) { return std::abs(dir.y) < 0.99 ? dvec3(0, 1, 0) : dvec3(0, 0, 1); }

// lookAt from `eye` along `dir`: the rotation alone, then the translation
// (lookAt(eye, eye + dir) loses `dir` in eye's precision far from the origin).
dmat4 lookAlong(const dvec3& eye, const dvec3& dir, const dvec3& up) {
  return glm::lookAt(dvec3(0.0), dir, up) * glm::translate(dmat4(1.0), -eye);
}

dvec3 unitOr(const glm::vec3& v, const dvec3& fallback) {
  const dvec3 d(v);
  const double len = glm::length(d);
  return len > 0.0 && std::isfinite(len) ? d / len : fallback;
}

// The camera's frame and frustum shape, with Camera::projection's guards.
struct CameraFrame {
  dvec3 position, forward, right, up;
  double tanY = 0, aspect = 1, near = 0.1, far = 100;
};

CameraFrame cameraFrame(const Camera& camera, float aspect, float maxDistance) {
  CameraFrame f;
  f.position = dvec3(camera.position);
  f.forward = dvec3(camera.forward());
  f.right = glm::normalize(glm::cross(f.forward, dvec3(camera.validUp())));
  f.up = glm::cross(f.right, f.forward);
  f.tanY = std::tan(glm::radians(double(camera.fovY)) * 0.5);
  f.aspect = aspect > 0.0f ? aspect : 1.0;
  f.near = camera.near > 0.0f ? camera.near : 0.1;
  f.far = camera.far > f.near ? camera.far : f.near * 1000.0;
  if (maxDistance > 0.0f) f.far = std::min(f.far, double(maxDistance));
  f.far = std::max(f.far, f.near * (1.0 + 1e-4));  // a maxDistance below near: one thin cascade
  return f;
}

// The 8 world corners of the camera frustum between view depths d0 and d1.
std::array<dvec3, 8> sliceCorners(const CameraFrame& f, double d0, double d1) {
  std::array<dvec3, 8> out;
  for (int i = 0; i < 8; ++i) {
    const double d = (i & 4) ? d1 : d0;
    const double h = d * f.tanY, w = h * f.aspect;
    out[size_t(i)] = f.position + f.forward * d + f.right * ((i & 1) ? w : -w) + f.up * ((i & 2) ? h : -h);
  }
  return out;
}

// The smallest sphere centred on the view axis around the slice [d0, d1]:
// every corner at depth d lies d * t off the axis (t = tanY * sqrt(1 +
// aspect^2)); the centre depth c equalises the near and far corners'
// distances, (d0 + d1)(1 + t^2) / 2, or sits on the far plane when that lies
// beyond it (a wide, thin slice). From depths and the fov alone, so the radius
// is the same however the camera turns.
struct AxisSphere {
  double centreDepth, radius;
};

AxisSphere sliceSphere(const CameraFrame& f, double d0, double d1) {
  const double t2 = f.tanY * f.tanY * (1.0 + f.aspect * f.aspect);
  const double c = std::min((d0 + d1) * (1.0 + t2) * 0.5, d1);
  const double r = std::sqrt((d1 - c) * (d1 - c) + d1 * d1 * t2);
  // Rounded up to 1/16 of its power of two (at most 6% larger): a margin for
  // the corners' float rounding, and the same radius for nearby settings.
  const double quantum = std::ldexp(1.0, std::ilogb(r) - 4);
  return {c, std::ceil(r / quantum) * quantum};
}

// A caster's bounds in a directional light's rotation: its xy box, and its
// nearest depth along the light (dot with the direction).
struct CasterExtent {
  glm::dvec2 min, max;
  double nearDepth;
};

// Bounds of a primitive wherever its spin turns it: the box around the
// sphere about the pivot through the static bounds' farthest corner.
Bounds casterBounds(const Primitive& p) {
  if (!p.animated() || p.bounds.empty()) return p.bounds;
  float reach = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c((i & 1) ? p.bounds.max.x : p.bounds.min.x, (i & 2) ? p.bounds.max.y : p.bounds.min.y,
                      (i & 4) ? p.bounds.max.z : p.bounds.min.z);
    reach = std::max(reach, glm::length(c - p.spin.pivot));
  }
  Bounds b;
  b.expand(p.spin.pivot - glm::vec3(reach));
  b.expand(p.spin.pivot + glm::vec3(reach));
  return b;
}

std::vector<CasterExtent> casterExtents(const Scene& scene, const dmat4& rotation, const dvec3& dir) {
  std::vector<CasterExtent> out;
  for (const Primitive& p : scene.primitives) {
    if (!scene.castsShadows(p)) continue;
    const Bounds b = casterBounds(p);
    if (b.empty()) continue;
    CasterExtent e{glm::dvec2(std::numeric_limits<double>::infinity()),
                   glm::dvec2(-std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity()};
    for (int i = 0; i < 8; ++i) {
      const dvec3 c((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
      const glm::dvec2 xy(rotation * glm::dvec4(c, 1.0));
      e.min = glm::min(e.min, xy);
      e.max = glm::max(e.max, xy);
      e.nearDepth = std::min(e.nearDepth, glm::dot(c, dir));
    }
    out.push_back(e);
  }
  return out;
}

// The nearest depth along the light of the casters whose light-space box
// overlaps [lo, hi] (the cascade's footprint): what must still be drawn in
// front of the cascade. +infinity when none does.
double nearestCaster(const std::vector<CasterExtent>& casters, const glm::dvec2& lo, const glm::dvec2& hi) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const CasterExtent& c : casters)
    if (c.max.x >= lo.x && c.min.x <= hi.x && c.max.y >= lo.y && c.min.y <= hi.y)
      nearest = std::min(nearest, c.nearDepth);
  return nearest;
}

glm::mat4 toFloat(const dmat4& m) { return glm::mat4(m); }

// Stabilised: the slice's sphere, an ortho square of its diameter, the view's
// translation snapped so that the world origin lands on a texel corner.
void fitSphere(ShadowView& v, const CameraFrame& f, const dvec3& dir, const std::vector<CasterExtent>& casters,
               uint32_t resolution) {
  const AxisSphere s = sliceSphere(f, v.splitNear, v.splitFar);
  const double r = s.radius;
  const dvec3 centre = f.position + f.forward * s.centreDepth;
  const dvec3 up = safeUp(dir);
  const dmat4 rotation = glm::lookAt(dvec3(0.0), dir, up);
  const glm::dvec2 centreXY(rotation * glm::dvec4(centre, 1.0));
  const double sphereNear = glm::dot(centre, dir) - r;
  const double caster = nearestCaster(casters, centreXY - r, centreXY + r);
  const double pullBack = std::isfinite(caster) ? std::max(0.0, sphereNear - caster) : 0.0;
  const dmat4 view = lookAlong(centre - dir * (r + pullBack), dir, up);
  dmat4 proj = glm::ortho(-r, r, -r, r, 0.0, pullBack + 2.0 * r);
  // The world origin in texel coordinates ((ndc + 1) * resolution / 2),
  // rounded to whole texels by moving the projection: every world point then
  // keeps its sub-texel position while the camera moves.
  const glm::dvec4 origin = proj * view * glm::dvec4(0, 0, 0, 1);
  const double half = resolution * 0.5;
  const glm::dvec2 texel = (glm::dvec2(origin) + 1.0) * half;
  const glm::dvec2 offset = (glm::round(texel) - texel) / half;
  proj[3][0] += offset.x;
  proj[3][1] += offset.y;
  v.view = toFloat(view);
  v.proj = toFloat(proj);
  v.texelWorld = float(2.0 * r / resolution);
}

// Unstabilised: the tightest box around the slice's corners in light space.
void fitBox(ShadowView& v, const CameraFrame& f, const dvec3& dir, const std::vector<CasterExtent>& casters,
            uint32_t resolution) {
  const std::array<dvec3, 8> corners = sliceCorners(f, v.splitNear, v.splitFar);
  dvec3 centroid(0.0);
  for (const dvec3& c : corners) centroid += c / 8.0;
  const dvec3 up = safeUp(dir);
  const dmat4 view = lookAlong(centroid, dir, up);
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const dvec3& c : corners) {
    const dvec3 p(view * glm::dvec4(c, 1.0));
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // View space looks down -z: depths are -z. Casters nearer than the slice
  // along the light (depth relative to the centroid) pull the near plane.
  const glm::dvec2 centroidXY(glm::lookAt(dvec3(0.0), dir, up) * glm::dvec4(centroid, 1.0));
  const double caster = nearestCaster(casters, centroidXY + glm::dvec2(lo), centroidXY + glm::dvec2(hi));
  double near = -hi.z;
  if (std::isfinite(caster)) near = std::min(near, caster - glm::dot(centroid, dir));
  const dmat4 proj = glm::ortho(lo.x, hi.x, lo.y, hi.y, near, -lo.z);
  v.view = toFloat(view);
  v.proj = toFloat(proj);
  v.texelWorld = float(std::max(hi.x - lo.x, hi.y - lo.y) / resolution);
}

void directionalViews(const Scene& scene, const Camera& camera, float aspect, const ShadowSettings& settings,
                      const ShadowedLight& light, std::vector<ShadowView>& out) {
  if (light.light >= scene.directionalLights.size())
    throw RuntimeError("shadow views: directional light " + std::to_string(light.light) +
                       " does not exist (the scene has " + std::to_string(scene.directionalLights.size()) + ")");
  const dvec3 dir = unitOr(scene.directionalLights[light.light].direction, dvec3(0, -1, 0));
  const CameraFrame f = cameraFrame(camera, aspect, settings.maxDistance);
  const std::vector<CasterExtent> casters = casterExtents(scene, glm::lookAt(dvec3(0.0), dir, safeUp(dir)), dir);
  // The assignment's layer count is the cascade count: it is what the atlas
  // was allocated for.
  const std::vector<float> splits = cascadeSplits(float(f.near), float(f.far), light.layers, settings.lambda);
  const uint32_t resolution = std::max(settings.resolution, 1u);
  for (uint32_t i = 0; i < light.layers; ++i) {
    ShadowView v;
    v.layer = light.firstLayer + i;
    v.kind = LightKind::directional;
    v.light = light.light;
    v.cascade = i;
    v.splitNear = splits[i];
    v.splitFar = splits[i + 1];
    v.depthClamp = true;
    if (settings.stabilize)
      fitSphere(v, f, dir, casters, resolution);
    else
      fitBox(v, f, dir, casters, resolution);
    out.push_back(v);
  }
}

// How far a spot or point light's map must see: its reach, capped at the
// scene's farthest corner (nothing lies beyond it to cast or receive).
double lightReach(const Bounds& b, const PointLight& l) {
  double reach = l.radius > 0.0f ? double(l.radius) : double(lightRadius(l));
  double farthest = 0.0;
  if (!b.empty())
    for (int i = 0; i < 8; ++i) {
      const dvec3 c((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
      farthest = std::max(farthest, glm::length(c - dvec3(l.position)));
    }
  if (farthest > 0.0) reach = std::min(reach, farthest);
  // A light that never reaches the threshold lights nothing; its map still
  // gets a usable projection.
  if (!(reach > 0.0) || !std::isfinite(reach)) reach = farthest > 0.0 ? farthest : 1.0;
  return reach;
}

ShadowView perspectiveView(const ShadowedLight& light, uint32_t face, const dvec3& position, const dvec3& dir,
                           const dvec3& up, double halfAngle, double reach, uint32_t resolution) {
  ShadowView v;
  v.layer = light.firstLayer + face;
  v.kind = light.kind;
  v.light = light.light;
  v.cascade = face;
  const double near = reach * kNearOverFar;
  v.view = toFloat(lookAlong(position, dir, up));
  v.proj = toFloat(glm::perspective(2.0 * halfAngle, 1.0, near, reach));
  v.texelWorld = float(2.0 * std::tan(halfAngle) / resolution);
  v.lightPosition = glm::vec3(position);
  v.nearPlane = float(near);
  v.farPlane = float(reach);
  return v;
}

const PointLight& pointLight(const Scene& scene, const ShadowedLight& light) {
  const char* kind = light.kind == LightKind::spot ? "spot" : "point";
  if (light.light >= scene.pointLights.size())
    throw RuntimeError(std::string("shadow views: ") + kind + " light " + std::to_string(light.light) +
                       " does not exist (the scene has " + std::to_string(scene.pointLights.size()) +
                       " point and spot lights)");
  const PointLight& l = scene.pointLights[light.light];
  if (l.spot != (light.kind == LightKind::spot))
    throw RuntimeError(std::string("shadow views: light ") + std::to_string(light.light) + " is assigned as a " + kind +
                       " light but is a " + (l.spot ? "spot" : "point") + " light");
  return l;
}

void spotView(const Scene& scene, const Bounds& bounds, const ShadowSettings& settings, const ShadowedLight& light,
              std::vector<ShadowView>& out) {
  const PointLight& l = pointLight(scene, light);
  const dvec3 dir = unitOr(l.direction, dvec3(0, 0, -1));
  const double res = std::max(settings.resolution, 1u);
  // tan(half) chosen so that the rim (tan(outer) off the axis at unit
  // depth) lies kSpotMarginTexels inside the map's inscribed circle.
  const double outer = glm::radians(std::clamp(double(l.outerConeDeg), 0.0, 90.0));
  double half = outer >= glm::radians(kMaxSpotHalfAngleDeg)
                    ? glm::radians(kMaxSpotHalfAngleDeg)
                    : std::atan(std::tan(outer) / (1.0 - 2.0 * kSpotMarginTexels / res));
  half = std::clamp(half, glm::radians(1.0), glm::radians(kMaxSpotHalfAngleDeg));
  out.push_back(perspectiveView(light, 0, dvec3(l.position), dir, safeUp(dir), half, lightReach(bounds, l),
                                uint32_t(res)));
}

void pointViews(const Scene& scene, const Bounds& bounds, const ShadowSettings& settings,
                const ShadowedLight& light, std::vector<ShadowView>& out) {
  const PointLight& l = pointLight(scene, light);
  // GL cube-map faces in layer order and the up vectors that make a face's
  // image match what a cube-map lookup along its axis reads.
  static const std::array<std::pair<dvec3, dvec3>, 6> kFaces = {{{{1, 0, 0}, {0, -1, 0}},
                                                                  {{-1, 0, 0}, {0, -1, 0}},
                                                                  {{0, 1, 0}, {0, 0, 1}},
                                                                  {{0, -1, 0}, {0, 0, -1}},
                                                                  {{0, 0, 1}, {0, -1, 0}},
                                                                  {{0, 0, -1}, {0, -1, 0}}}};
  const double reach = lightReach(bounds, l);
  const uint32_t res = std::max(settings.resolution, 1u);
  const uint32_t faces = std::min<uint32_t>(light.layers, 6);
  for (uint32_t i = 0; i < faces; ++i)
    out.push_back(perspectiveView(light, i, dvec3(l.position), kFaces[i].first, kFaces[i].second,
                                  glm::radians(45.0), reach, res));
}

// ---------------------------------------------------------------- assignment strings

char kindLetter(LightKind k) { return k == LightKind::directional ? 'd' : k == LightKind::spot ? 's' : 'p'; }

[[noreturn]] void badToken(std::string_view token, const std::string& what) {
  throw RuntimeError("shadow assignment '" + std::string(token) + "': " + what);
}

// The unsigned number in `text` (the whole of it), named `what` in errors.
uint32_t parseNumber(std::string_view token, std::string_view text, const char* what) {
  if (text.empty()) badToken(token, std::string("missing ") + what);
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && end == text.data() + text.size() &&
                                               value > std::numeric_limits<uint32_t>::max()))
    badToken(token, std::string(what) + " '" + std::string(text) + "' is out of range (at most 4294967295)");
  if (ec != std::errc() || end != text.data() + text.size())
    badToken(token, std::string(what) + " '" + std::string(text) + "' is not a number");
  return uint32_t(value);
}

ShadowedLight parseToken(std::string_view token) {
  ShadowedLight l;
  switch (token[0]) {
    case 'd': l.kind = LightKind::directional; break;
    case 's': l.kind = LightKind::spot; break;
    case 'p': l.kind = LightKind::point; break;
    default: badToken(token, "unknown light kind '" + std::string(1, token[0]) + "' (d, s or p)");
  }
  const size_t colon = token.find(':');
  if (colon == std::string_view::npos) badToken(token, "missing ':<first layer>' (expected like d0:0+4)");
  const size_t plus = token.find('+', colon);
  if (plus == std::string_view::npos) badToken(token, "missing '+<layer count>' (expected like d0:0+4)");
  l.light = parseNumber(token, token.substr(1, colon - 1), "light index");
  l.firstLayer = parseNumber(token, token.substr(colon + 1, plus - colon - 1), "first layer");
  l.layers = parseNumber(token, token.substr(plus + 1), "layer count");
  if (l.layers == 0) badToken(token, "layer count must be at least 1");
  if (l.kind == LightKind::directional && l.layers > 4)
    badToken(token, "a directional light has 1 to 4 cascades, got " + std::to_string(l.layers));
  if (l.kind == LightKind::spot && l.layers != 1)
    badToken(token, "a spot light has 1 layer, got " + std::to_string(l.layers));
  if (l.kind == LightKind::point && l.layers != 6)
    badToken(token, "a point light has 6 layers (cube faces), got " + std::to_string(l.layers));
  if (uint64_t(l.firstLayer) + l.layers > std::numeric_limits<uint32_t>::max())
    badToken(token, "its layers end beyond layer 4294967295");
  return l;
}

}  // namespace

std::vector<float> cascadeSplits(float near, float far, uint32_t cascades, float lambda) {
  const uint32_t n = std::max(cascades, 1u);
  const double lo = near, hi = far, mix = std::clamp(double(lambda), 0.0, 1.0);
  std::vector<float> splits(n + 1);
  for (uint32_t i = 1; i < n; ++i) {
    const double t = double(i) / n;
    const double logarithmic = lo > 0.0 ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t;
    splits[i] = float(mix * logarithmic + (1.0 - mix) * (lo + (hi - lo) * t));
  }
  splits.front() = near;
  splits.back() = far;
  return splits;
}

std::vector<ShadowView> shadowViews(const Scene& scene, const Camera& camera, float aspect,
                                    const ShadowSettings& settings, const std::vector<ShadowedLight>& lights) {
  std::vector<ShadowView> out;
  size_t layers = 0;
  for (const ShadowedLight& l : lights) layers += l.layers;
  out.reserve(layers);
  const Bounds bounds = scene.bounds();  // once: every spot and point light's reach is capped by it
  for (const ShadowedLight& l : lights) {
    switch (l.kind) {
      case LightKind::directional: directionalViews(scene, camera, aspect, settings, l, out); break;
      case LightKind::spot: spotView(scene, bounds, settings, l, out); break;
      case LightKind::point: pointViews(scene, bounds, settings, l, out); break;
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const ShadowView& a, const ShadowView& b) { return a.layer < b.layer; });
  return out;
}

std::string encode(const std::vector<ShadowedLight>& lights) {
  std::string s;
  for (const ShadowedLight& l : lights) {
    if (!s.empty()) s += ' ';
    s += kindLetter(l.kind);
    s += std::to_string(l.light) + ':' + std::to_string(l.firstLayer) + '+' + std::to_string(l.layers);
  }
  return s;
}

std::vector<ShadowedLight> decode(std::string_view text) {
  std::vector<ShadowedLight> out;
  size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ') {
      ++i;
      continue;
    }
    const size_t end = std::min(text.find(' ', i), text.size());
    out.push_back(parseToken(text.substr(i, end - i)));
    i = end;
  }
  return out;
}

float texelFootprint(const ShadowView& view, const glm::vec3& p, uint32_t resolution) {
  // From the projection rather than texelWorld, so that a map drawn at another
  // resolution than the settings' (a downsized light) reports its own texels:
  // 2 / proj[0][0] is an ortho map's width, a perspective map's 2 tan(fov / 2)
  // (the larger of width and height: an unstabilised cascade is not square).
  const float scale = std::min(std::abs(view.proj[0][0]), std::abs(view.proj[1][1]));
  const float perUnit = 2.0f / std::max(scale, 1e-30f) / float(std::max(resolution, 1u));
  if (view.kind == LightKind::directional) return perUnit;
  const float depth = -(view.view * glm::vec4(p, 1.0f)).z;  // along the map's axis: view space looks down -z
  return perUnit * std::max(depth, 0.0f);
}

}  // namespace rgraph::shadows
