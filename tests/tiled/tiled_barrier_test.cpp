// The shipped tiled pipeline's memory barriers: tiled_deferred stores the HDR
// image with image stores and issues no barrier itself; the executor issues,
// from the declared access, a framebuffer barrier before the forward pass
// that loads that image as its colour attachment, a texture-fetch barrier
// before the tonemap pass that samples it, and the rest after the frame.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rgraph/adapt.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"

namespace {
using namespace rgraph;

using TiledBarriers = rtest::RenderTest;  // fails on GL debug errors

TEST_F(TiledBarriers, ShippedPipelineGetsBarriersFromDeclaredAccess) {
  const Scene scene = makeManyLightsScene(8);
  PipelineConfig cfg = rtest::loadPipeline(rtest::repoPath("pipelines/deferred-tiled.json"));
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  Executor exec(cfg, processRegistry(), *shaders, &scene);
  exec.resize({96, 64});
  const std::vector<uint32_t> bits = exec.memoryBarriers();
  ASSERT_EQ(bits.size(), exec.plan().order.size());
  std::vector<std::string> names;
  for (PassIndex p : exec.plan().order) names.push_back(exec.plan().pass(p).name);
  ASSERT_EQ(names, (std::vector<std::string>{"gbuffer", "tiled_lighting", "depth_blit", "light_boxes", "tonemap"}));
  EXPECT_EQ(bits[0], 0u);
  EXPECT_EQ(bits[1], 0u);  // reads the G-buffer, written by a fragment pass: coherent
  EXPECT_EQ(bits[2], 0u);
  EXPECT_EQ(bits[3], uint32_t(GL_FRAMEBUFFER_BARRIER_BIT)) << "light_boxes blends into the tiled pass's image";
  EXPECT_EQ(bits[4], uint32_t(GL_TEXTURE_FETCH_BARRIER_BIT)) << "tonemap samples it";
  EXPECT_EQ(exec.frameEndMemoryBarrier(),
            uint32_t(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT));
  exec.renderFrame();
  EXPECT_EQ(exec.readOutputRGBA8().size(), 96u * 64u * 4u);
}

}  // namespace
