#include "render_context.h"

#include <memory>
#include <vector>

#include "rgraph/gl/context.h"

namespace rgraph::bench {
namespace {
std::unique_ptr<GlContext>& context() {
  static std::unique_ptr<GlContext> c;
  return c;
}
std::vector<std::function<void()>>& releases() {
  static std::vector<std::function<void()>> r;
  return r;
}
}  // namespace

GlContext& renderContext() {
  if (!context()) context() = GlContext::create(ContextOptions{.debug = false});
  return *context();
}

void atContextRelease(std::function<void()> release) { releases().push_back(std::move(release)); }

void releaseRenderContext() {
  for (auto& r : releases()) r();
  releases().clear();
  context().reset();
}

}  // namespace rgraph::bench
