// Executor: what callers give it (imported textures) and read from it
// (outputs, any resource's pixels, GL names). See rgraph/gl/executor.h.
#include <GL/glcorearb.h>

#include <algorithm>

#include "executor_internal.h"
#include "rgraph/error.h"
#include "rgraph/gl/format.h"

namespace rgraph {

using exec_detail::ResourceObject;

void Executor::importTexture(const std::string& resource, uint32_t texture) {
  Impl& im = *impl_;
  if (std::string refusal = gl::checkImportName(im.pipeline.graph, resource); !refusal.empty())
    throw RuntimeError(refusal);
  auto it = im.imports.find(resource);
  if (it != im.imports.end() && it->second == texture) return;
  if (im.built) {
    const ResourceIndex r = im.resourceIndex(resource);
    const std::string mismatch = gl::checkImportedTexture(resource, im.declaredShape(r), texture);
    if (!mismatch.empty()) throw RuntimeError(mismatch);
    ResourceObject& obj = im.resources[r.value()];
    obj.ownTexture = {};
    obj.texture = texture;
    im.imports[resource] = texture;
    im.rebuildRuns();
    return;
  }
  im.imports[resource] = texture;
}

void Executor::Impl::checkImports() const {
  for (const auto& [resource, texture] : imports) {
    const ResourceIndex r = resourceIndex(resource);
    if (!r.valid()) continue;  // (importTexture and build refuse unknown names)
    const std::string mismatch = gl::checkImportedTexture(resource, declaredShape(r), texture);
    if (!mismatch.empty())
      throw RuntimeError("Executor::renderFrame: " + mismatch + " (deleted or redefined since importTexture?)");
  }
}

void Executor::Impl::requireContext(const char* who) const {
  if (!built || gl::currentContext() == context) return;
  throw RuntimeError(std::string(who) +
                     ": the current GL context is not the one this pipeline's GL objects were made in (its framebuffers "
                     "and vertex arrays exist only there): make that context current, or make a renderer for this one");
}

void Executor::releaseTexture(const std::string& resource) {
  Impl& im = *impl_;
  if (im.imports.erase(resource) == 0 || !im.built) return;
  const ResourceIndex r = im.resourceIndex(resource);
  if (!r.valid()) return;
  ResourceObject& obj = im.resources[r.value()];
  obj.ownTexture = im.takeTexture(obj.format, obj.extent, obj.mips, obj.samples, obj.layers, obj.cube);
  obj.texture = obj.ownTexture.id();
  im.rebuildRuns();
}

uint32_t Executor::outputTexture() const {
  if (!impl_->built) return 0;
  return impl_->resources[impl_->plan.outputResource.value()].texture;
}

Extent Executor::outputExtent() const {
  if (!impl_->built) return {};
  return impl_->resources[impl_->plan.outputResource.value()].extent;
}

Format Executor::outputFormat() const {
  if (!impl_->built) return Format::rgba8;
  return impl_->resources[impl_->plan.outputResource.value()].format;
}

namespace {
template <typename T>
void flipRows(std::vector<T>& data, size_t rowElems, size_t rows) {
  for (size_t y = 0; y < rows / 2; ++y)
    std::swap_ranges(data.begin() + static_cast<std::ptrdiff_t>(y * rowElems),
                     data.begin() + static_cast<std::ptrdiff_t>((y + 1) * rowElems),
                     data.begin() + static_cast<std::ptrdiff_t>((rows - 1 - y) * rowElems));
}
}  // namespace

std::vector<uint8_t> Executor::readOutputRGBA8() const {
  if (!impl_->built) throw RuntimeError("Executor::readOutputRGBA8: nothing rendered (call resize() first)");
  const ResourceObject& obj = impl_->resources[impl_->plan.outputResource.value()];
  if (obj.samples > 1) throw RuntimeError("the output image is multisampled and cannot be read back directly");
  if (gl::isDepth(obj.format)) throw RuntimeError("the output image has a depth format");
  size_t w = obj.extent.width, h = obj.extent.height;
  std::vector<uint8_t> data(w * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(obj.texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(data.size()), data.data());
  flipRows(data, w * 4, h);
  // GL reads a one-channel image as (r, 0, 0, 1): a mask, occlusion or depth
  // view would show as red. Its one value is grey.
  if (formatInfo(obj.format).components == 1)
    for (size_t i = 0; i < data.size(); i += 4) data[i + 1] = data[i + 2] = data[i];
  return data;
}

std::vector<float> Executor::readTextureRGBA32F(const std::string& name) const {
  const ResourceIndex r = impl_->resourceIndex(name);
  if (!impl_->built || !r.valid())
    throw RuntimeError("readTextureRGBA32F: no live resource or version named '" + name + "'");
  const ResourceObject& obj = impl_->resources[r.value()];
  if (!obj.texture) throw RuntimeError("readTextureRGBA32F: resource '" + name + "' has no texture");
  if (obj.samples > 1) throw RuntimeError("readTextureRGBA32F: resource '" + name + "' is multisampled");
  size_t w = obj.extent.width, h = obj.extent.height;
  std::vector<float> data(w * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  if (gl::isDepth(obj.format)) {
    std::vector<float> depth(w * h);
    glGetTextureSubImage(obj.texture, 0, 0, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), 1,
                         GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
    for (size_t i = 0; i < w * h; ++i) {
      data[i * 4 + 0] = depth[i];
      data[i * 4 + 1] = 0.0f;
      data[i * 4 + 2] = 0.0f;
      data[i * 4 + 3] = 1.0f;
    }
  } else if (formatInfo(obj.format).isInteger) {
    // Ids (rg32ui): read as integers (a float read of an integer texture is
    // a GL error), each converted to float, blue 0 and alpha 1.
    std::vector<uint32_t> ids(w * h * 2);
    glGetTextureSubImage(obj.texture, 0, 0, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), 1,
                         GL_RG_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(ids.size() * sizeof(uint32_t)),
                         ids.data());
    for (size_t i = 0; i < w * h; ++i) {
      data[i * 4 + 0] = static_cast<float>(ids[i * 2]);
      data[i * 4 + 1] = static_cast<float>(ids[i * 2 + 1]);
      data[i * 4 + 2] = 0.0f;
      data[i * 4 + 3] = 1.0f;
    }
  } else {
    // Level 0 of layer 0 (a cube's +x face) of any shape.
    glGetTextureSubImage(obj.texture, 0, 0, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), 1, GL_RGBA,
                         GL_FLOAT, static_cast<GLsizei>(data.size() * sizeof(float)), data.data());
  }
  flipRows(data, w * 4, h);
  return data;
}

uint32_t Executor::textureOf(const std::string& name) const {
  const ResourceIndex r = impl_->resourceIndex(name);
  return impl_->built && r.valid() ? impl_->resources[r.value()].texture : 0;
}

uint32_t Executor::bufferOf(const std::string& name) const {
  const ResourceIndex r = impl_->resourceIndex(name);
  return impl_->built && r.valid() ? impl_->resources[r.value()].buffer : 0;
}

void Executor::reuseTextures(const Executor& previous) {
  const Impl& from = *previous.impl_;
  const std::vector<bool> kept = Impl::keptPhysicals(from.plan);  // history pairs stay the previous one's
  impl_->reusable.clear();
  for (size_t i = 0; i < from.physicalTextures.size(); ++i)
    if (i >= kept.size() || !kept[i]) impl_->reusable.push_back(from.physicalTextures[i]);
  for (size_t r = 0; r < from.resources.size(); ++r) {
    const PlannedResource& pr = from.plan.resources[r];
    if (from.resources[r].ownTexture && !pr.historyOf.valid() && !pr.history.valid())
      impl_->reusable.push_back(from.resources[r].ownTexture);
  }
}

size_t Executor::ownedObjects() const {
  size_t n = 0;
  auto own = [](const exec_detail::SharedTexture& t) { return t.texture && t.texture.use_count() == 1 ? 1 : 0; };
  for (const auto& t : impl_->physicalTextures) n += own(t);
  for (const auto& b : impl_->physicalBuffers) n += b ? 1 : 0;
  for (const auto& r : impl_->resources) n += own(r.ownTexture) + (r.ownBuffer ? 1 : 0);
  n += impl_->cache.framebuffers() + impl_->cache.views() + (impl_->emptyVao ? 1 : 0);
  if (impl_->queryRing) n += impl_->queryRing->queryCount();
  return n;
}

}  // namespace rgraph
