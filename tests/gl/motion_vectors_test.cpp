// Motion vectors and jitter through GpuScene (the Frame block, u_prevModel,
// selectJitter) with the shipped shaders: scene.vert + gbuffer.frag
// (HAS_VELOCITY) for every G-buffer layout, and a probe shader for jitter.
// Each velocity is compared with the CPU projection of the same world point
// (found by casting the pixel centre's ray at the cube) through both frames'
// matrices.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "gl_test_util.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/jitter.h"
#include "rgraph/scene.h"
#include "support/cube_scene.h"

using namespace rgraph;

namespace {

constexpr Extent kSize{64, 48};
// rg16f holds a velocity of ~0.1 UV to ~5e-5; the fragment's interpolated
// clip positions and the CPU ray cast agree to ~1e-5. 1e-3 UV is 1/16 of a
// pixel here: a jittered matrix (up to 0.5 px = 8e-3 UV) or a missing model
// motion fails it.
constexpr float kTolUv = 1e-3f;

Scene cubeScene() {
  Scene s = testsupport::singleMeshScene(makeCube(0.5f));
  s.primitives[0].name = "cube";
  testsupport::lookAtOrigin(s, {0.6f, 0.9f, 3.0f});
  return s;
}

// Colour attachments 0..n-1 (rgba32f; the layout's targets, which these tests
// do not read), then `last` at n, and depth.
struct Targets {
  std::vector<gl::Texture> colors;
  gl::Texture depth;
  gl::Framebuffer fbo;
  Targets(int before, GLenum last) {
    std::vector<GLenum> bufs;
    fbo = gl::createFramebuffer();
    for (int i = 0; i <= before; ++i) {
      colors.push_back(gl::createTexture(GL_TEXTURE_2D));
      glTextureStorage2D(colors.back().id(), 1, i == before ? last : GL_RGBA32F, kSize.width, kSize.height);
      glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0 + i, colors.back().id(), 0);
      bufs.push_back(GL_COLOR_ATTACHMENT0 + i);
    }
    depth = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, kSize.width, kSize.height);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    glNamedFramebufferDrawBuffers(fbo.id(), static_cast<GLsizei>(bufs.size()), bufs.data());
  }
  void draw(GpuScene& gs, uint32_t program) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, kSize.width, kSize.height);
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    for (size_t i = 0; i < colors.size(); ++i) glClearNamedFramebufferfv(fbo.id(), GL_COLOR, GLint(i), zero);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    gs.drawPrimitives(program, {});
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  // RGBA float per pixel of colour attachment i (rows bottom-up, GL order).
  std::vector<glm::vec4> read(size_t i) const {
    std::vector<glm::vec4> px(size_t(kSize.width) * kSize.height);
    glGetTextureImage(colors[i].id(), 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(glm::vec4)), px.data());
    return px;
  }
  std::vector<float> readDepth() const {
    std::vector<float> d(size_t(kSize.width) * kSize.height);
    glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(d.size() * sizeof(float)), d.data());
    return d;
  }
};

float aspect() { return float(kSize.width) / float(kSize.height); }

// Where the ray through pixel (x, y)'s centre (unjittered) first meets the
// unit cube drawn with `model`; none if it misses or grazes an edge.
std::optional<glm::vec3> hitCube(const Camera& cam, const glm::mat4& model, uint32_t x, uint32_t y) {
  const glm::mat4 inv = glm::inverse(cam.projection(aspect()) * cam.view());
  const glm::vec2 ndc((x + 0.5f) / kSize.width * 2.0f - 1.0f, (y + 0.5f) / kSize.height * 2.0f - 1.0f);
  glm::vec4 a = inv * glm::vec4(ndc, -1.0f, 1.0f), b = inv * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::mat4 toLocal = glm::inverse(model);
  const glm::vec3 o = glm::vec3(toLocal * (a / a.w)), e = glm::vec3(toLocal * (b / b.w));
  const glm::vec3 d = e - o;
  float t0 = 0.0f, t1 = 1.0f;
  for (int k = 0; k < 3; ++k) {  // slabs of the box [-0.5, 0.5]^3
    if (std::abs(d[k]) < 1e-12f) {
      if (std::abs(o[k]) > 0.5f) return std::nullopt;
      continue;
    }
    float ta = (-0.5f - o[k]) / d[k], tb = (0.5f - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return std::nullopt;
  const glm::vec3 local = o + t0 * d;
  // Pixels within 2% of an edge of the hit face: coverage there may differ.
  int nearFace = 0;
  for (int k = 0; k < 3; ++k) nearFace += std::abs(local[k]) > 0.48f;
  if (nearFace > 1) return std::nullopt;
  return glm::vec3(model * glm::vec4(local, 1.0f));
}

glm::vec2 uvOf(const glm::mat4& viewProj, const glm::vec3& world) {
  const glm::vec4 c = viewProj * glm::vec4(world, 1.0f);
  return glm::vec2(c) / c.w * 0.5f + 0.5f;
}

struct VelocityLayout {
  const char* name;
  std::vector<std::string> defines;
  int location;  // where gbuffer.frag puts the velocity for this layout
};

const std::vector<VelocityLayout>& velocityLayouts() {
  static const std::vector<VelocityLayout> l = {
      {"learnopengl", {"GBUFFER_LEARNOPENGL"}, 3},
      {"pbr", {"GBUFFER_PBR"}, 4},
      {"pbr-constant", {"GBUFFER_PBR", "CONSTANT_MATERIAL", "CONSTANT_METALLIC=0.0", "CONSTANT_ROUGHNESS=1.0"}, 3},
      {"compact", {"GBUFFER_COMPACT"}, 3},
      {"compact-constant",
       {"GBUFFER_COMPACT", "CONSTANT_MATERIAL", "CONSTANT_METALLIC=0.0", "CONSTANT_ROUGHNESS=1.0"},
       2},
      {"fp32", {"GBUFFER_FP32"}, 4},
  };
  return l;
}

class MotionVectors : public test::GlTest {
 protected:
  uint32_t velocityProgram(const VelocityLayout& l) {
    std::vector<std::string> d = l.defines;
    d.push_back("HAS_VELOCITY");
    return shaders->program("scene.vert", "gbuffer.frag", d);
  }
  // Renders with the compact layout and returns the velocity target (xy).
  std::vector<glm::vec2> velocity(GpuScene& gs, const VelocityLayout& l = velocityLayouts()[4]) {
    Targets t(l.location, GL_RG16F);
    t.draw(gs, velocityProgram(l));
    std::vector<glm::vec2> v;
    for (const glm::vec4& p : t.read(size_t(l.location))) v.emplace_back(p.x, p.y);
    depth_ = t.readDepth();
    coverage_ = size_t(std::count_if(depth_.begin(), depth_.end(), [](float d) { return d < 1.0f; }));
    return v;
  }
  // Compares every pixel whose ray hits the cube with the CPU motion of that
  // point: model `now` / `prev` under view-projections `vpNow` / `vpPrev`.
  // Returns how many pixels were compared; the largest error goes to `maxErr`.
  size_t compare(const std::vector<glm::vec2>& v, const Camera& cam, const glm::mat4& now, const glm::mat4& prev,
                 const glm::mat4& vpPrev, float& maxErr, float& maxSpeed) {
    const glm::mat4 vpNow = cam.projection(aspect()) * cam.view();
    const glm::mat4 back = prev * glm::inverse(now);  // a world point now -> where it was
    size_t n = 0;
    maxErr = maxSpeed = 0.0f;
    for (uint32_t y = 0; y < kSize.height; ++y)
      for (uint32_t x = 0; x < kSize.width; ++x) {
        const auto hit = hitCube(cam, now, x, y);
        if (!hit) continue;
        const glm::vec3 was = glm::vec3(back * glm::vec4(*hit, 1.0f));
        const glm::vec2 expected = uvOf(vpNow, *hit) - uvOf(vpPrev, was);
        const glm::vec2 got = v[size_t(y) * kSize.width + x];
        maxErr = std::max(maxErr, glm::length(got - expected));
        maxSpeed = std::max(maxSpeed, glm::length(expected));
        ++n;
      }
    std::printf("[ measure  ] %zu pixels: velocity error max %.2e UV, largest motion %.4f UV\n", n, maxErr, maxSpeed);
    return n;
  }
  size_t coverage_ = 0;
  std::vector<float> depth_;
};

size_t nonZero(const std::vector<glm::vec2>& v) {
  return size_t(std::count_if(v.begin(), v.end(), [](const glm::vec2& p) { return p != glm::vec2(0.0f); }));
}

}  // namespace

TEST_F(MotionVectors, CameraMotionMatchesCpuProjection) {
  Scene scene = cubeScene();
  GpuScene gs(scene);
  Camera a = scene.camera, b = scene.camera;
  b.position += glm::vec3(0.15f, -0.05f, 0.2f);
  b.target += glm::vec3(0.05f, 0.0f, 0.0f);
  FrameMotion m;
  m.frame = 1;
  const glm::mat4 vpA = gs.updateFrame(kSize, a, m);
  EXPECT_EQ(vpA, a.projection(aspect()) * a.view());
  // The first frame has no previous one: no motion.
  std::vector<glm::vec2> v = velocity(gs);
  EXPECT_GT(coverage_, 300u);
  EXPECT_EQ(nonZero(v), 0u);
  m.frame = 2;
  m.prevViewProj = vpA;
  gs.updateFrame(kSize, b, m);
  for (const VelocityLayout& l : velocityLayouts()) {
    SCOPED_TRACE(l.name);
    v = velocity(gs, l);
    float err = 0, speed = 0;
    const size_t n = compare(v, b, glm::mat4(1.0f), glm::mat4(1.0f), vpA, err, speed);
    EXPECT_GT(n, 300u);
    EXPECT_GT(speed, 0.02f) << "the camera moved by over a pixel";
    EXPECT_LT(err, kTolUv) << "largest velocity error over " << n << " pixels (UV)";
    // Background pixels stay 0 (camera-only motion is not written there).
    size_t background = 0, backgroundMoving = 0;
    for (size_t i = 0; i < v.size(); ++i)
      if (depth_[i] == 1.0f) {
        ++background;
        backgroundMoving += v[i] != glm::vec2(0.0f);
      }
    EXPECT_GT(background, v.size() / 3);
    EXPECT_EQ(backgroundMoving, 0u);
  }
}

TEST_F(MotionVectors, StaticCameraIsExactlyZeroEvenWithJitter) {
  Scene scene = cubeScene();
  GpuScene gs(scene);
  FrameMotion m;
  m.jitterPhases = 8;
  std::optional<glm::mat4> prev;
  for (uint64_t f = 0; f < 4; ++f) {
    m.frame = f;
    m.prevViewProj = prev;
    prev = gs.updateFrame(kSize, scene.camera, m);
    const std::vector<glm::vec2> v = velocity(gs);
    EXPECT_GT(coverage_, 300u);
    EXPECT_EQ(nonZero(v), 0u) << "frame " << f << ": jitter must not leak into the velocity";
  }
}

// EXT_mesh_gpu_instancing: the previous position of a static instance is
// u_prevModel times the same instance matrix, so three instances of a cube
// (one draw) under a still camera with jitter have no motion at all.
TEST_F(MotionVectors, StaticInstancesAreExactlyZero) {
  Scene scene = cubeScene();
  for (float x : {-1.2f, 0.0f, 1.2f})
    scene.primitives[0].instances.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, -0.5f)) *
                                            glm::scale(glm::mat4(1.0f), glm::vec3(0.6f)));
  scene.primitives[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.2f, 0.0f));
  scene.primitives[0].bounds = scene.primitives[0].worldBounds(scene.meshes[0].bounds);
  GpuScene gs(scene);
  FrameMotion m;
  m.jitterPhases = 8;
  std::optional<glm::mat4> prev;
  size_t covered = 0;
  for (uint64_t f = 0; f < 3; ++f) {
    m.frame = f;
    m.prevViewProj = prev;
    prev = gs.updateFrame(kSize, scene.camera, m);
    const std::vector<glm::vec2> v = velocity(gs);
    EXPECT_EQ(nonZero(v), 0u) << "frame " << f << ": a static instance moved";
    if (f == 0) covered = coverage_;
  }
  std::printf("[ measure  ] three static instances cover %zu pixels\n", covered);
  EXPECT_GT(covered, 300u);  // measured 411 with all three drawn
}

TEST_F(MotionVectors, CameraCutGivesZero) {
  Scene scene = cubeScene();
  GpuScene gs(scene);
  Camera b = scene.camera;
  b.position.x += 0.5f;
  FrameMotion m;
  m.frame = 1;
  gs.updateFrame(kSize, scene.camera, m);
  m.frame = 2;  // moved, but no previous view-projection: a cut
  gs.updateFrame(kSize, b, m);
  EXPECT_EQ(nonZero(velocity(gs)), 0u);
  EXPECT_GT(coverage_, 300u);
}

TEST_F(MotionVectors, SpinningModelMatchesCpuMaths) {
  Scene scene = cubeScene();
  scene.primitives[0].spin.pivot = glm::vec3(0.0f);
  scene.primitives[0].spin.axis = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
  scene.primitives[0].spin.degreesPerSecond = 120.0f;  // 2 degrees a frame
  GpuScene gs(scene);
  FrameMotion m;
  m.frame = 10;
  m.prevViewProj = gs.updateFrame(kSize, scene.camera, m);
  m.frame = 11;
  const glm::mat4 vp = gs.updateFrame(kSize, scene.camera, m);
  const Primitive& p = scene.primitives[0];
  for (const VelocityLayout& l : velocityLayouts()) {
    SCOPED_TRACE(l.name);
    const std::vector<glm::vec2> v = velocity(gs, l);
    float err = 0, speed = 0;
    const size_t n = compare(v, scene.camera, p.transformAt(11 / 60.0), p.transformAt(10 / 60.0), vp, err, speed);
    EXPECT_GT(n, 300u);
    EXPECT_GT(speed, 0.005f) << "the cube turned by over a quarter pixel somewhere";
    EXPECT_LT(err, kTolUv) << "largest velocity error over " << n << " pixels (UV)";
    EXPECT_GT(nonZero(v), 300u);
  }
  // A cut keeps the model still too: previous = current.
  m.frame = 12;
  m.prevViewProj.reset();
  gs.updateFrame(kSize, scene.camera, m);
  EXPECT_EQ(nonZero(velocity(gs)), 0u);
}

TEST_F(MotionVectors, EditedTransformMovesTheModel) {
  Scene scene = cubeScene();
  GpuScene gs(scene);
  FrameMotion m;
  m.frame = 1;
  m.prevViewProj = gs.updateFrame(kSize, scene.camera, m);
  const glm::mat4 before = scene.primitives[0].transform;
  scene.primitives[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0.05f, 0.0f));
  m.frame = 2;
  const glm::mat4 vp = gs.updateFrame(kSize, scene.camera, m);
  const std::vector<glm::vec2> v = velocity(gs);
  float err = 0, speed = 0;
  const size_t n = compare(v, scene.camera, scene.primitives[0].transform, before, vp, err, speed);
  EXPECT_GT(n, 300u);
  EXPECT_GT(speed, 0.02f);
  EXPECT_LT(err, kTolUv);
}

TEST_F(MotionVectors, JitterShiftsTheImageBySubPixelsAndSelectJitterRemovesIt) {
  // A plane facing the camera: its world x (y) is linear in the pixel column
  // (row), so the jitter shows as a shift of the world position each pixel
  // centre sees, measured in pixels.
  Scene scene;
  scene.meshes.push_back(makePlane(4.0f, 4.0f));
  scene.materials.push_back(Material{});
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.transform = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
  p.bounds = {glm::vec3(-4, -4, 0), glm::vec3(4, 4, 0)};
  scene.primitives.push_back(p);
  scene.camera.position = {0.0f, 0.0f, 3.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.hasCamera = true;
  GpuScene gs(scene);
  const uint32_t probe = shaders->program("scene.vert", "motion_probe.frag");
  Targets plain(1, GL_RGBA32F), jittered(1, GL_RGBA32F), optedOut(1, GL_RGBA32F);
  gs.updateFrame(kSize, scene.camera);
  plain.draw(gs, probe);
  FrameMotion m;
  m.jitterPhases = 8;
  m.frame = 2;  // Halton index 3: (0.25, -0.389) pixels
  const glm::vec2 j = jitterPixels(m.frame, m.jitterPhases);
  gs.updateFrame(kSize, scene.camera, m);
  jittered.draw(gs, probe);
  gs.selectJitter(false);
  optedOut.draw(gs, probe);
  gs.selectJitter(true);

  const auto a = plain.read(0), b = jittered.read(0), c = optedOut.read(0);
  const auto at = [](uint32_t x, uint32_t y) { return size_t(y) * kSize.width + x; };
  // Pixel shift = world difference / world step per pixel, away from the borders.
  double sx = 0, sy = 0;
  int n = 0;
  for (uint32_t y = 4; y + 4 < kSize.height; y += 3)
    for (uint32_t x = 4; x + 4 < kSize.width; x += 3) {
      const float stepX = a[at(x + 1, y)].x - a[at(x, y)].x, stepY = a[at(x, y + 1)].y - a[at(x, y)].y;
      ASSERT_GT(stepX, 0.0f);
      ASSERT_GT(stepY, 0.0f);
      // The image moved by +j: the pixel centre now sees what was j pixels back.
      sx += (a[at(x, y)].x - b[at(x, y)].x) / stepX;
      sy += (a[at(x, y)].y - b[at(x, y)].y) / stepY;
      ++n;
    }
  std::printf("[ measure  ] jitter (%.4f, %.4f) px, measured shift (%.4f, %.4f) px\n", j.x, j.y, sx / n, sy / n);
  EXPECT_NEAR(sx / n, j.x, 2e-3) << "mean shift in x, pixels";
  EXPECT_NEAR(sy / n, j.y, 2e-3) << "mean shift in y, pixels";
  // The block's u_jitter: pixels and NDC; zero in the unjittered block.
  const auto bj = jittered.read(1), cj = optedOut.read(1);
  EXPECT_FLOAT_EQ(bj[at(30, 20)].x, j.x);
  EXPECT_FLOAT_EQ(bj[at(30, 20)].y, j.y);
  EXPECT_NEAR(bj[at(30, 20)].z, 2.0f * j.x / kSize.width, 1e-7f);
  EXPECT_NEAR(bj[at(30, 20)].w, 2.0f * j.y / kSize.height, 1e-7f);
  EXPECT_EQ(cj[at(30, 20)], glm::vec4(0.0f));
  // selectJitter(false): exactly the unjittered frame.
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) differ += a[i] != c[i];
  EXPECT_EQ(differ, 0u) << "a pass opted out of jitter sees the unjittered matrices";
  // And selectJitter(true) binds the jittered block again.
  Targets again(1, GL_RGBA32F);
  gs.bindFrame();
  again.draw(gs, probe);
  const auto d = again.read(0);
  EXPECT_TRUE(std::equal(b.begin(), b.end(), d.begin()));
}
