// glTF 2.0 loading with tinygltf (parsing only). Every accessor, buffer view,
// index and texture reference is validated here before it is read: tinygltf
// does not check all of them.
#include <tiny_gltf.h>

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <spdlog/spdlog.h>

#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

constexpr size_t kMaxElements = size_t(1) << 26;           // per accessor
constexpr size_t kMaxUnbackedElements = size_t(1) << 24;   // accessors without a buffer view (zeros)
constexpr int kMaxImageSide = 16384;

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// Decodes any stb_image format to RGBA8 into `image`.
bool decodeImage(tinygltf::Image* image, const unsigned char* bytes, size_t size, std::string* err) {
  if (size == 0 || size > size_t(INT_MAX)) {
    if (err) *err += "image '" + image->name + "': " + (size == 0 ? "empty data" : "data too large") + "\n";
    return false;
  }
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp)) {
    if (err) *err += "image '" + image->name + image->uri + "': cannot decode (" + stbi_failure_reason() + ")\n";
    return false;
  }
  if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide) {
    if (err) *err += "image '" + image->name + image->uri + "': unsupported size " + std::to_string(w) + "x" + std::to_string(h) + "\n";
    return false;
  }
  unsigned char* px = stbi_load_from_memory(bytes, int(size), &w, &h, &comp, 4);
  if (!px) {
    if (err) *err += "image '" + image->name + image->uri + "': cannot decode (" + stbi_failure_reason() + ")\n";
    return false;
  }
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(px, px + size_t(w) * size_t(h) * 4);
  stbi_image_free(px);
  return true;
}

// tinygltf's image callback. Images stored in buffer views are decoded later,
// after their buffer view has been checked (tinygltf passes them unchecked).
bool imageCallback(tinygltf::Image* image, const int /*index*/, std::string* err, std::string* /*warn*/, int, int,
                   const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  if (size < 0) return false;
  return decodeImage(image, bytes, size_t(size), err);
}

struct AccessorInfo {
  const unsigned char* data = nullptr;  // first element; nullptr: zeros (no buffer view)
  size_t stride = 0;
  size_t count = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

float readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return std::isfinite(f) ? f : 0.0f;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v = *p;
      return normalized ? float(v) / 255.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? float(double(v) / 4294967295.0) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default: return 0.0f;
  }
}

uint32_t readIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0;
  }
}

const char* componentTypeName(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return "unknown";
  }
}

class GltfLoader {
 public:
  explicit GltfLoader(std::string path) : path_(std::move(path)) {}

  Scene load() {
    parse();
    scene_.source = path_;
    try {
      convert();
    } catch (const RuntimeError&) {
      throw;
    } catch (const std::exception& e) {
      fail(std::string("unexpected failure: ") + e.what());
    }
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const std::string& msg) const { throw RuntimeError(path_ + ": " + msg); }
  void warn(const std::string& msg) const { spdlog::warn("{}: {}", path_, msg); }

  // ------------------------------------------------------------ parsing

  void parse() {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) fail("file not found");
    if (!std::filesystem::is_regular_file(path_, ec)) fail("not a regular file");
    char magic[4] = {0, 0, 0, 0};
    {
      std::ifstream f(path_, std::ios::binary);
      if (!f) fail("cannot open the file");
      f.read(magic, 4);
    }
    const bool binary = std::memcmp(magic, "glTF", 4) == 0;

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&imageCallback, nullptr);
    std::string err, warnText;
    bool ok = false;
    try {
      ok = binary ? loader.LoadBinaryFromFile(&model_, &err, &warnText, path_)
                  : loader.LoadASCIIFromFile(&model_, &err, &warnText, path_);
    } catch (const std::exception& e) {
      fail(std::string("glTF parser failed: ") + e.what());
    }
    tinyWarn_ = trimmed(warnText);
    if (!ok) {
      std::string msg = std::string("cannot load ") + (binary ? "binary glTF" : "glTF") + ": " + trimmed(err);
      if (!tinyWarn_.empty()) msg += " (warnings: " + tinyWarn_ + ")";
      fail(msg);
    }
    if (!tinyWarn_.empty()) {
      std::istringstream lines(tinyWarn_);
      for (std::string line; std::getline(lines, line);)
        if (!line.empty()) warn(line);
    }
    for (const std::string& ext : model_.extensionsRequired)
      if (ext != "KHR_lights_punctual" && ext != "KHR_materials_emissive_strength")
        fail("requires the unsupported extension " + ext);
  }

  // ------------------------------------------------------------ accessors

  // Checks accessor `index` against its buffer view and buffer; `what` names it in errors.
  AccessorInfo checkAccessor(int index, const std::string& what, std::initializer_list<int> types,
                             std::initializer_list<int> componentTypes) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(what + ": accessor " + std::to_string(index) + " does not exist (" + std::to_string(model_.accessors.size()) +
           " accessors)");
    const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (std::find(types.begin(), types.end(), acc.type) == types.end())
      fail(name + ": unexpected type " + std::to_string(acc.type));
    if (std::find(componentTypes.begin(), componentTypes.end(), acc.componentType) == componentTypes.end())
      fail(name + ": unexpected component type " + componentTypeName(acc.componentType));
    AccessorInfo info;
    info.componentType = acc.componentType;
    info.components = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
    info.normalized = acc.normalized;
    info.count = acc.count;
    const int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    if (info.components <= 0 || compSize <= 0) fail(name + ": invalid type");
    const size_t elemSize = size_t(info.components) * size_t(compSize);
    if (acc.count > kMaxElements) fail(name + ": count " + std::to_string(acc.count) + " is too large");

    if (acc.bufferView < 0) {
      if (acc.count > kMaxUnbackedElements) fail(name + ": count " + std::to_string(acc.count) + " is too large");
      info.stride = elemSize;
      return info;
    }
    const std::string bvDesc = checkBufferView(acc.bufferView, name);
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(acc.bufferView)];
    info.stride = bv.byteStride ? bv.byteStride : elemSize;
    if (bv.byteStride != 0 && bv.byteStride < elemSize)
      fail(name + ": byteStride " + std::to_string(bv.byteStride) + " is smaller than the element size " + std::to_string(elemSize));
    if (bv.byteStride > 252) fail(name + ": byteStride " + std::to_string(bv.byteStride) + " exceeds 252");
    if (acc.byteOffset > bv.byteLength)
      fail(name + ": byteOffset " + std::to_string(acc.byteOffset) + " lies beyond " + bvDesc + " (" + std::to_string(bv.byteLength) +
           " bytes)");
    if (acc.count > 0) {
      // No overflow: byteOffset <= byteLength <= buffer size, count <= 2^26, stride <= 252.
      const uint64_t need = uint64_t(acc.byteOffset) + uint64_t(info.stride) * uint64_t(acc.count - 1) + uint64_t(elemSize);
      if (need > bv.byteLength)
        fail(name + ": " + std::to_string(acc.count) + " elements at byteOffset " + std::to_string(acc.byteOffset) +
             " with stride " + std::to_string(info.stride) + " need " + std::to_string(need) + " bytes but " + bvDesc + " has " +
             std::to_string(bv.byteLength));
    }
    const tinygltf::Buffer& buf = model_.buffers[size_t(bv.buffer)];
    info.data = buf.data.data() + bv.byteOffset + acc.byteOffset;
    return info;
  }

  // Checks buffer view `index` lies inside its buffer; returns a description for messages.
  std::string checkBufferView(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.bufferViews.size())
      fail(what + ": buffer view " + std::to_string(index) + " does not exist (" + std::to_string(model_.bufferViews.size()) +
           " buffer views)");
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(index)];
    const std::string desc = "buffer view " + std::to_string(index);
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
      fail(what + ": " + desc + " refers to buffer " + std::to_string(bv.buffer) + ", which does not exist");
    const size_t size = model_.buffers[size_t(bv.buffer)].data.size();
    if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
      fail(what + ": " + desc + " (byteOffset " + std::to_string(bv.byteOffset) + ", byteLength " + std::to_string(bv.byteLength) +
           ") exceeds buffer " + std::to_string(bv.buffer) + " of " + std::to_string(size) + " bytes");
    return desc;
  }

  // Reads a numeric accessor as floats (count * components), applying sparse substitution.
  std::vector<float> readFloats(int index, const std::string& what, std::initializer_list<int> types,
                                std::initializer_list<int> componentTypes) const {
    const AccessorInfo info = checkAccessor(index, what, types, componentTypes);
    const size_t nc = size_t(info.components);
    const int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(info.componentType));
    std::vector<float> out(info.count * nc, 0.0f);
    if (info.data) {
      for (size_t i = 0; i < info.count; ++i) {
        const unsigned char* e = info.data + i * info.stride;
        for (size_t c = 0; c < nc; ++c) out[i * nc + c] = readComponent(e + c * size_t(compSize), info.componentType, info.normalized);
      }
    }
    const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
    if (acc.sparse.isSparse) applySparse(acc, what + " (accessor " + std::to_string(index) + ")", info, out);
    return out;
  }

  void applySparse(const tinygltf::Accessor& acc, const std::string& name, const AccessorInfo& info, std::vector<float>& out) const {
    const int n = acc.sparse.count;
    if (n <= 0 || size_t(n) > info.count) fail(name + ": sparse count " + std::to_string(n) + " out of range");
    const int it = acc.sparse.indices.componentType;
    if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(name + ": sparse indices have component type " + componentTypeName(it));
    const size_t is = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(it)));
    const size_t cs = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(info.componentType)));
    const size_t es = cs * size_t(info.components);
    auto region = [&](int bvIndex, int offset, size_t bytes, const char* what) -> const unsigned char* {
      const std::string desc = checkBufferView(bvIndex, name + " sparse " + what);
      const tinygltf::BufferView& bv = model_.bufferViews[size_t(bvIndex)];
      if (offset < 0 || size_t(offset) > bv.byteLength || bytes > bv.byteLength - size_t(offset))
        fail(name + ": sparse " + what + " exceed " + desc);
      return model_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + size_t(offset);
    };
    const unsigned char* idx = region(acc.sparse.indices.bufferView, acc.sparse.indices.byteOffset, is * size_t(n), "indices");
    const unsigned char* val = region(acc.sparse.values.bufferView, acc.sparse.values.byteOffset, es * size_t(n), "values");
    const size_t nc = size_t(info.components);
    for (int i = 0; i < n; ++i) {
      const uint32_t target = readIndex(idx + size_t(i) * is, it);
      if (target >= info.count)
        fail(name + ": sparse index " + std::to_string(target) + " >= count " + std::to_string(info.count));
      for (size_t c = 0; c < nc; ++c)
        out[size_t(target) * nc + c] = readComponent(val + size_t(i) * es + c * cs, info.componentType, info.normalized);
    }
  }

  std::vector<uint32_t> readIndices(int index, const std::string& what, size_t vertexCount) const {
    const AccessorInfo info = checkAccessor(
        index, what, {TINYGLTF_TYPE_SCALAR},
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    std::vector<uint32_t> out(info.count, 0);
    if (info.data)
      for (size_t i = 0; i < info.count; ++i) out[i] = readIndex(info.data + i * info.stride, info.componentType);
    const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
    if (acc.sparse.isSparse) {
      std::vector<float> tmp(out.begin(), out.end());  // exact for indices < 2^24; sparse indices are rare
      applySparse(acc, what + " (accessor " + std::to_string(index) + ")", info, tmp);
      for (size_t i = 0; i < out.size(); ++i) out[i] = uint32_t(tmp[i]);
    }
    for (size_t i = 0; i < out.size(); ++i)
      if (out[i] >= vertexCount)
        fail(what + " (accessor " + std::to_string(index) + "): index " + std::to_string(out[i]) + " at position " + std::to_string(i) +
             " is out of range (" + std::to_string(vertexCount) + " vertices)");
    return out;
  }

  // ------------------------------------------------------------ images, textures, materials

  const std::vector<uint8_t>& decodedPixels(int gltfImage, const std::string& what) {
    if (gltfImage < 0 || size_t(gltfImage) >= model_.images.size())
      fail(what + ": image " + std::to_string(gltfImage) + " does not exist (" + std::to_string(model_.images.size()) + " images)");
    tinygltf::Image& img = model_.images[size_t(gltfImage)];
    const std::string name = "image " + std::to_string(gltfImage) + (img.uri.empty() || img.uri.rfind("data:", 0) == 0 ? "" : " ('" + img.uri + "')");
    if (img.image.empty()) {
      if (img.bufferView >= 0) {
        const std::string desc = checkBufferView(img.bufferView, name);
        const tinygltf::BufferView& bv = model_.bufferViews[size_t(img.bufferView)];
        std::string err;
        if (!decodeImage(&img, model_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset, bv.byteLength, &err))
          fail(name + " in " + desc + ": " + trimmed(err));
      } else {
        std::string msg = name + ": could not be loaded";
        if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) {
          const std::filesystem::path p = std::filesystem::path(path_).parent_path() / img.uri;
          msg += " (missing or unreadable file " + p.string() + ")";
        }
        if (!tinyWarn_.empty()) msg += "; " + tinyWarn_;
        fail(msg);
      }
    }
    if (img.width <= 0 || img.height <= 0 || img.component != 4 || img.bits != 8 ||
        img.image.size() != size_t(img.width) * size_t(img.height) * 4)
      fail(name + ": unexpected decoded pixel layout");
    return img.image;
  }

  int sceneImage(int gltfImage, bool srgb, const std::string& what) {
    const auto key = std::make_pair(gltfImage, srgb);
    if (auto it = imageMap_.find(key); it != imageMap_.end()) return it->second;
    const std::vector<uint8_t>& px = decodedPixels(gltfImage, what);
    const tinygltf::Image& img = model_.images[size_t(gltfImage)];
    ImageData out;
    out.name = !img.name.empty() ? img.name : (img.uri.rfind("data:", 0) == 0 ? std::string() : img.uri);
    out.width = img.width;
    out.height = img.height;
    out.rgba = px;
    out.srgb = srgb;
    const int id = int(scene_.images.size());
    scene_.images.push_back(std::move(out));
    imageMap_.emplace(key, id);
    return id;
  }

  static bool validFilter(int f, bool minification) {
    if (f == SamplerDesc::kNearest || f == SamplerDesc::kLinear) return true;
    return minification && (f == SamplerDesc::kNearestMipmapNearest || f == SamplerDesc::kLinearMipmapNearest ||
                            f == SamplerDesc::kNearestMipmapLinear || f == SamplerDesc::kLinearMipmapLinear);
  }
  static bool validWrap(int w) {
    return w == SamplerDesc::kRepeat || w == SamplerDesc::kClampToEdge || w == SamplerDesc::kMirroredRepeat;
  }

  TextureRef textureRef(int gltfTexture, int texCoord, bool srgb, const std::string& what) {
    TextureRef ref;
    if (gltfTexture < 0) return ref;
    if (size_t(gltfTexture) >= model_.textures.size())
      fail(what + ": texture " + std::to_string(gltfTexture) + " does not exist (" + std::to_string(model_.textures.size()) +
           " textures)");
    const tinygltf::Texture& t = model_.textures[size_t(gltfTexture)];
    if (t.source < 0) {
      warn(what + ": texture " + std::to_string(gltfTexture) + " has no supported image source; ignored");
      return ref;
    }
    if (texCoord < 0 || texCoord > 1) {
      warn(what + ": texCoord " + std::to_string(texCoord) + " is not supported; using 0");
      texCoord = 0;
    }
    ref.texCoord = texCoord;
    const auto key = std::make_pair(gltfTexture, srgb);
    if (auto it = textureMap_.find(key); it != textureMap_.end()) {
      ref.texture = it->second;
      return ref;
    }
    SceneTexture st;
    st.image = sceneImage(t.source, srgb, what + " (texture " + std::to_string(gltfTexture) + ")");
    if (t.sampler >= 0) {
      if (size_t(t.sampler) >= model_.samplers.size())
        fail(what + ": texture " + std::to_string(gltfTexture) + " refers to sampler " + std::to_string(t.sampler) +
             ", which does not exist");
      const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
      const std::string sn = "sampler " + std::to_string(t.sampler);
      if (s.minFilter != -1) {
        if (validFilter(s.minFilter, true)) st.sampler.minFilter = s.minFilter;
        else warn(sn + ": invalid minFilter " + std::to_string(s.minFilter) + "; using the default");
      }
      if (s.magFilter != -1) {
        if (validFilter(s.magFilter, false)) st.sampler.magFilter = s.magFilter;
        else warn(sn + ": invalid magFilter " + std::to_string(s.magFilter) + "; using the default");
      }
      if (validWrap(s.wrapS)) st.sampler.wrapS = s.wrapS;
      else warn(sn + ": invalid wrapS " + std::to_string(s.wrapS) + "; using REPEAT");
      if (validWrap(s.wrapT)) st.sampler.wrapT = s.wrapT;
      else warn(sn + ": invalid wrapT " + std::to_string(s.wrapT) + "; using REPEAT");
    }
    ref.texture = int(scene_.textures.size());
    scene_.textures.push_back(st);
    textureMap_.emplace(key, ref.texture);
    return ref;
  }

  template <size_t N>
  bool factor(const std::vector<double>& v, float (&out)[N], const std::string& what) const {
    if (v.size() != N) {
      warn(what + " must have " + std::to_string(N) + " numbers; using the default");
      return false;
    }
    for (size_t i = 0; i < N; ++i) out[i] = std::isfinite(v[i]) ? float(v[i]) : 0.0f;
    return true;
  }

  static float finiteOr(double v, float fallback) { return std::isfinite(v) ? float(v) : fallback; }

  Material convertMaterial(size_t index) {
    const tinygltf::Material& m = model_.materials[index];
    const std::string what = "material " + std::to_string(index) + (m.name.empty() ? "" : " ('" + m.name + "')");
    Material out;
    out.name = m.name;
    const auto& pbr = m.pbrMetallicRoughness;
    float bc[4];
    if (factor(pbr.baseColorFactor, bc, what + " baseColorFactor")) out.baseColorFactor = glm::make_vec4(bc);
    out.metallicFactor = std::clamp(finiteOr(pbr.metallicFactor, 1.0f), 0.0f, 1.0f);
    out.roughnessFactor = std::clamp(finiteOr(pbr.roughnessFactor, 1.0f), 0.0f, 1.0f);
    float em[3];
    if (!m.emissiveFactor.empty() && factor(m.emissiveFactor, em, what + " emissiveFactor")) out.emissiveFactor = glm::make_vec3(em);
    if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
      const tinygltf::Value& v = it->second.Get("emissiveStrength");
      if (v.IsNumber()) out.emissiveFactor *= float(v.GetNumberAsDouble());
    }
    out.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true, what + " baseColorTexture");
    out.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                                              what + " metallicRoughnessTexture");
    out.normalTexture = textureRef(m.normalTexture.index, m.normalTexture.texCoord, false, what + " normalTexture");
    out.normalScale = finiteOr(m.normalTexture.scale, 1.0f);
    out.occlusionTexture = textureRef(m.occlusionTexture.index, m.occlusionTexture.texCoord, false, what + " occlusionTexture");
    out.occlusionStrength = std::clamp(finiteOr(m.occlusionTexture.strength, 1.0f), 0.0f, 1.0f);
    out.emissiveTexture = textureRef(m.emissiveTexture.index, m.emissiveTexture.texCoord, true, what + " emissiveTexture");
    if (m.alphaMode == "OPAQUE" || m.alphaMode.empty()) {
      out.alphaMode = AlphaMode::opaque;
    } else if (m.alphaMode == "MASK") {
      out.alphaMode = AlphaMode::mask;
    } else if (m.alphaMode == "BLEND") {
      out.alphaMode = AlphaMode::blend;
    } else {
      warn(what + ": unknown alphaMode '" + m.alphaMode + "'; using OPAQUE");
    }
    out.alphaCutoff = std::max(finiteOr(m.alphaCutoff, 0.5f), 0.0f);
    out.doubleSided = m.doubleSided;
    return out;
  }

  int defaultMaterial() {
    if (defaultMaterial_ < 0) {
      Material d;
      d.name = "default";
      defaultMaterial_ = int(scene_.materials.size());
      scene_.materials.push_back(d);
    }
    return defaultMaterial_;
  }

  // ------------------------------------------------------------ meshes

  // The scene mesh for glTF mesh `mi` primitive `pi`; -1 when skipped.
  int sceneMesh(int mi, size_t pi) {
    const auto key = std::make_pair(mi, pi);
    if (auto it = meshMap_.find(key); it != meshMap_.end()) return it->second;
    int id = -1;
    const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
    const tinygltf::Primitive& prim = gm.primitives[pi];
    const std::string what = "mesh " + std::to_string(mi) + (gm.name.empty() ? "" : " ('" + gm.name + "')") + " primitive " +
                             std::to_string(pi);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES) {
      warn(what + ": mode " + std::to_string(mode) + " is not TRIANGLES; skipped");
    } else if (prim.attributes.find("POSITION") == prim.attributes.end()) {
      warn(what + ": no POSITION attribute; skipped");
    } else {
      MeshData mesh = buildMesh(prim, what);
      if (mesh.indices.empty()) {
        warn(what + ": no triangles; skipped");
      } else {
        id = int(scene_.meshes.size());
        scene_.meshes.push_back(std::move(mesh));
        primMaterial_.push_back(resolvedMaterial_);
      }
    }
    meshMap_.emplace(key, id);
    return id;
  }

  MeshData buildMesh(const tinygltf::Primitive& prim, const std::string& what) {
    const std::initializer_list<int> quantized = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    MeshData mesh;
    mesh.name = what;

    // Material first: it decides whether tangents are needed.
    if (prim.material >= 0) {
      if (size_t(prim.material) >= model_.materials.size())
        fail(what + ": material " + std::to_string(prim.material) + " does not exist (" + std::to_string(model_.materials.size()) +
             " materials)");
      resolvedMaterial_ = prim.material;
    } else {
      resolvedMaterial_ = defaultMaterial();
    }
    const Material material = scene_.materials[size_t(resolvedMaterial_)];

    auto attr = [&](const char* name) -> int {
      auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    std::vector<float> pos = readFloats(attr("POSITION"), what + " POSITION", {TINYGLTF_TYPE_VEC3}, quantized);
    const size_t n = pos.size() / 3;
    if (n > size_t(UINT32_MAX)) fail(what + ": too many vertices");
    mesh.positions.resize(n);
    for (size_t i = 0; i < n; ++i) mesh.positions[i] = glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);

    auto readSized = [&](const char* name, int type, size_t comps, std::initializer_list<int> cts) -> std::vector<float> {
      const int a = attr(name);
      if (a < 0) return {};
      std::vector<float> v = readFloats(a, what + " " + name, {type}, cts);
      if (v.size() / comps != n)
        fail(what + " " + name + " (accessor " + std::to_string(a) + "): count " + std::to_string(v.size() / comps) +
             " differs from the POSITION count " + std::to_string(n));
      return v;
    };
    std::vector<float> nrm = readSized("NORMAL", TINYGLTF_TYPE_VEC3, 3,
                                       {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});
    const std::initializer_list<int> uvTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_SHORT};
    std::vector<float> uv0 = readSized("TEXCOORD_0", TINYGLTF_TYPE_VEC2, 2, uvTypes);
    std::vector<float> uv1 = readSized("TEXCOORD_1", TINYGLTF_TYPE_VEC2, 2, uvTypes);
    std::vector<float> tan = readSized("TANGENT", TINYGLTF_TYPE_VEC4, 4,
                                       {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT});

    mesh.hasUv0 = !uv0.empty();
    mesh.uv0.assign(n, glm::vec2(0.0f));
    if (!uv0.empty())
      for (size_t i = 0; i < n; ++i) mesh.uv0[i] = glm::vec2(uv0[2 * i], uv0[2 * i + 1]);
    if (!uv1.empty()) {
      mesh.uv1.resize(n);
      for (size_t i = 0; i < n; ++i) mesh.uv1[i] = glm::vec2(uv1[2 * i], uv1[2 * i + 1]);
    }

    if (prim.indices >= 0) {
      mesh.indices = readIndices(prim.indices, what + " indices", n);
    } else {
      mesh.indices.resize(n);
      for (size_t i = 0; i < n; ++i) mesh.indices[i] = uint32_t(i);
    }
    if (mesh.indices.size() % 3 != 0) {
      warn(what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3; extra indices dropped");
      mesh.indices.resize(mesh.indices.size() - mesh.indices.size() % 3);
    }

    const bool wantTangents = material.hasNormalMap();
    if (!nrm.empty()) {
      mesh.normals.resize(n);
      bool fixed = false;
      for (size_t i = 0; i < n; ++i) {
        glm::vec3 v(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
        const float len = glm::length(v);
        if (len > 1e-12f) {
          mesh.normals[i] = v / len;
        } else {
          mesh.normals[i] = glm::vec3(0.0f, 0.0f, 1.0f);
          fixed = true;
        }
      }
      if (fixed) warn(what + ": zero-length normals replaced");
      if (wantTangents && !tan.empty()) {
        mesh.tangents.resize(n);
        for (size_t i = 0; i < n; ++i) {
          glm::vec3 t(tan[4 * i], tan[4 * i + 1], tan[4 * i + 2]);
          const float len = glm::length(t);
          t = len > 1e-12f ? t / len : glm::vec3(1.0f, 0.0f, 0.0f);
          mesh.tangents[i] = glm::vec4(t, tan[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
        }
      }
    } else {
      // glTF: "When normals are not specified, client implementations MUST calculate flat normals."
      computeFlatNormals(mesh);  // unwelds; file tangents (if any) would no longer line up
    }
    if (wantTangents && mesh.tangents.empty()) {
      const bool useUv1 = material.normalTexture.texCoord == 1 && !mesh.uv1.empty();
      if (useUv1) std::swap(mesh.uv0, mesh.uv1);
      generateTangents(mesh);
      if (useUv1) std::swap(mesh.uv0, mesh.uv1);
    }
    mesh.updateBounds();
    return mesh;
  }

  // ------------------------------------------------------------ nodes

  glm::mat4 localMatrix(const tinygltf::Node& node, const std::string& what) const {
    auto finite = [&](const std::vector<double>& v, const char* name) {
      for (double d : v)
        if (!std::isfinite(d)) fail(what + ": '" + name + "' has a non-finite value");
    };
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) fail(what + ": 'matrix' must have 16 numbers");
      finite(node.matrix, "matrix");
      glm::mat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = float(node.matrix[size_t(c * 4 + r)]);  // column-major like glTF
      return m;
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) fail(what + ": 'translation' must have 3 numbers");
      finite(node.translation, "translation");
      m = glm::translate(m, glm::vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2])));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) fail(what + ": 'rotation' must have 4 numbers");
      finite(node.rotation, "rotation");
      glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));  // w, x, y, z
      const float len = glm::length(q);
      if (len > 0.0f) m = m * glm::mat4_cast(q / len);
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) fail(what + ": 'scale' must have 3 numbers");
      finite(node.scale, "scale");
      m = glm::scale(m, glm::vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
    }
    return m;
  }

  void visit(int nodeIndex, const glm::mat4& parent, std::vector<char>& onPath) {
    if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size())
      fail("node " + std::to_string(nodeIndex) + " does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
    if (onPath[size_t(nodeIndex)]) fail("node " + std::to_string(nodeIndex) + " is its own ancestor (cycle in the node hierarchy)");
    if (++visits_ > 4 * model_.nodes.size() + 16) fail("node hierarchy references nodes repeatedly");
    onPath[size_t(nodeIndex)] = 1;
    const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
    const std::string what = "node " + std::to_string(nodeIndex) + (node.name.empty() ? "" : " ('" + node.name + "')");
    const glm::mat4 world = parent * localMatrix(node, what);

    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model_.meshes.size())
        fail(what + ": mesh " + std::to_string(node.mesh) + " does not exist (" + std::to_string(model_.meshes.size()) + " meshes)");
      const tinygltf::Mesh& gm = model_.meshes[size_t(node.mesh)];
      for (size_t pi = 0; pi < gm.primitives.size(); ++pi) {
        const int mesh = sceneMesh(node.mesh, pi);
        if (mesh < 0) continue;
        Primitive p;
        p.mesh = mesh;
        p.material = primMaterial_[size_t(mesh)];
        p.transform = world;
        p.bounds = scene_.meshes[size_t(mesh)].bounds.transformed(world);
        p.name = node.name.empty() ? (gm.name.empty() ? what : gm.name) : node.name;
        scene_.primitives.push_back(std::move(p));
      }
    }
    if (node.camera >= 0) addCamera(node.camera, world, what);
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const tinygltf::Value& v = it->second.Get("light");
      if (!v.IsNumber()) fail(what + ": KHR_lights_punctual without a 'light' index");
      addLight(v.GetNumberAsInt(), world, what);
    }
    for (int child : node.children) visit(child, world, onPath);
    onPath[size_t(nodeIndex)] = 0;
  }

  void addCamera(int index, const glm::mat4& world, const std::string& what) {
    if (size_t(index) >= model_.cameras.size())
      fail(what + ": camera " + std::to_string(index) + " does not exist (" + std::to_string(model_.cameras.size()) + " cameras)");
    if (scene_.hasCamera) return;  // the first camera wins
    const tinygltf::Camera& c = model_.cameras[size_t(index)];
    if (c.type != "perspective") {
      warn(what + ": camera type '" + c.type + "' is not supported; ignored");
      return;
    }
    Camera cam;
    const auto& p = c.perspective;
    if (std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < 3.14) cam.fovY = float(glm::degrees(p.yfov));
    else warn(what + ": invalid yfov; using 45 degrees");
    if (std::isfinite(p.znear) && p.znear > 0.0) cam.near = float(p.znear);
    else warn(what + ": invalid znear; using 0.1");
    cameraHasFar_ = std::isfinite(p.zfar) && p.zfar > cam.near;
    cam.far = cameraHasFar_ ? float(p.zfar) : cam.near * 1000.0f;
    cam.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    glm::vec3 fwd = glm::mat3(world) * glm::vec3(0, 0, -1);
    glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
    fwd = glm::length(fwd) > 0.0f ? glm::normalize(fwd) : glm::vec3(0, 0, -1);
    cam.up = glm::length(up) > 0.0f ? glm::normalize(up) : glm::vec3(0, 1, 0);
    cam.target = cam.position + fwd;
    scene_.camera = cam;
    scene_.hasCamera = true;
  }

  void addLight(int index, const glm::mat4& world, const std::string& what) {
    if (index < 0 || size_t(index) >= model_.lights.size())
      fail(what + ": light " + std::to_string(index) + " does not exist (" + std::to_string(model_.lights.size()) + " lights)");
    const tinygltf::Light& l = model_.lights[size_t(index)];
    glm::vec3 color(1.0f);
    if (!l.color.empty()) {
      float c[3];
      if (factor(l.color, c, what + " light color")) color = glm::max(glm::make_vec3(c), glm::vec3(0.0f));
    }
    const float intensity = std::max(finiteOr(l.intensity, 1.0f), 0.0f);
    if (l.type == "directional") {
      DirectionalLight d;
      glm::vec3 dir = glm::mat3(world) * glm::vec3(0, 0, -1);
      d.direction = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0, 0, -1);
      d.color = color;
      d.intensity = intensity;
      scene_.directionalLights.push_back(d);
      return;
    }
    if (l.type == "spot") warn(what + ": spot light treated as a point light");
    else if (l.type != "point") {
      warn(what + ": unknown light type '" + l.type + "'; ignored");
      return;
    }
    // glTF point lights fall off with the inverse square of the distance; the
    // constant term 1 keeps the attenuation finite at the light.
    PointLight p;
    p.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    p.color = color;
    p.intensity = intensity;
    p.constant = 1.0f;
    p.linear = 0.0f;
    p.quadratic = 1.0f;
    p.radius = (std::isfinite(l.range) && l.range > 0.0) ? float(l.range) : lightRadius(p);
    scene_.pointLights.push_back(p);
  }

  // ------------------------------------------------------------ conversion

  void convert() {
    for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(convertMaterial(i));

    // Every node has at most one parent (glTF requires disjoint trees).
    std::vector<int> parents(model_.nodes.size(), 0);
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
      for (int c : model_.nodes[i].children) {
        if (c < 0 || size_t(c) >= model_.nodes.size())
          fail("node " + std::to_string(i) + ": child " + std::to_string(c) + " does not exist (" + std::to_string(model_.nodes.size()) +
               " nodes)");
        if (++parents[size_t(c)] > 1) fail("node " + std::to_string(c) + " has more than one parent");
      }
    }
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      int si = model_.defaultScene;
      if (si < 0 || size_t(si) >= model_.scenes.size()) {
        if (si >= 0) warn("default scene " + std::to_string(si) + " does not exist; using scene 0");
        si = 0;
      }
      roots = model_.scenes[size_t(si)].nodes;
    } else {
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (parents[i] == 0) roots.push_back(int(i));
    }
    std::vector<char> onPath(model_.nodes.size(), 0);
    for (int r : roots) visit(r, glm::mat4(1.0f), onPath);

    if (scene_.primitives.empty()) warn("no triangle geometry in the default scene");
    if (scene_.hasCamera && !cameraHasFar_) {
      // Infinite far plane in the file: cover the scene instead.
      const Bounds b = scene_.bounds();
      if (!b.empty())
        scene_.camera.far = std::max(glm::length(b.center() - scene_.camera.position) + b.radius() * 2.0f, scene_.camera.near * 100.0f);
    }
    scene_.validate();
  }

  std::string path_;
  tinygltf::Model model_;
  std::string tinyWarn_;
  Scene scene_;
  std::map<std::pair<int, bool>, int> imageMap_;
  std::map<std::pair<int, bool>, int> textureMap_;
  std::map<std::pair<int, size_t>, int> meshMap_;
  std::vector<int> primMaterial_;  // per scene mesh: its material
  int resolvedMaterial_ = -1;
  int defaultMaterial_ = -1;
  bool cameraHasFar_ = false;
  size_t visits_ = 0;
};

}  // namespace

Scene loadGltf(const std::string& path) { return GltfLoader(path).load(); }

}  // namespace rgraph
