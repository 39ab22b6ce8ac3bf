// What `rgraph validate` checks is what runs (issue 10): for every shipped
// pipeline, with the plugins it names loaded as the CLI loads them, the
// programs the shader checker compiles for a pass (PassTypeDesc::programs)
// are exactly the programs the executor builds for it, no more and no fewer,
// with the same files and defines; and a pass builds none of its own. On a
// static scene and on one that deforms: validate checks both variants of a
// scene program (rgraph/scene_program.h), the executor builds the scene's.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/scene_program.h"
#include "rgraph/shader_check.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;

namespace {

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = GlContext::create();
  ctx->makeCurrent();
  return *ctx;
}

std::vector<std::string> shippedPipelines() {
  std::vector<std::string> files;
  for (const char* dir : {"pipelines", "pipelines/examples"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string describe(const ProgramRequest& r) {
  std::string s = r.comp.empty() ? r.vert + " + " + r.frag : r.comp;
  for (const auto& d : r.defines) s += " -D" + d;
  return s;
}

ProgramRequest request(const ShaderProgramSpec& s) { return {s.vert, s.frag, s.comp, s.defines}; }

// Per pass, the programs as sorted descriptions (a spec listed twice counts once).
using ProgramsByPass = std::map<std::string, std::set<std::string>>;

// Whether checked program `p` is the other variant of a built scene program
// (with kSceneAnimationDefine where the scene is static, without it where
// the scene deforms): what validate checks for the other kind of scene.
bool otherSceneVariant(const std::string& p, const std::set<std::string>& built) {
  const std::string flag = std::string(" -D") + kSceneAnimationDefine;
  auto plain = [&](std::string d) {
    const size_t at = d.find(flag);
    if (at != std::string::npos) d.erase(at, flag.size());
    return d;
  };
  if (p.find("scene.vert") == std::string::npos) return false;
  for (const std::string& b : built)
    if (b != p && plain(b) == plain(p)) return true;
  return false;
}

}  // namespace

TEST(ProgramsBuilt, EveryShippedPipelineBuildsExactlyTheProgramsValidateChecks) {
  const uint64_t errorsAtStart = context().debugErrorCount();
  const std::vector<std::string> files = shippedPipelines();
  ASSERT_GE(files.size(), 12u);  // 10 in pipelines/, 2 in pipelines/examples/
  size_t pluginPipelines = 0;
  for (const Scene& scene : {makeLearnOpenGLScene(), makeWalkerScene()})
  for (const auto& file : files) {
    SCOPED_TRACE(file + " on " + scene.source);
    PassRegistry registry = PassRegistry::builtins();  // a copy: built-ins + this pipeline's plugins
    PluginLoader loader(registry);
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseFile(file, diags);
    for (const auto& name : doc.plugins()) {
      std::string error;
      ASSERT_NE(loader.load(name, std::filesystem::path(file).parent_path().string(), error), nullptr) << error;
    }
    pluginPipelines += doc.plugins().empty() ? 0 : 1;
    PipelineConfig cfg = doc.build(registry, diags);
    ASSERT_FALSE(hasErrors(diags)) << formatDiagnostic(diags.front());
    // Adapted to the scene as `rgraph render` runs it: a shadow_map template
    // runs only expanded, and validate then checks the expanded passes.
    adaptToScene(cfg, registry, sceneFeatures(scene));

    ShaderLibrary shaders;
    Executor exec(cfg, registry, shaders, &scene);
    exec.resize({64, 64});
    exec.renderFrame();  // a pass that built a program while executing would show too

    ShaderChecker checker(shaders.searchDirectories());
    const Diagnostics shaderDiags = checker.checkPipeline(cfg, exec.plan(), registry);
    EXPECT_FALSE(hasErrors(shaderDiags));

    // The passes the plan runs (the checker also checks culled ones).
    std::set<std::string> planned;
    for (PassIndex i : exec.plan().order) planned.insert(exec.plan().pass(i).name);
    ProgramsByPass checked, built;
    for (const auto& c : checker.checkedPrograms())
      if (planned.count(c.pass)) checked[c.pass].insert(describe(request(c.spec)));
    for (const auto& b : exec.builtPrograms()) built[b.pass].insert(describe(b.program));
    EXPECT_FALSE(built.empty());
    for (const auto& pass : planned) {
      SCOPED_TRACE("pass '" + pass + "'");
      std::vector<std::string> onlyBuilt, onlyChecked;
      std::set_difference(built[pass].begin(), built[pass].end(), checked[pass].begin(), checked[pass].end(),
                          std::back_inserter(onlyBuilt));
      std::set_difference(checked[pass].begin(), checked[pass].end(), built[pass].begin(), built[pass].end(),
                          std::back_inserter(onlyChecked));
      for (const auto& p : onlyBuilt) ADD_FAILURE() << "built but never checked by validate: " << p;
      for (const auto& p : onlyChecked)
        if (!otherSceneVariant(p, built[pass])) ADD_FAILURE() << "checked by validate but not built: " << p;
    }
    for (const auto& [pass, programs] : built)
      EXPECT_TRUE(planned.count(pass)) << "programs built for '" << pass << "', which the plan does not run";
  }
  EXPECT_GE(pluginPipelines, 1u);  // deferred-ssao-bloom.json: bloom and ssao
  EXPECT_EQ(context().debugErrorCount(), errorsAtStart) << context().lastDebugError();
}

// The executor binds every sampled slot a spec names to the spec's unit and
// sets the sampler uniform to it, so a shader without layout(binding) reads
// the right texture: the fullscreen pass's input1 (unit 1) comes through.
TEST(ProgramsBuilt, SampledSlotsAreBoundToTheUnitsTheSpecNames) {
  context();
  const std::string json = R"({
    "version": 1,
    "resources": { "a": { "format": "rgba8" }, "b": { "format": "rgba8" }, "out": { "format": "rgba8" } },
    "passes": [
      { "name": "fill_a", "type": "fullscreen", "params": { "shader": "solid_color.frag", "color": [0, 0, 1, 1] },
        "outputs": { "color": "a" } },
      { "name": "fill_b", "type": "fullscreen", "params": { "shader": "solid_color.frag", "color": [0, 1, 0, 1] },
        "outputs": { "color": "b" } },
      { "name": "copy", "type": "fullscreen", "params": { "shader": "copy_input1.frag" },
        "inputs": { "input0": "a", "input1": "b" }, "outputs": { "color": "out" } }
    ],
    "output": "out"
  })";
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(json, "units.json", diags);
  const PipelineConfig cfg = doc.build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags)) << formatDiagnostic(diags.front());
  ShaderLibrary shaders;
  shaders.addSearchDirectory(std::string(RGRAPH_SOURCE_DIR) + "/tests/plugin/shaders");
  Executor exec(cfg, processRegistry(), shaders);
  exec.resize({8, 8});
  exec.renderFrame();
  const std::vector<uint8_t> rgba = exec.readOutputRGBA8();
  ASSERT_EQ(rgba.size(), 8u * 8u * 4u);
  EXPECT_EQ(rgba[0], 0);  // not input0 (blue) nor texture 0 (black): input1, green
  EXPECT_EQ(rgba[1], 255);
  EXPECT_EQ(rgba[2], 0);
}
