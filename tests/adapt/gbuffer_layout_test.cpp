// The G-buffer layout table (passes/common): a pipeline built from each row
// passes every check validate runs, shaders included (gbuffer.frag's outputs
// against the row's targets, the readers' needs), and `rgraph plan`'s bytes
// per pixel is the row's; the passes' declarations agree with the table; and
// gbufferBytesPerPixel counts what pass types declare, not a type name.
#include "rgraph/passes/gbuffer_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/pass_check.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/pipeline_load.h"

namespace rgraph {
namespace {

using nlohmann::json;

// geometry -> deferred_lighting -> tonemap, with the row's targets and formats.
std::string pipelineFor(const gbuffer::Layout& layout) {
  json res = json::object(), gOut = json::object(), gIn = json::object();
  for (const auto& t : layout.targets) {
    if (t.optional) continue;
    res["g_" + t.slot] = {{"format", formatName(t.format)}, {"size", "output"}};
    gOut[t.slot] = gIn[t.slot] = "g_" + t.slot;
  }
  res["g_depth"] = {{"format", formatName(layout.depth)}, {"size", "output"}};
  gOut["depth"] = "g_depth";
  if (layout.positionFromDepth) gIn["depth"] = "g_depth";
  res["hdr"] = {{"format", "rgba16f"}, {"size", "output"}};
  res["output"] = {{"format", "rgba8"}, {"size", "output"}};
  json passes = json::array();
  passes.push_back(
      {{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", layout.name}}}, {"outputs", gOut}});
  passes.push_back({{"name", "lighting"},
                    {"type", "deferred_lighting"},
                    {"params", {{"layout", layout.name}}},
                    {"inputs", gIn},
                    {"outputs", {{"color", "hdr"}}}});
  passes.push_back(
      {{"name", "tonemap"}, {"type", "tonemap"}, {"inputs", {{"hdr", "hdr"}}}, {"outputs", {{"output", "output"}}}});
  return json{{"version", 1}, {"resources", res}, {"passes", passes}, {"output", "output"}}.dump(2);
}

std::string messages(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

TEST(GBufferLayoutTable, EachRowValidatesWithItsShadersAndCountsItsBytes) {
  ASSERT_EQ(gbuffer::names(), (std::vector<std::string>{"learnopengl", "pbr", "compact", "fp32"}));
  ShaderChecker checker;
  for (const auto& layout : gbuffer::layouts()) {
    SCOPED_TRACE(layout.name);
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(pipelineFor(layout), layout.name + ".json", diags);
    PipelineConfig pipeline = doc.build(processRegistry(), diags);
    ASSERT_FALSE(hasErrors(diags)) << messages(diags);
    const Plan plan = compile(pipeline.graph, CompileOptions{Extent{64, 64}});
    ASSERT_TRUE(plan.ok()) << messages(plan.diagnostics);
    PassCheckOptions options;
    options.scenePresent = true;
    EXPECT_FALSE(hasErrors(runPassChecks(pipeline, plan, processRegistry(), options)))
        << messages(runPassChecks(pipeline, plan, processRegistry(), options));
    const Diagnostics shaders = checker.checkPipeline(pipeline, plan, processRegistry());
    EXPECT_FALSE(hasErrors(shaders)) << messages(shaders);
    EXPECT_EQ(gbufferBytesPerPixel(pipeline, plan, processRegistry()), layout.bytesPerPixel());
  }
  // The figures docs/performance.md quotes for rgraph bench's pipelines.
  EXPECT_EQ(gbuffer::find("learnopengl").bytesPerPixel(), 24u);
  EXPECT_EQ(gbuffer::find("pbr").bytesPerPixel(), 36u);
  EXPECT_EQ(gbuffer::find("compact").bytesPerPixel(), 14u);
  EXPECT_EQ(gbuffer::find("fp32").bytesPerPixel(), 68u);
}

// gbuffer.frag's output locations follow geometry's colour slot order, and
// geometry must accept every format and leave optional what some layout lacks.
TEST(GBufferLayoutTable, TheGeometryPassDeclaresWhatTheTableWrites) {
  const PassTypeDesc* geometry = processRegistry().find("geometry");
  ASSERT_NE(geometry, nullptr);
  std::vector<std::string> color;
  for (const auto& s : geometry->slots) {
    EXPECT_TRUE(s.gbufferTarget) << s.name;
    if (s.access == Access::color_attachment) color.push_back(s.name);
  }
  // The layouts' targets, then the optional motion vectors (rgraph/passes/velocity.h), then the ids
  // picking asks for (gbuffer::objectIdTarget), last, optional and of the table's format only.
  std::vector<std::string> expected = gbuffer::colorSlots();
  expected.push_back("velocity");
  expected.push_back(gbuffer::objectIdTarget().slot);
  EXPECT_EQ(color, expected);
  const SlotDecl* ids = geometry->findSlot(gbuffer::objectIdTarget().slot);
  ASSERT_NE(ids, nullptr);
  EXPECT_FALSE(ids->required);
  EXPECT_EQ(ids->formats, std::vector<Format>{gbuffer::objectIdTarget().format});
  for (const auto& layout : gbuffer::layouts()) {
    for (const auto& slot : gbuffer::colorSlots()) {
      const SlotDecl* decl = geometry->findSlot(slot);
      const bool everyLayout = std::all_of(gbuffer::layouts().begin(), gbuffer::layouts().end(),
                                           [&](const gbuffer::Layout& l) {
                                             return l.writes(slot) && !l.target(slot)->optional;
                                           });
      EXPECT_EQ(decl->required, everyLayout) << slot;
      if (const gbuffer::Target* t = layout.target(slot)) {
        EXPECT_TRUE(decl->formats.empty() || std::count(decl->formats.begin(), decl->formats.end(), t->format))
            << layout.name << " " << slot;
      }
    }
    const auto& depth = geometry->findSlot("depth")->formats;
    EXPECT_TRUE(std::count(depth.begin(), depth.end(), layout.depth)) << layout.name;
  }
  for (const PassTypeDesc* type : processRegistry().all()) {
    if (const ParamDecl* p = type->findParam("layout")) {
      EXPECT_EQ(p->choices, gbuffer::names()) << type->name;
      EXPECT_EQ(std::get<std::string>(p->defaultValue), gbuffer::kDefaultLayout) << type->name;
    }
  }
}

TEST(GBufferLayoutTable, ReadersNeedTheirPositionSourceAndTheMaterial) {
  EXPECT_EQ(gbuffer::find("learnopengl").readerSlots(false),
            (std::vector<std::string>{"normal", "albedo", "position"}));
  EXPECT_EQ(gbuffer::find("compact").readerSlots(false),
            (std::vector<std::string>{"normal", "albedo", "depth", "material"}));
  EXPECT_EQ(gbuffer::find("pbr").readerSlots(true), (std::vector<std::string>{"normal", "albedo", "position"}));
  EXPECT_EQ(gbuffer::find("no such layout").name, "pbr");
}

// Core knows no pass type by name: a type called "geometry" whose slots are
// not G-buffer targets counts nothing; another type's declared targets count.
TEST(GBufferBytesPerPixel, CountsTheSlotsTypesDeclareNotATypeName) {
  PassRegistry registry;
  auto addType = [&](const std::string& name, bool gbuffer) {
    PassTypeDesc d;
    d.name = name;
    d.slots = {decl::slot("out", Access::color_attachment, true, SlotDecl::Load::never, "target")};
    d.slots[0].gbufferTarget = gbuffer;
    d.sideEffect = true;  // never culled
    d.create = [] { return std::unique_ptr<PassInstance>(); };  // never run: only compiled
    std::string error;
    ASSERT_TRUE(registry.add(std::move(d), &error)) << error;
  };
  addType("geometry", false);
  addType("my_gbuffer", true);
  const std::string text = R"({"version": 1,
    "resources": {"a": {"format": "rgba8", "size": "output"}, "b": {"format": "rgba32f", "size": "output"}},
    "passes": [{"name": "g", "type": "geometry", "outputs": {"out": "a"}},
               {"name": "m", "type": "my_gbuffer", "outputs": {"out": "b"}}],
    "output": "b"})";
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(text, "types.json", diags);
  PipelineConfig pipeline = doc.build(registry, diags);
  ASSERT_FALSE(hasErrors(diags)) << messages(diags);
  const Plan plan = compile(pipeline.graph, CompileOptions{Extent{8, 8}});
  ASSERT_TRUE(plan.ok()) << messages(plan.diagnostics);
  EXPECT_EQ(gbufferBytesPerPixel(pipeline, plan, registry), 16u);  // b only
}

}  // namespace
}  // namespace rgraph
