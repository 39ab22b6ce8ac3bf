// ResourceInspector: copies the selected resource right after its last write
// in the frame (Renderer::setAfterPass), so that even a transient whose
// memory is aliased and overwritten later shows what it held then, and
// draws that copy through a value mapping (view_panels_map.h) into an RGBA8
// texture shown with ImGui::Image. One layer (a cube's face) and one mip
// level of an array, cube or mip-mapped resource is copied: a 2D texture the
// display shader reads as any other.
#include <GL/glcorearb.h>
#include <imgui.h>

#include <algorithm>
#include <cstring>

#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gl_state.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/passes/shadow_budget.h"
#include "view_panels.h"
#include "view_panels_map.h"

namespace rgraph::view {

namespace {

constexpr const char* kDisplayVert = R"(#version 450 core
out vec2 v_uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Mirrors mapValue() in view_panels_map.cpp (the CPU reference the tests check).
constexpr const char* kDisplayFrag = R"(#version 450 core
in vec2 v_uv;
out vec4 o_color;
layout(binding = 0) uniform sampler2D u_src;
uniform int u_mode;      // 0 raw, 1 depth, 2 normal, 3 position
uniform int u_channel;   // 0 rgba, 1 r, 2 g, 3 b, 4 a
uniform vec2 u_range;    // min, max
uniform int u_log;
uniform vec2 u_planes;   // near, far
uniform vec3 u_boundsMin, u_boundsMax;
float safeLog(float v) { return log2(max(v, 1e-6)); }
void main() {
  vec4 v = texelFetch(u_src, ivec2(v_uv * vec2(textureSize(u_src, 0))), 0);
  if (u_mode == 1) {
    float n = u_planes.x, f = u_planes.y, ndc = v.r * 2.0 - 1.0;
    float lin = (2.0 * n * f / (f + n - ndc * (f - n)) - n) / (f - n);
    v = vec4(lin, lin, lin, 1.0);
  } else if (u_mode == 2) {
    v = vec4(v.rgb * 0.5 + 0.5, v.a);
  } else if (u_mode == 3) {
    v = vec4((v.rgb - u_boundsMin) / max(u_boundsMax - u_boundsMin, vec3(1e-6)), v.a);
  }
  float lo = u_range.x, hi = u_range.y;
  if (u_log != 0) {
    v = vec4(safeLog(v.r), safeLog(v.g), safeLog(v.b), safeLog(v.a));
    lo = safeLog(lo);
    hi = safeLog(hi);
  }
  float span = abs(hi - lo) < 1e-12 ? 1e-12 : hi - lo;
  v = clamp((v - lo) / span, 0.0, 1.0);
  if (u_channel == 1) v = vec4(v.rrr, 1.0);
  else if (u_channel == 2) v = vec4(v.ggg, 1.0);
  else if (u_channel == 3) v = vec4(v.bbb, 1.0);
  else if (u_channel == 4) v = vec4(v.aaa, 1.0);
  o_color = v;
}
)";

// The shader is a literal of this file, so a failure is rgraph's bug or a
// driver's refusal: the message carries the driver's log.
void throwUnless(GLint ok, uint32_t object, void (*infoLog)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  if (ok) return;
  char log[2048] = {};
  infoLog(object, sizeof(log), nullptr, log);
  throw RuntimeError(std::string("resource inspector display shader: ") + log);
}

gl::Shader compileStage(unsigned stage, const char* source) {
  gl::Shader shader = gl::createShader(stage);
  glShaderSource(shader.id(), 1, &source, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  throwUnless(ok, shader.id(), glGetShaderInfoLog);
  return shader;
}

gl::Program buildDisplayProgram() {
  gl::Shader vs = compileStage(GL_VERTEX_SHADER, kDisplayVert), fs = compileStage(GL_FRAGMENT_SHADER, kDisplayFrag);
  gl::Program program = gl::createProgram();
  glAttachShader(program.id(), vs.id());
  glAttachShader(program.id(), fs.id());
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  throwUnless(ok, program.id(), glGetProgramInfoLog);
  glDetachShader(program.id(), vs.id());
  glDetachShader(program.id(), fs.id());
  return program;
}

// The resource a resource or version name belongs to (invalid: none).
ResourceIndex findResource(const Plan& plan, const std::string& name) {
  for (size_t r = 0; r < plan.resources.size(); ++r) {
    const PlannedResource& res = plan.resources[r];
    if (res.name == name || std::find(res.versions.begin(), res.versions.end(), name) != res.versions.end())
      return ResourceIndex(uint32_t(r));
  }
  return {};
}

}  // namespace

struct ResourceInspector::Impl {
  Renderer* renderer = nullptr;
  std::string selected;
  uint32_t layer = 0, mip = 0;  // of the selection
  StepIndex target;             // this frame's capture step
  // The copy: single-sample, one level and layer of the resource, its format and that level's size.
  gl::Texture copy;
  Format copyFormat = Format::rgba8;
  Extent copyExtent;
  bool hasCopy = false;
  uint64_t captures = 0, creations = 0;
  bool fitPending = false;             // draw(): fit the range to the next copy (a shadow map was picked)
  gl::Framebuffer blitRead, blitDraw;  // multisampled resources are resolved by a blit
  std::string problem;                 // why nothing was copied (shown by draw())
  // Display.
  gl::Program program;
  std::unique_ptr<gl::FullscreenTriangle> triangle;
  gl::Texture display;
  gl::Framebuffer displayFbo;
  Extent displayExtent;
  ValueMapping mapping;

  void afterPass(size_t step);
  // `source` is a texture of GL target `sourceTarget`; its level `level` is `extent`.
  void copyOut(uint32_t source, unsigned sourceTarget, Format format, Extent extent, uint32_t samples, uint32_t level);
  void render();
};

void ResourceInspector::Impl::afterPass(size_t step) {
  if (selected.empty()) return;
  const Plan& plan = renderer->plan();
  if (step == 0) {
    target = captureStep(plan, selected);
    hasCopy = false;
    problem = target.valid() ? "" : "no pass that runs this frame writes '" + selected + "'";
  }
  if (!target.valid() || step != target.value()) return;
  const ResourceIndex r = findResource(plan, selected);
  const ResourceDecl& decl = renderer->pipeline().graph.resources[r.value()];
  if (decl.kind != ResourceKind::texture) {
    problem = "'" + selected + "' is a buffer";
    return;
  }
  const TextureDesc& t = decl.texture;
  if (formatInfo(t.format).isInteger) {  // sampled as floats they would be undefined
    problem = "'" + selected + "' holds integer ids (" + std::string(formatName(t.format)) +
              "): the inspector shows colour and depth only (Renderer::requestPick reads ids)";
    return;
  }
  const Extent base = plan.resource(r).extent;
  const uint32_t layers = arrayLayers(t), levels = mipLevels(t, base);
  if (layer >= layers || mip >= levels) {
    problem = "'" + selected + "' has " + std::to_string(layers) + " layer(s) and " + std::to_string(levels) +
              " mip level(s): no layer " + std::to_string(layer) + " at level " + std::to_string(mip);
    return;
  }
  const Extent extent{std::max(base.width >> mip, 1u), std::max(base.height >> mip, 1u)};
  copyOut(renderer->executor()->textureOf(selected), gl::textureTarget(t.samples, t.layers, t.cube), t.format, extent,
          t.samples, mip);
}

void ResourceInspector::Impl::copyOut(uint32_t source, unsigned sourceTarget, Format format, Extent extent,
                                      uint32_t samples, uint32_t level) {
  if (!copy || copyFormat != format || copyExtent != extent) {
    copy = gl::createTexture2D(format, extent);
    copyFormat = format;
    copyExtent = extent;
    ++creations;
  }
  const GLsizei w = GLsizei(extent.width), h = GLsizei(extent.height);
  if (samples <= 1) {
    // The z of an array, cube or cube array source is its layer (a cube's: its face).
    const GLint z = sourceTarget == GL_TEXTURE_2D ? 0 : GLint(layer);
    glCopyImageSubData(source, sourceTarget, GLint(level), 0, 0, z, copy.id(), GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
  } else {
    // A resolve: only a blit reads a multisampled texture into a single-sampled one.
    if (!blitRead) blitRead = gl::createFramebuffer(), blitDraw = gl::createFramebuffer();
    const GLenum attachment = gl::attachmentPoint(format);
    if (sourceTarget == GL_TEXTURE_2D_MULTISAMPLE_ARRAY)
      glNamedFramebufferTextureLayer(blitRead.id(), attachment, source, 0, GLint(layer));
    else
      glNamedFramebufferTexture(blitRead.id(), attachment, source, 0);
    glNamedFramebufferTexture(blitDraw.id(), attachment, copy.id(), 0);
    const bool depth = gl::isDepth(format);
    const GLbitfield mask =
        depth ? GL_DEPTH_BUFFER_BIT | (gl::hasStencil(format) ? GL_STENCIL_BUFFER_BIT : 0) : GL_COLOR_BUFFER_BIT;
    // Blits obey the scissor test and sRGB conversion: neither belongs in a copy.
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(blitRead.id(), blitDraw.id(), 0, 0, w, h, 0, 0, w, h, mask, GL_NEAREST);
    if (scissor) glEnable(GL_SCISSOR_TEST);
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
  }
  hasCopy = true;
  ++captures;
}

// Draws the copy through the mapping into `display` (RGBA8, the copy's size).
void ResourceInspector::Impl::render() {
  if (!program) program = buildDisplayProgram(), triangle = std::make_unique<gl::FullscreenTriangle>();
  if (!display || displayExtent != copyExtent) {
    display = gl::createTexture2D(Format::rgba8, copyExtent);
    displayFbo = gl::createFramebuffer();
    glNamedFramebufferTexture(displayFbo.id(), GL_COLOR_ATTACHMENT0, display.id(), 0);
    displayExtent = copyExtent;
  }
  gl::GlStateGuard guard;
  gl::applyRendererDefaults();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, displayFbo.id());
  glViewport(0, 0, GLsizei(copyExtent.width), GLsizei(copyExtent.height));
  for (GLenum cap : {GL_BLEND, GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE, GL_SCISSOR_TEST, GL_FRAMEBUFFER_SRGB})
    glDisable(cap);
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glUseProgram(program.id());
  const ValueMapping& m = mapping;
  gl::Uniform(program.id(), "u_mode").set(int(m.mode));
  gl::Uniform(program.id(), "u_channel").set(int(m.channel));
  gl::Uniform(program.id(), "u_range").set(m.min, m.max);
  gl::Uniform(program.id(), "u_log").set(m.log);
  gl::Uniform(program.id(), "u_planes").set(m.near, m.far);
  gl::Uniform(program.id(), "u_boundsMin").setVec3Array(&m.boundsMin.x, 1);
  gl::Uniform(program.id(), "u_boundsMax").setVec3Array(&m.boundsMax.x, 1);
  glBindTextureUnit(0, copy.id());
  triangle->draw();
}

ResourceInspector::ResourceInspector() : impl_(std::make_unique<Impl>()) {}
ResourceInspector::~ResourceInspector() { detach(); }

void ResourceInspector::attach(Renderer& renderer) {
  impl_->renderer = &renderer;
  impl_->hasCopy = false;
  // A renderer attached before (and perhaps gone now) is not touched: its
  // hook, if it still runs, sees it is no longer the inspector's and returns.
  renderer.setAfterPass([impl = impl_.get(), r = &renderer](size_t step) {
    if (impl->renderer == r) impl->afterPass(step);
  });
}

void ResourceInspector::detach() {
  if (impl_->renderer) impl_->renderer->setAfterPass({});
  impl_->renderer = nullptr;
}

void ResourceInspector::select(const std::string& name) {
  Impl& im = *impl_;
  if (name == im.selected) return;
  im.selected = name;
  im.layer = im.mip = 0;
  im.hasCopy = false;
  im.problem.clear();
  if (!im.renderer) return;
  const ResourceIndex r = findResource(im.renderer->plan(), name);
  if (!r.valid()) return;
  const ResourceDecl& decl = im.renderer->pipeline().graph.resources[r.value()];
  // The camera's depth linearised with its planes; the layers of a depth array or cube (shadow maps, drawn
  // from other views with other planes) fitted to their own values instead, once copied.
  const bool depth = decl.kind == ResourceKind::texture && isDepthFormat(decl.texture.format);
  im.mapping.mode = depth ? ValueMapping::Mode::depth : ValueMapping::Mode::raw;
  im.mapping.channel = ValueMapping::Channel::rgba;
  im.mapping.min = 0.0f, im.mapping.max = 1.0f;
  im.mapping.log = false;
  im.fitPending = depth && arrayLayers(decl.texture) > 1;
}

void ResourceInspector::setLayer(uint32_t layer) {
  if (layer == impl_->layer) return;
  // A depth layer shown raw (fitted) is fitted again: another map, another range.
  const bool copied = impl_->hasCopy || impl_->fitPending;
  if (copied && gl::isDepth(impl_->copyFormat) && impl_->mapping.mode == ValueMapping::Mode::raw)
    impl_->fitPending = true;
  impl_->layer = layer;
  impl_->hasCopy = false;
}

void ResourceInspector::setMip(uint32_t mip) {
  if (mip == impl_->mip) return;
  impl_->mip = mip;
  impl_->hasCopy = false;
}

uint32_t ResourceInspector::layer() const { return impl_->layer; }
uint32_t ResourceInspector::mip() const { return impl_->mip; }
const std::string& ResourceInspector::problem() const { return impl_->problem; }

std::vector<std::string> ResourceInspector::layerLabels(const Renderer& renderer, const std::string& name) {
  const Plan& plan = renderer.plan();
  const PipelineConfig& pipeline = renderer.pipeline();
  const ResourceIndex r = findResource(plan, name);
  if (!r.valid() || pipeline.graph.resources[r.value()].kind != ResourceKind::texture) return {};
  const TextureDesc& t = pipeline.graph.resources[r.value()].texture;
  std::vector<std::string> labels(arrayLayers(t));
  if (t.cube) {
    static const char* const kFaces[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (size_t i = 0; i < labels.size(); ++i)
      labels[i] = (t.layers > 1 ? "cube " + std::to_string(i / 6) + " " : std::string()) + "face " + kFaces[i % 6];
    return labels;
  }
  // A shadow atlas: the expansion's map passes carry which light owns which layers.
  for (size_t p = 0; p < pipeline.graph.passes.size(); ++p) {
    const PassDecl& pass = pipeline.graph.passes[p];
    if (pass.type != "shadow_map" || p >= pipeline.params.size()) continue;
    const ParamSet& params = pipeline.params[p];
    if (params.getString("role") != "map") continue;
    const bool writesIt = std::any_of(pass.uses.begin(), pass.uses.end(), [&](const ResourceUse& u) {
      return u.slot == "atlas" && findResource(plan, u.output) == r;
    });
    if (!writesIt) continue;
    try {
      const std::vector<shadows::ShadowedLight> lights = shadows::decode(params.getString("lights"));
      for (size_t i = 0; i < labels.size(); ++i) labels[i] = shadows::layerLabel(lights, uint32_t(i));
    } catch (const RuntimeError&) {
      // Not an assignment the expansion wrote (a hand-written instance): no labels, the layers still show.
    }
    break;
  }
  return labels;
}

const std::string& ResourceInspector::selected() const { return impl_->selected; }
uint32_t ResourceInspector::capturedTexture() const { return impl_->hasCopy ? impl_->copy.id() : 0; }
Extent ResourceInspector::capturedExtent() const { return impl_->hasCopy ? impl_->copyExtent : Extent{}; }
uint64_t ResourceInspector::captureCount() const { return impl_->captures; }
uint64_t ResourceInspector::textureCreations() const { return impl_->creations; }

std::vector<std::string> ResourceInspector::selectableNames(const Plan& plan) {
  std::vector<std::string> names;
  for (const PlannedResource& r : plan.resources) {
    names.push_back(r.name);
    for (size_t v = 1; v < r.versions.size(); ++v) names.push_back(r.versions[v]);
  }
  return names;
}

StepIndex ResourceInspector::captureStep(const Plan& plan, const std::string& name) {
  const ResourceIndex r = findResource(plan, name);
  if (!r.valid()) return {};
  // A later version is captured after the pass that writes it; the resource's
  // own name (its first version too) after the last write of the frame.
  const bool resourceName = plan.resource(r).name == name;
  StepIndex found;
  for (size_t s = 0; s < plan.order.size(); ++s) {
    for (const BoundUse& use : plan.uses(plan.order[s])) {
      if (use.resource != r || !isWriteAccess(use.access)) continue;
      if (resourceName || use.writeVersion == name) found = StepIndex(uint32_t(s));
    }
  }
  return found;
}

std::vector<float> ResourceInspector::readCaptured() const {
  const uint32_t texture = capturedTexture();
  if (!texture) return {};
  const size_t w = impl_->copyExtent.width, h = impl_->copyExtent.height;
  std::vector<float> data(w * h * 4);
  gl::GlStateGuard guard;
  gl::applyRendererDefaults();
  if (gl::isDepth(impl_->copyFormat)) {
    std::vector<float> depth(w * h);
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth.size() * sizeof(float)), depth.data());
    for (size_t i = 0; i < w * h; ++i) {
      data[i * 4] = depth[i];
      data[i * 4 + 3] = 1.0f;
    }
  } else {
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(data.size() * sizeof(float)), data.data());
  }
  // GL rows run bottom-up; the renderer's read-backs give them top-down.
  for (size_t y = 0; y < h / 2; ++y)
    std::swap_ranges(data.begin() + y * w * 4, data.begin() + (y + 1) * w * 4, data.begin() + (h - 1 - y) * w * 4);
  return data;
}

glm::vec4 ResourceInspector::readCapturedTexel(uint32_t x, uint32_t yTop) const {
  const uint32_t texture = capturedTexture();
  if (!texture || x >= impl_->copyExtent.width || yTop >= impl_->copyExtent.height) return glm::vec4(0.0f);
  gl::GlStateGuard guard;
  gl::applyRendererDefaults();
  const GLint row = GLint(impl_->copyExtent.height - 1 - yTop);
  glm::vec4 v(0.0f, 0.0f, 0.0f, 1.0f);
  if (gl::isDepth(impl_->copyFormat))
    glGetTextureSubImage(texture, 0, GLint(x), row, 0, 1, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, sizeof(float), &v.x);
  else
    glGetTextureSubImage(texture, 0, GLint(x), row, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof(v), &v.x);
  return v;
}

ValueMapping& ResourceInspector::mapping() { return impl_->mapping; }

bool ResourceInspector::fitRange() {
  if (!capturedTexture()) return false;
  const glm::vec2 range = valueRange(readCaptured(), gl::isDepth(impl_->copyFormat));
  impl_->mapping.mode = ValueMapping::Mode::raw;
  if (gl::isDepth(impl_->copyFormat)) impl_->mapping.channel = ValueMapping::Channel::r;  // grey, not red
  impl_->mapping.min = range.x;
  impl_->mapping.max = range.y;
  return true;
}

uint32_t ResourceInspector::renderDisplay() {
  if (!capturedTexture()) return 0;
  impl_->render();
  return impl_->display.id();
}

namespace {
const char* const kModeNames[] = {"raw", "depth (linear)", "normal", "position"};
const char* const kChannelNames[] = {"RGBA", "R", "G", "B", "A"};
}  // namespace

// The layer and mip pickers of an array, cube or mip-mapped selection.
void ResourceInspector::drawSubresourcePickers(const Renderer& renderer) {
  Impl& im = *impl_;
  const Plan& plan = renderer.plan();
  const ResourceIndex r = findResource(plan, im.selected);
  if (!r.valid() || renderer.pipeline().graph.resources[r.value()].kind != ResourceKind::texture) return;
  const TextureDesc& t = renderer.pipeline().graph.resources[r.value()].texture;
  const std::vector<std::string> labels = layerLabels(renderer, im.selected);
  auto layerName = [&](uint32_t i) {
    return "layer " + std::to_string(i) + (i < labels.size() && !labels[i].empty() ? ": " + labels[i] : "");
  };
  if (labels.size() > 1 && ImGui::BeginCombo("layer", layerName(im.layer).c_str())) {
    for (uint32_t i = 0; i < labels.size(); ++i)
      if (ImGui::Selectable(layerName(i).c_str(), i == im.layer)) setLayer(i);
    ImGui::EndCombo();
  }
  const uint32_t levels = mipLevels(t, plan.resource(r).extent);
  int mip = int(im.mip);
  if (levels > 1 && ImGui::SliderInt("mip", &mip, 0, int(levels) - 1)) setMip(uint32_t(mip));
}

void ResourceInspector::draw(Renderer& renderer) {
  Impl& im = *impl_;
  const Plan& plan = renderer.plan();
  if (ImGui::BeginCombo("resource", im.selected.empty() ? "(none)" : im.selected.c_str())) {
    for (const std::string& name : selectableNames(plan)) {
      const ResourceIndex r = findResource(plan, name);
      const bool version = plan.resource(r).name != name;
      const std::string label = (version ? "    " : "") + name;
      if (ImGui::Selectable(label.c_str(), name == im.selected)) select(name);
    }
    ImGui::EndCombo();
  }
  if (im.selected.empty()) return ImGui::TextDisabled("pick a resource to see it after its last write");
  drawSubresourcePickers(renderer);
  const StepIndex step = captureStep(plan, im.selected);
  if (step.valid()) ImGui::Text("copied after step %u (%s)", step.value(), plan.pass(plan.step(step)).name.c_str());
  if (!im.problem.empty()) return ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "%s", im.problem.c_str());
  if (!capturedTexture()) return ImGui::TextDisabled("not copied yet (next frame)");
  if (im.fitPending) im.fitPending = !fitRange();

  ValueMapping& m = im.mapping;
  int mode = int(m.mode), channel = int(m.channel);
  if (ImGui::Combo("mode", &mode, kModeNames, IM_ARRAYSIZE(kModeNames))) m.mode = ValueMapping::Mode(mode);
  if (ImGui::Combo("channel", &channel, kChannelNames, IM_ARRAYSIZE(kChannelNames)))
    m.channel = ValueMapping::Channel(channel);
  ImGui::DragFloatRange2("range", &m.min, &m.max, 0.01f);
  ImGui::SameLine();
  ImGui::Checkbox("log", &m.log);
  ImGui::SameLine();
  if (ImGui::Button("fit")) fitRange();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("range from this copy's values (depth: without the cleared 1s)");
  m.near = renderer.camera().near;
  m.far = renderer.camera().far;
  if (renderer.scene()) {
    const Bounds b = renderer.scene()->scene().bounds();
    if (!b.empty()) m.boundsMin = b.min, m.boundsMax = b.max;
  }

  const uint32_t display = renderDisplay();
  const Extent e = im.copyExtent;
  // The whole image within the window: as wide as it is, as high as the lines below leave.
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float aspect = float(e.height) / float(std::max(e.width, 1u));
  const float width =
      std::max(std::min(avail.x, (avail.y - 2.5f * ImGui::GetTextLineHeightWithSpacing()) / aspect), 16.0f);
  const ImVec2 size(width, width * aspect);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  // GL's first row is the bottom one: flip v.
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(display)), size, ImVec2(0, 1), ImVec2(1, 0));
  ImGui::Text("%s  %ux%u", std::string(formatName(im.copyFormat)).c_str(), e.width, e.height);
  if (ImGui::IsItemHovered() || ImGui::IsMouseHoveringRect(origin, ImVec2(origin.x + size.x, origin.y + size.y))) {
    const ImVec2 mouse = ImGui::GetMousePos();
    const uint32_t x = uint32_t(std::clamp((mouse.x - origin.x) / size.x, 0.0f, 0.9999f) * float(e.width));
    const uint32_t y = uint32_t(std::clamp((mouse.y - origin.y) / size.y, 0.0f, 0.9999f) * float(e.height));
    const glm::vec4 v = readCapturedTexel(x, y);
    ImGui::Text("(%u, %u): %.5g %.5g %.5g %.5g", x, y, v.r, v.g, v.b, v.a);
  }
}

}  // namespace rgraph::view
