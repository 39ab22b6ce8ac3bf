// The chain pipeline the executor's cost is measured and counted on
// (bench/render_executor_overhead.cpp, tests/gl_calls/): a gradient, then
// `passes` - 1 fullscreen inverts, each reading the one before, every
// target rgba8 at the output size. JSON text for loadPipelineTextOrThrow.
#pragma once

#include <string>

namespace rgraph::bench {

inline std::string chainPipelineJson(int passes) {
  std::string json = R"({"version": 1, "resources": {)";
  for (int i = 0; i < passes; ++i)
    json += (i ? "," : "") + std::string("\"t") + std::to_string(i) + "\": {\"format\": \"rgba8\", \"size\": \"output\"}";
  json += R"(}, "passes": [{"name": "p0", "type": "fullscreen", "params": {"shader": "gradient.frag"},
             "outputs": {"color": "t0"}})";
  for (int i = 1; i < passes; ++i)
    json += ",{\"name\": \"p" + std::to_string(i) + "\", \"type\": \"fullscreen\", \"params\": {\"shader\": " +
            "\"invert.frag\"}, \"inputs\": {\"input0\": \"t" + std::to_string(i - 1) + "\"}, \"outputs\": " +
            "{\"color\": \"t" + std::to_string(i) + "\"}}";
  json += "], \"output\": \"t" + std::to_string(passes - 1) + "\"}";
  return json;
}

}  // namespace rgraph::bench
