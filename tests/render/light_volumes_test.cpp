// Light volumes (instanced spheres scaled to each light's radius, additive)
// against the fullscreen lighting pass with the same cut-off: the same image
// within 2/255. Both write an rgba32f HDR target, so the additive blending
// adds no half-float rounding. And a camera inside a light's volume still
// sees that light with front faces culled; back-face culling loses it (the
// documented failure mode of `"cull": "back"`).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr int kTolerance = 2;
constexpr double kThreshold = 5.0 / 256.0;

struct Result {
  Image image;
  std::vector<float> hdr;
};

class LightVolumes : public RenderTest {
 protected:
  Result renderWith(PipelineConfig cfg, const Scene& scene, Extent size, const std::string& hdrName) {
    Result r;
    r.image = render(cfg, scene, size, *shaders, [&](Executor& e) { r.hdr = e.readTextureRGBA32F(hdrName); });
    return r;
  }

  PipelineConfig fullscreen(const std::string& model, const std::string& attenuation) {
    PipelineConfig cfg = loadPipeline(testPipeline("fullscreen-cutoff.json"));
    setParam(cfg, "lighting", "model", model);
    setParam(cfg, "lighting", "attenuation", attenuation);
    setParam(cfg, "lighting", "threshold", kThreshold);
    return cfg;
  }
  PipelineConfig volumes(const std::string& model, const std::string& attenuation, const std::string& cull = "front") {
    PipelineConfig cfg = loadPipeline(testPipeline("light-volumes-fp32.json"));
    for (const char* pass : {"ambient", "volumes"}) {
      setParam(cfg, pass, "model", model);
      setParam(cfg, pass, "attenuation", attenuation);
    }
    setParam(cfg, "volumes", "threshold", kThreshold);
    setParam(cfg, "volumes", "cull", cull);
    return cfg;
  }

  void expectAgree(const Scene& scene, const std::string& model, const std::string& attenuation,
                   const std::string& name, Extent size = {256, 256}) {
    const Result a = renderWith(fullscreen(model, attenuation), scene, size, "hdr");
    const Result b = renderWith(volumes(model, attenuation), scene, size, "hdr_lit");
    float maxHdr = 0.0f;
    for (size_t i = 0; i < a.hdr.size(); ++i)
      if ((i & 3) != 3) maxHdr = std::max(maxHdr, std::abs(a.hdr[i] - b.hdr[i]));
    const double lit = coverage(a.image, {0, 0, 0});
    EXPECT_GT(lit, 0.2) << name << ": mostly background";
    expectLightsShow(a.image, fullscreen(model, attenuation), scene, *shaders, 0.05, name + "-fullscreen");
    const ImageDiff d = compareImages(a.image, b.image, kTolerance);
    std::printf("[ measure  ] %s: light volumes vs fullscreen (cut-off 5/256): %s; HDR max abs diff %.3g\n",
                name.c_str(), d.describe().c_str(), maxHdr);
    RecordProperty("max_abs_diff_" + name, d.maxDiff);
    EXPECT_LE(d.maxDiff, kTolerance) << name << ": " << d.describe() << "; images: "
                                     << saveImage(a.image, name + "-fullscreen") << ", "
                                     << saveImage(b.image, name + "-volumes");
  }
};

// A wall facing the camera and one white point light between them, close
// enough that the camera is inside the light's volume.
Scene wallWithLightBehindCamera(glm::vec3 lightPos) {
  Scene s;
  s.source = "test:wall";
  const int cube = addMesh(s, makeCube(1.0f));
  const int mat = addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.6f, 0.5f);
  // Front face at z = 0, 8 x 8 wide.
  addDraw(s, cube, mat, glm::scale(translate({0.0f, 0.0f, -0.25f}), glm::vec3(4.0f, 4.0f, 0.25f)), "wall");
  s.pointLights.push_back(pointLight(lightPos, {1.0f, 0.9f, 0.7f}));
  s.ambient = glm::vec3(0.05f);
  s.camera.position = glm::vec3(0.0f, 0.0f, 2.0f);
  s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
  s.camera.fovY = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 20.0f;
  s.hasCamera = true;
  return s;
}

}  // namespace

TEST_F(LightVolumes, MatchFullscreenOnTheLearnOpenGLScene) {
  expectAgree(makeLearnOpenGLScene(), "blinn_phong", "classic", "learnopengl");
}

TEST_F(LightVolumes, MatchFullscreenCookTorranceSmooth) {
  expectAgree(makeCookTorranceScene(), "cook_torrance", "smooth", "still-life-smooth");
  expectAgree(makeCookTorranceScene(), "cook_torrance", "classic", "still-life-classic");
}

TEST_F(LightVolumes, MatchFullscreenWithManyLights) {
  // Many overlapping volumes, several containing the camera or crossing the near plane.
  expectAgree(makeManyLightsScene(200, 7), "blinn_phong", "classic", "many-lights-200", {192, 192});
}

TEST_F(LightVolumes, CameraInsideAVolumeStillSeesItsLight) {
  // The light is 1 unit in front of the wall, the camera 2 units: the camera
  // is well inside the light's ~5-unit volume.
  const Scene scene = wallWithLightBehindCamera({0.0f, 0.0f, 1.0f});
  const std::vector<float> radii = [&] {
    std::vector<float> r;
    for (const auto& l : scene.pointLights) r.push_back(lightRadius(l, static_cast<float>(kThreshold)));
    return r;
  }();
  ASSERT_GT(radii[0], glm::length(scene.camera.position - scene.pointLights[0].position) * 2.0f)
      << "the camera must be inside the volume for this test";

  const Extent size{128, 128};
  const Result full = renderWith(fullscreen("blinn_phong", "classic"), scene, size, "hdr");
  const Result front = renderWith(volumes("blinn_phong", "classic", "front"), scene, size, "hdr_lit");
  const Result back = renderWith(volumes("blinn_phong", "classic", "back"), scene, size, "hdr_lit");

  // The centre pixel sees the wall lit (only) by that light, head on.
  const int cx = 64, crow = 64;
  const glm::ivec3 want = full.image.rgb(cx, crow), gotFront = front.image.rgb(cx, crow),
                   gotBack = back.image.rgb(cx, crow);
  std::printf("[ measure  ] camera inside volume, centre pixel: fullscreen %s, volumes front-culled %s, back-culled %s\n",
              pixelText(want).c_str(), pixelText(gotFront).c_str(), pixelText(gotBack).c_str());
  EXPECT_GT(want.r, 120) << "the light should light the wall brightly";
  const glm::ivec3 dFront = glm::abs(want - gotFront);
  EXPECT_LE(std::max({dFront.r, dFront.g, dFront.b}), kTolerance)
      << "front-culled volumes lose the light whose volume contains the camera: " << pixelText(gotFront) << " vs "
      << pixelText(want);
  // The whole image agrees too.
  const ImageDiff d = compareImages(full.image, front.image, kTolerance);
  EXPECT_LE(d.maxDiff, kTolerance) << d.describe() << " " << saveImage(front.image, "inside-volume-front");

  // Back-face culling draws the near side of the sphere, which is behind the
  // camera: nothing is drawn and the light is lost (ambient only).
  EXPECT_LT(gotBack.r, want.r - 100) << "back-culled volumes were expected to lose the light (the documented "
                                        "failure mode), got " << pixelText(gotBack);
  // Ambient only: 0.05 * 0.8 = 0.04 linear, about 56/255 after the sRGB curve.
  EXPECT_LE(gotBack.r, 60);
}

TEST_F(LightVolumes, BackFaceCullingIsFineWhenTheCameraIsOutside) {
  // The same light moved to 1 unit from the wall but the camera outside its
  // volume (a dim light: small radius): both cullings agree with fullscreen.
  Scene scene = wallWithLightBehindCamera({0.3f, -0.2f, 0.6f});
  scene.pointLights[0].intensity = 0.08f;
  scene.pointLights[0].radius = lightRadius(scene.pointLights[0]);
  ASSERT_LT(lightRadius(scene.pointLights[0], static_cast<float>(kThreshold)),
            glm::length(scene.camera.position - scene.pointLights[0].position));
  const Extent size{128, 128};
  const Result full = renderWith(fullscreen("blinn_phong", "classic"), scene, size, "hdr");
  const Result front = renderWith(volumes("blinn_phong", "classic", "front"), scene, size, "hdr_lit");
  const Result back = renderWith(volumes("blinn_phong", "classic", "back"), scene, size, "hdr_lit");
  const ImageDiff df = compareImages(full.image, front.image, kTolerance);
  const ImageDiff db = compareImages(full.image, back.image, kTolerance);
  EXPECT_LE(df.maxDiff, kTolerance) << "front: " << df.describe();
  EXPECT_LE(db.maxDiff, kTolerance) << "back: " << db.describe();
  // And the light does light something (the comparison is not vacuous).
  expectLightsShow(full.image, fullscreen("blinn_phong", "classic"), scene, *shaders, 0.3, "dim-light-fullscreen");
}

TEST_F(LightVolumes, CameraInsideAVolumeWithTheShippedPipelines) {
  // The same check through the shipped LearnOpenGL pipelines (rgba16f
  // targets, half-float positions): light volumes against the fullscreen loop.
  const Scene scene = wallWithLightBehindCamera({0.0f, 0.0f, 1.0f});
  const Extent size{128, 128};
  // deferred-blinn-phong.json shades with no cut-off (LearnOpenGL 8.1);
  // compare at the light volumes' own threshold so only the method differs.
  PipelineConfig loop = loadPipeline(repoPath("pipelines/deferred-blinn-phong.json"));
  setParam(loop, "lighting", "threshold", kThreshold);
  const Image full = render(loop, scene, size, *shaders);
  const Image volumes = render(loadPipeline(repoPath("pipelines/default.json")), scene, size, *shaders);
  const ImageDiff d = compareImages(full, volumes, kTolerance);
  std::printf("[ measure  ] camera inside volume, default.json vs deferred-blinn-phong.json: %s\n", d.describe().c_str());
  EXPECT_GT(full.rgb(64, 64).r, 120);
  EXPECT_LE(d.maxDiff, kTolerance) << d.describe() << " " << saveImage(volumes, "inside-volume-default");
}

TEST_F(LightVolumes, VolumeReachingPastTheFarPlaneKeepsItsLight) {
  // The far plane cuts the light's sphere: its back faces (the ones drawn)
  // lie beyond it. Depth clamping keeps them (at depth 1), so the wall in
  // front of the far plane is still lit.
  Scene scene = wallWithLightBehindCamera({0.0f, 0.0f, 0.0f});
  scene.primitives[0].transform = glm::scale(translate({0.0f, 0.0f, -17.25f}), glm::vec3(12.0f, 12.0f, 0.25f));
  scene.primitives[0].bounds = scene.meshes[0].bounds.transformed(scene.primitives[0].transform);
  scene.pointLights[0] = pointLight({0.0f, 0.0f, -15.5f}, {1.0f, 0.9f, 0.7f}, 1.0f);
  scene.camera.far = 19.5f;  // the far plane at z = -17.5, just behind the wall's front face (z = -17)
  const float radius = lightRadius(scene.pointLights[0], static_cast<float>(kThreshold));
  ASSERT_LT(-15.5f - radius, -17.5f) << "the light's sphere must reach past the far plane";
  const Extent size{96, 96};
  const Result full = renderWith(fullscreen("blinn_phong", "classic"), scene, size, "hdr");
  const Result front = renderWith(volumes("blinn_phong", "classic", "front"), scene, size, "hdr_lit");
  const glm::ivec3 want = full.image.rgb(48, 48), got = front.image.rgb(48, 48);
  std::printf("[ measure  ] volume past the far plane, centre pixel: fullscreen %s, volumes %s\n",
              pixelText(want).c_str(), pixelText(got).c_str());
  EXPECT_GT(want.r, 100);
  const ImageDiff d = compareImages(full.image, front.image, kTolerance);
  EXPECT_LE(d.maxDiff, kTolerance) << d.describe() << " " << saveImage(front.image, "far-plane-volumes");
}
