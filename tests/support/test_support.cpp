#include "test_support.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "rgraph/error.h"
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

PipelineConfig buildOrThrow(ConfigDocument doc, Diagnostics diags, const std::string& name, const std::string& context) {
  PipelineConfig cfg;
  if (doc.ok()) cfg = doc.build(PassRegistry::builtins(), diags);
  if (!doc.ok() || hasErrors(diags)) {
    std::string msg = "pipeline " + name + " has errors:";
    for (const auto& d : diags) msg += "\n  " + formatDiagnostic(d);
    if (!context.empty()) msg += "\n" + context;
    throw RuntimeError(msg);
  }
  return cfg;
}

}  // namespace

GlContext& sharedGlContext() {
  auto& ctx = contextSlot();
  if (!ctx) ctx = GlContext::create(ContextOptions{});
  return *ctx;
}

bool hasSharedGlContext() { return contextSlot() != nullptr; }

void destroyBeforeContext(std::function<void()> fn) { teardowns().push_back(std::move(fn)); }

PipelineConfig loadPipelineOrThrow(const std::string& path) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  return buildOrThrow(std::move(doc), std::move(diags), path, {});
}

PipelineConfig buildPipelineOrThrow(const std::string& text, const std::string& name, const std::string& context) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(text, name, diags);
  return buildOrThrow(std::move(doc), std::move(diags), name, context);
}

}  // namespace rgraph::testsupport
