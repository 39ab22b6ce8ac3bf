#include "test_support.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/registry.h"

namespace rgraph::testsupport {
namespace {

std::unique_ptr<GlContext>& contextSlot() {
  static std::unique_ptr<GlContext> ctx;
  return ctx;
}

std::vector<std::function<void()>>& teardowns() {
  static std::vector<std::function<void()>> fns;
  return fns;
}

class GlEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    for (auto& fn : teardowns()) fn();
    teardowns().clear();
    contextSlot().reset();
  }
};
[[maybe_unused]] ::testing::Environment* const gEnv = ::testing::AddGlobalTestEnvironment(new GlEnvironment);

// With the caller's context (what the test was doing) after the diagnostics.
PipelineConfig withContext(const std::function<PipelineConfig()>& load, const std::string& context) {
  try {
    return load();
  } catch (const RuntimeError& e) {
    if (context.empty()) throw;
    throw RuntimeError(std::string(e.what()) + "\n" + context);
  }
}

}  // namespace

GlContext& sharedGlContext() {
  auto& ctx = contextSlot();
  if (!ctx) ctx = GlContext::create(ContextOptions{});
  return *ctx;
}

bool hasSharedGlContext() { return contextSlot() != nullptr; }

void destroyBeforeContext(std::function<void()> fn) { teardowns().push_back(std::move(fn)); }

PipelineConfig loadPipelineOrThrow(const std::string& path) { return loadPipelineFileOrThrow(path); }

PipelineConfig buildPipelineOrThrow(const std::string& text, const std::string& name, const std::string& context) {
  return withContext([&] { return loadPipelineTextOrThrow(text, "pipeline " + name); }, context);
}

std::string errorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const RuntimeError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace rgraph::testsupport
