// What the executor tells the scene each frame (GpuScene::updateFrame with
// FrameMotion) and each pass (GpuScene::selectJitter): the frame number, the
// pipeline's jitter phases, the previous frame's unjittered view-projection
// (none, so previous = current, on the first frame and after a cut or a
// resize), and the jittered or unjittered Frame block per PassDecl::jitter.
// A probe pass reads the Frame block bound while it runs.
#include <GL/glcorearb.h>

#include <glm/gtc/type_ptr.hpp>

#include "gl_test_util.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/jitter.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr Extent kSize{32, 16};

// The std140 Frame block of shaders/include/frame.glsl (gpu_scene.cpp's
// FrameBlock): five mat4, six vec4, then prevViewProj, viewProjNoJitter,
// jitter (xy pixels, zw NDC), frame (x index, y phases).
struct FrameSeen {
  std::string pass;
  glm::mat4 viewProj, prevViewProj, viewProjNoJitter;
  glm::vec4 jitter;
  glm::ivec4 frame;
};
constexpr GLintptr kViewProj = 2 * 64, kPrevViewProj = 5 * 64 + 6 * 16, kNoJitter = kPrevViewProj + 64,
                   kJitter = kNoJitter + 64, kFrame = kJitter + 16;

std::vector<FrameSeen>& seenLog() {
  static std::vector<FrameSeen> log;
  return log;
}

class FrameProbe final : public PassInstance {
 public:
  void execute(PassContext& ctx) override {
    GLint buffer = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &buffer);
    FrameSeen s;
    s.pass = ctx.passName();
    if (buffer != 0) {
      const auto b = static_cast<GLuint>(buffer);
      glGetNamedBufferSubData(b, kViewProj, 64, glm::value_ptr(s.viewProj));
      glGetNamedBufferSubData(b, kPrevViewProj, 64, glm::value_ptr(s.prevViewProj));
      glGetNamedBufferSubData(b, kNoJitter, 64, glm::value_ptr(s.viewProjNoJitter));
      glGetNamedBufferSubData(b, kJitter, 16, glm::value_ptr(s.jitter));
      glGetNamedBufferSubData(b, kFrame, 16, glm::value_ptr(s.frame));
    }
    seenLog().push_back(s);
  }
};

PassRegistry probeRegistry() {
  PassRegistry reg = PassRegistry::builtins();
  PassTypeDesc d;
  d.name = "frame_probe";
  d.description = "test: records the Frame block bound while it runs";
  d.slots.resize(1);
  d.slots[0].name = "color";
  d.slots[0].access = Access::color_attachment;
  d.create = [] { return std::make_unique<FrameProbe>(); };
  reg.add(std::move(d));
  return reg;
}

// "jittered" then "steady" (PassDecl::jitter false).
PipelineConfig probeGraph(uint32_t jitterPhases) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).output("out");
  g.pass("jittered", "frame_probe", {writeUse("color", Access::color_attachment, "a")}, {}, true);
  g.pass("steady", "frame_probe", {writeUse("color", Access::color_attachment, "out")});
  g.config().graph.passes.back().jitter = false;
  g.config().jitterPhases = jitterPhases;
  return g.config();
}

bool same(const glm::mat4& a, const glm::mat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (std::abs(a[c][r] - b[c][r]) > 1e-6f) return false;
  return true;
}

Camera movedCamera(Camera c) {
  c.position += glm::vec3(0.5f, 0.0f, 0.0f);
  return c;
}

}  // namespace

TEST_F(GlTest, ExecutorFrameMotionFollowsFramesCutsAndResizes) {
  const PassRegistry reg = probeRegistry();
  const Scene scene = loadSceneAny("learnopengl");
  Executor exec(probeGraph(8), reg, *shaders, &scene);
  exec.resize(kSize);
  const Camera a = scene.camera, b = movedCamera(scene.camera);
  // Frame: camera, cut before it, resize before it.
  struct Step {
    Camera camera;
    bool cut = false;
    bool resize = false;
  };
  const Step steps[] = {{a}, {b}, {a, true}, {b}, {a, false, true}, {b}};
  seenLog().clear();
  glm::mat4 lastUnjittered(0.0f);
  for (size_t n = 0; n < std::size(steps); ++n) {
    if (steps[n].cut) exec.cameraCut();
    if (steps[n].resize) exec.resize({kSize.width + 8, kSize.height});
    exec.setCamera(steps[n].camera);
    exec.renderFrame();
    ASSERT_EQ(seenLog().size(), 2 * (n + 1));
    const FrameSeen& j = seenLog()[2 * n];
    const FrameSeen& s = seenLog()[2 * n + 1];
    ASSERT_EQ(j.pass, "jittered");
    ASSERT_EQ(s.pass, "steady");
    const bool fresh = n == 0 || steps[n].cut || steps[n].resize;
    for (const FrameSeen* f : {&j, &s}) {
      EXPECT_EQ(f->frame.x, static_cast<int>(n)) << f->pass;
      EXPECT_EQ(f->frame.y, 8) << f->pass;
      // No previous frame: previous = current; else the last frame's.
      EXPECT_TRUE(same(f->prevViewProj, fresh ? f->viewProjNoJitter : lastUnjittered)) << f->pass << " frame " << n;
    }
    if (!fresh) EXPECT_FALSE(same(j.prevViewProj, j.viewProjNoJitter)) << "the camera moved: frame " << n;
    // Per pass: the jittered block, then the unjittered one, every frame.
    const glm::vec2 want = jitterPixels(n, 8);
    EXPECT_NE(want, glm::vec2(0.0f));
    EXPECT_NEAR(j.jitter.x, want.x, 1e-6f) << n;
    EXPECT_NEAR(j.jitter.y, want.y, 1e-6f) << n;
    EXPECT_FALSE(same(j.viewProj, j.viewProjNoJitter)) << n;
    EXPECT_EQ(s.jitter, glm::vec4(0.0f)) << n;
    EXPECT_TRUE(same(s.viewProj, s.viewProjNoJitter)) << n;
    lastUnjittered = j.viewProjNoJitter;
  }
  EXPECT_EQ(exec.frameIndex(), std::size(steps));
}

TEST_F(GlTest, ExecutorFrameMotionWithoutJitterPhases) {
  const PassRegistry reg = probeRegistry();
  const Scene scene = loadSceneAny("learnopengl");
  Executor exec(probeGraph(0), reg, *shaders, &scene);
  exec.resize(kSize);
  seenLog().clear();
  exec.renderFrame();
  exec.renderFrame();
  ASSERT_EQ(seenLog().size(), 4u);
  for (const FrameSeen& f : seenLog()) {
    EXPECT_EQ(f.jitter, glm::vec4(0.0f)) << f.pass;
    EXPECT_EQ(f.frame.y, 0) << f.pass;
    EXPECT_TRUE(same(f.viewProj, f.viewProjNoJitter)) << f.pass;
  }
  EXPECT_EQ(seenLog()[3].frame.x, 1);
}
