// The cheaper G-buffer layouts against the fp32 reference, all lit by light
// volumes into an rgba32f target: the differences are what their precision
// costs (8-bit albedo and metallic/roughness, half-float position or
// position rebuilt from depth, octahedral rg16f normals), bounded here.
#include <cstdio>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{256, 256};

class GBufferLayouts : public RenderTest {
 protected:
  void expectClose(const Scene& scene, const std::string& pipeline, const std::string& model, int tolerance,
                   const std::string& name) {
    PipelineConfig ref = loadPipeline(testPipeline("light-volumes-fp32.json"));
    PipelineConfig cand = loadPipeline(testPipeline(pipeline));
    for (PipelineConfig* cfg : {&ref, &cand})
      for (const char* pass : {"ambient", "volumes"}) setParam(*cfg, pass, "model", model);
    const Image a = render(ref, scene, kSize, *shaders);
    const Image b = render(cand, scene, kSize, *shaders);
    EXPECT_GT(coverage(a, {0, 0, 0}), 0.2);
    expectLightsShow(a, ref, scene, *shaders, 0.05, name + "-fp32");
    const ImageDiff d = compareImages(a, b, tolerance);
    std::printf("[ measure  ] %s: %s vs fp32 G-buffer: %s\n", name.c_str(), pipeline.c_str(), d.describe().c_str());
    RecordProperty("max_abs_diff_" + name, d.maxDiff);
    EXPECT_LE(d.maxDiff, tolerance) << d.describe() << "; images " << saveImage(a, name + "-fp32") << ", "
                                    << saveImage(b, name + "-" + pipeline);
  }
};

}  // namespace

TEST_F(GBufferLayouts, CompactCloseToFp32) {
  expectClose(makeLearnOpenGLScene(), "compact-volumes.json", "blinn_phong", 3, "compact-learnopengl");
  // Metallic and roughness in 8 bits (0.5 stored as 128/255) move GGX
  // highlights by a few levels: measured 4/255 at one pixel.
  expectClose(makeCookTorranceScene(), "compact-volumes.json", "cook_torrance", 5, "compact-still-life");
}

TEST_F(GBufferLayouts, LearnOpenGLCloseToFp32) {
  expectClose(makeLearnOpenGLScene(), "light-volumes-learnopengl.json", "blinn_phong", 3, "learnopengl-layout");
}
