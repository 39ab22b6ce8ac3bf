// Pass types of the application's own code (RendererOptions::registry): a
// type defined here, registered in-process, used by a pipeline's JSON, with
// its shader named by an absolute path outside every shader folder. One
// registry per renderer: what one renderer is given or loads (plugins) is
// seen by no other renderer and never reaches PassRegistry::builtins(), so
// these tests pass in any order (--gtest_shuffle) and repeated.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;
namespace fs = std::filesystem;

// The application's pass: its source times a colour.
class TintPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const std::vector<double> c = ctx.params().getVector("color");
    color_.set(float(c[0]), float(c[1]), float(c[2]), float(c[3]));
  }
  ProgramUniform color_{this, "u_color"};
};

PassTypeDesc tintType(const std::string& name, const std::string& frag) {
  using namespace rgraph::decl;
  PassTypeDesc d = passType(name, "the source times a colour (the application's own pass)");
  d.slots = {slot("src", Access::sampled, true, SlotDecl::Load::never, "the image"),
             slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the result (src's size)")};
  d.params = {ranged("color", ParamType::vec4, std::vector<double>{1, 1, 1, 1}, 0.0, 100.0, "the factor")};
  d.programs = gl::fullscreenPrograms(frag, {{"src", "u_src", 0}});
  d.create = [] { return std::make_unique<TintPass>(); };
  return d;
}

std::string tintPipeline(const std::string& type, const std::string& plugins = "") {
  return R"({
  "version": 1,)" + plugins + R"(
  "resources": {
    "src":    { "format": "rgba16f", "size": "output", "imported": true },
    "output": { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "tint", "type": ")" + type + R"(", "params": { "color": [0.5, 1.0, 0.25, 1.0] },
      "inputs": { "src": "src" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";
}

// fxaa from the in-tree plugin (found beside librgraph.so).
const char* kFxaaPipeline = R"({
  "version": 1,
  "plugins": ["fxaa"],
  "resources": {
    "ldr":    { "format": "rgba8", "size": "output", "imported": true },
    "output": { "format": "rgba8", "size": "output" }
  },
  "passes": [ { "name": "aa", "type": "fxaa", "inputs": { "input": "ldr" }, "outputs": { "output": "output" } } ],
  "output": "output"
})";

constexpr Extent kSize{8, 4};

class RendererPassTypes : public ::testing::Test {
 protected:
  void SetUp() override {
    testsupport::sharedGlContext();
    // The shader and a file it includes, in a folder no shader search path has.
    dir_ = fs::temp_directory_path() / ("rgraph-own-types-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "tint_common.glsl") << "vec4 tinted(vec4 c, vec4 k) { return c * k; }\n";
    std::ofstream(dir_ / "tint.frag") << "#version 450 core\n"
                                          "#include \"tint_common.glsl\"\n"
                                          "layout(binding = 0) uniform sampler2D u_src;\n"
                                          "uniform vec4 u_color;\n"
                                          "layout(location = 0) out vec4 o_color;\n"
                                          "void main() { o_color = tinted(texelFetch(u_src, ivec2(gl_FragCoord.xy), 0), "
                                          "u_color); }\n";
    types_ = PassRegistry::builtins();  // a copy: the built-in types, then the application's
    std::string error;
    ASSERT_TRUE(types_.add(tintType("app_tint", (dir_ / "tint.frag").string()), &error)) << error;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  RendererOptions options(const PassRegistry* types) const {
    RendererOptions o;
    o.size = kSize;
    o.registry = types;
    return o;
  }

  // Renders with `src` cleared to (0.5, 0.5, 1, 1); the first pixel of the output.
  std::vector<uint8_t> firstPixel(Renderer& r) {
    src_ = gl::createTexture2D(Format::rgba16f, kSize, 1, 1);
    const float colour[4] = {0.5f, 0.5f, 1.0f, 1.0f};
    glClearTexImage(src_.id(), 0, GL_RGBA, GL_FLOAT, colour);
    r.importTexture(r.importableResources().front() == "src" ? "src" : "ldr", src_.id());
    r.render();
    const std::vector<uint8_t> out = r.readOutputRGBA8();
    return {out.begin(), out.begin() + 4};
  }

  fs::path dir_;
  PassRegistry types_;
  gl::Texture src_;
};

bool anyMessage(const Diagnostics& diags, const std::string& part) {
  return std::any_of(diags.begin(), diags.end(),
                     [&](const Diagnostic& d) { return d.message.find(part) != std::string::npos; });
}

std::string allOf(const Diagnostics& diags) {
  std::string s;
  for (const auto& d : diags) s += formatDiagnostic(d) + "\n";
  return s.empty() ? "no diagnostics" : s;
}

// The shader check (glslang, runChecks) and the executor both take the absolute path as it is,
// and the file it includes beside it.
TEST_F(RendererPassTypes, AnApplicationsOwnTypeRunsWithItsShaderAtAnAbsolutePath) {
  Diagnostics diags;
  auto r = Renderer::fromJson(tintPipeline("app_tint"), "tint.json", options(&types_), diags);
  ASSERT_TRUE(r) << allOf(diags);
  EXPECT_TRUE(diags.empty()) << allOf(diags);
  EXPECT_EQ(firstPixel(*r), (std::vector<uint8_t>{64, 128, 64, 255})) << "(0.5, 0.5, 1) x (0.5, 1, 0.25)";
  ASSERT_NE(r->passTypes().find("app_tint"), nullptr);
  EXPECT_EQ(PassRegistry::builtins().find("app_tint"), nullptr) << "the built-in types are never changed";
}

TEST_F(RendererPassTypes, ARendererWithoutTheTypeDoesNotSeeIt) {
  Diagnostics diags;
  auto with = Renderer::fromJson(tintPipeline("app_tint"), "tint.json", options(&types_), diags);
  ASSERT_TRUE(with) << allOf(diags);
  diags.clear();
  EXPECT_FALSE(Renderer::fromJson(tintPipeline("app_tint"), "tint.json", options(nullptr), diags));
  EXPECT_TRUE(anyMessage(diags, "unknown pass type 'app_tint'")) << allOf(diags);
}

// The renderer copies the registry when it is made: a type added afterwards is not its.
TEST_F(RendererPassTypes, TheRegistryIsCopiedWhenTheRendererIsMade) {
  Diagnostics diags;
  auto r = Renderer::fromJson(tintPipeline("app_tint"), "tint.json", options(&types_), diags);
  ASSERT_TRUE(r) << allOf(diags);
  std::string error;
  ASSERT_TRUE(types_.add(tintType("app_tint_later", (dir_ / "tint.frag").string()), &error)) << error;
  EXPECT_EQ(r->passTypes().find("app_tint_later"), nullptr);
  EXPECT_FALSE(r->reloadJson(tintPipeline("app_tint_later"), diags));
  EXPECT_TRUE(anyMessage(diags, "unknown pass type 'app_tint_later'")) << allOf(diags);
}

// A missing absolute path: the check names it; without checks, the build does.
TEST_F(RendererPassTypes, AMissingShaderAtAnAbsolutePathIsNamed) {
  const std::string missing = (dir_ / "missing.frag").string();
  PassRegistry types = PassRegistry::builtins();
  ASSERT_TRUE(types.add(tintType("app_tint", missing)));
  Diagnostics diags;
  EXPECT_FALSE(Renderer::fromJson(tintPipeline("app_tint"), "tint.json", options(&types), diags));
  EXPECT_TRUE(anyMessage(diags, "shader file '" + missing + "' not found")) << allOf(diags);

  RendererOptions unchecked = options(&types);
  unchecked.runChecks = false;
  diags.clear();
  auto r = Renderer::fromJson(tintPipeline("app_tint"), "tint.json", unchecked, diags);
  ASSERT_TRUE(r) << allOf(diags);
  const std::string what = testsupport::errorOf([&] { firstPixel(*r); });
  EXPECT_NE(what.find("shader file '" + missing + "' not found"), std::string::npos) << what;
}

// A plugin one renderer loads is that renderer's: another renderer may have a type of the same name
// in-process, and one without either knows neither.
TEST_F(RendererPassTypes, APluginLoadsIntoItsRenderersTypesOnly) {
  Diagnostics diags;
  auto withPlugin = Renderer::fromJson(kFxaaPipeline, "fxaa.json", options(&types_), diags);
  ASSERT_TRUE(withPlugin) << allOf(diags);
  ASSERT_NE(withPlugin->passTypes().find("fxaa"), nullptr);
  EXPECT_NE(withPlugin->passTypes().find("fxaa")->origin.find("librgraph_fxaa.so"), std::string::npos);
  ASSERT_EQ(withPlugin->loadedPlugins().size(), 1u);
  EXPECT_EQ(types_.find("fxaa"), nullptr) << "the application's registry is copied, not loaded into";
  EXPECT_EQ(PassRegistry::builtins().find("fxaa"), nullptr);

  // An application type named like the plugin's: no "already registered".
  PassRegistry mine = PassRegistry::builtins();
  ASSERT_TRUE(mine.add(tintType("fxaa", (dir_ / "tint.frag").string())));
  diags.clear();
  auto own = Renderer::fromJson(tintPipeline("fxaa"), "own-fxaa.json", options(&mine), diags);
  ASSERT_TRUE(own) << allOf(diags);
  EXPECT_EQ(firstPixel(*own), (std::vector<uint8_t>{64, 128, 64, 255})) << "the application's fxaa, not the plugin's";

  // Neither the plugin's nor the application's type without asking for it.
  diags.clear();
  EXPECT_FALSE(Renderer::fromJson(tintPipeline("fxaa"), "plain.json", options(nullptr), diags));
  EXPECT_TRUE(anyMessage(diags, "unknown pass type 'fxaa'")) << allOf(diags);
}

// The application loaded the plugin into its registry itself; a pipeline naming it loads it again into the
// renderer's copy: the same library's types are there already, not a clash.
TEST_F(RendererPassTypes, TypesGivenWithAPluginTakeThatPluginAgain) {
  PassRegistry withFxaa = PassRegistry::builtins();
  PluginLoader loader(withFxaa);
  std::string error;
  ASSERT_NE(loader.load("fxaa", "", error), nullptr) << error;
  Diagnostics diags;
  auto r = Renderer::fromJson(kFxaaPipeline, "fxaa.json", options(&withFxaa), diags);
  ASSERT_TRUE(r) << allOf(diags);
  EXPECT_EQ(r->passTypes().find("fxaa")->origin, withFxaa.find("fxaa")->origin);
}

}  // namespace
