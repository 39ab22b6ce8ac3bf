// The SSAO plugin's defining properties against its definition
// (plugins/ssao/ssao.cpp, LearnOpenGL's SSAO): the ambient visibility of a
// pixel at P with normal N is 1 - (occluded samples) / n, the samples lying in
// the hemisphere of radius R over N; a sample s counts as occluded when the
// surface seen through it is in front of it by at least `bias` (view depth),
// weighted by smoothstep(R / |depth(P) - depth(surface)|).
//
// What the tests check:
//   open surfaces  a plane facing the camera, a plane seen 40 degrees off its
//                  normal, a convex cube: AO = 1 exactly (r32f targets), given
//                  that the bias exceeds the depth error of the shader's
//                  nearest-texel lookup (the depth change of the plane across
//                  a texel, computed from the camera: a stated precondition);
//   concave corner floor meeting a wall: per image row, the blurred AO against
//                  an oracle evaluated in double precision (quasi-Monte Carlo
//                  over the kernel's documented distribution: direction
//                  uniform in the unit half-cube, length uniform times
//                  0.1 + 0.9 (i/n)^2, rotation uniform about the normal; the
//                  occlusion test, bias and range weight as defined above),
//                  independent of the plugin's particular random samples.
//                  Tolerance 0.06: the render is a finite-sample estimate
//                  (32 samples x 16 rotations) of that integral, ~2.7 standard
//                  deviations of a mean of 512 indicators (<= 0.5 / sqrt(512));
//                  measured worst 0.026. AO rises monotonically away from the
//                  crease, is below 0.92 next to it and exactly 1 beyond R;
//   range weight   an occluder far in front (depth gap g) counts
//                  smoothstep(R / g) per sample: raw AO = 1 - w k / n, k whole;
//   power          raw AO with power 3 = (raw AO with power 1)^3.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "plugin_oracle.h"
#include "render/test_scenes.h"

using namespace rgraph;
using namespace rgraph::poracle;
using rgraph::rtest::addDraw;
using rgraph::rtest::addMaterial;
using rgraph::rtest::addMesh;

namespace {

struct Ssao {
  double radius = 0.5, bias = 0.025, power = 1.0;
  int kernel = 32;
};

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// (unformatted: the config reads as JSON)
// clang-format off
std::string config(const Ssao& a) {
  return R"({
    "version": 1,
    "resources": {
      "gPosition": { "format": "rgba32f" }, "gNormal": { "format": "rgba16f" },
      "gAlbedo": { "format": "rgba16f" }, "gMaterial": { "format": "rgba16f" }, "gDepth": { "format": "depth32f" },
      "ao_raw": { "format": "r32f" }, "ao": { "format": "r32f" } },
    "passes": [
      { "name": "gbuffer", "type": "geometry", "params": { "layout": "pbr" },
        "outputs": { "position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial",
                     "depth": "gDepth" } },
      { "name": "ssao", "type": "ssao",
        "params": { "layout": "pbr", "radius": )" + num(a.radius) + R"(, "bias": )" + num(a.bias) + R"(,
                    "kernel_size": )" + std::to_string(a.kernel) + R"(, "power": )" + num(a.power) + R"( },
        "inputs": { "position": "gPosition", "normal": "gNormal" }, "outputs": { "ao": "ao_raw" } },
      { "name": "ssao_blur", "type": "ssao_blur", "inputs": { "src": "ao_raw" }, "outputs": { "ao": "ao" } }
    ],
    "output": "ao"
  })";
}
// clang-format on

Camera camera(glm::vec3 position, glm::vec3 target, glm::vec3 up = {0, 1, 0}) {
  Camera c;
  c.position = position;
  c.target = target;
  c.up = up;
  c.fovY = 45.0f;
  c.near = 0.1f;
  c.far = 50.0f;
  return c;
}

// Planes (makePlane: y = 0 facing +Y) under the given transforms.
Scene planes(const std::vector<glm::mat4>& transforms, float halfSize, const Camera& cam) {
  Scene s;
  s.source = "test:ssao-oracle";
  const int mesh = addMesh(s, makePlane(halfSize, halfSize));
  const int mat = addMaterial(s, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), 0.0f, 0.5f);
  for (const glm::mat4& t : transforms) addDraw(s, mesh, mat, t);
  s.camera = cam;
  s.hasCamera = true;
  return s;
}

// ---- camera maths in double: rays through points of the image

struct View {
  glm::dvec3 eye, right, up, forward;
  double tanHalf;  // tan(fovY / 2); square images
};
View view(const Camera& c) {
  View v;
  v.eye = glm::dvec3(c.position);
  v.forward = glm::normalize(glm::dvec3(c.target) - v.eye);
  v.right = glm::normalize(glm::cross(v.forward, glm::dvec3(c.validUp())));
  v.up = glm::cross(v.right, v.forward);
  v.tanHalf = std::tan(glm::radians(static_cast<double>(c.fovY)) / 2.0);
  return v;
}
// The hit of the ray through image point (x, row) (pixels from the top-left
// corner of a size x size image) with the plane {p : dot(p, n) = d}, and its
// view depth (along forward); depth <= 0 when the plane is behind the eye.
struct Hit {
  glm::dvec3 p;
  double depth;
};
Hit planeHit(const View& v, int size, double x, double row, glm::dvec3 n, double d) {
  const double u = (x / size * 2.0 - 1.0) * v.tanHalf, w = (1.0 - row / size * 2.0) * v.tanHalf;
  const glm::dvec3 dir = v.forward + u * v.right + w * v.up;  // depth 1 per unit of t
  const double t = (d - glm::dot(v.eye, n)) / glm::dot(dir, n);
  return {v.eye + t * dir, t};
}
// The largest view-depth change of that plane between a pixel centre and any
// point of its texel (the corners: depth is monotonic along a plane), over the
// pixels whose centre's hit lies where `inside` says: the depth error of the
// shader's nearest-texel lookup of a sample that lands in that texel.
double lookupDepthError(const View& v, int size, glm::dvec3 n, double d,
                        const std::function<bool(glm::dvec3)>& inside = {}) {
  double e = 0.0;
  for (int row = 0; row < size; ++row)
    for (int x = 0; x < size; ++x) {
      const Hit c = planeHit(v, size, x + 0.5, row + 0.5, n, d);
      if (c.depth <= 0.0 || (inside && !inside(c.p))) continue;
      for (double ox : {0.0, 1.0})
        for (double oy : {0.0, 1.0}) {
          const Hit h = planeHit(v, size, x + ox, row + oy, n, d);
          e = h.depth > 0.0 ? std::max(e, std::abs(h.depth - c.depth)) : 1e9;
        }
    }
  return e;
}

// ---- the corner oracle

double radicalInverse(uint32_t i, uint32_t base) {
  double f = 1.0, r = 0.0;
  for (; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}
double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// Expected occlusion at P on the plane with normal nA, next to the plane
// through the origin with normal nB (the crease along x): kernel samples
// (their distribution as documented, rotated uniformly about nA) that lie
// behind B and whose ray from the eye meets B in front of them by >= bias.
double cornerOcclusion(const View& v, glm::dvec3 P, glm::dvec3 nA, glm::dvec3 nB, const Ssao& a) {
  constexpr uint32_t kPoints = 60000;
  const glm::dvec3 toward = -nB, along{1.0, 0.0, 0.0};
  const double depthP = glm::dot(P - v.eye, v.forward);
  double occ = 0.0;
  for (uint32_t k = 1; k <= kPoints; ++k) {
    double x = radicalInverse(k, 2) * 2.0 - 1.0, y = radicalInverse(k, 3) * 2.0 - 1.0, z = radicalInverse(k, 5);
    const double len = std::sqrt(x * x + y * y + z * z);
    const int i = std::min(a.kernel - 1, static_cast<int>(radicalInverse(k, 7) * a.kernel));
    const double f = static_cast<double>(i) / a.kernel;
    const double r = radicalInverse(k, 11) * (0.1 + 0.9 * f * f) / len * a.radius;
    const double rho = std::sqrt(x * x + y * y) * r, phi = radicalInverse(k, 13) * 2.0 * M_PI;
    const glm::dvec3 s = P + rho * std::cos(phi) * toward + rho * std::sin(phi) * along + z * r * nA;
    if (glm::dot(s, nB) >= 0.0) continue;  // in front of B: the surface seen through it is behind it
    const glm::dvec3 dir = s - v.eye;
    const glm::dvec3 Q = v.eye + dir * (-glm::dot(v.eye, nB) / glm::dot(dir, nB));
    const double depthQ = glm::dot(Q - v.eye, v.forward), depthS = glm::dot(dir, v.forward);
    if (depthS - depthQ < a.bias) continue;
    occ += smoothstep01(a.radius / std::max(std::abs(depthP - depthQ), 1e-4));
  }
  return occ / kPoints;
}

class OracleSsao : public PluginOracleTest {
 protected:
  std::map<std::string, Rgba> run(const Scene& scene, const Ssao& a, int size) {
    return render(config(a), {static_cast<uint32_t>(size), static_cast<uint32_t>(size)},
                  {"gPosition", "gNormal", "ao_raw", "ao"}, &scene);
  }
};

// Every pixel of the raw and the blurred AO is exactly 1.
void expectAllOpen(const std::map<std::string, Rgba>& r, const std::string& what) {
  for (const char* target : {"ao_raw", "ao"}) {
    const Plane& ao = r.at(target).c[0];
    const auto lowest = std::min_element(ao.v.begin(), ao.v.end());
    const size_t i = static_cast<size_t>(lowest - ao.v.begin());
    EXPECT_EQ(*lowest, 1.0) << what << ": " << target << " at x " << i % ao.width << " row " << i / ao.width;
  }
}

}  // namespace

TEST_F(OracleSsao, FlatPlaneFacingTheCameraIsOpen) {
  const Scene s = planes({glm::mat4(1.0f)}, 6.0f, camera({0, 6, 0}, {0, 0, 0}, {0, 0, -1}));
  const auto r = run(s, Ssao{}, 64);
  const Plane& covered = r.at("gNormal").c[3];
  EXPECT_EQ(*std::min_element(covered.v.begin(), covered.v.end()), 1.0) << "the plane must fill the frame";
  expectAllOpen(r, "plane facing the camera");
}

TEST_F(OracleSsao, TiltedPlaneIsOpen) {
  // Seen 40 degrees off its normal: the nearest-texel depth error grows toward the top of the image.
  const double a = glm::radians(40.0);
  const Camera cam =
      camera({0.0f, static_cast<float>(4 * std::cos(a)), static_cast<float>(4 * std::sin(a))}, {0, 0, 0});
  const Scene s = planes({glm::mat4(1.0f)}, 12.0f, cam);
  Ssao p;
  p.bias = 0.08;  // the lookup error below is 0.051
  const double e = lookupDepthError(view(cam), 64, {0, 1, 0}, 0.0);
  std::printf("tilted plane: nearest-texel depth error %.4f, bias %.3f\n", e, p.bias);
  ASSERT_LT(e, p.bias) << "precondition: the bias must exceed the lookup error for the plane to be open";
  const auto r = run(s, p, 64);
  const Plane& covered = r.at("gNormal").c[3];
  EXPECT_EQ(*std::min_element(covered.v.begin(), covered.v.end()), 1.0) << "the plane must fill the frame";
  expectAllOpen(r, "tilted plane");
}

// A cube in empty space seen on a corner: three convex edges, nothing in front of any sample.
TEST_F(OracleSsao, ConvexEdgesStayOpen) {
  Scene s;
  s.source = "test:ssao-cube";
  addDraw(s, addMesh(s, makeCube(1.0f)), addMaterial(s, glm::vec4(0.8f), 0.0f, 0.5f), glm::mat4(1.0f));
  s.camera = camera({3.0f, 3.5f, 4.0f}, {0, 0, 0});
  s.hasCamera = true;
  // The bias must exceed the lookup error on every visible face (x = 1, y = 1, z = 1 within the cube);
  // on a convex edge the other face lies behind the first one's plane, so that bound holds across edges.
  const View v = view(s.camera);
  const auto onCube = [](glm::dvec3 p) { return std::abs(p.x) <= 1.0 && std::abs(p.y) <= 1.0 && std::abs(p.z) <= 1.0; };
  double e = 0.0;
  for (glm::dvec3 n : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)})
    e = std::max(e, lookupDepthError(v, 128, n, 1.0, [&](glm::dvec3 p) { return onCube(p + 1e-9 * -n); }));
  Ssao p;
  p.bias = 0.12;  // the lookup error is 0.087 (on the faces seen at ~60 degrees)
  std::printf("cube: nearest-texel depth error %.4f, bias %.3f\n", e, p.bias);
  ASSERT_LT(e, p.bias) << "precondition: the bias must exceed the lookup error for the cube to be open";
  const auto r = run(s, p, 128);
  const Plane& covered = r.at("gNormal").c[3];
  EXPECT_GT(std::count(covered.v.begin(), covered.v.end(), 1.0), 128 * 128 / 8) << "the cube must be in view";
  expectAllOpen(r, "convex cube");
}

namespace {
// The rows next to the crease (h about 0.1 R) must be at least this dark:
// the oracle gives 1 - occlusion = 0.78..0.85 there (R = 1), 0.06 the tolerance.
constexpr double kCreaseBound = 0.92;

struct CornerRow {
  int row;
  bool floor;       // else the wall
  double h;         // distance from the crease
  double ao;        // mean blurred AO over the middle columns
  double expected;  // 1 - the oracle's occlusion, averaged over the blur's 4 rows
};
}  // namespace

// Floor (y = 0, z >= 0) meeting a wall (z = 0, y >= 0): a concave 90-degree
// corner whose crease runs horizontally across the image. Per image row (the
// middle 32 columns, where the 4x4 blur has averaged all 16 rotations), the
// blurred AO against the oracle; AO falls monotonically toward the crease
// and is exactly 1 where no sample can reach the other plane (h > R).
TEST_F(OracleSsao, ConcaveCornerOccludesTowardTheCrease) {
  constexpr int kImage = 128;
  const Camera cam = camera({0.0f, 2.0f, 3.5f}, {0.0f, 0.4f, 0.0f});
  const glm::mat4 floorXf = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 6.0f});
  const glm::mat4 wallXf = glm::translate(glm::mat4(1.0f), {0.0f, 6.0f, 0.0f}) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1.0f, 0.0f, 0.0f});
  const Scene s = planes({floorXf, wallXf}, 6.0f, cam);
  Ssao p;
  p.radius = 1.0;
  const auto r = run(s, p, kImage);
  const View v = view(cam);
  const Plane &py = r.at("gPosition").c[1], &pz = r.at("gPosition").c[2], &ny = r.at("gNormal").c[1],
              &nz = r.at("gNormal").c[2], &ao = r.at("ao").c[0];
  constexpr int x0 = 48, x1 = 80;
  // Rows whose middle columns all lie on one plane: their surface and distance from the crease.
  std::vector<int> surface(kImage, 0);  // 1 floor, 2 wall, 0 mixed
  std::vector<double> dist(kImage, 0.0), mean(kImage, 0.0);
  for (int row = 0; row < kImage; ++row) {
    int floorPx = 0, wallPx = 0;
    for (int x = x0; x < x1; ++x) {
      floorPx += ny.at(x, row) > 0.99 ? 1 : 0;
      wallPx += nz.at(x, row) > 0.99 ? 1 : 0;
      dist[row] += ny.at(x, row) > 0.99 ? pz.at(x, row) : py.at(x, row);
      mean[row] += ao.at(x, row);
    }
    surface[row] = floorPx == x1 - x0 ? 1 : wallPx == x1 - x0 ? 2 : 0;
    dist[row] /= x1 - x0;
    mean[row] /= x1 - x0;
  }
  std::vector<CornerRow> rows;
  std::vector<double> oracle(kImage, -1.0);
  for (int row = 1; row + 2 < kImage; ++row) {
    const int kind = surface[row];
    bool uniform = kind != 0;
    for (int j = row - 1; j <= row + 2; ++j) uniform = uniform && surface[j] == kind;
    if (!uniform) continue;
    double minH = 1e9, expected = 0.0;
    for (int j = row - 1; j <= row + 2; ++j) {
      minH = std::min(minH, dist[j]);
      if (dist[j] > p.radius) {
        oracle[j] = 0.0;  // no sample reaches the other plane
      } else if (oracle[j] < 0.0) {
        oracle[j] = kind == 1 ? cornerOcclusion(v, {0.0, 0.0, dist[j]}, {0, 1, 0}, {0, 0, 1}, p)
                              : cornerOcclusion(v, {0.0, dist[j], 0.0}, {0, 0, 1}, {0, 1, 0}, p);
      }
      expected += (1.0 - oracle[j]) / 4.0;
    }
    if (minH > 1.5 * p.radius) continue;
    rows.push_back({row, kind == 1, dist[row], mean[row], expected});
  }
  ASSERT_GE(rows.size(), 20u) << "too few rows near the crease";
  double worst = 0.0;
  for (const CornerRow& c : rows) {
    if (c.row % 4 == 0)
      std::printf("%s row %3d h %.3f: AO %.4f oracle %.4f\n", c.floor ? "floor" : "wall ", c.row, c.h, c.ao,
                  c.expected);
    worst = std::max(worst, std::abs(c.ao - c.expected));
    EXPECT_NEAR(c.ao, c.expected, 0.06) << (c.floor ? "floor" : "wall") << " row " << c.row << " h " << c.h;
    if (c.expected == 1.0) {
      EXPECT_EQ(c.ao, 1.0) << "beyond the radius nothing occludes: row " << c.row;
    }
  }
  std::printf("corner: worst |AO - oracle| %.4f over %zu rows\n", worst, rows.size());
  // Monotonic: on each plane, farther from the crease is never darker (noise: 2 steps of 1/512,
  // one sample of one rotation).
  for (size_t i = 1; i < rows.size(); ++i) {
    const CornerRow &a = rows[i - 1], &b = rows[i];
    if (a.floor != b.floor) continue;
    const CornerRow& nearer = a.h < b.h ? a : b;
    const CornerRow& farther = a.h < b.h ? b : a;
    EXPECT_GE(farther.ao, nearer.ao - 2.0 / 512.0)
        << "AO must not fall away from the crease: rows " << a.row << ", " << b.row;
  }
  // Below a bound at the crease: the rows nearest it on either plane.
  for (bool onFloor : {true, false}) {
    const CornerRow* nearest = nullptr;
    for (const CornerRow& c : rows)
      if (c.floor == onFloor && (!nearest || c.h < nearest->h)) nearest = &c;
    ASSERT_NE(nearest, nullptr);
    EXPECT_LT(nearest->ao, kCreaseBound) << (onFloor ? "floor" : "wall") << " next to the crease";
  }
}

// visibility = (1 - occlusion)^power, pixel by pixel of the raw AO.
TEST_F(OracleSsao, PowerRaisesTheVisibility) {
  const Camera cam = camera({0.0f, 2.0f, 3.5f}, {0.0f, 0.4f, 0.0f});
  const Scene s = planes({glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 6.0f}),
                          glm::translate(glm::mat4(1.0f), {0.0f, 6.0f, 0.0f}) *
                              glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1.0f, 0.0f, 0.0f})},
                         6.0f, cam);
  Ssao linear;
  linear.radius = 1.0;
  Ssao cubed = linear;
  cubed.power = 3.0;
  const Plane a = run(s, linear, 64).at("ao_raw").c[0], b = run(s, cubed, 64).at("ao_raw").c[0];
  size_t occluded = 0;
  for (size_t i = 0; i < a.v.size(); ++i) {
    occluded += a.v[i] < 0.9 ? 1 : 0;
    // fp32 pow: a few ulps of a value <= 1.
    ASSERT_NEAR(b.v[i], a.v[i] * a.v[i] * a.v[i], 1e-6) << "texel " << i;
  }
  EXPECT_GT(occluded, 20u) << "the corner must give occluded texels to compare";
}

// The range check: a surface far in front of P (a square hovering 3 units
// above a floor seen from straight above) occludes each sample that lands on
// it with weight w = smoothstep(R / 3) only. All floor depths are equal (6)
// and all square depths too (3), so the raw AO of a floor texel is exactly
// 1 - w k / n for an integer k, the number of its samples landing on the square.
TEST_F(OracleSsao, DistantOccluderCountsWithTheRangeWeight) {
  Scene s;
  s.source = "test:ssao-range";
  const int mat = addMaterial(s, glm::vec4(0.8f), 0.0f, 0.5f);
  addDraw(s, addMesh(s, makePlane(6.0f, 6.0f)), mat, glm::mat4(1.0f), "floor");
  addDraw(s, addMesh(s, makePlane(0.6f, 0.6f)), mat, glm::translate(glm::mat4(1.0f), {0.0f, 3.0f, 0.0f}), "square");
  s.camera = camera({0, 6, 0}, {0, 0, 0}, {0, 0, -1});
  s.hasCamera = true;
  const Ssao p;
  const double gap = 3.0, w = smoothstep01(p.radius / gap);
  const auto r = run(s, p, 64);
  const Plane &y = r.at("gPosition").c[1], &ao = r.at("ao_raw").c[0];
  double worstFraction = 0.0, maxK = 0.0;
  size_t squareTexels = 0;
  for (size_t i = 0; i < ao.v.size(); ++i) {
    if (y.v[i] > 1.5) {
      ++squareTexels;
      EXPECT_EQ(ao.v[i], 1.0) << "nothing is in front of the square: texel " << i;
      continue;
    }
    const double k = (1.0 - ao.v[i]) * p.kernel / w;
    maxK = std::max(maxK, k);
    worstFraction = std::max(worstFraction, std::abs(k - std::round(k)));
  }
  std::printf("range weight %.4f: most samples on the square %.3f, worst distance from an integer count %.2e\n", w,
              maxK, worstFraction);
  EXPECT_GT(squareTexels, 100u) << "the square must be in view";
  // fp32: the sum of k weights and 1 - sum / n carry ~1e-6 relative error, amplified by n / w = 432.
  EXPECT_LT(worstFraction, 0.01) << "occlusion that is not a whole number of samples times the range weight";
  EXPECT_LE(maxK, p.kernel + 0.01) << "more occlusion than all samples times the range weight";
  EXPECT_GE(maxK, 4.0) << "samples next to the square's outline must land on it";
}
