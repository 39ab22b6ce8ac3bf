// "did you mean" on unknown names is budgeted per compile: each suggestion
// compares the name with every resource, so a large config with an unknown
// name in every pass would otherwise cost passes x resources comparisons.
// Every unknown name is still reported; only the hint stops.
#include <gtest/gtest.h>

#include <string>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

bool suggests(const Diagnostic& d) { return d.message.find("(did you mean '") != std::string::npos; }

TEST(SuggestionBudget, EveryUnknownNameIsReportedAndHintsStopOnceTheBudgetIsSpent) {
  // 4,000 resources and 3,000 passes reading a misspelled one: 12M name
  // comparisons if every message had its hint.
  constexpr int kResources = 4000, kPasses = 3000;
  GraphDesc d;
  for (int i = 0; i < kResources; ++i) d.resources.push_back(tex("res" + std::to_string(i)));
  d.resources.push_back(importedTex("out", false));
  for (int i = 0; i < kPasses; ++i)
    d.passes.push_back(pass("p" + std::to_string(i), {rd("src", "res" + std::to_string(i) + "x"), wr("color", "out")}));
  d.output = "out";

  Plan plan = compile(d);
  auto unknown = withCode(plan, DiagCode::unknown_resource);
  ASSERT_EQ(unknown.size(), static_cast<size_t>(kPasses)) << dumpDiagnostics(plan);
  // The first ones name the resource meant, in full.
  EXPECT_TRUE(suggests(*unknown.front())) << unknown.front()->message;
  EXPECT_NE(unknown.front()->message.find("reads 'res0x', which is not a declared resource"), std::string::npos)
      << unknown.front()->message;
  // The last ones still say what is wrong, without the hint.
  const Diagnostic& last = *unknown.back();
  EXPECT_FALSE(suggests(last)) << last.message;
  EXPECT_NE(last.message.find("reads 'res" + std::to_string(kPasses - 1) + "x', which is not a declared resource"),
            std::string::npos)
      << last.message;
  EXPECT_EQ(last.pass, "p" + std::to_string(kPasses - 1));
  // Hints are given in order until the budget runs out, never after.
  size_t hinted = 0;
  while (hinted < unknown.size() && suggests(*unknown[hinted])) ++hinted;
  EXPECT_GT(hinted, 100u);
  for (size_t i = hinted; i < unknown.size(); ++i) EXPECT_FALSE(suggests(*unknown[i])) << unknown[i]->message;
}

}  // namespace
