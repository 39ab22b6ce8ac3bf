#include "rgraph/gl/gl_state.h"

#include <GL/glcorearb.h>

#include <iterator>

// The saved state is a few tables walked twice, in the same order: capture()
// reads each entry's values into one flat array, restore() hands the same
// values to the entry's setter. Adding state is adding a table row.

namespace rgraph::gl {
namespace {

using Values = const int64_t*;

GLuint u(int64_t v) { return static_cast<GLuint>(v); }
GLint i(int64_t v) { return static_cast<GLint>(v); }
GLenum e(int64_t v) { return static_cast<GLenum>(v); }
GLboolean b(int64_t v) { return v != 0 ? GL_TRUE : GL_FALSE; }

// Values glGetInteger64v writes for `pname` (most write one).
constexpr size_t valueCount(GLenum pname) {
  switch (pname) {
    case GL_VIEWPORT:
    case GL_SCISSOR_BOX:
    case GL_COLOR_WRITEMASK:
      return 4;
    case GL_POLYGON_MODE:
      return 2;  // front and back (core sets both at once)
    default:
      return 1;
  }
}

// Context-wide state: read with glGetInteger64v, pname by pname.
struct Global {
  std::array<GLenum, 3> pnames;  // 0 ends the list
  void (*restore)(Values v);
};

// Restored last (after the indexed buffer bindings and texture units, which
// change the generic buffer bindings and the active unit on the way).
constexpr Global kGlobals[] = {
    {{GL_DRAW_FRAMEBUFFER_BINDING}, [](Values v) { glBindFramebuffer(GL_DRAW_FRAMEBUFFER, u(v[0])); }},
    {{GL_READ_FRAMEBUFFER_BINDING}, [](Values v) { glBindFramebuffer(GL_READ_FRAMEBUFFER, u(v[0])); }},
    // A program the caller deleted while it was current lives only while it
    // stays current: once the frame used others it is gone, and none is
    // current again (what GL would have left had the caller unbound it).
    {{GL_CURRENT_PROGRAM}, [](Values v) { glUseProgram(v[0] != 0 && glIsProgram(u(v[0])) ? u(v[0]) : 0u); }},
    {{GL_VERTEX_ARRAY_BINDING}, [](Values v) { glBindVertexArray(u(v[0])); }},
    {{GL_ARRAY_BUFFER_BINDING}, [](Values v) { glBindBuffer(GL_ARRAY_BUFFER, u(v[0])); }},
    {{GL_UNIFORM_BUFFER_BINDING}, [](Values v) { glBindBuffer(GL_UNIFORM_BUFFER, u(v[0])); }},
    {{GL_SHADER_STORAGE_BUFFER_BINDING}, [](Values v) { glBindBuffer(GL_SHADER_STORAGE_BUFFER, u(v[0])); }},
    {{GL_VIEWPORT}, [](Values v) { glViewport(i(v[0]), i(v[1]), i(v[2]), i(v[3])); }},
    {{GL_SCISSOR_BOX}, [](Values v) { glScissor(i(v[0]), i(v[1]), i(v[2]), i(v[3])); }},
    {{GL_DEPTH_FUNC}, [](Values v) { glDepthFunc(e(v[0])); }},
    {{GL_DEPTH_WRITEMASK}, [](Values v) { glDepthMask(b(v[0])); }},
    {{GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK},
     [](Values v) { glStencilFuncSeparate(GL_FRONT, e(v[0]), i(v[1]), u(v[2])); }},
    {{GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK},
     [](Values v) { glStencilFuncSeparate(GL_BACK, e(v[0]), i(v[1]), u(v[2])); }},
    {{GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS},
     [](Values v) { glStencilOpSeparate(GL_FRONT, e(v[0]), e(v[1]), e(v[2])); }},
    {{GL_STENCIL_BACK_FAIL, GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS},
     [](Values v) { glStencilOpSeparate(GL_BACK, e(v[0]), e(v[1]), e(v[2])); }},
    {{GL_STENCIL_WRITEMASK}, [](Values v) { glStencilMaskSeparate(GL_FRONT, u(v[0])); }},
    {{GL_STENCIL_BACK_WRITEMASK}, [](Values v) { glStencilMaskSeparate(GL_BACK, u(v[0])); }},
    {{GL_CULL_FACE_MODE}, [](Values v) { glCullFace(e(v[0])); }},
    {{GL_FRONT_FACE}, [](Values v) { glFrontFace(e(v[0])); }},
    {{GL_POLYGON_MODE}, [](Values v) { glPolygonMode(GL_FRONT_AND_BACK, e(v[0])); }},
    {{GL_PIXEL_PACK_BUFFER_BINDING}, [](Values v) { glBindBuffer(GL_PIXEL_PACK_BUFFER, u(v[0])); }},
    {{GL_PIXEL_UNPACK_BUFFER_BINDING}, [](Values v) { glBindBuffer(GL_PIXEL_UNPACK_BUFFER, u(v[0])); }},
    {{GL_CLIP_ORIGIN, GL_CLIP_DEPTH_MODE}, [](Values v) { glClipControl(e(v[0]), e(v[1])); }},
    {{GL_ACTIVE_TEXTURE}, [](Values v) { glActiveTexture(e(v[0])); }},
};

// glEnable/glDisable capabilities (blend is per draw buffer: kIndexed).
// GL_DEPTH_CLAMP: the light_volumes pass turns it on and off. From
// GL_RASTERIZER_DISCARD on: what applyRendererDefaults() turns off.
constexpr GLenum kEnables[] = {GL_DEPTH_TEST,
                               GL_STENCIL_TEST,
                               GL_CULL_FACE,
                               GL_SCISSOR_TEST,
                               GL_FRAMEBUFFER_SRGB,
                               GL_POLYGON_OFFSET_FILL,
                               GL_MULTISAMPLE,
                               GL_DEPTH_CLAMP,
                               GL_RASTERIZER_DISCARD,
                               GL_COLOR_LOGIC_OP,
                               GL_PRIMITIVE_RESTART,
                               GL_PRIMITIVE_RESTART_FIXED_INDEX,
                               GL_SAMPLE_ALPHA_TO_COVERAGE,
                               GL_SAMPLE_COVERAGE,
                               GL_SAMPLE_MASK};
constexpr GLenum kDefaultOff[] = {
    GL_POLYGON_OFFSET_FILL,           GL_RASTERIZER_DISCARD,       GL_COLOR_LOGIC_OP,  GL_PRIMITIVE_RESTART,
    GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK};

constexpr bool allSaved() {
  for (GLenum off : kDefaultOff) {
    bool found = false;
    for (GLenum cap : kEnables) found = found || cap == off;
    if (!found) return false;
  }
  return true;
}
static_assert(allSaved(), "applyRendererDefaults() must change only state the guard saves");

// glPixelStorei state: rgraph uploads scene textures and reads images back
// with the caller's pixel store in effect unless applyRendererDefaults() ran.
constexpr GLenum kPixelStore[] = {GL_PACK_ALIGNMENT,   GL_PACK_ROW_LENGTH,    GL_PACK_IMAGE_HEIGHT,
                                  GL_PACK_SKIP_ROWS,   GL_PACK_SKIP_PIXELS,   GL_PACK_SKIP_IMAGES,
                                  GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH,  GL_UNPACK_IMAGE_HEIGHT,
                                  GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_IMAGES};

// rgraph sets blend and colour mask for every draw buffer at once
// (glBlendFunc, glColorMask); the caller may have set them per buffer.
constexpr GLuint kDrawBuffers = 8;  // GL_MAX_DRAW_BUFFERS is at least 8
constexpr GLuint kBufferBindings = 8;
constexpr GLuint kImageUnits = 8;

// Indexed state: read with glGetInteger64i_v(pname, index) for index < count.
struct Indexed {
  std::array<GLenum, 6> pnames;  // 0 ends the list
  GLuint count;
  void (*restore)(GLuint index, Values v);
};

void bindBuffer(GLenum target, GLuint index, Values v) {
  // START and SIZE read 0 for a glBindBufferBase binding (and for none).
  if (v[1] == 0 && v[2] == 0)
    glBindBufferBase(target, index, u(v[0]));
  else
    glBindBufferRange(target, index, u(v[0]), static_cast<GLintptr>(v[1]), static_cast<GLsizeiptr>(v[2]));
}

// Restored first: binding an indexed buffer also sets the generic binding,
// which kGlobals puts back afterwards.
constexpr Indexed kIndexed[] = {
    {{GL_BLEND}, kDrawBuffers, [](GLuint n, Values v) { v[0] ? glEnablei(GL_BLEND, n) : glDisablei(GL_BLEND, n); }},
    {{GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA},
     kDrawBuffers,
     [](GLuint n, Values v) { glBlendFuncSeparatei(n, e(v[0]), e(v[1]), e(v[2]), e(v[3])); }},
    {{GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA},
     kDrawBuffers,
     [](GLuint n, Values v) { glBlendEquationSeparatei(n, e(v[0]), e(v[1])); }},
    {{GL_COLOR_WRITEMASK},
     kDrawBuffers,
     [](GLuint n, Values v) { glColorMaski(n, b(v[0]), b(v[1]), b(v[2]), b(v[3])); }},
    {{GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE},
     kBufferBindings,
     [](GLuint n, Values v) { bindBuffer(GL_UNIFORM_BUFFER, n, v); }},
    {{GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE},
     kBufferBindings,
     [](GLuint n, Values v) { bindBuffer(GL_SHADER_STORAGE_BUFFER, n, v); }},
    {{GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED, GL_IMAGE_BINDING_LAYER,
      GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT},
     kImageUnits,
     [](GLuint n, Values v) { glBindImageTexture(n, u(v[0]), i(v[1]), b(v[2]), i(v[3]), e(v[4]), e(v[5])); }},
};

// Texture units: every target, since rgraph unbinds a unit with
// glBindTextureUnit(unit, 0), which empties all of its targets.
constexpr GLuint kTextureUnits = 16;
constexpr GLenum kTextureBindings[] = {
    GL_TEXTURE_BINDING_1D,        GL_TEXTURE_BINDING_1D_ARRAY,       GL_TEXTURE_BINDING_2D,
    GL_TEXTURE_BINDING_2D_ARRAY,  GL_TEXTURE_BINDING_2D_MULTISAMPLE, GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY,
    GL_TEXTURE_BINDING_3D,        GL_TEXTURE_BINDING_CUBE_MAP,       GL_TEXTURE_BINDING_CUBE_MAP_ARRAY,
    GL_TEXTURE_BINDING_RECTANGLE, GL_TEXTURE_BINDING_BUFFER};
constexpr GLenum kTextureTargets[] = {GL_TEXTURE_1D,        GL_TEXTURE_1D_ARRAY,       GL_TEXTURE_2D,
                                      GL_TEXTURE_2D_ARRAY,  GL_TEXTURE_2D_MULTISAMPLE, GL_TEXTURE_2D_MULTISAMPLE_ARRAY,
                                      GL_TEXTURE_3D,        GL_TEXTURE_CUBE_MAP,       GL_TEXTURE_CUBE_MAP_ARRAY,
                                      GL_TEXTURE_RECTANGLE, GL_TEXTURE_BUFFER};
static_assert(std::size(kTextureBindings) == std::size(kTextureTargets));
constexpr size_t kValuesPerUnit = std::size(kTextureTargets) + 1;  // + the sampler

constexpr size_t pnameValues(const GLenum* pnames, size_t n) {
  size_t total = 0;
  for (size_t k = 0; k < n && pnames[k] != 0; ++k) total += valueCount(pnames[k]);
  return total;
}

constexpr size_t totalValues() {
  size_t total = std::size(kEnables) + std::size(kPixelStore) + kTextureUnits * kValuesPerUnit;
  for (const Global& g : kGlobals) total += pnameValues(g.pnames.data(), g.pnames.size());
  for (const Indexed& x : kIndexed) total += x.count * pnameValues(x.pnames.data(), x.pnames.size());
  return total;
}
static_assert(totalValues() == SavedState::kValueCount, "update SavedState::kValueCount to totalValues()");

}  // namespace

SavedState SavedState::capture() {
  SavedState s;
  int64_t* out = s.values_.data();
  for (const Global& g : kGlobals) {
    for (GLenum pname : g.pnames) {
      if (pname == 0) break;
      glGetInteger64v(pname, out);
      out += valueCount(pname);
    }
  }
  for (GLenum cap : kEnables) *out++ = glIsEnabled(cap);
  for (GLenum pname : kPixelStore) glGetInteger64v(pname, out++);
  for (const Indexed& x : kIndexed) {
    for (GLuint n = 0; n < x.count; ++n) {
      for (GLenum pname : x.pnames) {
        if (pname == 0) break;
        if (pname == GL_BLEND) {
          *out = glIsEnabledi(GL_BLEND, n);  // the spec's query for it
        } else if (pname == GL_COLOR_WRITEMASK) {
          GLboolean m[4] = {};
          glGetBooleani_v(GL_COLOR_WRITEMASK, n, m);
          for (int c = 0; c < 4; ++c) out[c] = m[c];
        } else {
          glGetInteger64i_v(pname, n, out);
        }
        out += valueCount(pname);
      }
    }
  }
  // Texture bindings are read through the active unit (no indexed query in core 4.5).
  GLint active = GL_TEXTURE0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  for (GLuint unit = 0; unit < kTextureUnits; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    for (GLenum binding : kTextureBindings) glGetInteger64v(binding, out++);
    glGetInteger64v(GL_SAMPLER_BINDING, out++);
  }
  glActiveTexture(static_cast<GLenum>(active));
  glGetFloatv(GL_BLEND_COLOR, s.blendColor_.data());
  return s;
}

void SavedState::restore() const {
  // Same order as capture(), each table restored from its own offset.
  const int64_t* globals = values_.data();
  const int64_t* in = globals;
  for (const Global& g : kGlobals) in += pnameValues(g.pnames.data(), g.pnames.size());
  for (GLenum cap : kEnables) *in++ ? glEnable(cap) : glDisable(cap);
  for (GLenum pname : kPixelStore) glPixelStorei(pname, i(*in++));
  for (const Indexed& x : kIndexed) {
    const size_t stride = pnameValues(x.pnames.data(), x.pnames.size());
    for (GLuint n = 0; n < x.count; ++n, in += stride) x.restore(n, in);
  }
  // glBindTextures binds each name to its own target and leaves the unit's
  // other targets alone: empty all units first, then one call for the units
  // with at most one target bound; a unit with several goes target by target.
  std::array<GLuint, kTextureUnits> names{}, samplers{};
  std::array<const int64_t*, kTextureUnits> several{};
  for (GLuint unit = 0; unit < kTextureUnits; ++unit, in += kValuesPerUnit) {
    size_t bound = 0;
    for (size_t t = 0; t < std::size(kTextureTargets); ++t) {
      if (in[t] == 0) continue;
      names[unit] = u(in[t]);
      ++bound;
    }
    if (bound > 1) {
      names[unit] = 0;
      several[unit] = in;
    }
    samplers[unit] = u(in[std::size(kTextureTargets)]);
  }
  glBindTextures(0, kTextureUnits, nullptr);  // every target of every unit empty first
  glBindTextures(0, kTextureUnits, names.data());
  glBindSamplers(0, kTextureUnits, samplers.data());
  for (GLuint unit = 0; unit < kTextureUnits; ++unit) {
    if (!several[unit]) continue;
    glActiveTexture(GL_TEXTURE0 + unit);
    for (size_t t = 0; t < std::size(kTextureTargets); ++t) glBindTexture(kTextureTargets[t], u(several[unit][t]));
  }
  in = globals;
  for (const Global& g : kGlobals) {
    g.restore(in);
    in += pnameValues(g.pnames.data(), g.pnames.size());
  }
  glBlendColor(blendColor_[0], blendColor_[1], blendColor_[2], blendColor_[3]);
}

void applyRendererDefaults() {
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  for (GLenum cap : kDefaultOff) glDisable(cap);
  glEnable(GL_MULTISAMPLE);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  for (GLenum pname : kPixelStore)
    glPixelStorei(pname, pname == GL_PACK_ALIGNMENT || pname == GL_UNPACK_ALIGNMENT ? 4 : 0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glBindSamplers(0, kTextureUnits, nullptr);  // passes are promised sampler 0 (pass_programs.h)
}

}  // namespace rgraph::gl
