// The scene's depth for the caller's overlays (RendererOptions::keepDepth,
// Renderer::outputDepthTexture): after render(), a quad drawn with the
// renderer's camera and a depth test against rgraph's depth is hidden behind
// the scene's geometry and shown in front of it. And RenderScene::fromScene
// derives the bounds and light radii renderer.h says it does.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";
constexpr Extent kSize{64, 48};

// A unit cube (half extent 0.5) at the origin, seen from +Z; a light above
// the view (its marker is out of the picture) keeps the forward pass running.
std::shared_ptr<RenderScene> cubeScene() {
  Scene s;
  s.meshes.push_back(makeCube(0.5f));
  s.materials.push_back(Material{});
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  s.primitives.push_back(p);
  PointLight light;
  light.position = {0.0f, 3.0f, 3.0f};
  s.pointLights.push_back(light);
  s.camera.position = {0.0f, 0.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.hasCamera = true;
  return RenderScene::fromScene(std::move(s));
}

// The caller's overlay: a square of half size `half` at depth z (world), drawn magenta.
class Overlay {
 public:
  Overlay() {
    const char* vs = R"(#version 450 core
uniform mat4 u_viewProj;
uniform float u_z, u_half;
void main() {
  vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0) * u_half;
  gl_Position = u_viewProj * vec4(c, u_z, 1.0);
})";
    const char* fs = R"(#version 450 core
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(1.0, 0.0, 1.0, 1.0); })";
    program_ = gl::createProgram();
    for (auto [stage, text] : {std::pair{GLenum(GL_VERTEX_SHADER), vs}, std::pair{GLenum(GL_FRAGMENT_SHADER), fs}}) {
      gl::Shader shader = gl::createShader(stage);
      glShaderSource(shader.id(), 1, &text, nullptr);
      glCompileShader(shader.id());
      glAttachShader(program_.id(), shader.id());
    }
    glLinkProgram(program_.id());
    GLint linked = 0;
    glGetProgramiv(program_.id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    vao_ = gl::createVertexArray();
  }

  // Into `fbo` (colour and depth attached), depth-tested (GL_LESS), depth not written.
  void draw(uint32_t fbo, Extent size, const glm::mat4& viewProj, float z, float half) const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, GLsizei(size.width), GLsizei(size.height));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glUseProgram(program_.id());
    glProgramUniformMatrix4fv(program_.id(), glGetUniformLocation(program_.id(), "u_viewProj"), 1, GL_FALSE,
                              &viewProj[0][0]);
    glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "u_z"), z);
    glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "u_half"), half);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glUseProgram(0);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }

 private:
  gl::Program program_;
  gl::VertexArray vao_;
};

bool depthHasStencil(uint32_t format) { return format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8; }

// The caller's own framebuffer: a colour target cleared to 0 and a depth
// buffer of rgraph's depth format, filled from outputDepthTexture() by a blit.
struct CallerTarget {
  gl::Texture color, depth;
  gl::Framebuffer fbo, read;
  Extent size;

  CallerTarget(const Renderer& r, bool copyDepth) : size(r.outputDepthExtent()) {
    color = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(color.id(), 1, GL_RGBA8, GLsizei(size.width), GLsizei(size.height));
    depth = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(depth.id(), 1, r.outputDepthFormat(), GLsizei(size.width), GLsizei(size.height));
    const GLenum at = depthHasStencil(r.outputDepthFormat()) ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT;
    fbo = gl::createFramebuffer();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    glNamedFramebufferTexture(fbo.id(), at, depth.id(), 0);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    if (!copyDepth) return;
    read = gl::createFramebuffer();
    glNamedFramebufferTexture(read.id(), at, r.outputDepthTexture(), 0);
    glBlitNamedFramebuffer(read.id(), fbo.id(), 0, 0, GLint(size.width), GLint(size.height), 0, 0,
                           GLint(size.width), GLint(size.height), GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  }
  // Whether the overlay covers pixel (x, y) (from the lower-left corner).
  bool magenta(int x, int y) const {
    uint8_t px[4] = {};
    glGetTextureSubImage(color.id(), 0, x, y, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, sizeof px, px);
    return px[0] == 255 && px[1] == 0 && px[2] == 255;
  }
};

class RendererDepth : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }

  std::unique_ptr<Renderer> make(bool keepDepth, const std::string& resource = {}) {
    RendererOptions options;
    options.size = kSize;
    options.keepDepth = keepDepth;
    options.depthResource = resource;
    Diagnostics diags;
    auto r = Renderer::fromFile(kDefault, options, diags);
    EXPECT_TRUE(r) << (diags.empty() ? std::string() : formatDiagnostic(diags.front()));
    if (r) r->setScene(cubeScene());
    return r;
  }
  static glm::mat4 viewProj(const Renderer& r) {
    return r.camera().viewProjection(float(kSize.width) / float(kSize.height));
  }
};

// The cube covers the centre (its front face to x = 38 at 64x48); (42, 24) is beside it, inside the overlay
// square (half size 2: to x = 51 at z = -1, to x = 61 at z = 1).
constexpr int kCentreX = 32, kCentreY = 24, kBesideX = 42;

TEST_F(RendererDepth, AnOverlayIsHiddenBehindTheSceneAndShownInFrontOfIt) {
  auto r = make(true);
  ASSERT_TRUE(r);
  r->render();
  ASSERT_NE(r->outputDepthTexture(), 0u);
  EXPECT_EQ(r->outputDepthResource(), "forwardDepth") << "default.json's last scene depth";
  EXPECT_EQ(r->outputDepthFormat(), GLenum(GL_DEPTH24_STENCIL8));
  EXPECT_EQ(r->outputDepthExtent(), kSize);
  Overlay overlay;

  CallerTarget behind(*r, true);
  overlay.draw(behind.fbo.id(), behind.size, viewProj(*r), -1.0f, 2.0f);  // behind the cube (z -0.5..0.5)
  EXPECT_FALSE(behind.magenta(kCentreX, kCentreY)) << "hidden where the cube is in front of it";
  EXPECT_TRUE(behind.magenta(kBesideX, kCentreY)) << "shown beside the cube";

  CallerTarget front(*r, true);
  overlay.draw(front.fbo.id(), front.size, viewProj(*r), 1.0f, 2.0f);  // in front of the cube
  EXPECT_TRUE(front.magenta(kCentreX, kCentreY));
  EXPECT_TRUE(front.magenta(kBesideX, kCentreY));

  // Without rgraph's depth the overlay would cover the cube: what the depth changes.
  CallerTarget noDepth(*r, false);
  overlay.draw(noDepth.fbo.id(), noDepth.size, viewProj(*r), -1.0f, 2.0f);
  EXPECT_TRUE(noDepth.magenta(kCentreX, kCentreY));
}

// The depth follows the camera frame by frame (a copy per render()).
TEST_F(RendererDepth, TheDepthIsThatOfTheLastFrame) {
  auto r = make(true);
  ASSERT_TRUE(r);
  r->render();
  Camera aside = r->camera();
  aside.position.x += 20.0f;  // the cube leaves the view
  aside.target.x += 20.0f;
  r->setCamera(aside);
  r->render();
  CallerTarget behind(*r, true);
  Overlay().draw(behind.fbo.id(), behind.size, viewProj(*r), -1.0f, 100.0f);
  EXPECT_TRUE(behind.magenta(kCentreX, kCentreY)) << "nothing in front of it any more";
}

TEST_F(RendererDepth, WithoutKeepDepthThereIsNoneAndAnUnknownResourceIsRefused) {
  auto r = make(false);
  ASSERT_TRUE(r);
  r->render();
  EXPECT_EQ(r->outputDepthTexture(), 0u);
  EXPECT_EQ(r->outputDepthFormat(), 0u);
  EXPECT_EQ(r->outputDepthResource(), "");

  auto named = make(true, "gDepth");
  ASSERT_TRUE(named);
  named->render();
  EXPECT_EQ(named->outputDepthResource(), "gDepth");
  EXPECT_NE(named->outputDepthTexture(), 0u);

  auto wrong = make(true, "hdr");
  ASSERT_TRUE(wrong);
  const std::string what = testsupport::errorOf([&] { wrong->render(); });
  EXPECT_NE(what.find("RendererOptions::depthResource 'hdr': no pass that runs attaches it as depth"),
            std::string::npos)
      << what;
}

// renderer.h: fromScene fills in what code may leave out, and keeps what is given.
TEST(RenderSceneFromScene, DerivesBoundsAndLightRadii) {
  Scene s;
  s.meshes.push_back(makeCube(0.5f));
  s.meshes[0].bounds = Bounds{};  // left out
  s.materials.push_back(Material{});
  Primitive moved;
  moved.mesh = 0;
  moved.material = 0;
  moved.transform = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 0.0f, 0.0f));
  s.primitives.push_back(moved);
  Primitive given = moved;
  given.bounds.expand(glm::vec3(-7.0f));
  given.bounds.expand(glm::vec3(7.0f));
  s.primitives.push_back(given);
  PointLight derived;
  derived.position = {0.0f, 2.0f, 0.0f};
  PointLight kept = derived;
  kept.radius = 3.0f;
  s.pointLights = {derived, kept};

  const auto scene = RenderScene::fromScene(s);
  const Scene& out = scene->scene();
  EXPECT_EQ(out.meshes[0].bounds.min, glm::vec3(-0.5f));
  EXPECT_EQ(out.meshes[0].bounds.max, glm::vec3(0.5f));
  EXPECT_EQ(out.primitives[0].bounds.min, glm::vec3(1.5f, -0.5f, -0.5f));
  EXPECT_EQ(out.primitives[0].bounds.max, glm::vec3(2.5f, 0.5f, 0.5f));
  EXPECT_EQ(out.primitives[1].bounds.min, glm::vec3(-7.0f)) << "given bounds are kept";
  EXPECT_GT(out.pointLights[0].radius, 0.0f);
  EXPECT_FLOAT_EQ(out.pointLights[0].radius, lightRadius(derived));
  EXPECT_FLOAT_EQ(out.pointLights[1].radius, 3.0f) << "a given radius is kept";
  EXPECT_EQ(out.bounds().max, glm::vec3(7.0f));
}

}  // namespace
