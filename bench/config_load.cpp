// Loading a pipeline config must take time linear in its size. Timed: what
// `rgraph validate` does with a config text (parse, the checks against the
// pass types, compile; with the glslang shader checks in the second
// benchmark), on a chain of N passes over N resources built outside the
// timed loop, as scripts/gen-chain-config.py writes it. Complexity(oN)
// reports the fit; a quadratic step shows as a growing time per pass
// (50,000 passes took 25x the time of 5,000 before the loader was fixed).
#include <benchmark/benchmark.h>

#include <string>

#include "rgraph/config.h"
#include "rgraph/graph.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/pipeline_load.h"

namespace {

// clear -> r0, then pass i copies r{i-1} into r{i}: with blit (no shader) or
// with fullscreen passes that all run one program (invert.frag).
std::string chainConfig(size_t passes, bool fullscreen) {
  std::string text = "{\n  \"version\": 1,\n  \"resources\": {\n";
  for (size_t i = 0; i < passes; ++i)
    text += "    \"r" + std::to_string(i) + "\": {\"format\": \"rgba8\", \"size\": \"output\"}" +
            (i + 1 < passes ? ",\n" : "\n");
  text += "  },\n  \"passes\": [\n    {\"name\": \"p0\", \"type\": \"clear\", \"outputs\": {\"color\": \"r0\"}}";
  for (size_t i = 1; i < passes; ++i) {
    const std::string in = "r" + std::to_string(i - 1), out = "r" + std::to_string(i);
    text += ",\n    {\"name\": \"p" + std::to_string(i) + "\", ";
    if (fullscreen)
      text += "\"type\": \"fullscreen\", \"params\": {\"shader\": \"invert.frag\"}, \"inputs\": {\"input0\": \"" + in +
              "\"}, \"outputs\": {\"color\": \"" + out + "\"}}";
    else
      text += "\"type\": \"blit\", \"inputs\": {\"src\": \"" + in + "\"}, \"outputs\": {\"dst\": \"" + out + "\"}}";
  }
  text += "\n  ],\n  \"output\": \"r" + std::to_string(passes - 1) + "\"\n}\n";
  return text;
}

void loadValidate(benchmark::State& state, bool shaders) {
  const size_t passes = static_cast<size_t>(state.range(0));
  const std::string text = chainConfig(passes, shaders);
  const rgraph::PassRegistry& registry = rgraph::processRegistry();
  size_t live = 0, programs = 0;
  for (auto _ : state) {
    rgraph::Diagnostics diags;
    rgraph::ConfigDocument doc = rgraph::ConfigDocument::parseText(text, "chain.json", diags);
    rgraph::PipelineConfig config = doc.build(registry, diags);
    rgraph::Plan plan = rgraph::compile(config.graph);
    diags.insert(diags.end(), plan.diagnostics.begin(), plan.diagnostics.end());
    if (shaders) {
      // A fresh checker each time: one program compiled, then cached for every pass.
      rgraph::ShaderChecker checker(rgraph::defaultShaderSearchDirectories());
      rgraph::Diagnostics d = checker.checkPipeline(config, plan, registry);
      diags.insert(diags.end(), d.begin(), d.end());
      programs = checker.stats().programsCompiled;
    }
    if (rgraph::hasErrors(diags)) {
      state.SkipWithError(("the generated config does not validate: " + rgraph::formatDiagnostic(diags[0])).c_str());
      break;
    }
    live = plan.order.size();
    benchmark::DoNotOptimize(plan);
  }
  state.counters["live_passes"] = static_cast<double>(live);
  state.counters["MB"] = static_cast<double>(text.size()) / 1e6;
  if (shaders) state.counters["programs_compiled"] = static_cast<double>(programs);  // 1 whatever the passes
  state.SetComplexityN(state.range(0));
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(text.size()));
}

void BM_ConfigLoadValidate(benchmark::State& state) { loadValidate(state, false); }
void BM_ConfigLoadValidateShaders(benchmark::State& state) { loadValidate(state, true); }

// Arg: passes (and resources). 1M passes is a 150 MB config.
BENCHMARK(BM_ConfigLoadValidate)
    ->ArgName("passes")
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Complexity(benchmark::oN)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ConfigLoadValidateShaders)
    ->ArgName("passes")
    ->RangeMultiplier(10)
    ->Range(1000, 100000)
    ->Complexity(benchmark::oN)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
