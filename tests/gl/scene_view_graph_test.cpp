// The scene drawn from other views THROUGH THE GRAPH (issue 27): a test pass
// type draws it from a cube face's view or a view along a path into whatever
// its slots bind ("env.face[+x]", "atlas.layer[2]", "atlas.layer[*]", a whole
// cube, "chain.mip[1]"), and a readback pass reads what it sees of its sampled
// slot at its place in the frame. Every face, layer and level must equal the
// render of the same view by the same pass type into a plain 2D texture, bit
// for bit (rgba32f world positions and depth), and differ from the other
// faces or layers: a black, a cleared or an all-alike image fails. Unlike
// gpu_scene_view_test.cpp (GpuScene alone, framebuffers made by the test),
// every framebuffer here comes from the executor's cache, every order from
// the compiler's per-subresource versions, every pipeline from JSON.
#include <GL/glcorearb.h>

#include <cstring>
#include <iostream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <memory>
#include <string>

#include "gl_test_util.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr uint32_t kSide = 48;  // every target is square: cube faces are
using Pixels = std::vector<glm::vec4>;
using Readbacks = std::map<std::string, Pixels>;

const char* const kFaces[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

// View `index` of a set: "cube", the six faces from `eye` (GL's face order
// and up vectors, 90 degrees); "path", a circle of eyes around the scene
// looking at its middle, 40 degrees apart.
GpuScene::View viewAt(const std::string& set, glm::vec3 eye, int64_t index) {
  GpuScene::View v;
  if (set == "cube") {
    const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    v.view = glm::lookAt(eye, eye + dirs[index % 6], ups[index % 6]);
    v.proj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 50.0f);
  } else {
    const float a = glm::radians(40.0f) * float(index) + 0.3f;
    v.view = glm::lookAt(glm::vec3(7.0f * std::cos(a), 3.0f, 7.0f * std::sin(a)), glm::vec3(0, -0.5f, 0),
                         glm::vec3(0, 1, 0));
    v.proj = glm::perspective(glm::radians(50.0f), 1.0f, 0.1f, 50.0f);
  }
  v.cull = GpuScene::Cull::none;  // a cube seen from inside flips winding; one cull for every layered view
  return v;
}

// scene_view: views first .. first + count - 1 into the layers its slots
// bind. count 1: one drawView into the pass's framebuffer (one layer or face,
// or a 2D texture, or one level); count > 1: the slots bind that many layers,
// drawn with one layered draw ("layered": where the device has gl_Layer from
// the vertex shader, else one draw per layer) or one draw per layer ("each"),
// each layer attached through the executor's cache.
class SceneViewPass final : public PassInstance {
  uint32_t program = 0, layered = 0;
  void setup(PassContext& ctx) override {
    program = ctx.program(0);
    if (ctx.params().getInt("count", 1) > 1 && ctx.gpuScene()->supportsLayeredDraw())
      layered = ctx.shaders().program("scene.vert", "view_probe.frag", {"LAYERED"});
  }
  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const std::string set = p.getString("views", "cube");
    const std::vector<double> e = p.getVector("eye", {0, 0, 0});
    const glm::vec3 eye{float(e[0]), float(e[1]), float(e[2])};
    const int64_t first = p.getInt("first", 0), count = p.getInt("count", 1);
    std::vector<GpuScene::View> views;
    for (int64_t i = 0; i < count; ++i) views.push_back(viewAt(set, eye, first + i));
    GpuScene& scene = *ctx.gpuScene();
    glEnable(GL_DEPTH_TEST);
    if (count == 1) {
      gl::bindPassFramebuffer(ctx);
      scene.drawView(program, views[0]);
    } else if (layered && p.getString("method", "layered") == "layered") {
      gl::bindPassFramebuffer(ctx);  // the slots' layers attached whole: a layered framebuffer
      scene.drawLayered(layered, views);
    } else {
      scene.drawEachLayer(program, views, [&](size_t i) {
        gl::bindPassFramebuffer(ctx, {{"color", 0, uint32_t(i)}, {"depth", 0, uint32_t(i)}});
      });
    }
    glDisable(GL_DEPTH_TEST);
  }
};

// readback: what its 'src' slot shows (one face, layer or level: the
// executor's view of it, or the texture with its base level narrowed), read
// in the frame right after the writers the graph ordered before it.
class ReadbackPass final : public PassInstance {
  Readbacks* out;

 public:
  explicit ReadbackPass(Readbacks* o) : out(o) {}
  void execute(PassContext& ctx) override {
    const uint32_t tex = ctx.texture("src");
    const Extent e = ctx.extent("src");
    GLint level = 0;  // a view's own level 0, or the narrowed base level (RGRAPH_SUBRESOURCE_SAMPLING=levels)
    glGetTextureParameteriv(tex, GL_TEXTURE_BASE_LEVEL, &level);
    Pixels& px = (*out)[ctx.params().getString("key", "")];
    px.assign(size_t(e.width) * e.height, glm::vec4(0));
    glGetTextureSubImage(tex, level, 0, 0, 0, GLsizei(e.width), GLsizei(e.height), 1, GL_RGBA, GL_FLOAT,
                         GLsizei(px.size() * sizeof(glm::vec4)), px.data());
  }
  uint32_t changedState() const override { return 0; }
};

PassRegistry viewRegistry(Readbacks* readbacks) {
  using namespace rgraph::decl;
  PassRegistry reg = PassRegistry::builtins();
  PassTypeDesc view;
  view.name = "scene_view";
  view.description = "test: the scene from given views into the layers its slots bind";
  view.slots = {slot("color", Access::color_attachment, true, SlotDecl::Load::never, "world position, depth"),
                slot("depth", Access::depth_attachment, true, SlotDecl::Load::never, "depth")};
  view.params = {param("views", ParamType::enumeration, std::string("cube"), "which views", {"cube", "path"}),
                 param("eye", ParamType::vec3, std::vector<double>{0, 0, 0}, "the cube views' centre"),
                 ranged("first", ParamType::integer, int64_t{0}, 0.0, 63.0, "the first view"),
                 ranged("count", ParamType::integer, int64_t{1}, 1.0, 32.0, "views (= layers the slots bind)"),
                 param("method", ParamType::enumeration, std::string("layered"), "several views: how",
                       {"layered", "each"})};
  view.programs = [](const ParamSet&) {
    return std::vector<ShaderProgramSpec>{programSpec("scene.vert", "view_probe.frag")};
  };
  view.create = [] { return std::make_unique<SceneViewPass>(); };
  view.needsScene = true;
  EXPECT_TRUE(reg.add(view));
  PassTypeDesc read;
  read.name = "readback";
  read.description = "test: reads its sampled slot back to the CPU";
  read.slots = {slot("src", Access::sampled, true, SlotDecl::Load::never, "what is read")};
  read.params = {param("key", ParamType::string, std::string(), "where the pixels go")};
  read.sideEffect = true;
  read.create = [readbacks] { return std::make_unique<ReadbackPass>(readbacks); };
  EXPECT_TRUE(reg.add(read));
  return reg;
}

// A pipeline's JSON, written a pass at a time.
struct Json {
  std::string resources = R"("out": {"format": "rgba8"})", passes = R"({"name": "out", "type": "clear", )"
                                                                      R"("outputs": {"color": "out"}})";
  void texture(const std::string& name, const std::string& shape) {
    resources += ",\n\"" + name + R"(": {"format": "rgba32f", "size": [)" + std::to_string(kSide) + "," +
                 std::to_string(kSide) + "], \"clear\": [0, 0, 0, 0]" + shape + "},\n\"" + name +
                 R"(_z": {"format": "depth32f", "size": [)" + std::to_string(kSide) + "," + std::to_string(kSide) +
                 "], \"clear\": 1.0" + shape + "}";
  }
  // A scene_view pass writing `part` ("" or ".face[+x]"...) of `target` and its depth twin.
  void view(const std::string& name, const std::string& target, const std::string& part, const std::string& params) {
    passes += ",\n{\"name\": \"" + name + R"(", "type": "scene_view", "params": {)" + params +
              R"(}, "outputs": {"color": ")" + target + part + R"(", "depth": ")" + target + "_z" + part + "\"}}";
  }
  void readback(const std::string& name, const std::string& what) {
    passes += ",\n{\"name\": \"" + name + R"(", "type": "readback", "params": {"key": ")" + name +
              R"("}, "inputs": {"src": ")" + what + "\"}}";
  }
  std::string text() const {
    return "{\"version\": 1, \"resources\": {" + resources + "},\n\"passes\": [" + passes + "],\n\"output\": \"out\"}";
  }
};

std::string viewParams(const std::string& set, int64_t first, int64_t count = 1, const std::string& method = "") {
  return R"("views": ")" + set + R"(", "eye": [0, -0.5, 1.5], "first": )" + std::to_string(first) +
         R"(, "count": )" + std::to_string(count) + (method.empty() ? "" : R"(, "method": ")" + method + "\"");
}

size_t differing(const Pixels& a, const Pixels& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(glm::vec4)) != 0;
  return n;
}
size_t covered(const Pixels& a) {
  return size_t(std::count_if(a.begin(), a.end(), [](const glm::vec4& p) { return p.w != 0.0f; }));
}

// The LearnOpenGL objects (a 3x3 grid at y -1..0) and one cube above and one
// below the cube views' eye (0, -0.5, 1.5), so that each of the six faces
// sees something of its own.
Scene sceneAllAround() {
  Scene s = makeLearnOpenGLScene();
  for (float y : {3.0f, -4.0f}) {
    Primitive p = s.primitives[0];  // a cube
    p.transform = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, y, 1.5f)), glm::vec3(0.5f));
    p.bounds = s.meshes[size_t(p.mesh)].bounds.transformed(p.transform);
    p.name = y > 0 ? "above" : "below";
    s.primitives.push_back(p);
  }
  return s;
}

class SceneViewGraphTest : public GlTest {
 protected:
  Scene scene = sceneAllAround();
  Readbacks got;
  PassRegistry reg = viewRegistry(&got);
  std::unique_ptr<Executor> exec;

  void render(const Json& json) {
    PipelineLoadOptions opts;
    opts.registry = &reg;
    const PipelineConfig cfg = loadPipelineTextOrThrow(json.text(), "<scene-view>", opts);
    exec = std::make_unique<Executor>(cfg, reg, *shaders, &scene);
    exec->resize({kSide, kSide});
    exec->renderFrame();
  }
  // `part` equals `plain` bit for bit and shows the scene.
  void expectEqual(const std::string& part, const std::string& plain) {
    ASSERT_TRUE(got.count(part) && got.count(plain)) << part << " / " << plain << ": not read back";
    EXPECT_EQ(differing(got[part], got[plain]), 0u) << part << " against " << plain;
    EXPECT_GT(covered(got[part]), 50u) << part << " shows (nearly) nothing";
  }
  // No two of `keys` are alike: each shows its own view.
  void expectAllDifferent(const std::vector<std::string>& keys) {
    for (size_t i = 0; i < keys.size(); ++i)
      for (size_t j = i + 1; j < keys.size(); ++j)
        EXPECT_GT(differing(got[keys[i]], got[keys[j]]), 50u) << keys[i] << " and " << keys[j] << " are alike";
  }
  // Layer `layer` of `resource` after the frame, never written: still cleared.
  void expectCleared(const std::string& resource, int layer) {
    Pixels px(size_t(kSide) * kSide, glm::vec4(1));
    glGetTextureSubImage(exec->textureOf(resource), 0, 0, 0, layer, kSide, kSide, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(px.size() * sizeof(glm::vec4)), px.data());
    EXPECT_EQ(covered(px), 0u) << resource << " layer " << layer << " was written";
  }
};

// (1) and (4): six passes, one per face of "env", each face read back, each
// equal to the same face's view rendered into a 2D texture.
TEST_F(SceneViewGraphTest, EachCubeFaceEqualsThePlain2DRenderOfItsView) {
  Json j;
  j.texture("env", R"(, "cube": true)");
  std::vector<std::string> faces;
  for (int f = 0; f < 6; ++f) {
    const std::string face = std::string(".face[") + kFaces[f] + "]", flat = "flat" + std::to_string(f);
    j.texture(flat, "");
    j.view("draw_face" + std::to_string(f), "env", face, viewParams("cube", f));
    j.view("draw_" + flat, flat, "", viewParams("cube", f));
    j.readback("face" + std::to_string(f), "env" + face);
    j.readback(flat, flat);
    faces.push_back("face" + std::to_string(f));
  }
  render(j);
  for (int f = 0; f < 6; ++f) expectEqual("face" + std::to_string(f), "flat" + std::to_string(f));
  expectAllDifferent(faces);
  GLint target = 0;
  glGetTextureParameteriv(exec->textureOf("env"), GL_TEXTURE_TARGET, &target);
  EXPECT_EQ(target, GL_TEXTURE_CUBE_MAP);
}

// (2) and (4): layers 1, 2 and 4 (the last) of a 5-layer array, each from
// its own view along the path; layers 0 and 3 are left as cleared.
TEST_F(SceneViewGraphTest, EachArrayLayerEqualsThePlain2DRenderOfItsView) {
  Json j;
  j.texture("atlas", R"(, "layers": 5)");
  std::vector<std::string> layers;
  for (int k : {1, 2, 4}) {
    const std::string part = ".layer[" + std::to_string(k) + "]", n = std::to_string(k);
    j.texture("flat" + n, "");
    j.view("draw_layer" + n, "atlas", part, viewParams("path", k));
    j.view("draw_flat" + n, "flat" + n, "", viewParams("path", k));
    j.readback("layer" + n, "atlas" + part);
    j.readback("flat" + n, "flat" + n);
    layers.push_back("layer" + n);
  }
  render(j);
  for (int k : {1, 2, 4}) expectEqual("layer" + std::to_string(k), "flat" + std::to_string(k));
  expectAllDifferent(layers);
  expectCleared("atlas", 0);
  expectCleared("atlas", 3);
}

// (3) and (4): one pass writes every layer of a 4-layer array
// ("atlas.layer[*]") and one every face of a cube (bound whole), with one
// layered draw where the device can, and again one draw per layer through the
// cache's per-layer framebuffers ("method": "each"); every layer equals the
// plain 2D render of its view.
TEST_F(SceneViewGraphTest, LayeredPassesEqualThePlain2DRendersOfTheirViews) {
  Json j;
  for (const char* method : {"layered", "each"}) {
    const std::string m = method;
    j.texture("atlas_" + m, R"(, "layers": 4)");
    j.texture("env_" + m, R"(, "cube": true)");
    j.view("draw_atlas_" + m, "atlas_" + m, ".layer[*]", viewParams("path", 0, 4, m));
    j.view("draw_env_" + m, "env_" + m, "", viewParams("cube", 0, 6, m));
    for (int k = 0; k < 4; ++k)
      j.readback("atlas_" + m + std::to_string(k), "atlas_" + m + ".layer[" + std::to_string(k) + "]");
    for (int f = 0; f < 6; ++f)
      j.readback("env_" + m + std::to_string(f), "env_" + m + ".face[" + kFaces[f] + "]");
  }
  for (int k = 0; k < 6; ++k) {
    const std::string n = std::to_string(k);
    if (k < 4) {
      j.texture("path" + n, "");
      j.view("draw_path" + n, "path" + n, "", viewParams("path", k));
      j.readback("path" + n, "path" + n);
    }
    j.texture("cube" + n, "");
    j.view("draw_cube" + n, "cube" + n, "", viewParams("cube", k));
    j.readback("cube" + n, "cube" + n);
  }
  render(j);
  if (!exec->gpuScene()->supportsLayeredDraw()) std::cout << "[ INFO ] no gl_Layer from the vertex shader: "
                                                             "\"layered\" drew one layer at a time\n";
  for (const char* method : {"layered", "each"}) {
    SCOPED_TRACE(method);
    std::vector<std::string> atlas, env;
    for (int k = 0; k < 4; ++k) {
      atlas.push_back(std::string("atlas_") + method + std::to_string(k));
      expectEqual(atlas.back(), "path" + std::to_string(k));
    }
    for (int f = 0; f < 6; ++f) {
      env.push_back(std::string("env_") + method + std::to_string(f));
      expectEqual(env.back(), "cube" + std::to_string(f));
    }
    expectAllDifferent(atlas);
    expectAllDifferent(env);
  }
}

// A mip level as the target: "chain.mip[1]" of a 96x96 texture (48x48)
// equals the plain 48x48 render; level 0 stays cleared.
TEST_F(SceneViewGraphTest, AMipLevelEqualsThePlain2DRenderAtItsSize) {
  Json j;
  j.texture("flat", "");
  j.resources += R"(,
"chain": {"format": "rgba32f", "size": [96, 96], "mips": 2, "clear": [0, 0, 0, 0]},
"chain_z": {"format": "depth32f", "size": [48, 48], "clear": 1.0})";
  j.passes += R"(,
{"name": "draw_mip", "type": "scene_view", "params": {)" + viewParams("path", 2) +
              R"(}, "outputs": {"color": "chain.mip[1]", "depth": "chain_z"}})";
  j.view("draw_flat", "flat", "", viewParams("path", 2));
  j.readback("mip1", "chain.mip[1]");
  j.readback("flat", "flat");
  render(j);
  expectEqual("mip1", "flat");
  Pixels level0(96 * 96, glm::vec4(1));
  glGetTextureSubImage(exec->textureOf("chain"), 0, 0, 0, 0, 96, 96, 1, GL_RGBA, GL_FLOAT,
                       GLsizei(level0.size() * sizeof(glm::vec4)), level0.data());
  EXPECT_EQ(covered(level0), 0u) << "level 0 was written";
}

}  // namespace
