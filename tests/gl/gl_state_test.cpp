// The GL state contract (rgraph/renderer.h): gl::SavedState / GlStateGuard
// put back every listed piece of state, and a caller's own drawing after a
// real pipeline frame gives the pixels it gives without one.
//
// The state is set and read back here with the test's own GL calls (the
// `items()` list below), not with gl_state.cpp's tables, so an item missing
// there fails here by name.
#include "rgraph/gl/gl_state.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <functional>

#include "gl_test_util.h"
#include "rgraph/gl/objects.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/caller_drawing.h"
#include "support/test_support.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

using Values = std::vector<int64_t>;

Values get(GLenum pname, size_t n = 1) {
  Values v(n);
  glGetInteger64v(pname, v.data());
  return v;
}

Values getIndexed(std::initializer_list<GLenum> pnames, GLuint index) {
  Values v;
  for (GLenum p : pnames) {
    GLint64 x = 0;
    glGetInteger64i_v(p, index, &x);
    v.push_back(x);
  }
  return v;
}

Values textureBindings(GLuint unit) {
  static constexpr GLenum kBindings[] = {
      GL_TEXTURE_BINDING_1D,        GL_TEXTURE_BINDING_1D_ARRAY,       GL_TEXTURE_BINDING_2D,
      GL_TEXTURE_BINDING_2D_ARRAY,  GL_TEXTURE_BINDING_2D_MULTISAMPLE, GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY,
      GL_TEXTURE_BINDING_3D,        GL_TEXTURE_BINDING_CUBE_MAP,       GL_TEXTURE_BINDING_CUBE_MAP_ARRAY,
      GL_TEXTURE_BINDING_RECTANGLE, GL_TEXTURE_BINDING_BUFFER};
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glActiveTexture(GL_TEXTURE0 + unit);
  Values v;
  for (GLenum b : kBindings) v.push_back(get(b)[0]);
  v.push_back(get(GL_SAMPLER_BINDING)[0]);
  glActiveTexture(static_cast<GLenum>(active));
  return v;
}

// GL objects to bind: two of each kind (variant 0 and 1) where one is enough.
struct Objects {
  gl::Framebuffer fb[2] = {gl::createFramebuffer(), gl::createFramebuffer()};
  gl::Program program[2];
  gl::VertexArray vao[2] = {gl::createVertexArray(), gl::createVertexArray()};
  std::vector<gl::Buffer> buffers;
  std::vector<gl::Texture> tex2d;  // [variant * 16 + unit]
  gl::Texture cube[2] = {gl::createTexture(GL_TEXTURE_CUBE_MAP), gl::createTexture(GL_TEXTURE_CUBE_MAP)};
  gl::Texture multisample = gl::createTexture(GL_TEXTURE_2D_MULTISAMPLE);
  gl::Texture array = gl::createTexture(GL_TEXTURE_2D_ARRAY);
  gl::Texture volume = gl::createTexture(GL_TEXTURE_3D);
  gl::Texture image[2] = {gl::createTexture(GL_TEXTURE_2D_ARRAY), gl::createTexture(GL_TEXTURE_2D_ARRAY)};
  std::vector<gl::Sampler> samplers;  // 4

  Objects() {
    for (int v = 0; v < 2; ++v) {
      const char* src = v ? "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n"
                          : "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(0.5); }\n";
      program[v] = gl::Program(glCreateShaderProgramv(GL_FRAGMENT_SHADER, 1, &src));
      glTextureStorage3D(image[v].id(), 2, GL_RGBA8, 8, 8, 3);
      glTextureStorage2D(cube[v].id(), 1, GL_RGBA8, 4, 4);
    }
    for (int k = 0; k < 20; ++k) {
      buffers.push_back(gl::createBuffer());
      glNamedBufferStorage(buffers.back().id(), 4096, nullptr, 0);
    }
    for (int k = 0; k < 32; ++k) {
      tex2d.push_back(gl::createTexture(GL_TEXTURE_2D));
      glTextureStorage2D(tex2d.back().id(), 1, GL_RGBA8, 2, 2);
    }
    glTextureStorage2DMultisample(multisample.id(), 4, GL_RGBA8, 4, 4, GL_TRUE);
    glTextureStorage3D(array.id(), 1, GL_RGBA8, 2, 2, 2);
    glTextureStorage3D(volume.id(), 1, GL_RGBA8, 2, 2, 2);
    for (int k = 0; k < 4; ++k) samplers.push_back(gl::createSampler());
  }
  GLuint buf(size_t k) const { return buffers.at(k).id(); }
};

struct Item {
  std::string name;
  std::function<void(int variant)> set;  // 0: the caller's state; 1: scrambled, different in every item
  std::function<Values()> read;
};

void addEnable(std::vector<Item>& items, const char* name, GLenum cap, bool initial) {
  items.push_back({name, [=](int v) { (v == 0) != initial ? glEnable(cap) : glDisable(cap); },
                   [=] { return Values{glIsEnabled(cap)}; }});
}

void bindBuffer(GLenum target, GLuint index, GLuint buffer, bool range, int k) {
  if (range)
    glBindBufferRange(target, index, buffer, 256 * (1 + k % 3), 64 + 16 * k);
  else
    glBindBufferBase(target, index, buffer);
}

// Every piece of state the contract lists, in the order it is set (indexed
// buffer bindings before the generic ones they overwrite, the active texture
// unit last).
std::vector<Item> contractItems(const Objects& o) {
  std::vector<Item> it;
  it.push_back({"draw framebuffer", [&](int v) { glBindFramebuffer(GL_DRAW_FRAMEBUFFER, o.fb[v].id()); },
                [] { return get(GL_DRAW_FRAMEBUFFER_BINDING); }});
  it.push_back({"read framebuffer", [&](int v) { glBindFramebuffer(GL_READ_FRAMEBUFFER, o.fb[1 - v].id()); },
                [] { return get(GL_READ_FRAMEBUFFER_BINDING); }});
  it.push_back({"program", [&](int v) { glUseProgram(o.program[v].id()); }, [] { return get(GL_CURRENT_PROGRAM); }});
  it.push_back(
      {"vertex array", [&](int v) { glBindVertexArray(o.vao[v].id()); }, [] { return get(GL_VERTEX_ARRAY_BINDING); }});
  it.push_back({"array buffer", [&](int v) { glBindBuffer(GL_ARRAY_BUFFER, o.buf(v)); },
                [] { return get(GL_ARRAY_BUFFER_BINDING); }});
  it.push_back({"viewport", [](int v) { v ? glViewport(5, 6, 77, 88) : glViewport(1, 2, 33, 44); },
                [] { return get(GL_VIEWPORT, 4); }});
  it.push_back({"scissor box", [](int v) { v ? glScissor(7, 8, 99, 11) : glScissor(3, 4, 21, 23); },
                [] { return get(GL_SCISSOR_BOX, 4); }});
  addEnable(it, "depth test", GL_DEPTH_TEST, false);
  addEnable(it, "stencil test", GL_STENCIL_TEST, false);
  addEnable(it, "cull face", GL_CULL_FACE, false);
  addEnable(it, "scissor test", GL_SCISSOR_TEST, false);
  addEnable(it, "framebuffer sRGB", GL_FRAMEBUFFER_SRGB, false);
  addEnable(it, "polygon offset fill", GL_POLYGON_OFFSET_FILL, false);
  addEnable(it, "multisample", GL_MULTISAMPLE, true);
  addEnable(it, "depth clamp", GL_DEPTH_CLAMP, false);
  addEnable(it, "rasterizer discard", GL_RASTERIZER_DISCARD, false);
  addEnable(it, "colour logic op", GL_COLOR_LOGIC_OP, false);
  addEnable(it, "primitive restart", GL_PRIMITIVE_RESTART, false);
  addEnable(it, "primitive restart (fixed index)", GL_PRIMITIVE_RESTART_FIXED_INDEX, false);
  addEnable(it, "sample alpha to coverage", GL_SAMPLE_ALPHA_TO_COVERAGE, false);
  addEnable(it, "sample coverage", GL_SAMPLE_COVERAGE, false);
  addEnable(it, "sample mask", GL_SAMPLE_MASK, false);
  static constexpr GLenum kFactors[] = {
      GL_SRC_ALPHA, GL_ONE_MINUS_DST_COLOR, GL_CONSTANT_ALPHA, GL_DST_ALPHA, GL_ONE, GL_SRC_COLOR, GL_ZERO};
  static constexpr GLenum kEquations[] = {GL_FUNC_SUBTRACT, GL_MIN, GL_FUNC_REVERSE_SUBTRACT, GL_MAX};
  for (GLuint n = 0; n < 8; ++n) {
    const std::string b = " on draw buffer " + std::to_string(n);
    it.push_back({"blend" + b, [=](int v) { (n + v) % 2 ? glEnablei(GL_BLEND, n) : glDisablei(GL_BLEND, n); },
                  [=] { return Values{glIsEnabledi(GL_BLEND, n)}; }});
    it.push_back({"blend functions" + b,
                  [=](int v) {
                    auto f = [&](int k) { return kFactors[(n + k + 3 * v) % 7]; };
                    glBlendFuncSeparatei(n, f(0), f(1), f(2), f(3));
                  },
                  [=] {
                    return getIndexed({GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA}, n);
                  }});
    it.push_back(
        {"blend equations" + b,
         [=](int v) { glBlendEquationSeparatei(n, kEquations[(n + 2 * v) % 4], kEquations[(n + 1 + 2 * v) % 4]); },
         [=] {
           return getIndexed({GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA}, n);
         }});
    it.push_back({"colour mask" + b,
                  [=](int v) {
                    const GLuint m = v ? ~n : n;
                    glColorMaski(n, m & 1, (m >> 1) & 1, (m >> 2) & 1, v);
                  },
                  [=] {
                    GLboolean m[4] = {};
                    glGetBooleani_v(GL_COLOR_WRITEMASK, n, m);
                    return Values{m[0], m[1], m[2], m[3]};
                  }});
  }
  it.push_back({"blend colour",
                [](int v) { v ? glBlendColor(0.9f, 0.1f, 0.2f, 0.3f) : glBlendColor(0.125f, 0.25f, 0.375f, 0.5f); },
                [] {
                  float c[4] = {};
                  glGetFloatv(GL_BLEND_COLOR, c);
                  Values out;
                  for (float x : c) out.push_back(std::bit_cast<int32_t>(x));
                  return out;
                }});
  it.push_back(
      {"depth function", [](int v) { glDepthFunc(v ? GL_NOTEQUAL : GL_GEQUAL); }, [] { return get(GL_DEPTH_FUNC); }});
  it.push_back(
      {"depth mask", [](int v) { glDepthMask(v ? GL_TRUE : GL_FALSE); }, [] { return get(GL_DEPTH_WRITEMASK); }});
  it.push_back({"stencil function (front)",
                [](int v) {
                  v ? glStencilFuncSeparate(GL_FRONT, GL_LEQUAL, 9, 0xF0)
                    : glStencilFuncSeparate(GL_FRONT, GL_GREATER, 5, 0x3C);
                },
                [] {
                  return Values{get(GL_STENCIL_FUNC)[0], get(GL_STENCIL_REF)[0], get(GL_STENCIL_VALUE_MASK)[0]};
                }});
  it.push_back(
      {"stencil function (back)",
       [](int v) {
         v ? glStencilFuncSeparate(GL_BACK, GL_ALWAYS, 1, 0x55) : glStencilFuncSeparate(GL_BACK, GL_EQUAL, 7, 0x0F);
       },
       [] {
         return Values{get(GL_STENCIL_BACK_FUNC)[0], get(GL_STENCIL_BACK_REF)[0], get(GL_STENCIL_BACK_VALUE_MASK)[0]};
       }});
  it.push_back(
      {"stencil operations (front)",
       [](int v) {
         v ? glStencilOpSeparate(GL_FRONT, GL_ZERO, GL_REPLACE, GL_INCR)
           : glStencilOpSeparate(GL_FRONT, GL_INCR_WRAP, GL_DECR, GL_INVERT);
       },
       [] {
         return Values{get(GL_STENCIL_FAIL)[0], get(GL_STENCIL_PASS_DEPTH_FAIL)[0], get(GL_STENCIL_PASS_DEPTH_PASS)[0]};
       }});
  it.push_back({"stencil operations (back)",
                [](int v) {
                  v ? glStencilOpSeparate(GL_BACK, GL_INVERT, GL_INCR, GL_KEEP)
                    : glStencilOpSeparate(GL_BACK, GL_DECR_WRAP, GL_ZERO, GL_REPLACE);
                },
                [] {
                  return Values{get(GL_STENCIL_BACK_FAIL)[0], get(GL_STENCIL_BACK_PASS_DEPTH_FAIL)[0],
                                get(GL_STENCIL_BACK_PASS_DEPTH_PASS)[0]};
                }});
  it.push_back({"stencil write mask (front)", [](int v) { glStencilMaskSeparate(GL_FRONT, v ? 0xF3 : 0x0F); },
                [] { return get(GL_STENCIL_WRITEMASK); }});
  it.push_back({"stencil write mask (back)", [](int v) { glStencilMaskSeparate(GL_BACK, v ? 0x5A : 0xA5); },
                [] { return get(GL_STENCIL_BACK_WRITEMASK); }});
  it.push_back({"cull face mode", [](int v) { glCullFace(v ? GL_FRONT : GL_FRONT_AND_BACK); },
                [] { return get(GL_CULL_FACE_MODE); }});
  it.push_back({"front face", [](int v) { glFrontFace(v ? GL_CCW : GL_CW); }, [] { return get(GL_FRONT_FACE); }});
  it.push_back({"polygon mode", [](int v) { glPolygonMode(GL_FRONT_AND_BACK, v ? GL_POINT : GL_LINE); },
                [] { return get(GL_POLYGON_MODE, 2); }});
  // Units: a 2D texture everywhere; unit 3 also a cube map and a multisample
  // texture, unit 5 only a multisample texture, unit 12 a 3D and an array
  // texture; the scramble binds other 2D textures and a cube map on unit 7.
  for (GLuint unit = 0; unit < 16; ++unit) {
    it.push_back({"textures on unit " + std::to_string(unit),
                  [&o, unit](int v) {
                    glBindTextureUnit(unit, 0);
                    if (v == 1) {
                      glBindTextureUnit(unit, o.tex2d[16 + unit].id());
                      if (unit == 7) glBindTextureUnit(unit, o.cube[1].id());
                      return;
                    }
                    if (unit != 5 && unit != 12) glBindTextureUnit(unit, o.tex2d[unit].id());
                    if (unit == 3) glBindTextureUnit(unit, o.cube[0].id());
                    if (unit == 3 || unit == 5) glBindTextureUnit(unit, o.multisample.id());
                    if (unit == 12) glBindTextureUnit(unit, o.volume.id());
                    if (unit == 12) glBindTextureUnit(unit, o.array.id());
                  },
                  [unit] {
                    Values t = textureBindings(unit);
                    t.pop_back();  // the sampler: its own item
                    return t;
                  }});
    it.push_back({"sampler on unit " + std::to_string(unit),
                  [&o, unit](int v) { glBindSampler(unit, o.samplers[2 * v + unit % 2].id()); },
                  [unit] { return Values{textureBindings(unit).back()}; }});
  }
  // Buffer bindings: ranges on even indices and whole buffers on odd ones,
  // the other way round in the scramble.
  for (GLenum target : {GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER}) {
    const bool ubo = target == GL_UNIFORM_BUFFER;
    for (GLuint n = 0; n < 8; ++n) {
      it.push_back(
          {std::string(ubo ? "uniform" : "shader storage") + " buffer binding " + std::to_string(n),
           [&o, target, n, ubo](int v) {
             bindBuffer(target, n, o.buf(2 + n + (ubo ? 0 : 8) + v), (n + v) % 2 == 0, static_cast<int>(n + v));
           },
           [target, n, ubo] {
             return ubo ? getIndexed({GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE}, n)
                        : getIndexed({GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                                      GL_SHADER_STORAGE_BUFFER_SIZE},
                                     n);
           }});
    }
  }
  it.push_back({"uniform buffer (generic binding)", [&](int v) { glBindBuffer(GL_UNIFORM_BUFFER, o.buf(18 + v)); },
                [] { return get(GL_UNIFORM_BUFFER_BINDING); }});
  it.push_back({"shader storage buffer (generic binding)",
                [&](int v) { glBindBuffer(GL_SHADER_STORAGE_BUFFER, o.buf(19 - v)); },
                [] { return get(GL_SHADER_STORAGE_BUFFER_BINDING); }});
  static constexpr GLenum kAccess[] = {GL_READ_ONLY, GL_WRITE_ONLY, GL_READ_WRITE};
  static constexpr GLenum kFormats[] = {GL_RGBA8, GL_R32F, GL_RGBA8UI, GL_R32UI};
  for (GLuint n = 0; n < 8; ++n) {
    it.push_back({"image unit " + std::to_string(n),
                  [&o, n](int v) {
                    glBindImageTexture(n, o.image[v].id(), static_cast<GLint>((n + v) % 2), (n + v) % 2 == 0,
                                       static_cast<GLint>((n + v) % 3), kAccess[(n + v) % 3], kFormats[(n + v) % 4]);
                  },
                  [n] {
                    return getIndexed({GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED,
                                       GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT},
                                      n);
                  }});
  }
  static constexpr std::pair<GLenum, const char*> kPixelStore[] = {
      {GL_PACK_ALIGNMENT, "pack alignment"},           {GL_PACK_ROW_LENGTH, "pack row length"},
      {GL_PACK_IMAGE_HEIGHT, "pack image height"},     {GL_PACK_SKIP_ROWS, "pack skip rows"},
      {GL_PACK_SKIP_PIXELS, "pack skip pixels"},       {GL_PACK_SKIP_IMAGES, "pack skip images"},
      {GL_UNPACK_ALIGNMENT, "unpack alignment"},       {GL_UNPACK_ROW_LENGTH, "unpack row length"},
      {GL_UNPACK_IMAGE_HEIGHT, "unpack image height"}, {GL_UNPACK_SKIP_ROWS, "unpack skip rows"},
      {GL_UNPACK_SKIP_PIXELS, "unpack skip pixels"},   {GL_UNPACK_SKIP_IMAGES, "unpack skip images"}};
  for (size_t k = 0; k < std::size(kPixelStore); ++k) {
    const auto [pname, name] = kPixelStore[k];
    const bool alignment = pname == GL_PACK_ALIGNMENT || pname == GL_UNPACK_ALIGNMENT;
    it.push_back({name,
                  [=](int v) { glPixelStorei(pname, alignment ? (v ? 8 : 2) : static_cast<GLint>(3 + k + 20 * v)); },
                  [=] { return get(pname); }});
  }
  it.push_back({"pixel pack buffer", [&](int v) { glBindBuffer(GL_PIXEL_PACK_BUFFER, o.buf(v)); },
                [] { return get(GL_PIXEL_PACK_BUFFER_BINDING); }});
  it.push_back({"pixel unpack buffer", [&](int v) { glBindBuffer(GL_PIXEL_UNPACK_BUFFER, o.buf(1 - v)); },
                [] { return get(GL_PIXEL_UNPACK_BUFFER_BINDING); }});
  it.push_back({"clip control",
                [](int v) {
                  v ? glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE)
                    : glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
                },
                [] {
                  return Values{get(GL_CLIP_ORIGIN)[0], get(GL_CLIP_DEPTH_MODE)[0]};
                }});
  it.push_back({"active texture unit", [](int v) { glActiveTexture(v ? GL_TEXTURE2 : GL_TEXTURE7); },
                [] { return get(GL_ACTIVE_TEXTURE); }});
  return it;
}

void setAll(const std::vector<Item>& it, int variant) {
  for (const Item& i : it) i.set(variant);
}

std::vector<Values> readAll(const std::vector<Item>& it) {
  std::vector<Values> v;
  for (const Item& i : it) v.push_back(i.read());
  return v;
}

std::string text(const Values& v) {
  std::string s;
  for (int64_t x : v) s += (s.empty() ? "" : " ") + std::to_string(x);
  return s;
}

// Items whose value differs between two readings, with both values.
std::vector<std::string> changed(const std::vector<Item>& it, const std::vector<Values>& want,
                                 const std::vector<Values>& got) {
  std::vector<std::string> out;
  for (size_t k = 0; k < it.size(); ++k)
    if (want[k] != got[k]) out.push_back(it[k].name + ": " + text(want[k]) + " became " + text(got[k]));
  return out;
}

std::string lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += "\n  " + l;
  return s;
}

// Leaves the context in its initial state for the tests after these.
void resetToDefaults() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_MULTISAMPLE);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ZERO);
  glBlendEquation(GL_FUNC_ADD);
  glBlendColor(0, 0, 0, 0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glStencilFunc(GL_ALWAYS, 0, ~0u);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glStencilMask(~0u);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  for (GLuint n = 0; n < 16; ++n) {
    glBindTextureUnit(n, 0);
    glBindSampler(n, 0);
  }
  for (GLuint n = 0; n < 8; ++n) {
    glBindBufferBase(GL_UNIFORM_BUFFER, n, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, n, 0);
    glBindImageTexture(n, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
  }
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  gl::applyRendererDefaults();  // pixel store, clip control, the other enables
  glActiveTexture(GL_TEXTURE0);
}

// The contract's items at the caller's values (variant 0), as read back.
struct CallerState {
  Objects objects;
  std::vector<Item> items = contractItems(objects);
  std::vector<Values> values;
  CallerState() {
    setAll(items, 0);
    reread();
  }
  void reread() { values = readAll(items); }
  void scramble() const { setAll(items, 1); }
  // Items whose value differs from the caller's now, one per line.
  std::vector<std::string> changes() const { return changed(items, values, readAll(items)); }
  std::string changeText() const { return lines(changes()); }
};

class GlStateTest : public GlTest {
 protected:
  void TearDown() override {
    resetToDefaults();
    GlTest::TearDown();
  }
};

constexpr Extent kFrameSize{64, 64};

PipelineConfig defaultPipeline() {
  return testsupport::loadPipelineOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json");
}

}  // namespace

TEST_F(GlStateTest, EveryListedItemComesBackAfterAScramble) {
  CallerState caller;
  caller.scramble();
  const std::vector<Values> scrambled = readAll(caller.items);
  setAll(caller.items, 0);
  ASSERT_EQ(readAll(caller.items), caller.values);
  // Each item's two values differ, so an item left scrambled shows.
  for (size_t k = 0; k < caller.items.size(); ++k)
    ASSERT_NE(caller.values[k], scrambled[k]) << caller.items[k].name << ": " << text(scrambled[k]);

  const gl::SavedState saved = gl::SavedState::capture();
  EXPECT_EQ(caller.changeText(), "") << "capture() changed state";
  caller.scramble();
  ASSERT_EQ(readAll(caller.items), scrambled);
  saved.restore();
  EXPECT_EQ(caller.changeText(), "") << "not restored";
  std::printf("[ measure  ] %zu items checked\n", caller.items.size());
}

TEST_F(GlStateTest, TheGuardRestoresAtTheEndOfItsScope) {
  CallerState caller;
  {
    gl::GlStateGuard guard;
    caller.scramble();
  }
  EXPECT_EQ(caller.changeText(), "");
}

TEST_F(GlStateTest, CaptureAndRestoreCost) {
  CallerState caller;
  using Clock = std::chrono::steady_clock;
  constexpr size_t kRounds = 2000;
  std::vector<double> captureUs, restoreUs;
  for (size_t r = 0; r < kRounds; ++r) {
    const auto t0 = Clock::now();
    const gl::SavedState s = gl::SavedState::capture();
    const auto t1 = Clock::now();
    caller.scramble();  // what a frame does: restore has every item to change back
    const auto t2 = Clock::now();
    s.restore();
    const auto t3 = Clock::now();
    captureUs.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    restoreUs.push_back(std::chrono::duration<double, std::micro>(t3 - t2).count());
  }
  glFinish();
  EXPECT_EQ(caller.changeText(), "");
  // Medians: the build machine's cores are shared, and the means jump with it.
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  std::printf("[ measure  ] on %s: capture %.1f us, restore of %zu changed items %.1f us (medians of %zu)\n",
              glContext().renderer().c_str(), median(captureUs), caller.items.size(), median(restoreUs), kRounds);
}

// The caller's state survives a real pipeline frame (first frame: scene
// upload, textures, programs; then a second frame) inside the guard.
TEST_F(GlStateTest, CallerStateSurvivesAPipelineFrameInsideTheGuard) {
  CallerState caller;
  Scene scene = makeLearnOpenGLScene();
  Executor exec(defaultPipeline(), processRegistry(), *shaders, &scene);
  for (int frame = 0; frame < 2; ++frame) {
    {
      gl::GlStateGuard guard;
      gl::applyRendererDefaults();
      exec.resize(kFrameSize);
      exec.renderFrame();
    }
    EXPECT_EQ(caller.changeText(), "") << "frame " << frame;
  }
}

// The caller's own drawing after a guarded frame gives exactly the pixels it
// gives with no frame in between.
TEST_F(GlStateTest, CallerDrawingAfterAGuardedPipelineFrameIsUnchanged) {
  testsupport::CallerDrawing caller;
  const std::vector<uint8_t> alone = caller.drawAround({});
  Scene scene = makeLearnOpenGLScene();
  Executor exec(defaultPipeline(), processRegistry(), *shaders, &scene);
  for (int frame = 0; frame < 2; ++frame) {
    const std::vector<uint8_t> after = caller.drawAround([&] {
      gl::GlStateGuard guard;
      gl::applyRendererDefaults();
      exec.resize(kFrameSize);
      exec.renderFrame();
    });
    std::string first;
    EXPECT_EQ(testsupport::differingPixels(alone, after, caller.size(), &first), 0u)
        << "frame " << frame << ": " << first;
  }
}

// What the two tests above guard against: the same frame without the guard
// changes the caller's state and its drawing (the checks can fail).
TEST_F(GlStateTest, APipelineFrameWithoutTheGuardChangesCallerStateAndDrawing) {
  CallerState caller;
  Scene scene = makeLearnOpenGLScene();
  Executor exec(defaultPipeline(), processRegistry(), *shaders, &scene);
  gl::applyRendererDefaults();  // no uploads through the caller's pixel buffers
  caller.reread();
  exec.resize(kFrameSize);
  exec.renderFrame();
  const std::vector<std::string> lost = caller.changes();
  EXPECT_GE(lost.size(), 10u) << lines(lost);
  std::printf("[ measure  ] an unguarded frame changes %zu of %zu items\n", lost.size(), caller.items.size());
  resetToDefaults();

  testsupport::CallerDrawing drawing;
  const std::vector<uint8_t> alone = drawing.drawAround({});
  const std::vector<uint8_t> after = drawing.drawAround([&] { exec.renderFrame(); });
  // The caller's draw then goes to framebuffer 0, which a surfaceless
  // context does not have: a GL error, itself a symptom of the lost binding.
  errorsAtStart = glContext().debugErrorCount();
  const size_t differ = testsupport::differingPixels(alone, after, drawing.size());
  EXPECT_GT(differ, 100u);
  std::printf("[ measure  ] the caller's drawing after an unguarded frame: %zu of %u pixels differ\n", differ,
              drawing.size().width * drawing.size().height);
}

// The caller's drawing (tests/support/caller_drawing.h) notices each piece of
// the state it relies on: changed alone by a "frame", the pixels change.
TEST_F(GlStateTest, CallerDrawingNoticesEachPieceOfItsState) {
  testsupport::CallerDrawing drawing;
  const std::vector<uint8_t> alone = drawing.drawAround({});
  const Extent s = drawing.size();
  gl::Buffer zeros = gl::createBuffer();
  glNamedBufferStorage(zeros.id(), 1024, nullptr, 0);
  const std::pair<const char*, std::function<void()>> changes[] = {
      {"viewport", [&] { glViewport(0, 0, static_cast<GLsizei>(s.width), static_cast<GLsizei>(s.height)); }},
      {"scissor box", [&] { glScissor(0, 0, static_cast<GLsizei>(s.width), static_cast<GLsizei>(s.height)); }},
      {"scissor test", [] { glDisable(GL_SCISSOR_TEST); }},
      {"blend", [] { glDisable(GL_BLEND); }},
      {"blend functions", [] { glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA); }},
      {"blend equations", [] { glBlendEquation(GL_FUNC_ADD); }},
      {"blend colour", [] { glBlendColor(0, 0, 0, 0); }},
      {"depth test", [] { glDisable(GL_DEPTH_TEST); }},
      {"depth function", [] { glDepthFunc(GL_LESS); }},
      {"depth mask", [] { glDepthMask(GL_FALSE); }},
      {"stencil test", [] { glDisable(GL_STENCIL_TEST); }},
      {"stencil function", [] { glStencilFunc(GL_ALWAYS, 0, 0xFF); }},
      {"stencil operations", [] { glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP); }},
      {"stencil write mask", [] { glStencilMask(0); }},
      {"cull face", [] { glDisable(GL_CULL_FACE); }},
      {"front face", [] { glFrontFace(GL_CCW); }},
      {"polygon mode", [] { glPolygonMode(GL_FRONT_AND_BACK, GL_LINE); }},
      {"framebuffer sRGB", [] { glDisable(GL_FRAMEBUFFER_SRGB); }},
      {"colour mask", [] { glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE); }},
      {"texture on unit 0", [] { glBindTextureUnit(0, 0); }},
      {"sampler on unit 0", [] { glBindSampler(0, 0); }},
      {"texture on unit 1", [] { glBindTextureUnit(1, 0); }},
      {"uniform buffer range", [&] { glBindBufferBase(GL_UNIFORM_BUFFER, 0, zeros.id()); }},
      {"shader storage buffer", [&] { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, zeros.id()); }},
      {"unpack alignment", [] { glPixelStorei(GL_UNPACK_ALIGNMENT, 4); }},
  };
  for (const auto& [name, change] : changes)
    EXPECT_GT(testsupport::differingPixels(alone, drawing.drawAround(change), s), 0u) << name << " went unnoticed";
}

// applyRendererDefaults() changes only state the guard puts back.
TEST_F(GlStateTest, TheGuardUndoesTheRendererDefaults) {
  CallerState caller;
  {
    gl::GlStateGuard guard;
    gl::applyRendererDefaults();
    EXPECT_GE(caller.changes().size(), 20u);
  }
  EXPECT_EQ(caller.changeText(), "");
}

// State a caller may leave behind that rgraph's passes never set themselves:
// with applyRendererDefaults() inside the guard, the frame is the one a clean
// context renders, exactly, and the caller's state comes back. Without it,
// every case but "multisample off" (this pipeline has no multisampled
// target) changes the frame or its read-back (measured, llvmpipe).
TEST_F(GlStateTest, CallerStateLeftBehindDoesNotChangeTheFrame) {
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig cfg = defaultPipeline();
  auto frame = [&] {
    gl::GlStateGuard guard;
    gl::applyRendererDefaults();
    Executor exec(cfg, processRegistry(), *shaders, &scene);
    exec.resize(kFrameSize);
    exec.renderFrame();
    return exec.readOutputRGBA8();
  };
  const std::vector<uint8_t> clean = frame();
  gl::Buffer junk = gl::createBuffer();
  glNamedBufferStorage(junk.id(), 64, nullptr, 0);
  struct Case {
    const char* name;
    std::function<void()> set;
    GLenum pname;  // read before and after the frame
  };
  const Case cases[] = {
      {"polygon mode line", [] { glPolygonMode(GL_FRONT_AND_BACK, GL_LINE); }, GL_POLYGON_MODE},
      {"polygon offset fill",
       [] {
         glPolygonOffset(4.0f, 64.0f);
         glEnable(GL_POLYGON_OFFSET_FILL);
       },
       GL_POLYGON_OFFSET_FILL},
      {"rasterizer discard", [] { glEnable(GL_RASTERIZER_DISCARD); }, GL_RASTERIZER_DISCARD},
      {"colour logic op",
       [] {
         glLogicOp(GL_XOR);
         glEnable(GL_COLOR_LOGIC_OP);
       },
       GL_COLOR_LOGIC_OP},
      {"primitive restart at index 0",
       [] {
         glPrimitiveRestartIndex(0);
         glEnable(GL_PRIMITIVE_RESTART);
       },
       GL_PRIMITIVE_RESTART},
      {"multisample off", [] { glDisable(GL_MULTISAMPLE); }, GL_MULTISAMPLE},
      {"clip control", [] { glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE); }, GL_CLIP_ORIGIN},
      {"unpack row length", [] { glPixelStorei(GL_UNPACK_ROW_LENGTH, 3); }, GL_UNPACK_ROW_LENGTH},
      {"unpack skip rows", [] { glPixelStorei(GL_UNPACK_SKIP_ROWS, 2); }, GL_UNPACK_SKIP_ROWS},
      {"pack row length", [] { glPixelStorei(GL_PACK_ROW_LENGTH, 7); }, GL_PACK_ROW_LENGTH},
      {"pixel unpack buffer", [&] { glBindBuffer(GL_PIXEL_UNPACK_BUFFER, junk.id()); }, GL_PIXEL_UNPACK_BUFFER_BINDING},
      {"pixel pack buffer", [&] { glBindBuffer(GL_PIXEL_PACK_BUFFER, junk.id()); }, GL_PIXEL_PACK_BUFFER_BINDING},
  };
  for (const Case& c : cases) {
    resetToDefaults();
    c.set();
    const Values before = get(c.pname, c.pname == GL_POLYGON_MODE ? 2 : 1);
    const std::vector<uint8_t> got = frame();
    std::string first;
    EXPECT_EQ(testsupport::differingPixels(clean, got, kFrameSize, &first), 0u) << c.name << ": " << first;
    EXPECT_EQ(get(c.pname, before.size()), before) << c.name << " not restored";
  }
  glPrimitiveRestartIndex(0);
  glPolygonOffset(0.0f, 0.0f);
  glLogicOp(GL_COPY);
}
