// Memory barriers from declared access: the executor, not the passes, issues
// glMemoryBarrier before a pass that touches what an earlier pass wrote with
// image stores or storage-buffer writes, with the bit for the way it touches
// it (core/src/gl/memory_barriers.h). The compute passes of this file issue
// no barrier themselves; each test checks the bits the executor derived and
// that the image arrives intact.
#include <GL/glcorearb.h>

#include "gl_test_util.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr Extent kSize{64, 64};

// What every texture written incoherently needs after the frame, for readers
// outside the graph (readback, window blit, next frame), unless already issued.
constexpr uint32_t kTextureAfterFrame = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                                        GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                                        GL_PIXEL_BUFFER_BARRIER_BIT;

// A compute pass of this test: its bound slots in declaration order, images
// on image units 0, 1, ... and the buffer on storage binding 0; one
// invocation per pixel of kSize.
class ComputePass final : public PassInstance {
 public:
  ComputePass(std::string shader, std::vector<SlotDecl> slots, bool sizeUniform)
      : shader_(std::move(shader)), slots_(std::move(slots)), sizeUniform_(sizeUniform) {}
  void setup(PassContext& ctx) override { program_ = ctx.shaders().computeProgram(shader_); }
  void execute(PassContext& ctx) override {
    glUseProgram(program_);
    GLuint unit = 0;
    for (const SlotDecl& s : slots_) {
      if (ctx.buffer(s.name)) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, ctx.buffer(s.name));
        continue;
      }
      const GLenum rw = s.access == Access::storage_read ? GL_READ_ONLY : GL_WRITE_ONLY;
      glBindImageTexture(unit++, ctx.texture(s.name), 0, GL_FALSE, 0, rw, GL_RGBA8);
    }
    if (sizeUniform_)
      glProgramUniform2i(program_, 0, static_cast<GLint>(kSize.width), static_cast<GLint>(kSize.height));
    glDispatchCompute((kSize.width + 7) / 8, (kSize.height + 7) / 8, 1);
    for (GLuint u = 0; u < unit; ++u) glBindImageTexture(u, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  }

 private:
  std::string shader_;
  std::vector<SlotDecl> slots_;
  bool sizeUniform_ = false;  // layout(location = 0) uniform ivec2 u_size
  uint32_t program_ = 0;
};

SlotDecl storageSlot(const std::string& name, Access access) {
  SlotDecl s;
  s.name = name;
  s.access = access;
  return s;
}

void addComputeType(PassRegistry& reg, const std::string& name, const std::string& shader, std::vector<SlotDecl> slots,
                    bool sizeUniform = false) {
  PassTypeDesc d;
  d.name = name;
  d.description = "test compute pass (" + shader + ")";
  d.slots = slots;
  d.create = [shader, slots, sizeUniform] { return std::make_unique<ComputePass>(shader, slots, sizeUniform); };
  std::string error;
  ASSERT_TRUE(reg.add(std::move(d), &error)) << error;
}

PassRegistry testRegistry() {
  PassRegistry reg = PassRegistry::builtins();
  addComputeType(reg, "fill_image", "barrier_fill.comp", {storageSlot("image", Access::storage_write)});
  addComputeType(reg, "copy_image", "barrier_copy.comp",
                 {storageSlot("src", Access::storage_read), storageSlot("dst", Access::storage_write)});
  addComputeType(reg, "fill_buffer", "barrier_fill_buffer.comp", {storageSlot("buffer", Access::storage_write)}, true);
  addComputeType(reg, "buffer_to_image", "barrier_buffer_to_image.comp",
                 {storageSlot("buffer", Access::storage_read), storageSlot("image", Access::storage_write)});
  return reg;
}

std::string bitsText(const std::vector<uint32_t>& bits) {
  std::string s;
  for (uint32_t b : bits) s += (s.empty() ? "" : ", ") + std::to_string(b);
  return "{" + s + "}";
}

// Whether the executor issues `want` (one set of bits a pass, in order); both lists when not.
::testing::AssertionResult barriersAre(const Executor& exec, const std::vector<uint32_t>& want) {
  if (exec.memoryBarriers() == want) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "memory barriers " << bitsText(exec.memoryBarriers()) << ", expected "
                                       << bitsText(want);
}

}  // namespace

// The case of the issue: a compute pass writes an image, a fragment pass
// samples it: a texture-fetch barrier before the fragment pass.
TEST_F(GlTest, ImageStoreThenSampledGetsTextureFetchBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  g.texture("img", Format::rgba8).output("out");
  g.pass("fill", "fill_image", {writeUse("image", Access::storage_write, "img")});
  g.present("img");
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  EXPECT_TRUE(barriersAre(exec, {0, GL_TEXTURE_FETCH_BARRIER_BIT}));
  // The fetch was ordered before the present pass; the rest is for readers after the frame.
  EXPECT_EQ(exec.frameEndMemoryBarrier(), kTextureAfterFrame & ~GL_TEXTURE_FETCH_BARRIER_BIT);
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
  // Read back directly too (glGetTextureImage: the frame-end barrier's texture-update bit).
  const std::vector<float> img = exec.readTextureRGBA32F("img");
  ASSERT_EQ(img.size(), kSize.width * kSize.height * 4u);
  const size_t bottomRight = ((kSize.height - 1) * kSize.width + kSize.width - 1) * 4;  // top-down: last row is y = 0
  EXPECT_FLOAT_EQ(img[bottomRight + 0], ((63 * 4) & 255) / 255.0f);
  EXPECT_FLOAT_EQ(img[bottomRight + 1], 0.0f);
}

// Image loads after image stores: the image-access bit; the sampled image
// written after that needs its own fetch barrier (a barrier covers only the
// writes issued before it).
TEST_F(GlTest, ImageStoreThenImageLoadGetsImageAccessBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("b", Format::rgba8).output("out");
  g.pass("fill", "fill_image", {writeUse("image", Access::storage_write, "a")});
  g.pass("copy", "copy_image",
         {readUse("src", Access::storage_read, "a"), writeUse("dst", Access::storage_write, "b")});
  g.present("b");
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  EXPECT_TRUE(barriersAre(exec, {0, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, GL_TEXTURE_FETCH_BARRIER_BIT}));
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

// A blit reads its source through a framebuffer.
TEST_F(GlTest, ImageStoreThenBlitGetsFramebufferBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  g.texture("img", Format::rgba8).output("out");
  g.pass("fill", "fill_image", {writeUse("image", Access::storage_write, "img")});
  g.pass("copy", "blit", {readUse("src", Access::blit_src, "img"), writeUse("dst", Access::blit_dst, "out")});
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  EXPECT_TRUE(barriersAre(exec, {0, GL_FRAMEBUFFER_BARRIER_BIT}));
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

// Storage-buffer writes read as a storage buffer: the shader-storage bit.
TEST_F(GlTest, BufferWriteThenBufferReadGetsShaderStorageBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  ResourceDecl pixels;
  pixels.name = "pixels";
  pixels.kind = ResourceKind::buffer;
  pixels.bufferBytes = uint64_t(kSize.width) * kSize.height * 4;
  g.config().graph.resources.push_back(pixels);
  g.texture("img", Format::rgba8).output("out");
  g.pass("fill", "fill_buffer", {writeUse("buffer", Access::storage_write, "pixels")});
  g.pass("unpack", "buffer_to_image",
         {readUse("buffer", Access::storage_read, "pixels"), writeUse("image", Access::storage_write, "img")});
  g.present("img");
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  EXPECT_TRUE(barriersAre(exec, {0, GL_SHADER_STORAGE_BARRIER_BIT, GL_TEXTURE_FETCH_BARRIER_BIT}));
  EXPECT_NE(exec.frameEndMemoryBarrier() & GL_BUFFER_UPDATE_BARRIER_BIT, 0u);  // a buffer readback after the frame
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

// Without image or storage writes nothing is issued (pipelines that never
// needed barriers run exactly the GL calls they ran before).
TEST_F(GlTest, NoStorageWritesNoBarriers) {
  GraphBuilder g;
  g.texture("hdr", Format::rgba16f).output("out");
  g.pass("clear", "clear", {writeUse("color", Access::color_attachment, "hdr")});
  g.present("hdr");
  Executor exec(g.config(), processRegistry(), *shaders);
  exec.resize(kSize);
  EXPECT_TRUE(barriersAre(exec, {0, 0}));
  EXPECT_EQ(exec.frameEndMemoryBarrier(), 0u);
}

// Aliased textures share memory: a pass that overwrites an alias of an image
// written with image stores needs a barrier too (write after write), and a
// bit already issued since that write is not issued again.
TEST_F(GlTest, AliasOfImageStoreTargetGetsFramebufferBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("c", Format::rgba8).output("out", Format::rgba8, "out_2");
  g.pass("fill", "fill_image", {writeUse("image", Access::storage_write, "a")});
  g.present("a");
  g.gradient("c");
  g.pass("copy", "blit", {readUse("src", Access::blit_src, "c"), writeUse("dst", Access::blit_dst, "out_2", "out")});
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  const Plan& plan = exec.plan();
  ASSERT_EQ(plan.order.size(), 4u);
  ASSERT_TRUE(plan.resources[0].physical.valid());
  ASSERT_EQ(plan.resources[0].physical, plan.resources[1].physical) << "a and c are expected to share memory";
  EXPECT_TRUE(barriersAre(exec, {0, GL_TEXTURE_FETCH_BARRIER_BIT, GL_FRAMEBUFFER_BARRIER_BIT, 0}));
  EXPECT_EQ(exec.frameEndMemoryBarrier(),
            kTextureAfterFrame & ~(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT));
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

// The executor clears a resource's first version before its first writer;
// into an alias of an image-store target that is not attached, that clear is
// a texture update (glClearTexImage) and needs its own bit.
TEST_F(GlTest, ClearOfAnAliasOfImageStoreTargetGetsTextureUpdateBarrier) {
  const PassRegistry reg = testRegistry();
  GraphBuilder g;
  g.texture("a", Format::rgba8)
      .texture("c", Format::rgba8, SizeSpec::output(), std::vector<float>{1, 0, 0, 1})
      .output("out", Format::rgba8, "out_2");
  g.pass("fill", "fill_image", {writeUse("image", Access::storage_write, "a")});
  g.present("a");
  g.pass("refill", "fill_image", {writeUse("image", Access::storage_write, "c")});
  g.pass("copy", "blit", {readUse("src", Access::blit_src, "c"), writeUse("dst", Access::blit_dst, "out_2", "out")});
  Executor exec(g.config(), reg, *shaders);
  exec.resize(kSize);
  const Plan& plan = exec.plan();
  ASSERT_EQ(plan.order.size(), 4u);
  ASSERT_TRUE(plan.resources[0].physical.valid());
  ASSERT_EQ(plan.resources[0].physical, plan.resources[1].physical) << "a and c are expected to share memory";
  EXPECT_TRUE(barriersAre(
      exec, {0, GL_TEXTURE_FETCH_BARRIER_BIT, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT,
             GL_FRAMEBUFFER_BARRIER_BIT}));
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}
