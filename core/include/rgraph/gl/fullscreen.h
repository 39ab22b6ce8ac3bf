// Helpers for passes that draw a fullscreen triangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/gl/objects.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/pass.h"

namespace rgraph::gl {

// An empty vertex array (core profile needs one bound) and a 3-vertex draw.
// Use with shaders/fullscreen.vert, which derives positions from gl_VertexID.
class FullscreenTriangle {
 public:
  FullscreenTriangle();  // needs a current context
  // Draws with someone else's empty vertex array (PassContext::emptyVertexArray).
  explicit FullscreenTriangle(uint32_t sharedVertexArray) : id_(sharedVertexArray) {}
  void draw() const;  // binds the vertex array and draws 3 vertices (and leaves it bound)
  void draw(PassContext& ctx) const;  // the same, binding through ctx.bindings()
 private:
  VertexArray vao_;  // own, when none is shared
  uint32_t id_ = 0;
};

// Binds ctx.framebuffer() as draw framebuffer and sets the viewport to its
// extent. These three bind through ctx.bindings(), skipping what is already
// bound; a pass that binds only through them may leave kGlStateBindings out
// of its changedState().
void bindPassFramebuffer(PassContext& ctx);
// Where a framebuffer is bound by bindPassFramebuffer(ctx, attachments, ...).
enum class FramebufferTarget { draw, read };
// Binds ctx.framebuffer(attachments) (the executor's cached framebuffer of
// exactly those images) and returns it. As the draw framebuffer (through
// ctx.bindings(), like the one above), with the viewport at (0, 0) and the
// extent of those images at their level; as the read framebuffer (for
// glReadPixels, glCopyTexSubImage*), leaving the viewport alone. Throws what
// ctx.framebuffer throws.
PassFramebuffer bindPassFramebuffer(PassContext& ctx, std::initializer_list<AttachmentRef> attachments,
                                    FramebufferTarget target = FramebufferTarget::draw);
void useProgram(PassContext& ctx, uint32_t program);
void bindVertexArray(PassContext& ctx, uint32_t vertexArray);

// The spec of a program drawn over a fullscreen triangle: fullscreen.vert +
// `frag`, reading `samplers` (slot, uniform, unit), for PassTypeDesc::programs.
ShaderProgramSpec fullscreenProgram(std::string frag, std::vector<SamplerSlot> samplers = {},
                                    std::vector<std::string> defines = {});
// PassTypeDesc::programs of a pass whose one program does not depend on its
// parameters: fullscreenProgram(frag, samplers).
std::function<std::vector<ShaderProgramSpec>(const ParamSet&)> fullscreenPrograms(std::string frag,
                                                                                  std::vector<SamplerSlot> samplers);

// A pass that draws one fullscreen triangle with one of its type's programs
// (ctx.program(index): the executor built it from the spec and binds the
// sampled slots the spec names before execute()). Derive from it and fill in
// the hooks and declare its uniforms as members; the executor has reset
// blend, depth, stencil, cull and scissor state before execute(), so a pass
// sets only what it needs:
//
//   class Vignette final : public gl::FullscreenPass {
//     void update(PassContext& ctx) override { strength_.set(float(ctx.params().getNumber("strength", 0.6))); }
//     ProgramUniform strength_{this, "u_strength"};
//   };
class FullscreenPass : public PassInstance {
 public:
  explicit FullscreenPass(size_t programIndex = 0) : programIndex_(programIndex) {}
  FullscreenPass(const FullscreenPass&) = delete;
  FullscreenPass& operator=(const FullscreenPass&) = delete;
  // Takes the program, looks up every ProgramUniform and creates the
  // triangle (on the executor's shared empty vertex array), then calls prepare(ctx).
  void setup(PassContext& ctx) override;
  // Binds the pass's framebuffer (viewport to its extent) and the program,
  // calls update(ctx), draws the triangle.
  void execute(PassContext& ctx) override;

 protected:
  // Once per setup: look uniforms up, set those that never change.
  virtual void prepare(PassContext& /*ctx*/) {}
  // Every frame, before the draw: per-frame uniforms and state. Programs
  // are shared between passes with the same files and defines, so a value
  // that differs between passes of one type is set here, not in prepare().
  virtual void update(PassContext& /*ctx*/) {}

  // A uniform of the pass's program, declared as a member of the pass with
  // its name; setup() looks its location up once.
  class ProgramUniform : public Uniform {
   public:
    ProgramUniform(FullscreenPass* pass, const char* name) : name_(name) { pass->uniforms_.push_back(this); }
    ProgramUniform(const ProgramUniform&) = delete;
    ProgramUniform& operator=(const ProgramUniform&) = delete;

   private:
    friend class FullscreenPass;
    const char* name_;
  };

  uint32_t program() const { return program_; }
  Uniform uniform(const char* name) const { return Uniform(program_, name); }
  // The triangle alone, into whatever framebuffer is bound (passes that
  // draw into framebuffers of their own).
  void drawTriangle() const { triangle_->draw(); }

 private:
  size_t programIndex_;
  uint32_t program_ = 0;
  std::vector<ProgramUniform*> uniforms_;  // members of the derived pass
  std::unique_ptr<FullscreenTriangle> triangle_;
};

}  // namespace rgraph::gl
