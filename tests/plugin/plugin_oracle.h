// Shared by the plugin oracle tests (OracleSsao, OracleBloom): the bloom and
// ssao plugins loaded into a registry, a pipeline built from config text,
// rendered once, and several of its resources read back as floats.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace rgraph::poracle {

// One channel of an RGBA32F readback; rows top-down as the executor gives them.
struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  double at(int x, int row) const { return v[static_cast<size_t>(row) * width + x]; }
};

// The four channels of a readback.
struct Rgba {
  Plane c[4];
};

inline GlContext& oracleContext() {
  static std::unique_ptr<GlContext> ctx = GlContext::create();
  ctx->makeCurrent();
  return *ctx;
}

class PluginOracleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    errorsAtStart = oracleContext().debugErrorCount();
    std::string error;
    for (const char* name : {"bloom", "ssao"}) ASSERT_NE(loader.load(name, {}, error), nullptr) << error;
  }
  void TearDown() override {
    EXPECT_EQ(oracleContext().debugErrorCount(), errorsAtStart) << oracleContext().lastDebugError();
  }

  // Renders one frame of `json` at `size` and reads each of `resources`.
  std::map<std::string, Rgba> render(const std::string& json, Extent size, const std::vector<std::string>& resources,
                                     const Scene* scene = nullptr) {
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(json, "oracle.json", diags);
    PipelineConfig cfg = doc.build(registry, diags);
    for (const auto& d : diags) ADD_FAILURE() << formatDiagnostic(d);
    ShaderLibrary shaders;
    shaders.addSearchDirectory(std::string(RGRAPH_SOURCE_DIR) + "/tests/plugin/shaders");
    Executor exec(cfg, registry, shaders, scene);
    exec.resize(size);
    exec.renderFrame();
    std::map<std::string, Rgba> out;
    for (const std::string& r : resources) {
      std::vector<float> rgba = exec.readTextureRGBA32F(r);
      Rgba& img = out[r];
      for (size_t ch = 0; ch < 4; ++ch) {
        Plane& p = img.c[ch];
        // Square frames only: a scaled resource (bloom at half size) has side sqrt(texels).
        p.width = p.height = static_cast<int>(std::lround(std::sqrt(static_cast<double>(rgba.size() / 4))));
        for (size_t i = 0; i < rgba.size() / 4; ++i) p.v.push_back(rgba[i * 4 + ch]);
      }
    }
    return out;
  }

  PassRegistry registry = PassRegistry::builtins();
  PluginLoader loader{registry};
  uint64_t errorsAtStart = 0;
};

}  // namespace rgraph::poracle
