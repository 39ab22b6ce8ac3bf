// Fuzz target: pipeline config text -> diagnostics or a compiled graph, the
// steps `rgraph validate` runs before its shader checks (parse, build against
// the pass declarations, compile, DOT). The pass types are the config tests'
// fake ones (tests/config/test_registry.h): every slot access, load rule and
// parameter type, without GL.
//
// Beyond "no crash, no sanitizer report, no exception", it checks that every
// diagnostic from parsing or building names the file and a line, as the CLI
// promises (file:line:col), and that a built config is consistent.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "config/test_registry.h"
#include "fuzz_util.h"
#include "rgraph/config.h"
#include "rgraph/graph.h"

namespace {
constexpr const char* kFile = "fuzz.json";

void checkLocated(const rgraph::Diagnostics& diags) {
  for (const rgraph::Diagnostic& d : diags) {
    if (d.where.file != kFile || d.where.line < 1 || d.where.column < 0)
      rgraph::fuzz::fail("diagnostic without a location: " + rgraph::formatDiagnostic(d));
    if (d.message.empty()) rgraph::fuzz::fail("diagnostic without a message at line " + std::to_string(d.where.line));
  }
}

void print(const rgraph::Diagnostics& diags) {
  if (rgraph::fuzz::verbose())
    for (const rgraph::Diagnostic& d : diags) std::fprintf(stderr, "%s\n", rgraph::formatDiagnostic(d).c_str());
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rgraph::fuzz::quietLogs();
  (void)rgraph::test::testRegistry();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rgraph::Diagnostics diags;
  rgraph::ConfigDocument doc = rgraph::ConfigDocument::parseText(text, kFile, diags);
  checkLocated(diags);
  if (!doc.ok() || rgraph::hasErrors(diags)) {
    print(diags);
    return 0;
  }

  // What the CLI reads before building: plugin names and their locations.
  const std::vector<std::string> plugins = doc.plugins();
  for (size_t i = 0; i < plugins.size(); ++i)
    if (doc.pluginLocation(i).file != kFile) rgraph::fuzz::fail("plugin entry without a location");

  rgraph::PipelineConfig pipeline = doc.build(rgraph::test::testRegistry(), diags);
  checkLocated(diags);
  print(diags);
  if (rgraph::hasErrors(diags)) return 0;
  if (pipeline.params.size() != pipeline.graph.passes.size())
    rgraph::fuzz::fail("built config has " + std::to_string(pipeline.params.size()) + " parameter sets for " +
                       std::to_string(pipeline.graph.passes.size()) + " passes");

  // The output size only scales the plan's byte counts: keep it small.
  rgraph::CompileOptions options;
  options.output = rgraph::Extent{64, 64};
  const rgraph::Plan plan = rgraph::compile(pipeline.graph, options);
  for (const rgraph::Diagnostic& d : plan.diagnostics) (void)rgraph::formatDiagnostic(d);
  print(plan.diagnostics);
  if (plan.ok()) (void)rgraph::toDot(pipeline.graph, plan);
  return 0;
}
