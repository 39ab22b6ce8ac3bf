// Independent CPU oracle of the lighting and tone-mapping maths, in double
// precision, written from the published formulas (LearnOpenGL's "Advanced
// Lighting" Blinn-Phong and "PBR / Lighting" Cook-Torrance chapters, glTF's
// occlusion definition, KHR_lights_punctual's spot cone, Narkowicz's ACES fit, IEC 61966-2-1 sRGB) and NOT from
// shaders/include/lighting.glsl, which is what the oracle tests check. Keep it
// that way: a change here must come from the formulas, never from the GLSL.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace rgraph::oracle {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;

enum class Model { blinnPhong, cookTorrance };
enum class Falloff { classic, smooth };

struct Surface {
  dvec3 position{0.0}, normal{0.0, 1.0, 0.0};
  dvec3 albedo{1.0};
  double specular = 0.5;  // Blinn-Phong specular intensity
  double metallic = 0.0, roughness = 1.0;
  double ao = 1.0;  // ambient occlusion (1: none)
};

struct Point {
  dvec3 position{0.0};
  dvec3 radiance{1.0};  // colour * intensity
  double kc = 1.0, kl = 0.7, kq = 1.8;
  double radius = -1.0;  // smooth: where it reaches zero; classic: cut-off distance (< 0: none)
  // A spot light (glTF KHR_lights_punctual): unit axis, half-angles in degrees.
  bool spot = false;
  dvec3 axis{0.0, -1.0, 0.0};
  double innerDeg = 0.0, outerDeg = 45.0;
};

// KHR_lights_punctual's recommended angular attenuation of a spot light:
// lightAngleScale = 1 / max(0.001, cos(inner) - cos(outer)),
// lightAngleOffset = -cos(outer) * lightAngleScale, and with cd the cosine
// between the spot direction and the direction from the light to the point,
// clamp(cd * scale + offset, 0, 1) squared. 1 for a point light.
inline double spotAttenuation(const Point& l, dvec3 lightToPoint) {
  if (!l.spot) return 1.0;
  const double cosOuter = std::cos(l.outerDeg * kPi / 180.0), cosInner = std::cos(l.innerDeg * kPi / 180.0);
  const double scale = 1.0 / std::max(0.001, cosInner - cosOuter);
  const double offset = -cosOuter * scale;
  const double cd = glm::dot(l.axis, glm::normalize(lightToPoint));
  const double a = std::clamp(cd * scale + offset, 0.0, 1.0);
  return a * a;
}

// Classic: 1 / (kc + kl d + kq d^2), zero beyond the cut-off radius if there
// is one. Smooth: max(1 - (d/r)^2, 0).
inline double attenuation(const Point& l, double d, Falloff f) {
  if (f == Falloff::smooth) {
    const double x = d / l.radius;
    return std::max(1.0 - x * x, 0.0);
  }
  if (l.radius >= 0.0 && d > l.radius) return 0.0;
  return 1.0 / (l.kc + l.kl * d + l.kq * d * d);
}

// The distance where the classic falloff of the brightest channel reaches
// `threshold`: the positive root of kq r^2 + kl r + kc = brightest / threshold.
inline double radiusAtThreshold(const Point& l, double threshold) {
  const double brightest = std::max({l.radiance.r, l.radiance.g, l.radiance.b});
  const double c = l.kc - brightest / threshold;
  return (-l.kl + std::sqrt(l.kl * l.kl - 4.0 * l.kq * c)) / (2.0 * l.kq);
}

// LearnOpenGL Blinn-Phong: diffuse max(N.L, 0) albedo, specular
// max(N.H, 0)^16 times the specular intensity (no N.L factor on it).
inline dvec3 blinnPhong(dvec3 N, dvec3 V, dvec3 L, dvec3 radiance, const Surface& s) {
  const dvec3 H = glm::normalize(L + V);
  const double diffuse = std::max(glm::dot(N, L), 0.0);
  const double spec = std::pow(std::max(glm::dot(N, H), 0.0), 16.0) * s.specular;
  return diffuse * s.albedo * radiance + spec * radiance;
}

// Cook-Torrance for direct light, as in LearnOpenGL's PBR chapter.
inline dvec3 cookTorrance(dvec3 N, dvec3 V, dvec3 L, dvec3 radiance, const Surface& s) {
  const double nl = std::max(glm::dot(N, L), 0.0);
  if (nl == 0.0) return dvec3(0.0);  // the whole BRDF is multiplied by N.L
  const dvec3 H = glm::normalize(L + V);
  const double nv = std::max(glm::dot(N, V), 0.0);
  const double nh = std::max(glm::dot(N, H), 0.0);
  const double hv = std::max(glm::dot(H, V), 0.0);
  const double r = s.roughness;
  // Trowbridge-Reitz GGX with alpha = roughness^2.
  const double a = r * r, a2 = a * a;
  const double denom = nh * nh * (a2 - 1.0) + 1.0;
  const double D = a2 / (kPi * denom * denom);
  // Schlick-GGX with k = (r + 1)^2 / 8 (direct lighting), Smith's product.
  const double k = (r + 1.0) * (r + 1.0) / 8.0;
  const auto g1 = [k](double x) { return x / (x * (1.0 - k) + k); };
  const double G = g1(nv) * g1(nl);
  // Schlick Fresnel at H.V with F0 = mix(0.04, albedo, metallic).
  const dvec3 F0 = dvec3(0.04) * (1.0 - s.metallic) + s.albedo * s.metallic;
  const dvec3 F = F0 + (dvec3(1.0) - F0) * std::pow(1.0 - hv, 5.0);
  // The 0.001 guard of the chapter only matters at grazing angles.
  const dvec3 specular = D * G * F / std::max(4.0 * nv * nl, 0.001);
  const dvec3 kD = (dvec3(1.0) - F) * (1.0 - s.metallic);
  return (kD * s.albedo / kPi + specular) * radiance * nl;
}

inline dvec3 brdf(Model m, dvec3 N, dvec3 V, dvec3 L, dvec3 radiance, const Surface& s) {
  return m == Model::blinnPhong ? blinnPhong(N, V, L, radiance, s) : cookTorrance(N, V, L, radiance, s);
}

inline dvec3 pointLight(Model m, Falloff f, const Point& l, const Surface& s, dvec3 eye) {
  const dvec3 toLight = l.position - s.position;
  const double d = glm::length(toLight);
  const dvec3 V = glm::normalize(eye - s.position);
  return brdf(m, s.normal, V, toLight / d, l.radiance * attenuation(l, d, f) * spotAttenuation(l, -toLight), s);
}

// `direction`: where the light travels (the surface sees it from -direction).
inline dvec3 directionalLight(Model m, dvec3 direction, dvec3 radiance, const Surface& s, dvec3 eye) {
  const dvec3 V = glm::normalize(eye - s.position);
  return brdf(m, s.normal, V, -glm::normalize(direction), radiance, s);
}

inline dvec3 ambient(dvec3 ambientColour, const Surface& s) { return ambientColour * s.albedo * s.ao; }

// glTF 2.0: occlusion = 1 + strength * (texel - 1).
inline double gltfOcclusion(double texel, double strength) { return 1.0 + strength * (texel - 1.0); }

// ---------------------------------------------------------------- tone mapping

enum class Curve { none, reinhard, aces };

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14).
inline double acesFit(double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); }

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
inline double srgbEncode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

// One channel: exposure, the curve, clamp to [0, 1], then the sRGB curve
// (gamma 0) or pow(c, 1/gamma).
inline double toneMap(double hdr, Curve curve, double exposure, double gamma) {
  double c = std::max(hdr, 0.0) * exposure;
  if (curve == Curve::reinhard) c = c / (1.0 + c);
  if (curve == Curve::aces) c = acesFit(c);
  c = std::clamp(c, 0.0, 1.0);
  return gamma > 0.0 ? std::pow(c, 1.0 / gamma) : srgbEncode(c);
}

}  // namespace rgraph::oracle
