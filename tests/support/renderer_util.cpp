#include "renderer_util.h"

#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "rgraph/diagnostics.h"

namespace rgraph::testsupport {

std::string gbufferPipeline(const GBufferExtra& extra) {
  using nlohmann::ordered_json;
  ordered_json resources = ordered_json::object();
  auto resource = [&](const std::string& name, const std::string& format) {
    resources[name] = {{"format", format}, {"size", "output"}};
  };
  resource("gPosition", extra.positionFormat);
  resource("gNormal", "rgba16f");
  resource("gAlbedoSpec", "rgba8");
  resource(extra.resource, extra.format);
  resource("gDepth", "depth24_stencil8");
  ordered_json gbuffer = {
      {"name", "gbuffer"},
      {"type", "geometry"},
      {"params", {{"layout", "learnopengl"}, {extra.output, true}}},
      {"outputs",
       {{"position", "gPosition"}, {"normal", "gNormal"}, {"albedo", "gAlbedoSpec"}, {"depth", "gDepth"},
        {extra.output, extra.resource}}}};
  ordered_json pipeline = {{"version", 1}};
  if (extra.jitter > 0) pipeline["jitter"] = extra.jitter;
  pipeline["resources"] = resources;
  pipeline["passes"] = ordered_json::array({gbuffer});
  pipeline["output"] = "gAlbedoSpec";
  return pipeline.dump(2);
}

std::unique_ptr<Renderer> makeRenderer(const std::string& pipeline, const RendererOptions& options,
                                       std::shared_ptr<RenderScene> scene, const std::string& name) {
  Diagnostics diags;
  const size_t first = pipeline.find_first_not_of(" \t\r\n");
  auto r = first != std::string::npos && pipeline[first] == '{' ? Renderer::fromJson(pipeline, name, options, diags)
                                                                : Renderer::fromFile(pipeline, options, diags);
  // Thrown, not returned null: callers use the renderer at once, and gtest
  // turns an exception into a failure of this test instead of a crash of all.
  if (!r)
    throw std::runtime_error("makeRenderer: " +
                             (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front())));
  r->setScene(std::move(scene));
  return r;
}

}  // namespace rgraph::testsupport
