// The lighting maths of deferred_lighting and forward_lit against the
// independent double-precision oracle of lighting_oracle.h, at probed pixels
// of a known scene: one large plane (y = 0, normal +Y) seen from above at an
// angle, one material, known lights. Both pipelines render into rgba32f HDR
// targets (tests/render/pipelines/deferred-fp32.json and forward-lit.json)
// with no cut-off (threshold 0; the smooth falloff needs a radius, so there
// threshold 5/256), and the HDR floats are read back, not the 8-bit output.
//
// Expected value per probe: the oracle at the exact hit of the ray through the
// pixel centre. Tolerance per channel:
//   1e-4 * |expected|  fp32 evaluation of the formulas: a few dozen roundings of
//                      2^-24 each, pow() with exponent 16 multiplies the
//                      relative error of its base by 16, and GGX's peak at
//                      roughness 0.2 amplifies errors in N.H (measured worst:
//                      2.3e-5 there, ~1e-6 elsewhere), so 1e-4 leaves a margin
//                      of 4; every mutation of scripts/mutate-lighting.sh
//                      changes some probe by more;
//   + position term    the largest change of the oracle when the surface point
//                      moves by kPositionError along the plane (the rasterised
//                      position is interpolated in fp32; the deferred run
//                      checks that the G-buffer holds the hit within it);
//   + 1e-7             absolute floor for values that are (nearly) zero.
#include <cstdio>
#include <string>
#include <vector>

#include "oracle/lighting_oracle.h"
#include "support/render_util.h"
#include "render/test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;
namespace o = rgraph::oracle;

namespace {

constexpr Extent kSize{64, 64};
constexpr double kRelTolerance = 1e-4;
constexpr double kAbsTolerance = 1e-7;
constexpr double kPositionError = 1e-5;  // world units; ~20 fp32 ulps at |coordinate| <= 6
constexpr float kPlaneHalfSize = 6.0f;
constexpr float kRadiusThreshold = 5.0f / 256.0f;  // for the smooth falloff and the cut-off case

struct Light {
  glm::dvec3 position{0.0};
  glm::dvec3 color{1.0};  // intensity 1: the colour is the radiance
  double kc = 1.0, kl = 0.35, kq = 0.44;
  bool spot = false;  // a spot light: axis (unit), inner and outer half-angles in degrees
  glm::dvec3 axis{0.0, -1.0, 0.0};
  double innerDeg = 0.0, outerDeg = 45.0;
};

struct LitScene {
  o::Model model = o::Model::blinnPhong;
  o::Falloff falloff = o::Falloff::classic;
  glm::dvec3 albedo{0.8, 0.6, 0.4};
  double specular = 0.7, metallic = 0.0, roughness = 0.5;
  int occlusionByte = -1;  // >= 0: a 1x1 occlusion texture with this red byte
  double occlusionStrength = 1.0;
  std::vector<Light> points;
  bool sun = false;
  glm::dvec3 sunDirection{0.0, -1.0, 0.0}, sunColor{1.0};
  glm::dvec3 ambient{0.05, 0.05, 0.05};
  std::vector<glm::dvec3> focus;  // points on the plane whose pixels are probed too
  bool cutoff = false;             // classic falloff cut off at the threshold's radius
};

// The smooth falloff and the cut-off need a radius: the light's at 5/256.
bool usesRadius(const LitScene& u) { return u.falloff == o::Falloff::smooth || u.cutoff; }

// Values in the scene are floats; the oracle takes exactly those floats.
glm::dvec3 asFloat(glm::dvec3 v) { return glm::dvec3(glm::vec3(v)); }

Scene makeScene(const LitScene& u) {
  Scene s;
  s.source = "test:oracle-plane";
  const int plane = addMesh(s, makePlane(kPlaneHalfSize, kPlaneHalfSize));
  const int mat = addMaterial(s, glm::vec4(glm::vec3(u.albedo), 1.0f), static_cast<float>(u.metallic),
                              static_cast<float>(u.roughness), static_cast<float>(u.specular));
  if (u.occlusionByte >= 0) {
    ImageData img;
    img.name = "occlusion";
    img.width = img.height = 1;
    img.rgba = {static_cast<uint8_t>(u.occlusionByte), 0, 0, 255};
    s.images.push_back(img);
    SceneTexture t;
    t.image = 0;
    s.textures.push_back(t);
    s.materials[static_cast<size_t>(mat)].occlusionTexture.texture = 0;
    s.materials[static_cast<size_t>(mat)].occlusionStrength = static_cast<float>(u.occlusionStrength);
  }
  addDraw(s, plane, mat, glm::mat4(1.0f), "plane");
  for (const Light& l : u.points) {
    PointLight p = pointLight(glm::vec3(l.position), glm::vec3(l.color), 1.0f, static_cast<float>(l.kl),
                              static_cast<float>(l.kq));
    p.constant = static_cast<float>(l.kc);
    p.spot = l.spot;
    p.direction = glm::vec3(l.axis);
    p.innerConeDeg = static_cast<float>(l.innerDeg);
    p.outerConeDeg = static_cast<float>(l.outerDeg);
    s.pointLights.push_back(p);
  }
  if (u.sun) {
    DirectionalLight d;
    d.direction = glm::normalize(glm::vec3(u.sunDirection));
    d.color = glm::vec3(u.sunColor);
    s.directionalLights.push_back(d);
  }
  s.ambient = glm::vec3(u.ambient);
  s.camera.position = glm::vec3(0.0f, 4.0f, 3.0f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.near = 0.1f;
  s.camera.far = 30.0f;
  s.hasCamera = true;
  return s;
}

struct Probe {
  int x, row;
  glm::dvec3 hit;
};

// A grid of pixels whose rays hit the plane well inside its edges, and the
// pixels of the focus points.
std::vector<Probe> probes(const Camera& cam, const std::vector<glm::dvec3>& focus = {}) {
  std::vector<Probe> out;
  const auto add = [&](int x, int row) {
    const Ray r = pixelRay(cam, kSize, x, row);
    if (r.dir.y >= 0.0) return;
    const glm::dvec3 hit = r.origin + (-r.origin.y / r.dir.y) * r.dir;
    if (std::abs(hit.x) < kPlaneHalfSize - 0.5 && std::abs(hit.z) < kPlaneHalfSize - 0.5)
      out.push_back({x, row, glm::dvec3(hit.x, 0.0, hit.z)});
  };
  for (int row = 4; row < static_cast<int>(kSize.height); row += 7)
    for (int x = 3; x < static_cast<int>(kSize.width); x += 7) add(x, row);
  for (const glm::dvec3& f : focus) {
    const auto sp = project(cam, kSize, f);
    if (sp) add(sp->px(), sp->prow());
  }
  return out;
}

// The oracle's radiance at a surface point.
glm::dvec3 expected(const LitScene& u, const Scene& scene, glm::dvec3 p) {
  o::Surface s;
  s.position = p;
  s.normal = {0.0, 1.0, 0.0};
  s.albedo = asFloat(u.albedo);
  s.specular = static_cast<float>(u.specular);
  s.metallic = static_cast<float>(u.metallic);
  s.roughness = static_cast<float>(u.roughness);
  if (u.occlusionByte >= 0)
    s.ao = o::gltfOcclusion(u.occlusionByte / 255.0, static_cast<float>(u.occlusionStrength));
  const glm::dvec3 eye(scene.camera.position);
  glm::dvec3 c = o::ambient(asFloat(u.ambient), s);
  if (u.sun) c += o::directionalLight(u.model, asFloat(u.sunDirection), asFloat(u.sunColor), s, eye);
  for (const Light& l : u.points) {
    o::Point pl;
    pl.position = asFloat(l.position);
    pl.radiance = asFloat(l.color);
    pl.kc = static_cast<float>(l.kc);
    pl.kl = static_cast<float>(l.kl);
    pl.kq = static_cast<float>(l.kq);
    pl.radius = usesRadius(u) ? o::radiusAtThreshold(pl, kRadiusThreshold) : -1.0;
    pl.spot = l.spot;
    pl.axis = asFloat(l.axis);
    pl.innerDeg = static_cast<float>(l.innerDeg);
    pl.outerDeg = static_cast<float>(l.outerDeg);
    c += o::pointLight(u.model, u.falloff, pl, s, eye);
  }
  return c;
}

// Largest change of the oracle, per channel, when p moves by kPositionError in the plane.
glm::dvec3 positionSensitivity(const LitScene& u, const Scene& scene, glm::dvec3 p) {
  const glm::dvec3 c = expected(u, scene, p);
  glm::dvec3 worst(0.0);
  for (const glm::dvec3 step : {glm::dvec3(kPositionError, 0, 0), glm::dvec3(0, 0, kPositionError)})
    for (const double sign : {-1.0, 1.0}) worst = glm::max(worst, glm::abs(expected(u, scene, p + sign * step) - c));
  return worst;
}

struct PipelineRun {
  const char* file;
  const char* lightingPass;
};
constexpr PipelineRun kPipelines[] = {{"deferred-fp32.json", "lighting"}, {"forward-lit.json", "forward_lit"}};

class Oracle : public RenderTest {
 protected:
  // Renders `u` with both pipelines and checks every probe against the oracle.
  void check(const LitScene& u, const std::string& name) {
    const Scene scene = makeScene(u);
    const std::vector<Probe> ps = probes(scene.camera, u.focus);
    ASSERT_GE(ps.size(), 40u) << "the probe grid should mostly hit the plane";
    // The smooth radius must not be capped by the scene bounds (GpuScene caps it there).
    if (usesRadius(u)) {
      for (const PointLight& l : scene.pointLights)
        ASSERT_LT(lightRadius(l, kRadiusThreshold),
                  glm::length(l.position - scene.bounds().center()) + scene.bounds().radius());
    }
    for (const PipelineRun& run : kPipelines) {
      SCOPED_TRACE(std::string(run.file) + ", case " + name);
      PipelineConfig cfg = loadPipeline(testPipeline(run.file));
      const bool smooth = u.falloff == o::Falloff::smooth;
      for (const char* pass : {run.lightingPass, "forward"}) {
        setParam(cfg, pass, "model", std::string(u.model == o::Model::blinnPhong ? "blinn_phong" : "cook_torrance"));
        setParam(cfg, pass, "attenuation", std::string(smooth ? "smooth" : "classic"));
        setParam(cfg, pass, "threshold", usesRadius(u) ? static_cast<double>(kRadiusThreshold) : 0.0);
      }
      std::vector<float> hdr, position;
      render(cfg, scene, kSize, *shaders, [&](Executor& e) {
        hdr = e.readTextureRGBA32F("hdr_forward");
        if (e.textureOf("gPosition")) position = e.readTextureRGBA32F("gPosition");
      });
      ASSERT_EQ(hdr.size(), static_cast<size_t>(kSize.width) * kSize.height * 4);
      double worstRatio = 0.0, worstRel = 0.0, worstPosition = 0.0;
      for (const Probe& p : ps) {
        const size_t i = (static_cast<size_t>(p.row) * kSize.width + static_cast<size_t>(p.x)) * 4;
        if (!position.empty()) {
          const glm::dvec3 g(position[i], position[i + 1], position[i + 2]);
          worstPosition = std::max(worstPosition, glm::length(g - p.hit));
          ASSERT_LE(glm::length(g - p.hit), kPositionError)
              << "G-buffer position at (" << p.x << "," << p.row << ") is not the ray hit: the tolerance assumes it";
        }
        const glm::dvec3 want = expected(u, scene, p.hit);
        const glm::dvec3 slack = positionSensitivity(u, scene, p.hit);
        for (int c = 0; c < 3; ++c) {
          const double got = hdr[i + static_cast<size_t>(c)];
          const double tol = kRelTolerance * std::abs(want[c]) + slack[c] + kAbsTolerance;
          const double err = std::abs(got - want[c]);
          worstRatio = std::max(worstRatio, err / tol);
          if (std::abs(want[c]) > 1e-6) worstRel = std::max(worstRel, err / std::abs(want[c]));
          EXPECT_LE(err, tol) << "pixel (" << p.x << "," << p.row << ") channel " << c << ": got " << got
                              << ", oracle " << want[c] << " (hit " << p.hit.x << ", " << p.hit.z << ")";
        }
      }
      char gpos[64] = "";
      if (!position.empty()) std::snprintf(gpos, sizeof gpos, ", G-buffer position error %.3g", worstPosition);
      std::printf("[ measure  ] %s %s: %zu probes, worst error %.3g of the tolerance, worst relative error %.3g%s\n",
                  name.c_str(), run.file, ps.size(), worstRatio, worstRel, gpos);
    }
  }
};

LitScene cookTorrance(double metallic, double roughness) {
  LitScene u;
  u.model = o::Model::cookTorrance;
  u.metallic = metallic;
  u.roughness = roughness;
  u.points = {{{0.6, 1.2, 0.4}, {4.0, 3.6, 2.8}}};
  return u;
}

}  // namespace

TEST_F(Oracle, BlinnPhongClassicPointLight) {
  LitScene u;
  u.points = {{{0.6, 1.2, 0.4}, {2.0, 1.8, 1.4}}};
  check(u, "blinn-phong-classic");
}

TEST_F(Oracle, BlinnPhongSmoothPointLight) {
  LitScene u;
  u.falloff = o::Falloff::smooth;
  u.points = {{{0.6, 1.2, 0.4}, {2.0, 1.8, 1.4}, 1.0, 0.7, 1.8}};
  check(u, "blinn-phong-smooth");
}

TEST_F(Oracle, BlinnPhongQuadraticOnlyAndConstantOnlyTerms) {
  // Each coefficient alone, so that dropping any one term changes the result.
  LitScene u;
  u.points = {{{-1.5, 0.8, 0.5}, {3.0, 3.0, 3.0}, 0.5, 0.0, 2.0}, {{1.5, 0.8, -0.5}, {2.0, 2.5, 3.0}, 2.0, 1.5, 0.0}};
  check(u, "blinn-phong-coefficients");
}

TEST_F(Oracle, ClassicFalloffCutOffAtTheThresholdRadius) {
  // A dim light: its radius at 5/256 (~2.1) lies inside the view, so some
  // probes are beyond it (no light) and some inside.
  LitScene u;
  u.cutoff = true;
  u.points = {{{0.6, 0.3, 0.4}, {0.2, 0.2, 0.2}, 1.0, 0.7, 1.8}};
  o::Point pl;
  pl.radiance = asFloat(u.points[0].color);
  pl.kc = 1.0;
  pl.kl = static_cast<float>(0.7);
  pl.kq = static_cast<float>(1.8);
  const double r = o::radiusAtThreshold(pl, kRadiusThreshold);
  int inside = 0, beyond = 0;
  for (const Probe& p : probes(makeScene(u).camera)) (glm::length(p.hit - u.points[0].position) < r ? inside : beyond)++;
  ASSERT_GE(inside, 10);
  ASSERT_GE(beyond, 10);
  check(u, "classic-cut-off");
}

TEST_F(Oracle, CookTorranceDielectricSmoothSurface) { check(cookTorrance(0.0, 0.2), "ct-dielectric-r0.2"); }
TEST_F(Oracle, CookTorranceMetalSmoothSurface) { check(cookTorrance(1.0, 0.2), "ct-metal-r0.2"); }
TEST_F(Oracle, CookTorranceDielectricRoughSurface) { check(cookTorrance(0.0, 1.0), "ct-dielectric-r1"); }
TEST_F(Oracle, CookTorranceMetalRoughSurface) { check(cookTorrance(1.0, 1.0), "ct-metal-r1"); }
TEST_F(Oracle, CookTorranceHalfMetalSmoothFalloff) {
  LitScene u = cookTorrance(0.5, 0.5);
  u.falloff = o::Falloff::smooth;
  u.points[0].color = {1.5, 1.2, 1.0};
  u.points[0].kl = 0.7;
  u.points[0].kq = 1.8;
  check(u, "ct-half-metal-smooth");
}

TEST_F(Oracle, DirectionalLight) {
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.sun = true;
    u.sunDirection = {-0.3, -1.0, -0.5};
    u.sunColor = {0.9, 0.8, 1.0};
    check(u, m == o::Model::blinnPhong ? "directional-bp" : "directional-ct");
  }
}

TEST_F(Oracle, GrazingLight) {
  // N.L = 1e-4 for the directional light: Cook-Torrance's denominator guard
  // max(4 N.V N.L, 0.001) is active there. The point light skims the plane.
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.roughness = 0.3;
    u.sun = true;
    u.sunDirection = {1.0, -1e-4, 0.0};
    u.sunColor = {200.0, 150.0, 100.0};
    u.points = {{{-5.0, 0.05, -2.0}, {20.0, 20.0, 20.0}}};
    check(u, m == o::Model::blinnPhong ? "grazing-bp" : "grazing-ct");
  }
}

TEST_F(Oracle, LightBehindTheSurface) {
  // A light below the plane, straight up: N.L = -1, and N.H < 0 as N.V < 1, so
  // both models give nothing and only the ambient term remains.
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.sun = true;
    u.sunDirection = {0.0, 1.0, 0.0};
    u.sunColor = {5.0, 5.0, 5.0};
    if (m == o::Model::cookTorrance) u.points = {{{0.3, -1.0, 0.2}, {5.0, 5.0, 5.0}}};
    const Scene scene = makeScene(u);
    for (const Probe& p : probes(scene.camera)) {
      o::Surface s;
      s.albedo = asFloat(u.albedo);
      ASSERT_EQ(expected(u, scene, p.hit), o::ambient(asFloat(u.ambient), s)) << "the oracle should see no light";
    }
    check(u, m == o::Model::blinnPhong ? "behind-bp" : "behind-ct");
  }
}

TEST_F(Oracle, BlinnPhongSpecularOfALightJustBehindTheSurface) {
  // LearnOpenGL's Blinn-Phong has no N.L factor on the specular term: a light
  // slightly below the plane still gives a highlight where N.H > 0. The
  // renderers follow the formula; so does the oracle.
  LitScene u;
  u.points = {{{0.0, -0.3, -3.0}, {6.0, 6.0, 6.0}}};
  const Scene scene = makeScene(u);
  o::Surface s;
  s.albedo = asFloat(u.albedo);
  int leaks = 0;
  for (const Probe& p : probes(scene.camera))
    if (expected(u, scene, p.hit).r > o::ambient(asFloat(u.ambient), s).r + 1e-3) ++leaks;
  ASSERT_GE(leaks, 3) << "the case should have probes with a specular highlight from below";
  check(u, "behind-bp-specular-leak");
}

TEST_F(Oracle, LightVeryCloseToTheSurface) {
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.roughness = 0.4;
    u.points = {{{0.1, 0.01, 0.05}, {1.0, 0.8, 0.6}, 1.0, 0.7, 1.8}};
    u.focus = {{0.1, 0.0, 0.05}, {0.12, 0.0, 0.05}, {0.1, 0.0, 0.1}};  // right under the light
    check(u, m == o::Model::blinnPhong ? "close-bp" : "close-ct");
  }
}

TEST_F(Oracle, MultipleLightsSum) {
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.metallic = 0.3;
    u.roughness = 0.6;
    u.occlusionByte = 128;
    u.occlusionStrength = 0.8;
    u.ambient = {0.1, 0.12, 0.08};
    u.sun = true;
    u.sunDirection = {0.4, -1.0, 0.2};
    u.sunColor = {0.5, 0.4, 0.3};
    u.points = {{{-1.0, 0.7, 0.5}, {2.0, 0.5, 0.5}},
                {{1.2, 0.5, -0.4}, {0.4, 2.0, 0.6}},
                {{0.0, 1.5, 1.5}, {0.5, 0.6, 2.5}, 1.0, 0.7, 1.8}};
    check(u, m == o::Model::blinnPhong ? "multi-bp" : "multi-ct");
  }
}

TEST_F(Oracle, AmbientTimesOcclusion) {
  // No lights: only ambient * albedo * AO, AO from a 1x1 occlusion texture.
  for (const o::Model m : {o::Model::blinnPhong, o::Model::cookTorrance}) {
    LitScene u;
    u.model = m;
    u.ambient = {0.3, 0.25, 0.2};
    u.occlusionByte = 64;
    check(u, m == o::Model::blinnPhong ? "ambient-ao-bp" : "ambient-ao-ct");
  }
}

namespace {
// A spot light over the plane, its axis tilted; probes in its inner cone,
// on its ramp and outside its outer cone (at least 8 of each).
LitScene spotScene(o::Model m, o::Falloff f) {
  LitScene u;
  u.model = m;
  u.falloff = f;
  u.roughness = 0.4;
  Light spot{{0.4, 2.2, 0.3}, {3.0, 2.6, 2.0}};
  // The smooth falloff's radius must stay inside the scene's bounds (check()).
  spot.kl = f == o::Falloff::smooth ? 0.7 : 0.22;
  spot.kq = f == o::Falloff::smooth ? 1.8 : 0.2;
  spot.spot = true;
  spot.axis = glm::normalize(glm::dvec3(-0.25, -1.0, 0.15));
  spot.innerDeg = 22.0;
  spot.outerDeg = 40.0;
  u.points = {spot};
  u.focus = {{0.4 - 0.55, 0.0, 0.3 + 0.33}};  // on the axis
  return u;
}

void expectProbesAcrossTheCone(const LitScene& u) {
  const Light& l = u.points[0];
  int inner = 0, ramp = 0, outside = 0;
  for (const Probe& p : probes(makeScene(u).camera, u.focus)) {
    const double angle = std::acos(glm::dot(glm::normalize(p.hit - l.position), l.axis)) * 180.0 / o::kPi;
    (angle < l.innerDeg ? inner : angle < l.outerDeg ? ramp : outside)++;
  }
  std::printf("[ measure  ] spot probes: %d inside the inner cone, %d on the ramp, %d outside\n", inner, ramp, outside);
  ASSERT_GE(inner, 8);
  ASSERT_GE(ramp, 8);
  ASSERT_GE(outside, 8);
}
}  // namespace

TEST_F(Oracle, SpotLightConeBlinnPhongClassic) {
  const LitScene u = spotScene(o::Model::blinnPhong, o::Falloff::classic);
  expectProbesAcrossTheCone(u);
  check(u, "spot-bp-classic");
}

TEST_F(Oracle, SpotLightConeCookTorranceSmooth) {
  const LitScene u = spotScene(o::Model::cookTorrance, o::Falloff::smooth);
  expectProbesAcrossTheCone(u);
  check(u, "spot-ct-smooth");
}

TEST_F(Oracle, SpotLightBesidePointLights) {
  // Point lights next to a spot light keep their own (uncut) light: the
  // GPU buffer lists the spot light after them.
  LitScene u = spotScene(o::Model::blinnPhong, o::Falloff::classic);
  u.points.insert(u.points.begin(), Light{{-1.5, 0.8, 0.5}, {1.0, 2.0, 1.0}});
  u.points.push_back(Light{{1.5, 0.6, -1.0}, {2.0, 1.0, 1.0}});
  check(u, "spot-and-points");
}
