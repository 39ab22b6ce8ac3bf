#include "caller_drawing.h"

#include <GL/glcorearb.h>

#include <array>
#include <cstring>

#include "fixed_state.h"
#include "rgraph/error.h"
#include "rgraph/gl/objects.h"

namespace rgraph::testsupport {
namespace {

constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec2 a_uv;
out vec2 v_uv;
void main() { v_uv = a_uv; gl_Position = vec4(a_pos, 1.0); }
)";

// Every binding the drawing reads sits where rgraph binds its own (unit 0-1,
// uniform and storage binding 0).
constexpr const char* kFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_checker;
layout(binding = 1) uniform sampler2D u_detail;
layout(std140, binding = 0) uniform Tint { vec4 tint; };
layout(std430, binding = 0) readonly buffer Offset { vec4 offset; };
in vec2 v_uv;
out vec4 o_color;
void main() {
  o_color = texture(u_checker, v_uv) * tint + offset + vec4(texture(u_detail, v_uv).rgb * 0.25, 0.0);
}
)";

struct Vertex {
  float x, y, z, u, v;
};

// Front faces are clockwise (glFrontFace(GL_CW)). Depth GL_GREATER over a
// depth cleared to 0, stencil GL_NOTEQUAL 2 incrementing on pass: the third
// triangle, nearest by depth, is kept out by the stencil where the first two
// overlap (stencil 2) and drawn over the first alone (stencil 1); the fourth
// is kept out by the depth the first wrote.
constexpr Vertex kTriangles[] = {
    {-0.9f, -0.8f, -0.4f, 0.0f, 0.0f},
    {0.1f, 0.9f, -0.4f, 0.5f, 1.0f},
    {0.8f, -0.7f, -0.4f, 1.0f, 0.0f},
    {-0.6f, 0.7f, 0.4f, 0.0f, 1.0f},
    {0.9f, 0.6f, 0.4f, 1.0f, 1.0f},
    {-0.2f, -0.9f, 0.4f, 0.3f, 0.0f},
    {-1.0f, 0.0f, 0.6f, 0.0f, 0.5f},
    {0.2f, 1.0f, 0.6f, 0.6f, 1.0f},
    {1.0f, -0.2f, 0.6f, 1.0f, 0.4f},
    // Farthest, drawn last: hidden by the depth test where the first triangle is.
    {-0.9f, -0.95f, -0.7f, 0.2f, 0.0f},
    {-0.5f, -0.2f, -0.7f, 0.4f, 0.8f},
    {0.3f, -0.95f, -0.7f, 0.9f, 0.1f},
    // Counter-clockwise: a back face, culled.
    {-0.5f, -0.5f, 0.9f, 0.0f, 0.0f},
    {0.5f, -0.5f, 0.9f, 1.0f, 0.0f},
    {0.0f, 0.5f, 0.9f, 0.5f, 1.0f},
};

// 3x2 RGB8, rows of 9 bytes, uploaded with an unpack alignment of 1 (4
// would start the second row at byte 12).
constexpr std::array<uint8_t, 24> kDetail = {250, 10,  30, 20,  240, 40,  60, 70, 230, 0,   0,   0,
                                             90,  200, 20, 220, 30,  190, 15, 25, 35,  255, 255, 255};

gl::Shader compile(GLenum stage, const char* source) {
  gl::Shader s = gl::createShader(stage);
  glShaderSource(s.id(), 1, &source, nullptr);
  glCompileShader(s.id());
  GLint ok = 0;
  glGetShaderiv(s.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s.id(), sizeof log, nullptr, log);
    throw RuntimeError(std::string("caller_drawing.cpp: the caller's shader does not compile: ") + log);
  }
  return s;
}

}  // namespace

struct CallerDrawing::Impl {
  gl::Texture color = gl::createTexture(GL_TEXTURE_2D);
  gl::Texture depthStencil = gl::createTexture(GL_TEXTURE_2D);
  gl::Framebuffer fbo = gl::createFramebuffer();
  gl::Program program = gl::createProgram();
  gl::Buffer vertices = gl::createBuffer();
  gl::VertexArray vao = gl::createVertexArray();
  gl::Texture checker = gl::createTexture(GL_TEXTURE_2D);
  gl::Sampler nearest = gl::createSampler();
  gl::Texture detail = gl::createTexture(GL_TEXTURE_2D);
  gl::Buffer tint = gl::createBuffer();
  gl::Buffer offset = gl::createBuffer();

  // The fixed-function state its drawing uses, each item away from GL's
  // initial value (core/src/gl/fixed_state.h: the setter the executor's
  // hostile state goes through too).
  static gl::FixedState fixedState(Extent size) {
    gl::FixedState s;
    s.viewport = {3, 5, static_cast<int32_t>(size.width) - 10, static_cast<int32_t>(size.height) - 14};
    s.scissor = {6, 2, static_cast<int32_t>(size.width) - 14, static_cast<int32_t>(size.height) - 6};
    s.scissorTest = true;
    s.blend = true;
    s.blendSrcRgb = GL_SRC_ALPHA, s.blendDstRgb = GL_CONSTANT_COLOR, s.blendSrcAlpha = GL_ONE, s.blendDstAlpha = GL_ZERO;
    s.blendEquationRgb = GL_FUNC_ADD, s.blendEquationAlpha = GL_MIN;
    s.blendColor = {0.25f, 0.5f, 0.75f, 1.0f};
    s.depthTest = true;
    s.depthFunc = GL_GREATER;
    s.depthMask = true;
    s.stencilTest = true;
    s.stencilFunc = GL_NOTEQUAL, s.stencilRef = 2, s.stencilValueMask = 0xFF;
    s.stencilFail = GL_KEEP, s.stencilDepthFail = GL_KEEP, s.stencilPass = GL_INCR;
    s.stencilWriteMask = 0xFF;
    s.cullFace = true;
    s.cullMode = GL_BACK, s.frontFace = GL_CW;
    s.framebufferSrgb = true;
    s.colorMask = {true, true, false, true};
    return s;
  }

  void setState(Extent size) const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glUseProgram(program.id());
    glBindVertexArray(vao.id());
    glBindTextureUnit(0, checker.id());
    glBindSampler(0, nearest.id());
    glBindTextureUnit(1, detail.id());
    glBindSampler(1, 0);
    glBindBufferRange(GL_UNIFORM_BUFFER, 0, tint.id(), 256, 16);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, offset.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_POLYGON_OFFSET_FILL);
    gl::applyFixedState(fixedState(size));
  }
};

CallerDrawing::CallerDrawing(Extent size) : impl_(std::make_unique<Impl>()), size_(size) {
  Impl& m = *impl_;
  const auto w = static_cast<GLsizei>(size.width), h = static_cast<GLsizei>(size.height);
  glTextureStorage2D(m.color.id(), 1, GL_SRGB8_ALPHA8, w, h);
  glTextureStorage2D(m.depthStencil.id(), 1, GL_DEPTH24_STENCIL8, w, h);
  glNamedFramebufferTexture(m.fbo.id(), GL_COLOR_ATTACHMENT0, m.color.id(), 0);
  glNamedFramebufferTexture(m.fbo.id(), GL_DEPTH_STENCIL_ATTACHMENT, m.depthStencil.id(), 0);
  if (glCheckNamedFramebufferStatus(m.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RuntimeError("caller_drawing.cpp: the caller's framebuffer is incomplete");

  gl::Shader vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, kFragment);
  glAttachShader(m.program.id(), vs.id());
  glAttachShader(m.program.id(), fs.id());
  glLinkProgram(m.program.id());
  GLint linked = 0;
  glGetProgramiv(m.program.id(), GL_LINK_STATUS, &linked);
  if (!linked) throw RuntimeError("caller_drawing.cpp: the caller's program does not link");

  glNamedBufferStorage(m.vertices.id(), sizeof kTriangles, kTriangles, 0);
  glVertexArrayVertexBuffer(m.vao.id(), 0, m.vertices.id(), 0, sizeof(Vertex));
  glEnableVertexArrayAttrib(m.vao.id(), 0);
  glEnableVertexArrayAttrib(m.vao.id(), 1);
  glVertexArrayAttribFormat(m.vao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(m.vao.id(), 1, 2, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
  glVertexArrayAttribBinding(m.vao.id(), 0, 0);
  glVertexArrayAttribBinding(m.vao.id(), 1, 0);

  // A 4x4 checker filtered linearly by its own parameters, sampled nearest
  // through the sampler object: a lost sampler binding shows.
  std::array<uint8_t, 64> checker{};
  for (size_t t = 0; t < 16; ++t) {
    const bool on = ((t % 4) + (t / 4)) % 2 == 0;
    const uint8_t texel[4] = {static_cast<uint8_t>(on ? 230 : 40), static_cast<uint8_t>(on ? 60 : 200),
                              static_cast<uint8_t>(40 + 10 * t), 200};
    std::memcpy(&checker[t * 4], texel, 4);
  }
  glTextureStorage2D(m.checker.id(), 1, GL_RGBA8, 4, 4);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(m.checker.id(), 0, 0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, checker.data());
  glTextureParameteri(m.checker.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(m.checker.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(m.nearest.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(m.nearest.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureStorage2D(m.detail.id(), 1, GL_RGB8, 3, 2);
  glTextureParameteri(m.detail.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(m.detail.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  // The tint the drawing uses lies at 256 (bound as a range); a whole-buffer
  // binding would read the zeros at 0.
  std::array<float, 68> tint{};
  const float used[4] = {1.0f, 0.8f, 0.6f, 0.75f};
  std::memcpy(&tint[64], used, sizeof used);
  glNamedBufferStorage(m.tint.id(), sizeof tint, tint.data(), 0);
  const float offset[4] = {0.05f, 0.1f, 0.0f, 0.0f};
  glNamedBufferStorage(m.offset.id(), sizeof offset, offset, 0);
}

CallerDrawing::~CallerDrawing() = default;

uint32_t CallerDrawing::framebuffer() const { return impl_->fbo.id(); }

std::vector<uint8_t> CallerDrawing::drawAround(const std::function<void()>& frame) {
  Impl& m = *impl_;
  // Cleared without the caller's state (glClearTexImage ignores scissor and masks).
  const float clearColor[4] = {0.1f, 0.2f, 0.3f, 0.4f};
  glClearTexImage(m.color.id(), 0, GL_RGBA, GL_FLOAT, clearColor);
  const struct {
    float depth;
    uint32_t stencil;
  } clearDepth = {0.0f, 0};
  glClearTexImage(m.depthStencil.id(), 0, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &clearDepth);
  m.setState(size_);
  if (frame) frame();
  // What the caller does after the frame, with the state it set before.
  glTextureSubImage2D(m.detail.id(), 0, 0, 0, 3, 2, GL_RGB, GL_UNSIGNED_BYTE, kDetail.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(std::size(kTriangles)));
  std::vector<uint8_t> rgba(static_cast<size_t>(size_.width) * size_.height * 4);
  glGetTextureImage(m.color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgba.size()), rgba.data());
  return rgba;
}

size_t differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, Extent size, std::string* first) {
  const size_t pixels = static_cast<size_t>(size.width) * size.height;
  if (a.size() != pixels * 4 || b.size() != pixels * 4) {
    if (first) *first = "sizes differ: " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " bytes";
    return pixels;
  }
  size_t n = 0;
  for (size_t p = 0; p < pixels; ++p) {
    if (std::memcmp(&a[p * 4], &b[p * 4], 4) == 0) continue;
    if (n++ == 0 && first) {
      auto rgba = [](const uint8_t* q) {
        return std::to_string(q[0]) + "," + std::to_string(q[1]) + "," + std::to_string(q[2]) + "," +
               std::to_string(q[3]);
      };
      *first = "pixel (" + std::to_string(p % size.width) + "," + std::to_string(p / size.width) +
               ") from the bottom: " + rgba(&a[p * 4]) + " vs " + rgba(&b[p * 4]);
    }
  }
  return n;
}

}  // namespace rgraph::testsupport
