// The shader checks of sampler types against what their slots bind: the
// texture's shape (2D, array, cube, cube array, one layer of one) and the
// slot's compare mode (rgraph/shader_check.h). Mismatches name the sampler's
// declaration (shader FILE:LINE) and point at the binding in the config.
#include <gtest/gtest.h>

#include <string>

#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;

namespace {

const std::string kData = std::string(RGRAPH_TEST_DATA_DIR) + "/shadercheck";

std::vector<std::string> dirs() {
  std::vector<std::string> d = {kData + "/shaders"};
  for (auto& x : defaultShaderSearchDirectories()) d.push_back(x);
  return d;
}

std::string all(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

Diagnostics errors(const Diagnostics& diags) {
  Diagnostics out;
  for (const auto& d : diags)
    if (d.severity == Severity::error) out.push_back(d);
  return out;
}

// Loads a config of tests/shadercheck/configs and runs the shader checks.
Diagnostics checkConfig(const std::string& name) {
  Diagnostics config;
  ConfigDocument doc = ConfigDocument::parseFile(kData + "/configs/" + name, config);
  PipelineConfig pipe = doc.build(processRegistry(), config);
  Plan plan = compile(pipe.graph);
  EXPECT_FALSE(hasErrors(config)) << all(config);
  EXPECT_TRUE(plan.ok()) << all(plan.diagnostics);
  ShaderChecker checker(dirs());
  return checker.checkPipeline(pipe, plan, processRegistry());
}

void expectOneError(const Diagnostics& diags, const std::string& config, int line, int column,
                    const std::vector<std::string>& texts) {
  const Diagnostics e = errors(diags);
  ASSERT_EQ(e.size(), 1u) << all(diags);
  const Diagnostic& d = e[0];
  EXPECT_EQ(d.code, DiagCode::shader_error);
  EXPECT_EQ(d.pass, "probe");
  EXPECT_EQ(d.slot, "input0");
  EXPECT_NE(d.where.file.find(config), std::string::npos) << formatDiagnostic(d);
  EXPECT_EQ(d.where.line, line) << formatDiagnostic(d);
  EXPECT_EQ(d.where.column, column) << formatDiagnostic(d);
  EXPECT_EQ(d.where.path, "/passes/1/inputs/input0");
  for (const auto& t : texts) EXPECT_NE(d.message.find(t), std::string::npos) << t << "\n" << formatDiagnostic(d);
}

TEST(SamplerShape, ShadowSamplerWithoutCompareIsRefused) {
  expectOneError(checkConfig("shadow_without_compare.json"), "shadow_without_compare.json", 14, 19,
                 {"shadow sampler sampler2DShadow 'input0' (", "shadow_probe.frag:3)",
                  "the slot declares no sampler state", "\"compare\": \"less_equal\""});
}

TEST(SamplerShape, ShadowSamplerWithCompareIsClean) {
  const Diagnostics d = checkConfig("shadow_with_compare.json");
  EXPECT_TRUE(d.empty()) << all(d);
}

TEST(SamplerShape, CubeSamplerOnA2DTextureIsRefused) {
  expectOneError(checkConfig("cube_on_2d.json"), "cube_on_2d.json", 13, 19,
                 {"samplerCube 'input0' (", "cube_probe.frag:3)", "cannot read input 'input0' (image)",
                  "binds a 2D texture (sampler2D)"});
}

TEST(SamplerShape, ArraySamplerOnA2DTextureIsRefused) {
  expectOneError(checkConfig("array_on_2d.json"), "array_on_2d.json", 13, 19,
                 {"sampler2DArray 'input0' (", "array_probe.frag:3)", "binds a 2D texture"});
}

TEST(SamplerShape, CompareOnAPlainSamplerIsRefused) {
  expectOneError(checkConfig("compare_on_plain.json"), "compare_on_plain.json", 14, 19,
                 {"sampler2D 'input0' (", "plain_probe.frag:3) is not a shadow sampler",
                  "compare mode less (from its \"samplers\" entry at ", "compare_on_plain.json:12:",
                  "sampler2DShadow"});
}

// checkPass with hand-made bindings: every shape a slot can bind, against
// every sampler type.
class Shapes : public ::testing::Test {
 protected:
  Diagnostics check(const std::string& shader, uint32_t layers, bool cube, Subresource sub = {},
                    std::optional<SamplerState> sampler = std::nullopt, Format format = Format::rgba8) {
    const PassTypeDesc& type = *processRegistry().find("fullscreen");
    ParamSet params = defaultParams(type.params);
    params.set("shader", shader);
    BoundSlot in;
    in.slot = "input0";
    in.access = Access::sampled;
    in.resource = "tex";
    in.format = format;
    in.layers = layers;
    in.cube = cube;
    in.sub = sub;
    in.sampler = sampler;
    BoundSlot out;
    out.slot = "color";
    out.access = Access::color_attachment;
    out.resource = "out";
    out.format = Format::rgba8;
    return errors(checker.checkPass("probe", type, params, {in, out}));
  }
  static Subresource layer(uint32_t begin, uint32_t count) {
    Subresource s;
    s.layerBegin = begin;
    s.layerCount = count;
    return s;
  }
  ShaderChecker checker{dirs()};
};

TEST_F(Shapes, TwoDSampler) {
  EXPECT_TRUE(check("plain_probe.frag", 1, false).empty());
  EXPECT_TRUE(check("plain_probe.frag", 4, false, layer(2, 1)).empty()) << "one layer of an array is 2D";
  EXPECT_TRUE(check("plain_probe.frag", 1, true, layer(3, 1)).empty()) << "one face of a cube is 2D";
  const Diagnostics d = check("plain_probe.frag", 4, false);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("which binds a 2D array (sampler2DArray) (4 layers)"), std::string::npos)
      << d[0].message;
  EXPECT_EQ(check("plain_probe.frag", 1, true).size(), 1u);
  EXPECT_EQ(check("plain_probe.frag", 4, false, layer(0, 2)).size(), 1u);
}

TEST_F(Shapes, ArraySampler) {
  EXPECT_TRUE(check("array_probe.frag", 4, false).empty());
  EXPECT_TRUE(check("array_probe.frag", 4, false, layer(1, 2)).empty()) << "a layer range";
  EXPECT_TRUE(check("array_probe.frag", 1, true, layer(0, 3)).empty()) << "three faces of a cube";
  const Diagnostics d = check("array_probe.frag", 4, false, layer(3, 1));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("binds a 2D texture (sampler2D) (the subresource tex.layer[3])"), std::string::npos)
      << d[0].message;
}

TEST_F(Shapes, CubeSampler) {
  EXPECT_TRUE(check("cube_probe.frag", 1, true).empty());
  EXPECT_TRUE(check("cube_probe.frag", 2, true, layer(6, 6)).empty()) << "the second cube of an array";
  EXPECT_EQ(check("cube_probe.frag", 6, false).size(), 1u) << "six layers that are no cube";
  EXPECT_EQ(check("cube_probe.frag", 2, true).size(), 1u) << "a cube array";
  EXPECT_EQ(check("cube_probe.frag", 2, true, layer(1, 6)).size(), 1u) << "six faces not starting at +x";
}

TEST_F(Shapes, CubeArraySampler) {
  EXPECT_TRUE(check("cube_array_probe.frag", 3, true).empty());
  const Diagnostics d = check("cube_array_probe.frag", 1, true);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("samplerCubeArray 'input0'"), std::string::npos) << d[0].message;
  EXPECT_NE(d[0].message.find("binds a cube map (samplerCube) (1 cube)"), std::string::npos) << d[0].message;
}

TEST_F(Shapes, CompareModeAgainstShadowSamplers) {
  SamplerState compare;
  compare.compare = SamplerState::Compare::less;
  SamplerState plain;
  EXPECT_TRUE(check("shadow_probe.frag", 1, false, {}, compare, Format::depth32f).empty());
  const Diagnostics none = check("shadow_probe.frag", 1, false, {}, plain, Format::depth32f);
  ASSERT_EQ(none.size(), 1u);
  EXPECT_NE(none[0].message.find("has no compare mode (from its slot declaration)"), std::string::npos)
      << none[0].message;
  EXPECT_EQ(check("plain_probe.frag", 1, false, {}, compare).size(), 1u);
  EXPECT_TRUE(check("plain_probe.frag", 1, false, {}, plain).empty());
}

}  // namespace
