// The executor refuses what the pass types' check hooks refuse (rgraph/pass_check.h)
// before it creates any texture, framebuffer, program or pass instance.
#include <gtest/gtest.h>

#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "test_support.h"

namespace rgraph {
namespace {

std::string refusal(const PipelineConfig& pipeline, const Scene* scene, Extent size, size_t* objectsAfter) {
  testsupport::sharedGlContext();
  ShaderLibrary shaders;
  Executor executor(pipeline, processRegistry(), shaders, scene);
  std::string message;
  try {
    executor.resize(size);
  } catch (const RuntimeError& e) {
    message = e.what();
  }
  *objectsAfter = executor.ownedObjects();
  return message;
}

TEST(ExecutorPassChecks, APipelineThatDrawsTheSceneIsRefusedWithoutOne) {
  const std::string path = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr.json";
  size_t objects = 1;
  const std::string msg = refusal(testsupport::loadPipelineOrThrow(path), nullptr, {64, 64}, &objects);
  EXPECT_NE(msg.find("deferred-pbr.json:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/passes/0: geometry pass 'gbuffer': needs a scene"), std::string::npos) << msg;
  EXPECT_EQ(objects, 0u) << "refused after creating GL objects";
}

TEST(ExecutorPassChecks, ABindingThePassCannotUseIsRefusedAtItsLocation) {
  const std::string path = std::string(RGRAPH_SOURCE_DIR) + "/tests/configs/invalid/checks/present_depth_src.json";
  size_t objects = 1;
  Scene scene = loadSceneAny("learnopengl");
  const std::string msg = refusal(testsupport::loadPipelineOrThrow(path), &scene, {32, 16}, &objects);
  EXPECT_NE(msg.find("present_depth_src.json:14:59: error: /passes/1/inputs/src: present pass 'show': src has a depth "
                     "format (depth32f)"),
            std::string::npos)
      << msg;
  EXPECT_EQ(objects, 0u);
}

}  // namespace
}  // namespace rgraph
