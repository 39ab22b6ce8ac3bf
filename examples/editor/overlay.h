// The editor's own drawing over rgraph's frame, with plain GL: a grid on the
// ground and a gizmo (three axes) at the selected model. Depth-tested against
// the scene: the fragment shader reads rgraph's depth of the frame
// (RendererOptions::keepDepth, Renderer::outputDepthTexture) and drops what
// is behind the scene's surfaces.
#pragma once

#include <GL/glcorearb.h>

#include <optional>

#include <glm/glm.hpp>

namespace editor {

class Overlay {
 public:
  Overlay();  // needs the GL context current; throws std::runtime_error if the shader does not link
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  // Draws into the framebuffer bound now, over its whole viewport. `sceneDepth`:
  // rgraph's depth texture of the frame (window-space depth of
  // `viewProjection`), the same size as the viewport.
  void draw(const glm::mat4& viewProjection, GLuint sceneDepth, const std::optional<glm::vec3>& gizmoAt);

  // The colours it draws with (tests look for them).
  static constexpr glm::vec3 kGrid{0.55f, 0.55f, 0.6f};
  static constexpr glm::vec3 kAxes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

 private:
  GLuint program_ = 0, vao_ = 0, buffer_ = 0, sampler_ = 0;
  GLsizei gridVertices_ = 0;
};

}  // namespace editor
