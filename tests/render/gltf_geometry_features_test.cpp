// glTF geometry and texturing drawn (issue 29), each against what its sample
// model is built to show, through the deferred (geometry pass) and forward
// pipelines:
// - COLOR_0: VertexColorTest's vertex colours multiply its texture (the checks
//   come out red, green and blue as the reference row beneath them);
// - KHR_texture_transform: TextureTransformTest's six panels match a CPU ray
//   cast of the same geometry sampling the same images under each texture's
//   transform (dark arrow against light background, and the UV.png quadrant
//   each offset panel must show);
// - texCoord 1: a texture that names the second UV set samples it;
// - EXT_mesh_gpu_instancing: SimpleInstancing's 125 cubes, one instanced draw.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "support/render_util.h"
#include "rgraph/adapt.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{256, 256};

PipelineConfig pipelineFor(const std::string& file, const Scene& scene) {
  PipelineConfig cfg = loadPipeline(repoPath(file));
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  return cfg;
}

const char* const kPipelines[] = {"pipelines/default.json", "pipelines/forward.json"};

// ---------------------------------------------------------------- a CPU ray cast of the scene

struct Hit {
  size_t primitive = 0;
  glm::dvec3 bary{0.0};  // of the triangle's three vertices
  uint32_t v[3] = {0, 0, 0};
  double t = 0.0;
};

// The nearest triangle hit (both faces), by Moller-Trumbore in world space.
std::optional<Hit> castRay(const Scene& scene, const Ray& ray) {
  std::optional<Hit> best;
  for (size_t pi = 0; pi < scene.primitives.size(); ++pi) {
    const Primitive& p = scene.primitives[pi];
    const MeshData& m = scene.meshes[size_t(p.mesh)];
    const glm::dmat4 world(p.transform);
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      const uint32_t* idx = &m.indices[3 * t];
      const glm::dvec3 a(world * glm::dvec4(glm::dvec3(m.positions[idx[0]]), 1.0));
      const glm::dvec3 b(world * glm::dvec4(glm::dvec3(m.positions[idx[1]]), 1.0));
      const glm::dvec3 c(world * glm::dvec4(glm::dvec3(m.positions[idx[2]]), 1.0));
      const glm::dvec3 e1 = b - a, e2 = c - a, pv = glm::cross(ray.dir, e2);
      const double det = glm::dot(e1, pv);
      if (std::abs(det) < 1e-12) continue;
      const glm::dvec3 tv = ray.origin - a;
      const double u = glm::dot(tv, pv) / det;
      if (u < 0.0 || u > 1.0) continue;
      const glm::dvec3 qv = glm::cross(tv, e1);
      const double v = glm::dot(ray.dir, qv) / det;
      if (v < 0.0 || u + v > 1.0) continue;
      const double dist = glm::dot(e2, qv) / det;
      if (dist <= 1e-9 || (best && dist >= best->t)) continue;
      best = Hit{pi, glm::dvec3(1.0 - u - v, u, v), {idx[0], idx[1], idx[2]}, dist};
    }
  }
  return best;
}

// The texel (nearest, clamped: TextureTransformTest's sampler clamps) of `ref` at the hit.
glm::ivec3 texelAt(const Scene& scene, const Hit& h, const TextureRef& ref, glm::vec2* uvOut = nullptr) {
  const MeshData& m = scene.meshes[size_t(scene.primitives[h.primitive].mesh)];
  const std::vector<glm::vec2>& set = ref.texCoord == 1 && m.hasUv1() ? m.uv1 : m.uv0;
  const glm::vec2 uv = float(h.bary.x) * set[h.v[0]] + float(h.bary.y) * set[h.v[1]] + float(h.bary.z) * set[h.v[2]];
  const glm::vec2 st = ref.uvTransform() * glm::vec3(uv, 1.0f);
  if (uvOut) *uvOut = st;
  const ImageData& img = scene.images[size_t(scene.textures[size_t(ref.texture)].image)];
  const int x = std::clamp(int(std::floor(st.x * float(img.width))), 0, img.width - 1);
  const int y = std::clamp(int(std::floor(st.y * float(img.height))), 0, img.height - 1);
  const uint8_t* px = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return {px[0], px[1], px[2]};
}

// ---------------------------------------------------------------- colour classes

bool dark(glm::ivec3 c) { return std::max({c.r, c.g, c.b}) < 96; }
// The hue class of a saturated colour: 'r', 'g', 'b', 'y' (red + green), 'c' (green + blue), or 0.
char hue(glm::ivec3 c) {
  const int hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  if (hi < 40 || hi - lo < hi / 3) return 0;  // dark or grey
  const bool r = c.r > hi * 2 / 3, g = c.g > hi * 2 / 3, b = c.b > hi * 2 / 3;
  if (r && g && !b) return 'y';
  if (g && b && !r) return 'c';
  if (r && !g && !b) return 'r';
  if (g && !r && !b) return 'g';
  if (b && !r && !g) return 'b';
  return 0;
}

class GltfGeometryFeatures : public RenderTest, public ::testing::WithParamInterface<const char*> {};
class GltfInstancedShadows : public RenderTest {};

}  // namespace

// Whether the texels 3 texels around the hit's (in u and v) have the class of its own.
bool uniformAround(const Scene& scene, const Hit& h, const TextureRef& ref, glm::ivec3 want) {
  const ImageData& im = scene.images[size_t(scene.textures[size_t(ref.texture)].image)];
  const float du = 3.0f / float(im.width), dv = 3.0f / float(im.height);
  for (glm::vec2 d : {glm::vec2(du, 0), glm::vec2(-du, 0), glm::vec2(0, dv), glm::vec2(0, -dv)}) {
    TextureRef shifted = ref;
    shifted.offset += d;
    const glm::ivec3 n = texelAt(scene, h, shifted);
    if (dark(n) != dark(want) || hue(n) != hue(want)) return false;
  }
  return true;
}

// ---------------------------------------------------------------- COLOR_0

// VertexColorTest: each pixel of its coloured mesh where the vertex colour is
// not white (away from texel edges and from triangles whose corners differ
// in colour) has the class of texel times
// vertex colour: the checks red, green and blue, their "fail" marks (where
// the vertex colour is black) dark. Without vertex colours the texture alone
// shows (white checks, visible marks).
TEST_P(GltfGeometryFeatures, VertexColorTestMultipliesTheBaseColourByTheVertexColours) {
  const Scene scene = loadSceneAny(assetPath("gltf/VertexColorTest/VertexColorTest.glb"));
  ASSERT_TRUE(scene.hasVertexColors());
  const Image img = render(pipelineFor(GetParam(), scene), scene, kSize, *shaders);
  size_t checked = 0, agree = 0, white = 0;
  for (int row = 0; row < int(kSize.height); ++row) {
    for (int x = 0; x < int(kSize.width); ++x) {
      const std::optional<Hit> h = castRay(scene, pixelRay(scene.camera, kSize, x, row));
      if (!h) continue;
      const Primitive& p = scene.primitives[h->primitive];
      const MeshData& mesh = scene.meshes[size_t(p.mesh)];
      const Material& mat = scene.materials[size_t(p.material)];
      if (!mesh.hasColors() || !mat.baseColorTexture.valid()) continue;
      const glm::vec4 c = mesh.colors[h->v[0]];
      if (mesh.colors[h->v[1]] != c || mesh.colors[h->v[2]] != c) continue;
      if (c == glm::vec4(1.0f)) continue;  // white: the texture alone either way
      const glm::ivec3 texel = texelAt(scene, *h, mat.baseColorTexture);
      if (!uniformAround(scene, *h, mat.baseColorTexture, texel)) continue;
      const glm::ivec3 want(glm::vec3(texel) * glm::vec3(c));
      const glm::ivec3 got = img.rgb(x, row);
      ++checked;
      agree += hue(want) != 0 ? hue(got) == hue(want) : dark(got) == dark(want);
      white += !dark(got) && hue(got) == 0 && hue(want) != 0;  // a check left white
    }
  }
  const double share = checked ? double(agree) / double(checked) : 0.0;
  std::printf("[ measure  ] %s: VertexColorTest: %zu of %zu pixels of non-white vertex colour (%.1f%%) match texture x vertex colour; "
              "%zu white where a colour belongs\n",
              GetParam(), agree, checked, share * 100.0, white);
  EXPECT_GT(checked, size_t(kSize.width) * kSize.height / 100) << saveImage(img, "vertex-color");
  EXPECT_GE(share, 0.99) << saveImage(img, "vertex-color");
  EXPECT_LT(white, checked / 100) << saveImage(img, "vertex-color");
}

// ---------------------------------------------------------------- KHR_texture_transform

// Every pixel where the ray cast lands inside an arrow or UV panel (away from
// texel edges, where filtering mixes) must match the class of the texel the
// transform selects: dark or light for the arrows, the hue of the UV.png
// quadrant for the offsets.
TEST_P(GltfGeometryFeatures, TextureTransformTestMatchesTheTransformedTextures) {
  const Scene scene = loadSceneAny(assetPath("gltf/TextureTransformTest/TextureTransformTest.gltf"));
  const Image img = render(pipelineFor(GetParam(), scene), scene, kSize, *shaders);
  size_t checked = 0, agree = 0, yellow = 0;
  for (int row = 0; row < int(kSize.height); ++row) {
    for (int x = 0; x < int(kSize.width); ++x) {
      const std::optional<Hit> h = castRay(scene, pixelRay(scene.camera, kSize, x, row));
      if (!h) continue;
      const Material& mat = scene.materials[size_t(scene.primitives[h->primitive].material)];
      const TextureRef& ref = mat.baseColorTexture;
      if (!ref.valid() || ref.uvTransform() == glm::mat3x2(1.0f)) continue;  // markers: untransformed
      const glm::ivec3 want = texelAt(scene, *h, ref);
      if (!uniformAround(scene, *h, ref, want)) continue;  // away from edges, where filtering mixes
      const glm::ivec3 got = img.rgb(x, row);
      ++checked;
      const bool match = hue(want) != 0 ? hue(got) == hue(want) : dark(got) == dark(want);
      agree += match;
      yellow += hue(got) == 'y';  // UV.png's "not this quadrant" sign
    }
  }
  const double share = checked ? double(agree) / double(checked) : 0.0;
  std::printf("[ measure  ] %s: TextureTransformTest: %zu of %zu panel pixels (%.1f%%) match the transformed texture; "
              "%zu yellow\n",
              GetParam(), agree, checked, share * 100.0, yellow);
  EXPECT_GT(checked, size_t(kSize.width) * kSize.height / 10) << "the panels cover too little: " << saveImage(img, "tt");
  // Measured 100%; the rotation turned the other way gives 97.1%, no transform 46%.
  EXPECT_GE(share, 0.995) << saveImage(img, "texture-transform");
  EXPECT_LT(yellow, checked / 100) << saveImage(img, "texture-transform");
}

// The direction of rotation, against the model's own markers (not the
// loader's matrix, which the test above shares): the arrow drawn on the
// Rotation panel ends nearest its "Correct" marker, not at "Not Supported"
// (untransformed) or "Error" (rotated the other way). (The Scale panel's
// markers do not tell: its untransformed arrow passes its "Correct" marker
// too; the test above holds the scale.)
TEST_P(GltfGeometryFeatures, TextureTransformTestArrowsPointAtTheCorrectMarkers) {
  const Scene scene = loadSceneAny(assetPath("gltf/TextureTransformTest/TextureTransformTest.gltf"));
  const Image img = render(pipelineFor(GetParam(), scene), scene, kSize, *shaders);
  auto find = [&](const std::string& name) -> const Primitive* {
    for (const Primitive& p : scene.primitives)
      if (p.name == name) return &p;
    return nullptr;
  };
  for (const std::string panel : {"Rotation"}) {
    SCOPED_TRACE(panel);
    const Primitive* quad = find(panel);
    ASSERT_NE(quad, nullptr);
    const size_t quadIndex = size_t(quad - scene.primitives.data());
    // The arrow: dark pixels of the panel itself (markers in front are other primitives).
    std::vector<glm::dvec2> arrow;
    for (int row = 0; row < int(kSize.height); ++row)
      for (int x = 0; x < int(kSize.width); ++x) {
        const std::optional<Hit> h = castRay(scene, pixelRay(scene.camera, kSize, x, row));
        if (h && h->primitive == quadIndex && std::max({img.rgb(x, row).r, img.rgb(x, row).g, img.rgb(x, row).b}) < 60)
          arrow.emplace_back(x + 0.5, row + 0.5);
      }
    ASSERT_GT(arrow.size(), 20u) << saveImage(img, "texture-transform-arrows");
    // Screen distance from each marker's centre to the nearest arrow pixel.
    std::map<std::string, double> nearest;
    for (const char* marker : {"Correct", "Not Supported", "Error"}) {
      const Primitive* m = find(panel + " - " + marker);
      if (!m) continue;
      const std::optional<ScreenPoint> c = project(scene.camera, kSize, glm::dvec3(m->bounds.center()));
      ASSERT_TRUE(c.has_value());
      double d = 1e9;
      for (const glm::dvec2& a : arrow) d = std::min(d, glm::length(a - glm::dvec2(c->x, c->row)));
      nearest[marker] = d;
      std::printf("[ measure  ] %s: %s arrow: %.1f pixels from the '%s' marker\n", GetParam(), panel.c_str(), d, marker);
    }
    ASSERT_TRUE(nearest.count("Correct") && nearest.count("Not Supported"));
    for (const auto& [marker, d] : nearest)
      if (marker != "Correct") EXPECT_LT(nearest["Correct"], d) << marker << "; " << saveImage(img, "texture-transform-arrows");
  }
}

// ---------------------------------------------------------------- texCoord 1

// A quad whose TEXCOORD_0 is (0, 0) everywhere and whose TEXCOORD_1 spans the
// texture (red left half, green right half), its base colour texture naming
// texCoord 1: the left half of the quad comes out red, the right half green
// (sampling TEXCOORD_0 would make it all red).
TEST_P(GltfGeometryFeatures, ATextureNamingTexCoordOneSamplesTheSecondUvSet) {
  Scene scene;
  MeshData quad = makePlane(1.0f, 1.0f);  // y = 0, facing +Y
  quad.uv1 = quad.uv0;
  for (glm::vec2& uv : quad.uv0) uv = glm::vec2(0.0f);
  scene.meshes.push_back(quad);
  ImageData texture;
  texture.width = 2;
  texture.height = 1;
  texture.rgba = {255, 0, 0, 255, 0, 255, 0, 255};
  texture.srgb = true;
  scene.images.push_back(texture);
  SceneTexture st;
  st.image = 0;
  st.sampler.minFilter = st.sampler.magFilter = SamplerDesc::kNearest;
  st.sampler.wrapS = st.sampler.wrapT = SamplerDesc::kClampToEdge;
  scene.textures.push_back(st);
  Material m;
  m.metallicFactor = 0.0f;
  m.baseColorTexture.texture = 0;
  m.baseColorTexture.texCoord = 1;
  scene.materials.push_back(m);
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.bounds = scene.meshes[0].bounds.transformed(p.transform);
  scene.primitives.push_back(p);
  scene.camera.position = glm::vec3(0.0f, 3.0f, 0.001f);
  scene.camera.target = glm::vec3(0.0f);
  scene.hasCamera = true;
  applySceneDefaults(scene);
  const Image img = render(pipelineFor(GetParam(), scene), scene, kSize, *shaders);
  // Which texel each pixel's uv1 selects, by the ray cast.
  size_t checked = 0, agree = 0;
  for (int row = 0; row < int(kSize.height); row += 2) {
    for (int x = 0; x < int(kSize.width); x += 2) {
      const std::optional<Hit> h = castRay(scene, pixelRay(scene.camera, kSize, x, row));
      if (!h) continue;
      glm::vec2 uv;
      const glm::ivec3 want = texelAt(scene, *h, m.baseColorTexture, &uv);
      if (std::abs(uv.x - 0.5f) < 0.05f) continue;  // the seam
      ++checked;
      agree += hue(img.rgb(x, row)) == hue(want);
    }
  }
  std::printf("[ measure  ] %s: texCoord 1: %zu of %zu quad pixels match the texel of TEXCOORD_1\n", GetParam(), agree,
              checked);
  EXPECT_GT(checked, 1000u);
  EXPECT_GE(agree, checked * 99 / 100) << saveImage(img, "texcoord1");
}

// ---------------------------------------------------------------- EXT_mesh_gpu_instancing

// SimpleInstancing: 125 instances of one cube spread through a volume. The
// frame (camera fitted to the bounds of every instance) covers many times
// what one instance covers from the same camera; every instance centre that
// projects into the frame lands on a covered pixel.
TEST_P(GltfGeometryFeatures, SimpleInstancingDrawsEveryInstance) {
  const Scene scene = loadSceneAny(assetPath("gltf/SimpleInstancing/SimpleInstancing.glb"));
  ASSERT_EQ(scene.primitives.size(), 1u);
  ASSERT_EQ(scene.primitives[0].instances.size(), 125u);
  Scene single = scene;  // same camera and lights
  single.primitives[0].instances.clear();
  single.primitives[0].bounds = single.primitives[0].worldBounds(single.meshes[0].bounds);
  const Image img = render(pipelineFor(GetParam(), scene), scene, kSize, *shaders);
  const Image one = render(pipelineFor(GetParam(), single), single, kSize, *shaders);
  const glm::ivec3 background = img.rgb(0, 0);
  const double all = coverage(img, background), cube = coverage(one, background);
  size_t inFrame = 0, onCovered = 0;
  const Primitive& p = scene.primitives[0];
  for (const glm::mat4& instance : p.instances) {
    const glm::vec3 centre(p.transform * instance * glm::vec4(scene.meshes[0].bounds.center(), 1.0f));
    const std::optional<ScreenPoint> sp = project(scene.camera, kSize, glm::dvec3(centre));
    if (!sp || sp->px() < 0 || sp->prow() < 0 || sp->px() >= int(kSize.width) || sp->prow() >= int(kSize.height)) continue;
    ++inFrame;
    const glm::ivec3 d = glm::abs(img.rgb(sp->px(), sp->prow()) - background);
    onCovered += std::max({d.r, d.g, d.b}) > 2;
  }
  std::printf("[ measure  ] %s: SimpleInstancing covers %.1f%% of the frame, one instance %.2f%%; %zu of %zu instance "
              "centres in frame on covered pixels\n",
              GetParam(), all * 100.0, cube * 100.0, onCovered, inFrame);
  EXPECT_GT(cube, 0.0) << saveImage(one, "instancing-one");
  EXPECT_GT(all, 20.0 * cube) << saveImage(img, "instancing");
  EXPECT_GE(inFrame, 100u);
  EXPECT_EQ(onCovered, inFrame) << saveImage(img, "instancing");
}

// Shadow maps of instanced meshes: SimpleInstancing over a floor, under the
// default sun, through the shadow pipeline, looks as the same cubes placed
// one primitive each (world positions differ in the last bits: node * instance
// is multiplied on the CPU there, in the shader here).
TEST_F(GltfInstancedShadows, MatchOnePrimitivePerInstance) {
  Scene scene = loadSceneAny(assetPath("gltf/SimpleInstancing/SimpleInstancing.glb"));
  const Bounds b = scene.bounds();
  Scene floor;
  floor.meshes.push_back(makePlane(b.size().x, b.size().z));
  floor.materials.push_back(Material{});
  Primitive fp;
  fp.mesh = 0;
  fp.material = 0;
  fp.transform = glm::translate(glm::mat4(1.0f), glm::vec3(b.center().x, b.min.y - 0.1f * b.size().y, b.center().z));
  fp.bounds = fp.worldBounds(floor.meshes[0].bounds);
  floor.primitives.push_back(fp);
  appendScene(scene, floor);
  Scene expanded = scene;
  expanded.primitives.clear();
  for (const Primitive& p : scene.primitives) {
    if (p.instances.empty()) expanded.primitives.push_back(p);
    for (const glm::mat4& m : p.instances) {
      Primitive q = p;
      q.instances.clear();
      q.transform = p.transform * m;
      q.bounds = q.worldBounds(scene.meshes[size_t(p.mesh)].bounds);
      expanded.primitives.push_back(q);
    }
  }
  const PipelineConfig cfg = pipelineFor("pipelines/deferred-pbr-shadows.json", scene);
  const Image a = render(cfg, scene, kSize, *shaders), e = render(cfg, expanded, kSize, *shaders);
  const ImageDiff d = compareImages(a, e, 8);
  Scene unshadowed = scene;
  for (Primitive& p : unshadowed.primitives) p.castShadows = false;
  const ImageDiff shadows = compareImages(a, render(cfg, unshadowed, kSize, *shaders), 8);
  std::printf("[ measure  ] SimpleInstancing over a floor with shadows: instanced vs one primitive each: %s; "
              "against no casters: %zu pixels differ\n",
              d.describe().c_str(), shadows.over);
  EXPECT_GT(shadows.over, size_t(kSize.width) * kSize.height / 50) << "no shadows to compare: " << saveImage(a, "inst-shadows");
  EXPECT_LE(d.over, size_t(kSize.width) * kSize.height / 1000) << saveImage(a, "inst-shadows") << " "
                                                               << saveImage(e, "inst-shadows-expanded");
}

INSTANTIATE_TEST_SUITE_P(Pipelines, GltfGeometryFeatures, ::testing::ValuesIn(kPipelines),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.index == 0 ? "deferred" : "forward");
                         });
