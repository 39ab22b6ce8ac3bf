// rgraph/testing.h on the shipped pipelines: every query checked against the
// plan it wraps, and against figures read off `rgraph plan` by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "rgraph/testing.h"

namespace rt = rgraph::testing;
using rgraph::DiagCode;
using rgraph::Extent;

namespace {

std::string pipelinePath(const std::string& name) { return std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + name; }

rt::Options at(uint32_t w, uint32_t h) {
  rt::Options o;
  o.size = {w, h};
  return o;
}

std::vector<std::string> shippedPipelines() {
  std::vector<std::string> out;
  for (const char* dir : {"/pipelines", "/pipelines/examples"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + dir))
      if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(TestingShipped, DefaultPipelineOrderOutputAndMemory) {
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("default.json"), at(64, 64));
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_TRUE(p.loaded());
  EXPECT_TRUE(p.diagnostics().empty()) << p.describe();
  EXPECT_EQ(p.order(),
            (std::vector<std::string>{"gbuffer", "ambient", "light_volumes", "depth_blit", "light_boxes", "tonemap"}));
  EXPECT_EQ(p.passes(), p.order());  // nothing culled, config order is execution order here
  EXPECT_TRUE(p.culledPasses().empty());
  EXPECT_EQ(p.step("depth_blit"), 3u);
  EXPECT_TRUE(p.runsBefore("gbuffer", "tonemap"));
  EXPECT_FALSE(p.runsBefore("tonemap", "gbuffer"));
  EXPECT_EQ(p.outputResource(), "output");
  EXPECT_EQ(p.outputVersion(), "output");
  EXPECT_TRUE(p.imported("output"));  // the output image is the caller's
  EXPECT_FALSE(p.texture("output").has_value());
  // At 64x64: rgba32f 65536 + rgba16f 32768 + rgba8 16384 + d24s8 16384 +
  // r11g11b10f emissive 16384 (optional: adaptation drops it for a scene
  // without emissive materials; this plan is unadapted) + rgba16f hdr 32768 +
  // d24s8 forwardDepth 16384; nothing can alias.
  EXPECT_EQ(p.naiveBytes(), 65536u + 32768u + 16384u + 16384u + 16384u + 32768u + 16384u);
  EXPECT_EQ(p.allocatedBytes(), p.naiveBytes());
  EXPECT_EQ(p.textures().size(), 7u);
  EXPECT_TRUE(p.aliasGroups().empty());
  EXPECT_EQ(p.bytes("gPosition"), 65536u);
  EXPECT_EQ(p.extent("gPosition"), (Extent{64, 64}));
}

TEST(TestingShipped, DefaultPipelineLifetimesVersionsAndBindings) {
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("default.json"), at(64, 64));
  ASSERT_TRUE(p.ok()) << p.describe();
  // hdr: written by ambient (step 1), lit in place, last read by tonemap (step 5).
  const auto hdr = p.lifetime("hdr");
  ASSERT_TRUE(hdr.has_value());
  EXPECT_EQ(hdr->first, 1u);
  EXPECT_EQ(hdr->last, 5u);
  EXPECT_EQ(hdr->firstPass, "ambient");
  EXPECT_EQ(hdr->lastPass, "tonemap");
  const auto depth = p.lifetime("forwardDepth");
  ASSERT_TRUE(depth.has_value());
  EXPECT_EQ(depth->first, 3u);
  EXPECT_EQ(depth->last, 4u);
  // A version answers for its resource.
  EXPECT_EQ(p.resourceOf("hdr_lit"), "hdr");
  EXPECT_EQ(p.resourceOf("hdr_forward"), "hdr");
  EXPECT_EQ(p.versions("hdr"), (std::vector<std::string>{"hdr", "hdr_lit", "hdr_forward"}));
  EXPECT_EQ(p.lifetime("hdr_lit").value().first, 1u);
  ASSERT_TRUE(p.texture("hdr_forward").has_value());
  EXPECT_EQ(p.texture("hdr_forward").value().index, p.texture("hdr").value().index);
  // light_boxes loads hdr_lit and writes hdr_forward through one slot.
  const auto color = p.binding("light_boxes", "color");
  ASSERT_TRUE(color.has_value());
  EXPECT_EQ(color->resource, "hdr");
  EXPECT_EQ(color->readVersion, "hdr_lit");
  EXPECT_EQ(color->writeVersion, "hdr_forward");
  EXPECT_EQ(color->access, rgraph::Access::color_attachment);
  const auto src = p.binding("depth_blit", "src");
  ASSERT_TRUE(src.has_value());
  EXPECT_EQ(src->resource, "gDepth");
  EXPECT_EQ(src->access, rgraph::Access::blit_src);
  EXPECT_TRUE(src->writeVersion.empty());
  std::set<std::string> slots;
  for (const auto& b : p.bindings("gbuffer")) slots.insert(b.slot);
  EXPECT_EQ(slots, (std::set<std::string>{"position", "normal", "albedo", "emissive", "depth"}));
}

TEST(TestingShipped, PostChainAliasesEveryOtherTexture) {
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("examples/post-chain.json"), at(64, 64));
  ASSERT_TRUE(p.ok()) << p.describe();
  // Five rgba16f 64x64 transients (32768 bytes each) in two textures.
  EXPECT_EQ(p.naiveBytes(), 5u * 32768u);
  EXPECT_EQ(p.allocatedBytes(), 2u * 32768u);
  EXPECT_TRUE(p.aliased("scene", "post2"));
  EXPECT_TRUE(p.aliased("post2", "post4"));
  EXPECT_TRUE(p.aliased("post1", "post3"));
  EXPECT_FALSE(p.aliased("scene", "post1"));  // post1 is written while scene is read
  EXPECT_FALSE(p.aliased("scene", "scene"));  // one resource is not aliased with itself
  EXPECT_EQ(p.sharing("post4"), (std::vector<std::string>{"scene", "post2", "post4"}));
  EXPECT_EQ(p.aliasGroups(), (std::vector<std::vector<std::string>>{{"scene", "post2", "post4"}, {"post1", "post3"}}));
  const auto t = p.texture("post1");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->format, rgraph::Format::rgba16f);
  EXPECT_EQ(t->extent, (Extent{64, 64}));
  EXPECT_EQ(t->bytes, 32768u);
  // Without aliasing every transient has its own texture.
  rt::Options noAlias = at(64, 64);
  noAlias.alias = false;
  const rt::CompiledPipeline q = rt::compileFile(pipelinePath("examples/post-chain.json"), noAlias);
  ASSERT_TRUE(q.ok()) << q.describe();
  EXPECT_FALSE(q.aliased("scene", "post2"));
  EXPECT_TRUE(q.aliasGroups().empty());
  EXPECT_EQ(q.allocatedBytes(), q.naiveBytes());
  EXPECT_EQ(q.textures().size(), 5u);
}

TEST(TestingShipped, CulledDebugPassesAndTheirReasons) {
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("examples/culled-debug.json"), at(64, 64));
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"gradient", "present"}));
  EXPECT_EQ(p.culledPasses(), (std::vector<std::string>{"debug_source", "debug_view"}));
  EXPECT_TRUE(p.culled("debug_view"));
  EXPECT_FALSE(p.runs("debug_view"));
  EXPECT_FALSE(p.step("debug_view").has_value());
  EXPECT_EQ(p.cullReason("debug_view"), "its outputs (debugView) are never read by a pass that reaches the output");
  EXPECT_EQ(p.cullReason("gradient"), "");  // it runs
  EXPECT_FALSE(p.culled("gradient"));
  // Resources only culled passes touch are unused: no texture, no lifetime.
  EXPECT_FALSE(p.used("debugInput"));
  EXPECT_FALSE(p.lifetime("debugInput").has_value());
  EXPECT_FALSE(p.texture("debugInput").has_value());
  EXPECT_TRUE(p.sharing("debugInput").empty());
  EXPECT_TRUE(p.used("scene"));
  EXPECT_EQ(p.describePass("debug_view"),
            "pass 'debug_view' (type fullscreen) is culled: its outputs (debugView) are never read by a pass that "
            "reaches the output");
  EXPECT_EQ(p.describePass("present"), "pass 'present' (type present) runs at step 1 of 2");
  const std::string d = p.describe();
  EXPECT_NE(d.find("order: gradient -> present"), std::string::npos) << d;
  EXPECT_NE(d.find("culled: debug_source: its outputs (debugInput)"), std::string::npos) << d;
}

// Every shipped pipeline: loads, has no error, and each query agrees with
// the plan it wraps (order, culling, textures, lifetimes, memory).
TEST(TestingShipped, EveryShippedPipelineAgreesWithItsPlan) {
  const auto files = shippedPipelines();
  ASSERT_GE(files.size(), 12u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const rt::CompiledPipeline p = rt::compileFile(file, at(96, 64));
    ASSERT_TRUE(p.ok()) << p.describe();
    const rgraph::Plan& plan = p.plan();
    ASSERT_EQ(p.order().size(), plan.order.size());
    for (size_t s = 0; s < plan.order.size(); ++s) {
      const std::string& name = plan.pass(plan.order[s]).name;
      EXPECT_EQ(p.order()[s], name);
      EXPECT_EQ(p.step(name), s);
      EXPECT_TRUE(p.runs(name));
    }
    for (const auto& pp : plan.passes) {
      EXPECT_EQ(p.culled(pp.name), pp.culled);
      EXPECT_EQ(p.cullReason(pp.name), pp.culled ? pp.reason : "");
      EXPECT_EQ(p.bindings(pp.name).size(), plan.uses(pp.decl).size());
    }
    uint64_t allocated = 0;
    for (const auto& t : p.textures()) allocated += t.bytes;
    EXPECT_EQ(allocated, p.allocatedBytes());
    EXPECT_EQ(p.allocatedBytes(), plan.allocatedBytes);
    EXPECT_EQ(p.naiveBytes(), plan.naiveBytes);
    EXPECT_LE(p.allocatedBytes(), p.naiveBytes());
    for (const auto& r : plan.resources) {
      EXPECT_EQ(p.used(r.name), r.firstPass.valid());
      EXPECT_EQ(p.texture(r.name).has_value(), r.physical.valid());
      if (r.physical.valid()) {
        const auto shared = p.sharing(r.name);
        EXPECT_NE(std::find(shared.begin(), shared.end(), r.name), shared.end());
      }
    }
    EXPECT_EQ(p.outputResource(), plan.resource(plan.outputResource).name);
  }
}

TEST(TestingShipped, PluginPipelineLoadsItsPlugins) {
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("deferred-ssao-bloom.json"), at(64, 64));
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_TRUE(p.runs("ssao")) << p.describePass("ssao");
  EXPECT_TRUE(p.runsBefore("ssao", "lighting")) << p.describe();
  // Small rather than shared: every resource has a texture of its own.
  EXPECT_EQ(p.allocatedBytes(), p.naiveBytes());
  EXPECT_TRUE(p.aliasGroups().empty());
  EXPECT_EQ(p.extent("bright"), (Extent{32, 32})) << "bloom runs at half size";
}

TEST(TestingShipped, ShaderChecksOnShippedPipelinesFindNothing) {
  rt::Options o = at(64, 64);
  o.shaderChecks = true;
  for (const char* name : {"default.json", "deferred-pbr.json", "examples/post-chain.json"}) {
    const rt::CompiledPipeline p = rt::compileFile(pipelinePath(name), o);
    EXPECT_TRUE(p.ok()) << p.describe();
    EXPECT_FALSE(p.hasDiagnostic(DiagCode::shader_error)) << p.describe();
  }
}

TEST(TestingShipped, AdaptedToASceneWithoutPointLights) {
  rt::Options o = at(64, 64);
  rgraph::SceneFeatures noLights;
  noLights.pointLights = false;
  o.scene = noLights;
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("default.json"), o);
  ASSERT_TRUE(p.ok()) << p.describe();
  ASSERT_FALSE(p.adaptNotes().empty());
  EXPECT_NE(p.adaptNotes()[0].find("light_volumes"), std::string::npos) << p.adaptNotes()[0];
  EXPECT_TRUE(p.culled("light_volumes")) << p.describe();
  EXPECT_EQ(p.cullReason("light_volumes"), "disabled");
  // The same file without a scene: nothing adapted.
  const rt::CompiledPipeline plain = rt::compileFile(pipelinePath("default.json"), at(64, 64));
  EXPECT_TRUE(plain.adaptNotes().empty());
  EXPECT_TRUE(plain.runs("light_volumes"));
}

TEST(TestingShipped, ScenePresentFalseRefusesScenePasses) {
  rt::Options o = at(64, 64);
  o.scenePresent = false;
  const rt::CompiledPipeline p = rt::compileFile(pipelinePath("default.json"), o);
  EXPECT_TRUE(p.loaded());
  EXPECT_FALSE(p.ok());
  EXPECT_TRUE(p.hasError(DiagCode::needs_scene)) << p.describe();
  const rgraph::Diagnostic* d = p.find(DiagCode::needs_scene);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->pass, "gbuffer");
  // Unknown (the default), as `rgraph validate`: not refused.
  EXPECT_FALSE(rt::compileFile(pipelinePath("default.json"), at(64, 64)).hasDiagnostic(DiagCode::needs_scene));
}
