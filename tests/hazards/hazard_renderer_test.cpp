// Hazard modes through the public renderer (RendererOptions::hazards), with a
// caller's GL state around the frame.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {

using namespace rgraph;

GLint samplerOn(GLuint unit) {
  GLint active = GL_TEXTURE0, sampler = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glActiveTexture(GL_TEXTURE0 + unit);
  glGetIntegerv(GL_SAMPLER_BINDING, &sampler);
  glActiveTexture(static_cast<GLenum>(active));
  return sampler;
}

// Every pass is promised sampler 0 on every unit (state-scramble names a pass
// that leaves one): the renderer binds 0 at the start of a frame, so that a
// sampler object a caller left bound is neither sampled through by a pass nor
// blamed on the first one, and puts the caller's back afterwards.
TEST(HazardRenderer, ACallersSamplerLeftBoundIsNotBlamedOnAPass) {
  testsupport::sharedGlContext();
  RendererOptions o;
  o.size = {32, 32};
  o.runChecks = false;
  o.hazards = HazardModes::of(HazardMode::stateScramble);
  Diagnostics diags;
  std::unique_ptr<Renderer> r = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/forward.json", o, diags);
  ASSERT_TRUE(r);
  r->setScene(RenderScene::load("learnopengl"));
  gl::Sampler callers = gl::createSampler();
  for (GLuint unit = 0; unit < 16; ++unit) glBindSampler(unit, callers.id());
  EXPECT_NO_THROW(r->render());
  for (GLuint unit : {0u, 9u, 15u}) EXPECT_EQ(samplerOn(unit), static_cast<GLint>(callers.id())) << "unit " << unit;
  for (GLuint unit = 0; unit < 16; ++unit) glBindSampler(unit, 0);
}

}  // namespace
