// The plan's promise to the executor (rgraph/graph.h, above Plan): when a plan
// is ok, every binding names a resource and every resource a pass that runs
// uses is imported or has a physical texture, so the executor indexes without
// checking bounds. Checked for every shipped pipeline (with the plugins it
// names) and every config of the corpora that compiles to an ok plan.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;

namespace {

std::vector<std::string> jsonFiles(const std::vector<std::string>& dirs) {
  std::vector<std::string> files;
  for (const std::string& dir : dirs)
    for (const auto& e : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// The sizes and aliasing settings each config is compiled with.
std::vector<CompileOptions> optionsToTry() {
  std::vector<CompileOptions> all;
  for (Extent e : {Extent{1280, 720}, Extent{64, 64}, Extent{333, 77}})
    for (bool alias : {true, false}) {
      CompileOptions o;
      o.output = e;
      o.alias = alias;
      all.push_back(o);
    }
  return all;
}

// Loads `file` with the built-ins and the plugins it names; compiles it with
// every option set; checks the contract of each ok plan. Returns the number
// of ok plans.
size_t checkFile(const std::string& file) {
  SCOPED_TRACE(file);
  PassRegistry registry = PassRegistry::builtins();
  PluginLoader loader(registry);
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(file, diags);
  if (!doc.ok()) return 0;
  for (const auto& name : doc.plugins()) {
    std::string error;
    if (!loader.load(name, std::filesystem::path(file).parent_path().string(), error)) return 0;
  }
  const PipelineConfig cfg = doc.build(registry, diags);
  if (hasErrors(diags)) return 0;
  size_t ok = 0;
  for (const CompileOptions& o : optionsToTry()) {
    const Plan plan = compile(cfg.graph, o);
    if (!plan.ok()) continue;
    ++ok;
    EXPECT_EQ(checkPlanContract(plan), "") << o.output.width << "x" << o.output.height << " alias " << o.alias;
  }
  return ok;
}

}  // namespace

TEST(PlanContract, HoldsForEveryShippedPipeline) {
  const std::vector<std::string> files = jsonFiles({"pipelines", "pipelines/examples"});
  ASSERT_GE(files.size(), 12u);
  for (const std::string& file : files) EXPECT_EQ(checkFile(file), optionsToTry().size()) << file << " is not ok";
}

TEST(PlanContract, HoldsForEveryOkPlanOfTheCorpora) {
  // Configs whose graph is sound but which a pass check or a shader refuses:
  // their plans are ok and reach everything but the GPU.
  const std::vector<std::string> files = jsonFiles({"tests/configs/invalid/checks", "tests/shadercheck/configs"});
  size_t ok = 0;
  for (const std::string& file : files) ok += checkFile(file);
  EXPECT_GE(ok, 10 * optionsToTry().size());
}

// The check itself catches what the executor relies on.
TEST(PlanContract, CatchesAUsedResourceWithoutMemory) {
  const std::string file = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr.json";
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(file, diags);
  const PipelineConfig cfg = doc.build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags));
  Plan plan = compile(cfg.graph);
  ASSERT_TRUE(plan.ok());
  ASSERT_EQ(checkPlanContract(plan), "");

  Plan noMemory = plan;
  PlannedResource& normal = noMemory.resources.at(1);  // gNormal: a transient the lighting pass reads
  ASSERT_TRUE(normal.physical.valid() && !normal.imported) << normal.name;
  normal.physical = PhysicalIndex();
  EXPECT_EQ(checkPlanContract(noMemory),
            "resource '" + normal.name + "' is used but neither imported nor given a physical");

  Plan unbound = plan;
  unbound.bindings.at(plan.order.front().value()).at(0).resource = ResourceIndex();
  EXPECT_NE(checkPlanContract(unbound).find("binds no resource"), std::string::npos);

  Plan noOutput = plan;
  noOutput.outputResource = ResourceIndex();
  EXPECT_EQ(checkPlanContract(noOutput), "no output resource");
}
