// One function per `rgraph` subcommand; each returns the process exit code.
#pragma once

#include <cstdint>
#include <string>

namespace rgraph::cli {

struct SizeOptions {
  uint32_t width = 1280;
  uint32_t height = 720;
};

int runValidate(const std::string& pipeline, const SizeOptions& size, bool json);
int runPlan(const std::string& pipeline, const SizeOptions& size, bool json);
int runDot(const std::string& pipeline, const SizeOptions& size);
int runPasses(bool json);

struct RenderOptions {
  std::string pipeline;   // empty: the default pipeline
  std::string out;        // PNG path
  std::string scene;      // scene file, .gltf/.glb, or a procedural name
  std::string stats;      // stats JSON path (optional)
  SizeOptions size;
  uint32_t frames = 1;
  bool window = false;
};
int runRender(const RenderOptions& options);

}  // namespace rgraph::cli
