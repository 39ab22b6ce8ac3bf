// Shared by the GpuScene view tests (gpu_scene_view_test, gpu_scene_instancing_test):
// a colour texture (rgba32f) and a depth texture of one shape, side x side
// texels, and a framebuffer that attaches one layer of both, or all of them
// (layered). Binding clears both (colour to 0, depth to 1); depth testing is
// the test's to switch on.
#pragma once

#include <GL/glcorearb.h>

#include <gtest/gtest.h>

#include <vector>

#include <glm/glm.hpp>

#include "rgraph/gl/objects.h"

namespace rgraph::test {

using Pixels = std::vector<glm::vec4>;

struct LayeredTarget {
  GLenum target;
  uint32_t side;
  int layers;
  gl::Texture color, depth;
  gl::Framebuffer fbo = gl::createFramebuffer();

  // GL_TEXTURE_2D (1 layer), GL_TEXTURE_2D_ARRAY (n layers) or GL_TEXTURE_CUBE_MAP (6 faces); all layers attached.
  LayeredTarget(GLenum t, uint32_t side_, int n) : target(t), side(side_), layers(t == GL_TEXTURE_CUBE_MAP ? 6 : n) {
    color = gl::createTexture(target);
    depth = gl::createTexture(target);
    if (target == GL_TEXTURE_2D_ARRAY) {
      glTextureStorage3D(color.id(), 1, GL_RGBA32F, side, side, layers);
      glTextureStorage3D(depth.id(), 1, GL_DEPTH_COMPONENT32F, side, side, layers);
    } else {
      glTextureStorage2D(color.id(), 1, GL_RGBA32F, side, side);
      glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, side, side);
    }
    attachAll();
  }
  void checkComplete() const {
    ASSERT_EQ(glCheckNamedFramebufferStatus(fbo.id(), GL_DRAW_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  }
  // Layer (or cube face) `layer` of both, bound and cleared.
  void attachLayer(int layer) {
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0, layer);
    glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0, layer);
    bindAndClear();
  }
  // Every layer (a layered attachment for arrays and cube maps), bound and cleared.
  void attachAll() {
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    bindAndClear();
  }
  void bindAndClear() {
    checkComplete();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, GLsizei(side), GLsizei(side));
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &one);
  }
  // Layer `layer`'s colour, rows bottom-up (GL order).
  Pixels read(int layer) const {
    Pixels px(size_t(side) * side);
    glGetTextureSubImage(color.id(), 0, 0, 0, layer, GLsizei(side), GLsizei(side), 1, GL_RGBA, GL_FLOAT,
                         GLsizei(px.size() * sizeof(glm::vec4)), px.data());
    return px;
  }
};

}  // namespace rgraph::test
