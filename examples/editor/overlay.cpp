#include "overlay.h"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace editor {
namespace {

// The grid: lines one unit apart over -5..5 in x and z, a little above y = 0
// (the level's ground): exactly on the floor, the floor's depth and the
// lines' would tie and the lines would come and go with rounding.
constexpr int kGridHalf = 5;
constexpr float kGridHeight = 0.005f;
constexpr float kAxisLength = 1.0f;

struct Vertex {
  glm::vec3 position, colour;
};

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
layout(location = 0) uniform mat4 viewProjection;
out vec3 lineColour;
void main() {
  lineColour = colour;
  gl_Position = viewProjection * vec4(position, 1.0);
})";

// The depth test, by hand: rgraph's depth is a texture, not our depth buffer.
const char* kFragmentShader = R"(#version 450 core
layout(binding = 0) uniform sampler2D sceneDepth;
in vec3 lineColour;
out vec4 colour;
void main() {
  if (gl_FragCoord.z > texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r) discard;  // behind the scene
  colour = vec4(lineColour, 1.0);
})";

GLuint compile() {
  const GLuint program = glCreateProgram();
  for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, kVertexShader}, {GL_FRAGMENT_SHADER, kFragmentShader}}) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
    glDeleteShader(shader);  // freed with the program
  }
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error(std::string("the overlay shader does not link: ") + log);
  }
  return program;
}

}  // namespace

Overlay::Overlay() : program_(compile()) {
  std::vector<Vertex> grid;
  for (int i = -kGridHalf; i <= kGridHalf; ++i) {
    const float a = float(i), e = float(kGridHalf);
    grid.push_back({{a, kGridHeight, -e}, kGrid});
    grid.push_back({{a, kGridHeight, e}, kGrid});
    grid.push_back({{-e, kGridHeight, a}, kGrid});
    grid.push_back({{e, kGridHeight, a}, kGrid});
  }
  gridVertices_ = GLsizei(grid.size());
  // The grid once, then room for the gizmo's 6 vertices, rewritten per frame.
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr((grid.size() + 6) * sizeof(Vertex)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferSubData(buffer_, 0, GLsizeiptr(grid.size() * sizeof(Vertex)), grid.data());
  glCreateVertexArrays(1, &vao_);
  glVertexArrayVertexBuffer(vao_, 0, buffer_, 0, sizeof(Vertex));
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * GLuint(sizeof(glm::vec3)));
    glVertexArrayAttribBinding(vao_, a, 0);
  }
  // Depth read as a number: nearest, no comparison, whatever the texture's own settings.
  glCreateSamplers(1, &sampler_);
  glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(sampler_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
}

Overlay::~Overlay() {
  glDeleteSamplers(1, &sampler_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &buffer_);
  glDeleteProgram(program_);
}

void Overlay::draw(const glm::mat4& viewProjection, GLuint sceneDepth, const std::optional<glm::vec3>& gizmoAt) {
  GLsizei count = gridVertices_;
  if (gizmoAt) {
    Vertex gizmo[6];
    for (int axis = 0; axis < 3; ++axis) {
      glm::vec3 tip = *gizmoAt;
      tip[axis] += kAxisLength;
      gizmo[2 * axis] = {*gizmoAt, kAxes[axis]};
      gizmo[2 * axis + 1] = {tip, kAxes[axis]};
    }
    glNamedBufferSubData(buffer_, GLintptr(gridVertices_ * sizeof(Vertex)), sizeof gizmo, gizmo);
    count += 6;
  }
  glUseProgram(program_);
  glUniformMatrix4fv(0, 1, GL_FALSE, &viewProjection[0][0]);
  glBindVertexArray(vao_);
  glBindTextureUnit(0, sceneDepth);
  glBindSampler(0, sampler_);
  glDisable(GL_DEPTH_TEST);  // the shader tests against rgraph's depth instead
  glDrawArrays(GL_LINES, 0, count);
  glBindSampler(0, 0);
}

}  // namespace editor
