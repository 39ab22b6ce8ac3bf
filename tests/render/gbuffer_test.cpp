// G-buffer values at probed pixels of a known box: the centre pixel of each
// visible face. The expected values come from an analytic ray cast through
// that pixel's centre (double precision): the world position of the hit, the
// face normal, the material's albedo/specular/metallic/roughness.
//   fp32:        position within 1e-4, normal and material exact
//   learnopengl: position within one half-float ulp, normal exact, albedo and
//                specular exactly the bytes of the material colour
//   compact:     octahedral normal decoded (in the test and by gbuffer_view)
//                exactly for axis normals, within 2e-3 otherwise; position
//                rebuilt from depth within 1e-3; albedo and metallic/roughness bytes
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{128, 128};
const glm::vec4 kAlbedo{51 / 255.0f, 153 / 255.0f, 204 / 255.0f, 1.0f};  // 0.2, 0.6, 0.8: exact bytes
constexpr float kSpecular = 102 / 255.0f;                               // 0.4
constexpr float kMetallic = 0.25f, kRoughness = 0.75f;

// A unit cube (half extent 0.5) under `xf`, seen from above-front-right so
// that its +X, +Y and +Z faces are visible.
Scene boxScene(const glm::mat4& xf) {
  Scene s;
  s.source = "test:box";
  const int cube = addMesh(s, makeCube(0.5f));
  const int mat = addMaterial(s, kAlbedo, kMetallic, kRoughness, kSpecular);
  addDraw(s, cube, mat, xf, "box");
  DirectionalLight sun;
  s.directionalLights.push_back(sun);
  s.camera.position = glm::vec3(1.2f, 1.5f, 3.0f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = 20.0f;
  s.hasCamera = true;
  return s;
}

struct Probe {
  std::string face;
  int x = 0, row = 0;
  glm::dvec3 position;  // world
  glm::dvec3 normal;    // world, unit
};

// The centre pixel of each face whose normal faces the camera, with the
// analytic hit of the ray through that pixel's centre.
std::vector<Probe> probes(const Scene& s, const glm::dmat4& xf) {
  std::vector<Probe> out;
  const glm::dmat4 inv = glm::inverse(xf);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(xf)));
  const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (int f = 0; f < 6; ++f) {
    glm::dvec3 axis(0.0);
    axis[f / 2] = (f % 2 == 0) ? 1.0 : -1.0;
    const glm::dvec3 centre = glm::dvec3(xf * glm::dvec4(axis * 0.5, 1.0));
    const glm::dvec3 n = glm::normalize(normalMatrix * axis);
    if (glm::dot(n, glm::dvec3(s.camera.position) - centre) <= 0.1) continue;  // facing away (or nearly edge-on)
    auto sp = project(s.camera, kSize, centre);
    if (!sp) continue;
    Probe p;
    p.face = names[f];
    p.x = sp->px();
    p.row = sp->prow();
    const Ray ray = pixelRay(s.camera, kSize, p.x, p.row);
    // Cast in the box's local space.
    Ray local;
    local.origin = glm::dvec3(inv * glm::dvec4(ray.origin, 1.0));
    local.dir = glm::dvec3(inv * glm::dvec4(ray.dir, 0.0));
    auto t = hitBox(local, glm::dvec3(-0.5), glm::dvec3(0.5));
    if (!t) continue;
    const glm::dvec3 hitLocal = local.origin + *t * local.dir;
    // The pixel must really see this face, well inside it.
    if (std::abs(hitLocal[f / 2] - axis[f / 2] * 0.5) > 1e-9) continue;
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (a != f / 2 && std::abs(hitLocal[a]) > 0.4) inside = false;
    if (!inside) continue;
    p.position = glm::dvec3(xf * glm::dvec4(hitLocal, 1.0));
    p.normal = n;
    out.push_back(p);
  }
  return out;
}

struct Texel {
  const std::vector<float>& data;
  glm::vec4 at(int x, int row) const {
    const size_t i = (static_cast<size_t>(row) * kSize.width + static_cast<size_t>(x)) * 4;
    return {data[i], data[i + 1], data[i + 2], data[i + 3]};
  }
};

glm::dvec3 decodeOctahedral(glm::dvec2 e) {
  glm::dvec3 n(e.x, e.y, 1.0 - std::abs(e.x) - std::abs(e.y));
  const double t = std::clamp(-n.z, 0.0, 1.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return glm::normalize(n);
}

std::string vecText(glm::dvec3 v) {
  char b[128];
  std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return b;
}

double maxAbs(glm::dvec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

int byteOf(float unorm) { return static_cast<int>(std::lround(unorm * 255.0f)); }

class GBufferProbe : public RenderTest {
 protected:
  struct Targets {
    std::vector<float> position, normal, albedo, material, depth;
    Image view;
  };
  Targets renderLayout(const std::string& pipeline, const Scene& scene, const std::string& view = "normal") {
    PipelineConfig cfg = loadPipeline(testPipeline(pipeline));
    setParam(cfg, "show", "view", view);
    Targets t;
    t.view = render(cfg, scene, kSize, *shaders, [&](Executor& e) {
      for (const auto& [name, dst] : {std::pair<const char*, std::vector<float>*>{"gPosition", &t.position},
                                      {"gNormal", &t.normal},
                                      {"gAlbedoSpec", &t.albedo},
                                      {"gAlbedo", &t.albedo},
                                      {"gMaterial", &t.material},
                                      {"gDepth", &t.depth}})
        if (e.textureOf(name)) *dst = e.readTextureRGBA32F(name);
    });
    return t;
  }
};

void checkProbes(const std::vector<Probe>& ps, size_t wanted) {
  ASSERT_GE(ps.size(), wanted) << "expected " << wanted << " visible faces to probe";
}

}  // namespace

TEST_F(GBufferProbe, Fp32LayoutIsExact) {
  const Scene scene = boxScene(glm::mat4(1.0f));
  const auto ps = probes(scene, glm::dmat4(1.0));
  checkProbes(ps, 3);
  const Targets t = renderLayout("gbuffer-fp32.json", scene);
  ASSERT_FALSE(t.position.empty());
  ASSERT_FALSE(t.material.empty());
  double worstPos = 0.0;
  for (const Probe& p : ps) {
    SCOPED_TRACE("face " + p.face + " pixel (" + std::to_string(p.x) + "," + std::to_string(p.row) + ")");
    const glm::vec4 pos = Texel{t.position}.at(p.x, p.row);
    const glm::vec4 n = Texel{t.normal}.at(p.x, p.row);
    const glm::vec4 a = Texel{t.albedo}.at(p.x, p.row);
    const glm::vec4 m = Texel{t.material}.at(p.x, p.row);
    const double posErr = maxAbs(glm::dvec3(pos) - p.position);
    worstPos = std::max(worstPos, posErr);
    EXPECT_LE(posErr, 1e-4) << "position " << vecText(glm::dvec3(pos)) << ", ray hit " << vecText(p.position);
    EXPECT_EQ(pos.w, 1.0f);
    // An axis-aligned face: the normal is exactly the axis.
    EXPECT_EQ(glm::vec3(n), glm::vec3(p.normal)) << "normal " << vecText(glm::dvec3(n));
    EXPECT_EQ(n.w, 1.0f);
    EXPECT_EQ(glm::vec3(a), glm::vec3(kAlbedo));
    EXPECT_EQ(a.w, kSpecular);
    EXPECT_EQ(m.x, kMetallic);
    EXPECT_EQ(m.y, kRoughness);
    EXPECT_EQ(m.z, 1.0f);  // ambient occlusion: none
  }
  std::printf("[ measure  ] fp32 G-buffer: max position error %.3g at %zu probes\n", worstPos, ps.size());
  // Uncovered pixels are zero (normal.w = 0: no surface).
  EXPECT_EQ(Texel{t.normal}.at(0, 0), glm::vec4(0.0f));
  EXPECT_EQ(Texel{t.position}.at(0, 0), glm::vec4(0.0f));
}

TEST_F(GBufferProbe, Fp32LayoutRotatedBox) {
  const glm::mat4 xf = glm::rotate(glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0)),
                                   glm::radians(20.0f), glm::vec3(1, 0, 0));
  const Scene scene = boxScene(xf);
  const auto ps = probes(scene, glm::dmat4(xf));
  checkProbes(ps, 2);
  const Targets t = renderLayout("gbuffer-fp32.json", scene);
  for (const Probe& p : ps) {
    SCOPED_TRACE("face " + p.face);
    const glm::vec4 pos = Texel{t.position}.at(p.x, p.row);
    const glm::vec4 n = Texel{t.normal}.at(p.x, p.row);
    EXPECT_LE(maxAbs(glm::dvec3(pos) - p.position), 1e-4) << vecText(glm::dvec3(pos)) << " vs " << vecText(p.position);
    EXPECT_LE(maxAbs(glm::dvec3(n) - p.normal), 1e-6) << vecText(glm::dvec3(n)) << " vs " << vecText(p.normal);
    EXPECT_EQ(glm::vec3(Texel{t.albedo}.at(p.x, p.row)), glm::vec3(kAlbedo));
  }
}

TEST_F(GBufferProbe, LearnOpenGLLayoutWithinHalfPrecision) {
  const Scene scene = boxScene(glm::mat4(1.0f));
  const auto ps = probes(scene, glm::dmat4(1.0));
  checkProbes(ps, 3);
  const Targets t = renderLayout("gbuffer-learnopengl.json", scene, "albedo");
  ASSERT_FALSE(t.position.empty());
  ASSERT_FALSE(t.albedo.empty());
  for (const Probe& p : ps) {
    SCOPED_TRACE("face " + p.face);
    const glm::vec4 pos = Texel{t.position}.at(p.x, p.row);
    for (int c = 0; c < 3; ++c) {
      // Half floats keep 11 significant bits. GL lets the conversion round to
      // nearest or toward zero (llvmpipe truncates): up to one half-float ulp,
      // |v| * 2^-10, plus what the interpolation in fp32 adds.
      const double tol = std::abs(p.position[c]) * std::ldexp(1.0, -10) + 1e-5;
      EXPECT_NEAR(pos[c], p.position[c], tol) << "position component " << c;
    }
    EXPECT_EQ(glm::vec3(Texel{t.normal}.at(p.x, p.row)), glm::vec3(p.normal));
    const glm::vec4 a = Texel{t.albedo}.at(p.x, p.row);
    EXPECT_EQ(byteOf(a.r), 51);
    EXPECT_EQ(byteOf(a.g), 153);
    EXPECT_EQ(byteOf(a.b), 204);
    EXPECT_EQ(byteOf(a.a), 102);  // specular 0.4
    // The albedo view shows those very bytes.
    EXPECT_EQ(t.view.rgb(p.x, p.row), glm::ivec3(51, 153, 204));
  }
}

TEST_F(GBufferProbe, CompactLayoutDecodesNormalsAndRebuildsPosition) {
  for (bool rotated : {false, true}) {
    SCOPED_TRACE(rotated ? "rotated box" : "axis-aligned box");
    const glm::mat4 xf = rotated ? glm::rotate(glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0)),
                                               glm::radians(20.0f), glm::vec3(1, 0, 0))
                                 : glm::mat4(1.0f);
    const Scene scene = boxScene(xf);
    const auto ps = probes(scene, glm::dmat4(xf));
    checkProbes(ps, rotated ? 2 : 3);
    const Targets t = renderLayout("gbuffer-compact.json", scene, "normal_abs");
    ASSERT_FALSE(t.normal.empty());
    ASSERT_FALSE(t.depth.empty());
    const glm::dmat4 invViewProj = glm::inverse(glm::dmat4(scene.camera.viewProjection(1.0f)));
    double worstN = 0.0, worstP = 0.0;
    for (const Probe& p : ps) {
      SCOPED_TRACE("face " + p.face);
      const glm::vec4 enc = Texel{t.normal}.at(p.x, p.row);
      const glm::dvec3 n = decodeOctahedral({enc.x, enc.y});
      worstN = std::max(worstN, maxAbs(n - p.normal));
      if (!rotated) {
        EXPECT_EQ(n, p.normal) << "decoded " << vecText(n);
        // gbuffer_view decodes in the shader: |n| of an axis normal is exactly that axis.
        EXPECT_EQ(t.view.rgb(p.x, p.row), glm::ivec3(glm::abs(p.normal) * 255.0)) << "normal_abs view";
      } else {
        EXPECT_LE(maxAbs(n - p.normal), 2e-3) << "decoded " << vecText(n) << " vs " << vecText(p.normal);
      }
      // Position from depth, as the lighting passes rebuild it.
      const double depth = Texel{t.depth}.at(p.x, p.row).x;
      const glm::dvec4 ndc((p.x + 0.5) / kSize.width * 2.0 - 1.0, 1.0 - (p.row + 0.5) / kSize.height * 2.0,
                           depth * 2.0 - 1.0, 1.0);
      glm::dvec4 w = invViewProj * ndc;
      w /= w.w;
      worstP = std::max(worstP, maxAbs(glm::dvec3(w) - p.position));
      EXPECT_LE(maxAbs(glm::dvec3(w) - p.position), 1e-3) << vecText(glm::dvec3(w)) << " vs " << vecText(p.position);
      const glm::vec4 a = Texel{t.albedo}.at(p.x, p.row);
      EXPECT_EQ(glm::ivec4(byteOf(a.r), byteOf(a.g), byteOf(a.b), byteOf(a.a)), glm::ivec4(51, 153, 204, 102));
      const glm::vec4 m = Texel{t.material}.at(p.x, p.row);
      EXPECT_EQ(byteOf(m.x), 64);   // metallic 0.25
      EXPECT_EQ(byteOf(m.y), 191);  // roughness 0.75
    }
    std::printf("[ measure  ] compact G-buffer (%s): max decoded-normal error %.3g, position-from-depth error %.3g\n",
                rotated ? "rotated" : "axis-aligned", worstN, worstP);
    EXPECT_EQ(Texel{t.depth}.at(0, 0).x, 1.0f) << "background depth";
  }
}
