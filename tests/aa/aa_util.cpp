#include "aa/aa_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "render/test_scenes.h"
#include "rgraph/pipeline_check.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"

namespace rgraph::aatest {

PipelineConfig shippedPipeline(const std::string& name) {
  return loadPipelineFileOrThrow(rtest::repoPath("pipelines/" + name));
}

Frames::Frames(const PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders)
    : exec_(std::make_unique<Executor>(cfg, processRegistry(), shaders, &scene)) {
  exec_->resize(size);
}

Image Frames::next() {
  exec_->renderFrame();
  Image img;
  img.extent = exec_->outputExtent();
  img.rgba = exec_->readOutputRGBA8();
  return img;
}

Image supersampled(const PipelineConfig& cfg, const Scene& scene, Extent size, int factor, ShaderLibrary& shaders) {
  const Extent big{size.width * static_cast<uint32_t>(factor), size.height * static_cast<uint32_t>(factor)};
  const Image hi = rtest::render(cfg, scene, big, shaders);
  Image out;
  out.extent = size;
  out.rgba.assign(static_cast<size_t>(size.width) * size.height * 4, 255);
  const int n = factor * factor;
  for (int row = 0; row < static_cast<int>(size.height); ++row)
    for (int x = 0; x < static_cast<int>(size.width); ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += hi.at(x * factor + i, row * factor + j)[c];
        out.rgba[(static_cast<size_t>(row) * size.width + x) * 4 + c] = static_cast<uint8_t>((sum + n / 2) / n);
      }
  return out;
}

Mask edgeMask(const Image& ref, int threshold) {
  const int w = static_cast<int>(ref.extent.width), h = static_cast<int>(ref.extent.height);
  Mask m(static_cast<size_t>(w) * h, false);
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 4; ++k) {
        const int nx = x + dx[k], ny = row + dy[k];
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        for (int c = 0; c < 3; ++c)
          if (std::abs(ref.at(x, row)[c] - ref.at(nx, ny)[c]) >= threshold) m[static_cast<size_t>(row) * w + x] = true;
      }
  return m;
}

Mask awayFrom(const Mask& mask, Extent e, int radius) {
  const int w = static_cast<int>(e.width), h = static_cast<int>(e.height);
  Mask out(mask.size(), true);
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) {
      if (!mask[static_cast<size_t>(row) * w + x]) continue;
      for (int j = std::max(0, row - radius); j <= std::min(h - 1, row + radius); ++j)
        for (int i = std::max(0, x - radius); i <= std::min(w - 1, x + radius); ++i)
          out[static_cast<size_t>(j) * w + i] = false;
    }
  return out;
}

size_t count(const Mask& m) { return static_cast<size_t>(std::count(m.begin(), m.end(), true)); }

std::string Error::describe() const {
  char b[160];
  std::snprintf(b, sizeof b, "PSNR %.2f dB, MSE %.3f, max %d/255 over %zu pixels", psnr, mse, maxAbs, pixels);
  return b;
}

Error measure(const Image& a, const Image& b, const Mask* mask) {
  Error e;
  double sum = 0.0;
  const size_t n = static_cast<size_t>(a.extent.width) * a.extent.height;
  if (a.extent != b.extent) throw std::runtime_error("measure: images of different sizes");
  for (size_t i = 0; i < n; ++i) {
    if (mask && !(*mask)[i]) continue;
    ++e.pixels;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(a.rgba[i * 4 + c] - b.rgba[i * 4 + c]);
      e.maxAbs = std::max(e.maxAbs, d);
      sum += static_cast<double>(d) * d;
    }
  }
  e.mse = e.pixels ? sum / (3.0 * static_cast<double>(e.pixels)) : 0.0;
  e.psnr = e.mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / e.mse) : std::numeric_limits<double>::infinity();
  return e;
}

Mask differsFrom(const Image& img, const Image& background, int tolerance) {
  Mask m(static_cast<size_t>(img.extent.width) * img.extent.height, false);
  for (size_t i = 0; i < m.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (std::abs(img.rgba[i * 4 + c] - background.rgba[i * 4 + c]) > tolerance) m[i] = true;
  return m;
}

std::string checkErrors(const std::string& json, const std::string& name, Extent output) {
  Diagnostics diags;
  std::optional<PipelineConfig> cfg = loadPipelineText(json, name, "", {}, diags);
  EXPECT_TRUE(cfg.has_value()) << name << " does not load";
  if (!cfg) return {};
  CompileOptions compile;
  compile.output = output;
  PipelineCheckOptions check;
  check.shaders = ShaderCheckMode::skip;
  Diagnostics found;
  checkPipeline(*cfg, compile, check, found);
  std::string errors;
  for (const auto& d : found)
    if (d.severity == Severity::error) errors += formatDiagnostic(d) + "\n";
  std::printf("[ message  ] %s", errors.c_str());
  return errors;
}

Scene makeStage() {
  Scene s;
  const int grey = rtest::addMaterial(s, {0.5f, 0.5f, 0.5f, 1.0f}, 0.0f, 1.0f, 0.0f);
  const int red = rtest::addMaterial(s, {0.9f, 0.1f, 0.05f, 1.0f}, 0.0f, 1.0f, 0.0f);
  const int plane = rtest::addMesh(s, makePlane(20.0f, 20.0f));
  const int cube = rtest::addMesh(s, makeCube(0.35f));
  const glm::mat4 wall = glm::rotate(rtest::translate({0.0f, 0.0f, -2.0f}), glm::radians(90.0f), {1.0f, 0.0f, 0.0f});
  rtest::addDraw(s, plane, grey, wall, "wall");
  rtest::addDraw(s, cube, red, glm::mat4(1.0f), "cube");
  DirectionalLight sun;
  sun.direction = {0.0f, 0.0f, -1.0f};
  sun.intensity = 0.8f;
  s.directionalLights.push_back(sun);
  s.ambient = glm::vec3(0.2f);
  s.camera.position = {0.0f, 0.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.hasCamera = true;
  return s;
}

}  // namespace rgraph::aatest
