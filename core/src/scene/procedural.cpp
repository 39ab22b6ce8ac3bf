// Procedural scenes: the LearnOpenGL deferred-shading demo, a many-lights field and thin geometry
// (the walker: procedural_walker.cpp).
#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "procedural_internal.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph {

void addDraw(Scene& s, int mesh, int material, const glm::mat4& xf, const std::string& name) {
  Primitive p;
  p.mesh = mesh;
  p.material = material;
  p.transform = xf;
  p.bounds = s.meshes[size_t(mesh)].bounds.transformed(xf);
  p.name = name;
  s.primitives.push_back(std::move(p));
}

int addFlatMaterial(Scene& s, const std::string& name, glm::vec3 color, float specular, float roughness) {
  Material m;
  m.name = name;
  m.baseColorFactor = glm::vec4(color, 1.0f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = roughness;
  m.specular = specular;
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

void addFalloffLights(Scene& s, const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& colors) {
  for (size_t i = 0; i < positions.size() && i < colors.size(); ++i) {
    PointLight l;
    l.position = positions[i];
    l.color = colors[i];
    l.constant = 1.0f;
    l.linear = 0.22f;
    l.quadratic = 0.2f;
    l.radius = lightRadius(l);
    s.pointLights.push_back(l);
  }
}

void placeCamera(Scene& s, glm::vec3 position, glm::vec3 target, float far) {
  s.camera.position = position;
  s.camera.target = target;
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = far;
  s.hasCamera = true;
}

// ---------------------------------------------------------------- GlibcRandom
// glibc's random_r.c, TYPE_3: x[i] = x[i-3] + x[i-31] (mod 2^32), output x >> 1,
// state seeded with the Park-Miller generator and 310 outputs discarded.

GlibcRandom::GlibcRandom(uint32_t seed) {
  if (seed == 0) seed = 1;
  state_[0] = int32_t(seed);
  int32_t word = int32_t(seed);  // glibc keeps the seed in an int32_t (seeds >= 2^31 go negative)
  for (int i = 1; i < 31; ++i) {
    const int64_t hi = word / 127773, lo = word % 127773;
    word = int32_t(uint32_t(int64_t(16807) * lo - int64_t(2836) * hi));  // wraps to 32 bits as glibc does
    if (word < 0) word += 2147483647;
    state_[i] = word;
  }
  f_ = 3;
  r_ = 0;
  for (int i = 0; i < 310; ++i) next();
}

int GlibcRandom::next() {
  const uint32_t val = uint32_t(state_[f_]) + uint32_t(state_[r_]);
  state_[f_] = int32_t(val);
  const int result = int(val >> 1);
  if (++f_ >= 31) {
    f_ = 0;
    ++r_;
  } else if (++r_ >= 31) {
    r_ = 0;
  }
  return result;
}

namespace {

float uniform01(GlibcRandom& rng) { return float(double(rng.next()) / 2147483648.0); }

ImageData makeTileTexture(const std::string& name, int size, int tiles, glm::u8vec3 a, glm::u8vec3 b) {
  ImageData im;
  im.name = name;
  im.width = im.height = size;
  // LearnOpenGL loads its textures as plain (linear) RGBA and writes its
  // result without gamma: keeping these linear makes the demo look as the
  // chapter shows it (an sRGB decode here would darken every texel).
  im.srgb = false;
  im.rgba.resize(size_t(size) * size_t(size) * 4);
  const int tile = std::max(1, size / tiles);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const bool odd = ((x / tile) + (y / tile)) % 2 != 0;
      const bool grout = (x % tile) == 0 || (y % tile) == 0;
      glm::u8vec3 c = odd ? a : b;
      if (grout) c = glm::u8vec3(glm::vec3(c) * 0.6f);
      uint8_t* p = &im.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
      p[3] = 255;
    }
  }
  return im;
}

glm::vec3 hsvToRgb(float h, float s, float v) {
  h = h - std::floor(h);
  const float hh = h * 6.0f;
  const int i = int(hh) % 6;
  const float f = hh - std::floor(hh);
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

}  // namespace

// ---------------------------------------------------------------- LearnOpenGL demo

Scene makeLearnOpenGLScene() {
  Scene s;
  s.source = "learnopengl";
  s.meshes.push_back(makeCube(1.0f));      // mesh 0: [-1,1]^3 like the chapter's renderCube()
  s.meshes.push_back(makeUvSphere(1.0f));  // mesh 1

  s.images.push_back(makeTileTexture("learnopengl_albedo", 128, 4, {235, 225, 205}, {190, 160, 130}));
  SceneTexture tex;
  tex.image = 0;
  s.textures.push_back(tex);
  Material mat;
  mat.name = "learnopengl";
  mat.baseColorTexture.texture = 0;
  mat.metallicFactor = 0.0f;
  mat.roughnessFactor = 0.5f;
  mat.specular = 0.5f;
  s.materials.push_back(mat);

  // The chapter's objectPositions, in its order; scale 0.5.
  const float xz[3] = {-3.0f, 0.0f, 3.0f};
  int k = 0;
  for (float z : xz) {
    for (float x : xz) {
      const glm::mat4 xf = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(x, -0.5f, z)), glm::vec3(0.5f));
      const int mesh = (k % 2 == 0) ? 0 : 1;  // checkerboard: cubes at the corners and the centre
      addDraw(s, mesh, 0, xf, "object" + std::to_string(k));
      ++k;
    }
  }

  // The chapter: srand(13); per light three rand() for the position, three for the colour.
  GlibcRandom rng(13);
  for (int i = 0; i < 32; ++i) {
    PointLight l;
    l.position.x = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
    l.position.y = float(((rng.next() % 100) / 100.0) * 6.0 - 4.0);
    l.position.z = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
    l.color.r = float(((rng.next() % 100) / 200.0f) + 0.5);
    l.color.g = float(((rng.next() % 100) / 200.0f) + 0.5);
    l.color.b = float(((rng.next() % 100) / 200.0f) + 0.5);
    l.intensity = 1.0f;
    l.constant = 1.0f;
    l.linear = 0.7f;
    l.quadratic = 1.8f;
    l.radius = lightRadius(l);
    s.pointLights.push_back(l);
  }

  s.ambient = glm::vec3(0.1f);
  s.camera.position = glm::vec3(0.0f, 0.0f, 5.0f);
  s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
  s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = 100.0f;
  s.hasCamera = true;
  return s;
}

Scene makeLearnOpenGLOverviewScene() {
  // The chapter's start camera (0, 0, 5) sees 5 of the 9 objects; this one
  // stands back and above so the whole 3x3 grid and its lights are in view.
  Scene s = makeLearnOpenGLScene();
  s.source = "learnopengl:overview";
  s.camera.position = {0.0f, 4.5f, 9.5f};
  s.camera.target = {0.0f, -0.75f, 0.0f};
  return s;
}

Scene makeLearnOpenGLShadowsScene() {
  Scene s = makeLearnOpenGLOverviewScene();
  s.source = "learnopengl:shadows";
  const int plane = int(s.meshes.size());
  s.meshes.push_back(makePlane(10.0f, 10.0f, 5.0f));
  Material floor;
  floor.name = "floor";
  floor.baseColorFactor = glm::vec4(0.55f, 0.55f, 0.6f, 1.0f);
  floor.metallicFactor = 0.0f;
  floor.roughnessFactor = 0.8f;
  floor.specular = 0.2f;
  s.materials.push_back(floor);
  // The objects stand on it: their bottoms are at y = -0.5 - 0.5.
  addDraw(s, plane, int(s.materials.size()) - 1, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.0f, 0.0f)), "floor");
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(0.45f, -1.0f, -0.35f));
  sun.color = glm::vec3(1.0f, 0.95f, 0.85f);
  sun.intensity = 0.6f;
  sun.castShadows = true;
  s.directionalLights.push_back(sun);
  return s;
}

// ---------------------------------------------------------------- many lights

Scene makeManyLightsScene(int n, uint32_t seed) {
  if (n < 0 || size_t(n) > kMaxSceneLights)
    throw RuntimeError("many-lights: light count must be in 0.." + std::to_string(kMaxSceneLights) + ", got " + std::to_string(n));
  Scene s;
  s.source = "many-lights:" + std::to_string(n);
  GlibcRandom rng(seed);

  const float side = std::clamp(std::sqrt(float(n)) * 0.64f, 16.0f, 64.0f);
  const int grid = std::clamp(int(side / 2.5f), 6, 16);
  const float spacing = side / float(grid);

  s.meshes.push_back(makeCube(1.0f));
  s.meshes.push_back(makeUvSphere(1.0f, 24, 12));
  s.meshes.push_back(makePlane(side * 0.55f, side * 0.55f, side * 0.55f / 2.0f));

  s.images.push_back(makeTileTexture("floor_albedo", 64, 2, {150, 150, 150}, {110, 110, 110}));
  SceneTexture tex;
  tex.image = 0;
  s.textures.push_back(tex);
  Material floor;
  floor.name = "floor";
  floor.baseColorTexture.texture = 0;
  floor.metallicFactor = 0.0f;
  floor.roughnessFactor = 0.6f;
  floor.specular = 0.3f;
  s.materials.push_back(floor);
  const glm::vec3 palette[6] = {{0.8f, 0.2f, 0.2f}, {0.2f, 0.7f, 0.3f}, {0.25f, 0.35f, 0.85f},
                                {0.85f, 0.75f, 0.3f}, {0.7f, 0.7f, 0.7f}, {0.6f, 0.3f, 0.7f}};
  for (int i = 0; i < 6; ++i) {
    Material m;
    m.name = "object" + std::to_string(i);
    m.baseColorFactor = glm::vec4(palette[i], 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 0.6f;
    m.specular = 0.5f;
    s.materials.push_back(m);
  }

  addDraw(s, 2, 0, glm::mat4(1.0f), "floor");
  for (int gz = 0; gz < grid; ++gz) {
    for (int gx = 0; gx < grid; ++gx) {
      const float x = -side * 0.5f + spacing * (float(gx) + 0.5f);
      const float z = -side * 0.5f + spacing * (float(gz) + 0.5f);
      const bool sphere = rng.next() % 2 == 1;
      const float half = spacing * (0.15f + 0.15f * uniform01(rng));
      const int material = 1 + rng.next() % 6;
      const float angle = uniform01(rng) * glm::half_pi<float>();
      glm::mat4 xf = glm::translate(glm::mat4(1.0f), glm::vec3(x, half, z));
      xf = glm::rotate(xf, angle, glm::vec3(0, 1, 0));
      xf = glm::scale(xf, glm::vec3(half));
      addDraw(s, sphere ? 1 : 0, material, xf, "object_" + std::to_string(gx) + "_" + std::to_string(gz));
    }
  }

  // Radius so that on average ~16 light volumes overlap any point of the field.
  const float targetRadius =
      n > 0 ? std::clamp(std::sqrt(16.0f * side * side / (glm::pi<float>() * float(n))), 0.5f, side * 0.5f) : 1.0f;
  s.pointLights.reserve(size_t(n));
  for (int i = 0; i < n; ++i) {
    PointLight l;
    l.position = glm::vec3((uniform01(rng) - 0.5f) * side, 0.2f + uniform01(rng) * spacing * 0.6f,
                           (uniform01(rng) - 0.5f) * side);
    l.color = hsvToRgb(uniform01(rng), 0.5f + 0.5f * uniform01(rng), 1.0f);
    l.intensity = 1.0f;
    // constant + linear r + quadratic r^2 = brightest / threshold, split evenly.
    const float k = std::max({l.color.r, l.color.g, l.color.b}) * l.intensity / kLightThreshold;
    l.constant = 1.0f;
    l.linear = 0.5f * (k - 1.0f) / targetRadius;
    l.quadratic = 0.5f * (k - 1.0f) / (targetRadius * targetRadius);
    l.radius = lightRadius(l);
    s.pointLights.push_back(l);
  }

  s.ambient = glm::vec3(0.05f);
  s.camera.position = glm::vec3(0.0f, side * 0.55f, side * 0.75f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = side * 3.0f;
  s.hasCamera = true;
  return s;
}

Scene makeManyLightsPillarsScene(int n, uint32_t seed) {
  Scene s = makeManyLightsScene(n, seed);
  s.source += ":pillars";
  // The field's size, as makeManyLightsScene chose it (its floor is mesh 2,
  // half extent 0.55 side; its grid spacing is at least 1).
  const float side = s.meshes[2].bounds.max.x / 0.55f;
  const float spacing = side / float(std::clamp(int(side / 2.5f), 6, 16));
  const int grey = 5;  // makeManyLightsScene's object materials are 1..6

  // The far background: a wall across the far end of the field.
  const float wallHeight = 3.0f * spacing;
  addDraw(s, 0, 0,
          glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, wallHeight * 0.5f, -side * 0.5f - 0.5f)),
                     glm::vec3(side * 0.55f, wallHeight * 0.5f, 0.25f)),
          "far_wall");
  // The camera low at the near end, looking along the field to the wall.
  s.camera.position = glm::vec3(0.0f, 0.8f * spacing, side * 0.5f + 0.5f * spacing);
  s.camera.target = glm::vec3(0.0f, 0.6f * spacing, -side * 0.5f);
  // A row of tall, thin pillars a little way in front of it, across the
  // whole view: every tile a pillar's edge crosses holds pixels near the
  // camera and pixels at the far wall.
  const float dist = spacing;  // from the camera, along z
  const float z = s.camera.position.z - dist;
  const float halfWidth = dist * std::tan(glm::radians(s.camera.fovY * 0.5f)) * (16.0f / 9.0f);
  const int pillars = 7;
  for (int i = 0; i < pillars; ++i) {
    const float x = -halfWidth + (2.0f * halfWidth) * (float(i) + 0.5f) / float(pillars);
    const glm::mat4 xf = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(x, 2.0f * spacing, z)),
                                    glm::vec3(0.03f * spacing, 2.0f * spacing, 0.03f * spacing));
    addDraw(s, 0, grey, xf, "pillar" + std::to_string(i));
  }
  return s;
}

// ---------------------------------------------------------------- thin geometry

// Edges that alias (the bench's aa axis): at 640x360 the fence posts are
// 2-3 pixels wide, the wires and the far grid's bars a pixel or less, so
// every sample pattern shows in them. Flat colours only (no textures), so
// what differs between anti-aliasing methods is geometry edges, not texture
// filtering. Deterministic: no PRNG.
Scene makeThinScene() {
  Scene s;
  s.source = "thin";
  s.meshes.push_back(makeCube(1.0f));                 // mesh 0: scaled into posts, wires and bars
  s.meshes.push_back(makePlane(10.0f, 14.0f, 1.0f));  // mesh 1: the floor, 20 x 28
  auto material = [&](const std::string& name, glm::vec3 color, float specular) {
    return addFlatMaterial(s, name, color, specular, 0.7f);
  };
  const int floorMat = material("floor", {0.18f, 0.18f, 0.2f}, 0.1f);
  const int postMat = material("post", {0.85f, 0.7f, 0.5f}, 0.3f);
  const int wireMat = material("wire", {0.9f, 0.9f, 0.9f}, 0.8f);
  const int barMat = material("bar", {0.95f, 0.95f, 0.8f}, 0.5f);
  // A box with these half extents, turned by `degrees` about z, at `centre`.
  auto box = [&](glm::vec3 centre, glm::vec3 half, float degrees, int mat, const std::string& name) {
    glm::mat4 xf = glm::translate(glm::mat4(1.0f), centre);
    xf = glm::rotate(xf, glm::radians(degrees), glm::vec3(0, 0, 1));
    addDraw(s, 0, mat, glm::scale(xf, half), name);
  };

  addDraw(s, 1, floorMat, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -6.0f)), "floor");  // z in -20..8
  // The fence: 25 posts 0.03 wide, x in -4..4 at z = 0.
  for (int i = 0; i < kThinScenePosts; ++i)
    box({-4.0f + (8.0f / float(kThinScenePosts - 1)) * float(i), 0.6f, 0.0f}, {0.015f, 0.6f, 0.015f}, 0.0f, postMat,
        "post" + std::to_string(i));
  // Wires 0.008 thick (under a pixel), each tilted a little so its edge
  // crosses pixel rows: the stair pattern of a nearly horizontal line.
  for (int i = 0; i < kThinSceneWires; ++i)
    box({0.0f, 0.25f + 0.25f * float(i), 0.05f}, {4.0f, 0.004f, 0.004f}, 0.5f + 0.25f * float(i), wireMat,
        "wire" + std::to_string(i));
  // The far grid: bars 0.03 wide and 0.02 high on the floor, z in -18..-6
  // (12 to 24 units from the camera: half a pixel to a pixel wide).
  const int n = kThinSceneGridBars / 2;
  for (int i = 0; i < n; ++i) {
    const float t = float(i) / float(n - 1);
    box({-6.0f + 12.0f * t, 0.01f, -12.0f}, {0.015f, 0.01f, 6.0f}, 0.0f, barMat, "bar_z" + std::to_string(i));
    box({0.0f, 0.01f, -18.0f + 12.0f * t}, {6.0f, 0.01f, 0.015f}, 0.0f, barMat, "bar_x" + std::to_string(i));
  }

  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.5f));
  sun.color = glm::vec3(1.0f, 0.97f, 0.9f);
  sun.intensity = 0.8f;
  s.directionalLights.push_back(sun);
  addFalloffLights(s, {{-4.0f, 1.5f, 1.5f}, {0.0f, 3.0f, 4.0f}, {4.0f, 1.5f, 1.5f}, {0.0f, 1.0f, -10.0f}},
                   {{1.0f, 0.6f, 0.4f}, {0.6f, 0.8f, 1.0f}, {0.7f, 1.0f, 0.6f}, {1.0f, 1.0f, 0.8f}});

  s.ambient = glm::vec3(0.08f);
  placeCamera(s, {0.0f, 1.6f, 5.5f}, {0.0f, 0.5f, -4.0f}, 60.0f);
  return s;
}

}  // namespace rgraph
