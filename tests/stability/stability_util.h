// Helpers of the stability tests (issue 5): where rendering methods fail,
// measured. One headless GL context and one shader library per test program,
// pipelines written as JSON in the tests (so that they say exactly what each
// case compares) or loaded from pipelines/, frames rendered and compared
// (8-bit max error, PSNR, HDR floats), hand-built scenes.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/graph.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "render/test_scenes.h"

namespace rgraph::stab {

// The process-wide headless context (created on first use) and a shader
// library shared by every test of the program (programs compile once).
GlContext& glContext();
ShaderLibrary& sharedShaders();

// Fixture: fails the test when it caused GL debug errors.
class Stability : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  uint64_t errorsAtStart = 0;
};

// ---------------------------------------------------------------- pipelines

// Builds a pipeline from JSON with the built-in pass types; throws RuntimeError
// with every diagnostic when it has errors.
PipelineConfig pipelineFromJson(const nlohmann::json& doc, const std::string& name);
// pipelines/<name> of the source tree.
PipelineConfig repoPipeline(const std::string& name);
void setParam(PipelineConfig& cfg, const std::string& pass, const std::string& key, ParamValue value);

struct LightingParams {
  std::string model = "blinn_phong";
  std::string attenuation = "classic";
  double threshold = 0.0;  // 0: no cut-off
};

// G-buffer resources and the geometry pass of one layout (learnopengl, pbr,
// compact, fp32) with its real formats; depthFormat overrides the layout's
// default depth format when not empty.
struct GBufferSpec {
  std::string layout = "fp32";
  std::string depthFormat;  // "" -> the layout's usual one
};

// geometry -> deferred_lighting (fullscreen, every point light) -> rgba32f
// "hdr" -> tonemap (operator none; gamma 1: linear bytes, as the repo's
// LearnOpenGL pipelines) -> rgba8 "output".
nlohmann::json fullscreenPipeline(const GBufferSpec& g, const LightingParams& l, double gamma = 1.0);
// fullscreenPipeline with its lighting pass turned into another lighting
// pass type reading the same inputs (tiled_deferred, clustered_deferred),
// `extraParams` merged into its parameters.
nlohmann::json computePipeline(const std::string& type, const LightingParams& l,
                               const nlohmann::json& extraParams = nlohmann::json::object());
// geometry (fp32) -> deferred_lighting (ambient + directional only) ->
// light_volumes (cull front|back, depth-tested) into rgba32f "hdr" (final
// version "hdr_lit") -> tonemap -> output.
nlohmann::json lightVolumesPipeline(const std::string& cull, const LightingParams& l, double gamma = 1.0);
// forward_lit into rgba32f "hdr" (depth32f) -> tonemap -> output.
nlohmann::json forwardPipeline(const LightingParams& l, double gamma = 1.0);

// ---------------------------------------------------------------- frames

struct Frame {
  Extent size;
  std::vector<uint8_t> rgba;                          // output, rows top-down
  std::map<std::string, std::vector<float>> targets;  // read with readTextureRGBA32F, rows top-down
  const std::vector<float>& target(const std::string& name) const { return targets.at(name); }
};

// Renders one frame and reads the output plus the named targets (read after
// the frame: name resources that stay live to the end, see liveToTheEnd).
Frame renderFrame(const PipelineConfig& cfg, const Scene& scene, Extent size,
                  const std::vector<std::string>& targets = {});

// Whether the texture of `resource` still holds its last version after the
// frame: no other resource shares its physical texture with a first use after
// this resource's last use. (Aliasing reuses a dead resource's texture.)
bool liveToTheEnd(const Plan& plan, const std::string& resource, std::string* why = nullptr);

// ---------------------------------------------------------------- metrics

struct Diff {
  int maxAbs = 0;        // max over pixels and RGB channels of |a - b| (8-bit)
  double psnr = 0.0;     // over RGB channels; +inf when identical
  double mse = 0.0;
  size_t over1 = 0;      // pixels with some channel off by more than 1/255
  size_t pixels = 0;     // pixels compared
  int worstX = -1, worstRow = -1;
  std::string describe() const;
};
// Compares two RGBA8 images (RGB only). `mask`, when given, selects the
// pixels to compare (row-major, rows top-down, one entry per pixel).
Diff compare8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, Extent e,
              const std::vector<bool>* mask = nullptr);
std::string psnrText(double psnr);
// Pixels of `a` with some RGB channel at least `by` (8-bit) above `b`'s.
size_t pixelsBrighter(const Frame& a, const Frame& b, int by);

// Writes a PNG under <build dir>/stability-output (working directory of the
// test) for looking at failures; returns the path ("" when it could not).
std::string saveImage(const std::vector<uint8_t>& rgba, Extent e, const std::string& name);

// Half-float step (ulp) at magnitude |v|.
double halfUlp(double v);

// ---------------------------------------------------------------- scenes

// The image tests' scene builders (render/test_scenes.h).
using rtest::addDraw;
using rtest::addMaterial;
using rtest::addMesh;
using rtest::translate;
PointLight pointLight(glm::vec3 pos, glm::vec3 color, float intensity = 1.0f, float constant = 1.0f,
                      float linear = 0.7f, float quadratic = 1.8f);
// Gives the scene its camera: at `position` looking at `target`, `fovY`
// degrees vertically, between `nearPlane` and `farPlane`, `up` up.
void placeCamera(Scene& s, glm::vec3 position, glm::vec3 target, float fovY, float nearPlane, float farPlane,
                 glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f));

// A floor (6 x 6), a cube rotated on it and a sphere, one warm point light,
// ambient 0.05, no directional light; the camera ~4 units away. Everything
// shifted by `offset` (camera included).
Scene smallStillLife(glm::vec3 offset = glm::vec3(0.0f), bool withLight = true);

}  // namespace rgraph::stab
