// Scheduling independence of the compute passes: GL 4.5 promises no
// subgroup size, no lockstep and no order among a work group's invocations
// or its atomics (shaders/include/invocation.glsl). Each compute shader reads
// its IDs through a permutation the hidden `permute_invocations` parameter
// picks (rgraph/passes/invocation_order.h): reversed, rotated, transposed,
// work groups reversed. Every pass's output, the final image, the HDR target
// and the buffers the pass builds (light bins, cluster lists, cluster far
// fields), must be byte-identical to the identity's under each. Mode
// kOrderDependent appends its lists in atomic order, the way the shaders did
// before they were made order-independent: it must change the bytes, so that
// the comparison is seen to fail when order leaks into the output.
// Sizes are not multiples of the tiles (partial tiles at the right and top),
// with many lights straddling tiles.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rgraph/adapt.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/passes/invocation_order.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"
#include "support/test_support.h"

namespace {
using namespace rgraph;
using nlohmann::json;

constexpr Extent kSize{100, 70};  // 16-pixel tiles: 7 x 5, 32-pixel: 4 x 3, the last column and row partial

// geometry -> `type` (the pass under test, named "lighting", with `params`)
// into an rgba32f target -> tonemap.
PipelineConfig lightingPipeline(const std::string& type, const json& params) {
  const json res = {{"g_position", {{"format", "rgba32f"}, {"size", "output"}}},
                    {"g_normal", {{"format", "rgba16f"}, {"size", "output"}}},
                    {"g_albedo", {{"format", "rgba8"}, {"size", "output"}}},
                    {"g_material", {{"format", "rgba16f"}, {"size", "output"}}},
                    {"g_depth", {{"format", "depth32f"}, {"size", "output"}}},
                    {"hdr", {{"format", "rgba32f"}, {"size", "output"}, {"clear", {0.1, 0.2, 0.3, 1.0}}}},
                    {"output", {{"format", "rgba8"}, {"size", "output"}}}};
  const json g = {{"position", "g_position"}, {"normal", "g_normal"}, {"albedo", "g_albedo"}, {"material", "g_material"}};
  json gOut = g;
  gOut["depth"] = "g_depth";
  json lit = {{"layout", "pbr"}, {"model", "blinn_phong"}, {"attenuation", "classic"}};
  lit.update(params);
  const json passes = json::array(
      {{{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", "pbr"}}}, {"outputs", gOut}},
       {{"name", "lighting"}, {"type", type}, {"params", lit}, {"inputs", g}, {"outputs", {{"color", "hdr"}}}},
       {{"name", "tonemap"}, {"type", "tonemap"}, {"params", {{"operator", "none"}, {"gamma", 1.0}}},
        {"inputs", {{"hdr", "hdr"}}}, {"outputs", {{"output", "output"}}}}});
  const json doc = {{"version", 1}, {"resources", res}, {"passes", passes}, {"output", "output"}};
  return testsupport::buildPipelineOrThrow(doc.dump(), "<invocation order test>");
}

std::vector<uint32_t> readBuffer(GLuint buffer) {
  GLint bytes = 0;
  glGetNamedBufferParameteriv(buffer, GL_BUFFER_SIZE, &bytes);
  std::vector<uint32_t> data(static_cast<size_t>(bytes) / 4);
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(data.size() * 4), data.data());
  return data;
}

std::vector<uint32_t> readBinding(GLuint binding) {
  GLint buffer = 0;
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, binding, &buffer);
  return buffer ? readBuffer(static_cast<GLuint>(buffer)) : std::vector<uint32_t>{};
}

// What the shaders write of each buffer (the rest is never written, so its
// bytes are whatever the buffer held).
// Light bins (include/tile_bins.glsl): records of 200 + 512 uints: the count,
// the far field's point and sums (with far_field), the listed lights.
std::vector<uint32_t> binsWritten(const std::vector<uint32_t>& b, bool farField) {
  constexpr size_t kHeader = 200, kMax = 512;
  std::vector<uint32_t> out;
  for (size_t r = 0; r + kHeader + kMax <= b.size(); r += kHeader + kMax) {
    out.insert(out.end(), b.begin() + r, b.begin() + r + (farField ? kHeader : 8));
    out.insert(out.end(), b.begin() + r + kHeader, b.begin() + r + kHeader + std::min<size_t>(b[r], kMax));
  }
  return out;
}

// Cluster lists (include/clusters.glsl): the header, the counts, each list's entries.
std::vector<uint32_t> clustersWritten(const std::vector<uint32_t>& b, Extent size, size_t* listed = nullptr) {
  if (b.size() < 4 || b[1] == 0) return b;
  const size_t tile = b[1], slices = b[2], max = b[3];
  const size_t clusters = ((size.width + tile - 1) / tile) * ((size.height + tile - 1) / tile) * slices;
  std::vector<uint32_t> out(b.begin(), b.begin() + 4 + clusters);
  for (size_t c = 0; c < clusters; ++c) {
    const size_t base = 4 + clusters + c * max, n = std::min<size_t>(b[4 + c], max);
    out.insert(out.end(), b.begin() + base, b.begin() + base + n);
    if (listed) *listed += n;
  }
  return out;
}

// Cluster far fields (include/cluster_far_field.glsl): per cluster its bin
// bits, and its whole record of 196 uints when it has any.
std::vector<uint32_t> farFieldsWritten(const std::vector<uint32_t>& b) {
  constexpr size_t kRecord = 4 + 16 * 12;
  std::vector<uint32_t> out;
  for (size_t r = 0; r + kRecord <= b.size(); r += kRecord)
    out.insert(out.end(), b.begin() + r, b.begin() + r + (b[r] != 0 ? kRecord : 1));
  return out;
}

// One frame's bytes: the named outputs, each a byte string.
struct Frame {
  std::vector<std::string> names;
  std::vector<std::vector<uint8_t>> bytes;
  template <class T>
  void add(std::string name, const std::vector<T>& v) {
    names.push_back(std::move(name));
    bytes.emplace_back(reinterpret_cast<const uint8_t*>(v.data()),
                       reinterpret_cast<const uint8_t*>(v.data()) + v.size() * sizeof(T));
  }
};

using Reader = std::function<void(Executor&, Frame&)>;

class InvocationOrder : public rtest::RenderTest {
 protected:
  // Renders `cfg` once with the pass "lighting" (and every other pass that
  // is named in `passes`) under permutation `mode`.
  Frame render(PipelineConfig cfg, const std::vector<std::string>& passes, int mode, const Scene& scene,
               const Reader& read) {
    for (const auto& p : passes) rtest::setParam(cfg, p, invocations::kPermuteParam, int64_t{mode});
    adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
    Executor exec(cfg, processRegistry(), *shaders, &scene);
    exec.resize(kSize);
    exec.renderFrame();
    Frame f;
    if (read) read(exec, f);  // first: the passes' buffers are still bound
    f.add("output image", exec.readOutputRGBA8());
    return f;
  }

  // Bytes that differ between two frames, per output ("" when none).
  static std::string differences(const Frame& a, const Frame& b) {
    std::string out;
    for (size_t i = 0; i < a.bytes.size() && i < b.bytes.size(); ++i) {
      const auto &x = a.bytes[i], &y = b.bytes[i];
      if (x.size() != y.size()) {
        out += (out.empty() ? "" : ", ") + a.names[i] + ": " + std::to_string(x.size()) + " against " +
               std::to_string(y.size()) + " bytes";
        continue;
      }
      size_t n = 0;
      for (size_t k = 0; k < x.size(); ++k) n += x[k] != y[k];
      if (n) out += (out.empty() ? "" : ", ") + a.names[i] + ": " + std::to_string(n) + " of " + std::to_string(x.size()) + " bytes";
    }
    return out;
  }

  // Every permutation gives the identity's bytes; the order-dependent mode does not.
  void expectIndependent(const PipelineConfig& cfg, const std::vector<std::string>& passes, const Scene& scene,
                         const Reader& read) {
    const Frame identity = render(cfg, passes, 0, scene, read);
    for (const auto& bytes : identity.bytes) ASSERT_FALSE(bytes.empty());
    for (int mode = 1; mode <= invocations::kPermutations; ++mode)
      EXPECT_EQ(differences(identity, render(cfg, passes, mode, scene, read)), "") << "permutation " << mode;
  }

  // Mode kOrderDependent changes some of the bytes (prints which).
  void expectOrderDependentDiffers(const PipelineConfig& cfg, const std::vector<std::string>& passes,
                                   const Scene& scene, const Reader& read) {
    const std::string d = differences(render(cfg, passes, 0, scene, read),
                                      render(cfg, passes, invocations::kOrderDependent, scene, read));
    std::printf("[ measure  ] appended in atomic order: %s\n", d.empty() ? "no difference" : d.c_str());
    EXPECT_NE(d, "") << "lists appended in atomic order under reversed invocations gave the same bytes: the "
                        "permutation tests could not see an order dependence";
  }
};

Reader hdrAndBins(bool farField) {
  return [farField](Executor& exec, Frame& f) {
    f.add("light bins", binsWritten(readBinding(1), farField));
    f.add("hdr", exec.readTextureRGBA32F("hdr"));
  };
}

Reader clusteredBuffers(bool farField) {
  return [farField](Executor& exec, Frame& f) {
    size_t listed = 0;
    f.add("cluster lists", clustersWritten(readBinding(1), kSize, &listed));
    EXPECT_GT(listed, 100u) << "the clusters list few lights: the test would not see their order";
    f.add("light bins", binsWritten(readBinding(2), farField));
    if (farField) f.add("cluster far fields", farFieldsWritten(readBinding(3)));
    f.add("hdr", exec.readTextureRGBA32F("hdr"));
  };
}

TEST_F(InvocationOrder, TiledDeferred) {
  expectIndependent(lightingPipeline("tiled_deferred", json::object()), {"lighting"}, makeManyLightsScene(256),
                    hdrAndBins(false));
}

// Half rows and quarters of 6 and 7 pixels, groups of 169 invocations.
TEST_F(InvocationOrder, TiledDeferredOddTileSize) {
  expectIndependent(lightingPipeline("tiled_deferred", {{"tile_size", 13}}), {"lighting"}, makeManyLightsScene(256),
                    hdrAndBins(false));
}

TEST_F(InvocationOrder, TiledDeferredFarField) {
  expectIndependent(lightingPipeline("tiled_deferred", {{"far_field", true}}), {"lighting"},
                    makeManyLightsScene(256), hdrAndBins(true));
}

TEST_F(InvocationOrder, ClusteredDeferred) {
  expectIndependent(lightingPipeline("clustered_deferred", json::object()), {"lighting"}, makeManyLightsScene(256),
                    clusteredBuffers(false));
}

// Lists of 4 cut short, and shaded as they are (truncate): which lights a
// list keeps is then its order's.
TEST_F(InvocationOrder, ClusteredDeferredTruncatedLists) {
  expectIndependent(lightingPipeline("clustered_deferred", {{"max_cluster_lights", 4}, {"overflow", "truncate"}}),
                    {"lighting"}, makeManyLightsScene(256), clusteredBuffers(false));
}

TEST_F(InvocationOrder, ClusteredDeferredFarField) {
  expectIndependent(lightingPipeline("clustered_deferred", {{"far_field", true}}), {"lighting"},
                    makeManyLightsScene(256), clusteredBuffers(true));
}

// cluster_lights (the lists without depth bounds, every light culled) read
// by forward_lit.
TEST_F(InvocationOrder, ClusterLights) {
  PipelineConfig cfg = rtest::loadPipeline(rtest::repoPath("pipelines/forward-plus.json"));
  expectIndependent(cfg, {"cluster_lights"}, makeManyLightsScene(256), [](Executor& exec, Frame& f) {
    f.add("cluster lists", clustersWritten(readBuffer(exec.bufferOf("clusters")), kSize));
  });
}

TEST_F(InvocationOrder, AtomicOrderChangesTiledOutput) {
  expectOrderDependentDiffers(lightingPipeline("tiled_deferred", json::object()), {"lighting"},
                              makeManyLightsScene(256), hdrAndBins(false));
}

TEST_F(InvocationOrder, AtomicOrderChangesClusteredOutput) {
  expectOrderDependentDiffers(lightingPipeline("clustered_deferred", json::object()), {"lighting"},
                              makeManyLightsScene(256), clusteredBuffers(false));
}

}  // namespace
