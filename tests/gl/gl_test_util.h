// Shared helpers of the headless GL tests: one GlContext per test program,
// and a small builder for hand-written graphs (no config loader).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/graph.h"
#include "rgraph/registry.h"

namespace rgraph::test {

// The process-wide context (created on first use, ~70 ms).
GlContext& glContext();

// Fixture: a fresh ShaderLibrary that also searches tests/gl/shaders; checks
// that the test caused no GL debug errors.
class GlTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  GlContext& ctx() { return glContext(); }

  std::unique_ptr<ShaderLibrary> shaders;
  uint64_t errorsAtStart = 0;
};

inline ResourceUse writeUse(std::string slot, Access access, std::string output, std::string input = {}) {
  ResourceUse u;
  u.slot = std::move(slot);
  u.access = access;
  u.output = std::move(output);
  u.input = std::move(input);
  return u;
}

inline ResourceUse readUse(std::string slot, Access access, std::string input, bool acceptsMultisample = false) {
  ResourceUse u;
  u.slot = std::move(slot);
  u.access = access;
  u.input = std::move(input);
  u.acceptsMultisample = acceptsMultisample;
  return u;
}

class GraphBuilder {
 public:
  GraphBuilder& texture(const std::string& name, Format f, SizeSpec size = SizeSpec::output(),
                        std::optional<std::vector<float>> clear = std::nullopt, uint32_t samples = 1) {
    ResourceDecl r;
    r.name = name;
    r.texture.format = f;
    r.texture.size = size;
    r.texture.clear = std::move(clear);
    r.texture.samples = samples;
    cfg_.graph.resources.push_back(std::move(r));
    return *this;
  }
  // The imported output image (arrives without content) and graph.output.
  GraphBuilder& output(const std::string& name, Format f = Format::rgba8, const std::string& finalVersion = {}) {
    ResourceDecl r;
    r.name = name;
    r.texture.format = f;
    r.imported = true;
    r.importedHasContent = false;
    cfg_.graph.resources.push_back(std::move(r));
    cfg_.graph.output = finalVersion.empty() ? name : finalVersion;
    return *this;
  }
  GraphBuilder& outputVersion(const std::string& v) {
    cfg_.graph.output = v;
    return *this;
  }
  GraphBuilder& pass(const std::string& name, const std::string& type, std::vector<ResourceUse> uses,
                     ParamSet params = {}, bool sideEffect = false) {
    PassDecl p;
    p.name = name;
    p.type = type;
    p.uses = std::move(uses);
    p.sideEffect = sideEffect;
    cfg_.graph.passes.push_back(std::move(p));
    cfg_.params.push_back(std::move(params));
    return *this;
  }
  // A "fullscreen" pass drawing gradient.frag (gradientPixel's colours) into `target`.
  GraphBuilder& gradient(const std::string& target, const std::string& name = "gradient") {
    ParamSet p;
    p.set("shader", std::string("gradient.frag"));
    return pass(name, "fullscreen", {writeUse("color", Access::color_attachment, target)}, std::move(p));
  }
  // A "present" pass copying `src` into the output image "out".
  GraphBuilder& present(const std::string& src, const std::string& name = "present") {
    return pass(name, "present",
                {readUse("src", Access::sampled, src), writeUse("dst", Access::color_attachment, "out")});
  }
  const PipelineConfig& config() const { return cfg_; }
  PipelineConfig& config() { return cfg_; }

 private:
  PipelineConfig cfg_;
};

inline ParamSet params(std::initializer_list<std::pair<const std::string, ParamValue>> kv) {
  ParamSet p;
  for (const auto& [k, v] : kv) p.set(k, v);
  return p;
}

// The expected gradient.frag colour at (x, yGl) (yGl = 0 at the bottom row).
inline std::array<uint8_t, 4> gradientPixel(uint32_t x, uint32_t yGl) {
  return {static_cast<uint8_t>((x * 4) & 255), static_cast<uint8_t>((yGl * 4) & 255),
          static_cast<uint8_t>((x ^ yGl) & 255), 255};
}

// Compares a top-down RGBA8 readback with gradientPixel; returns the number of mismatches.
size_t gradientMismatches(const std::vector<uint8_t>& rgba, Extent e, std::string* first = nullptr);
// Whether the output image of `exec`'s last frame (`e`) is gradient.frag's,
// every pixel exactly; the mismatches and the first of them when not.
::testing::AssertionResult outputIsGradient(const Executor& exec, Extent e);

}  // namespace rgraph::test
