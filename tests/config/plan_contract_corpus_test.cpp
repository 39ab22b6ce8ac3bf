// The plan's promise to the executor (rgraph/graph.h, above Plan) for every
// config of tests/configs that compiles to an ok plan, with the test pass
// types (tests/plugin/plan_contract_test.cpp covers the shipped pipelines).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_registry.h"

namespace rgraph {
namespace {

TEST(PlanContract, HoldsForEveryOkPlanOfTheConfigCorpus) {
  size_t files = 0, ok = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(test::configsDir())) {
    if (e.path().extension() != ".json") continue;
    ++files;
    SCOPED_TRACE(e.path().string());
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseFile(e.path().string(), diags);
    if (!doc.ok()) continue;
    const PipelineConfig cfg = doc.build(test::testRegistry(), diags);
    if (hasErrors(diags)) continue;
    for (bool alias : {true, false}) {
      CompileOptions o;
      o.alias = alias;
      const Plan plan = compile(cfg.graph, o);
      if (!plan.ok()) continue;
      ++ok;
      EXPECT_EQ(checkPlanContract(plan), "");
    }
  }
  EXPECT_GE(files, 80u);
  EXPECT_GE(ok, 6u) << "of " << files;  // tests/configs/valid, twice each
}

}  // namespace
}  // namespace rgraph
