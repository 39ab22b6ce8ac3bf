// glTF images, textures, materials and lights (see gltf_internal.h).
//
// Values are held to the ranges of the glTF schema, the same rule scene files
// follow for the same quantities (scenes/README.md has the table): a value out
// of range is refused with the file, line:column (.gltf) and JSON pointer,
// never clamped silently. Extra to the schema, as in scene files:
// alphaCutoff <= 1 (above 1 every pixel would be cut).
#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include <stb_image.h>

#include <glm/gtc/type_ptr.hpp>

#include "gltf_internal.h"
#include "image_bytes.h"
#include "rgraph/error.h"

namespace rgraph::gltf_detail {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool validFilter(int f, bool minification) {
  if (f == SamplerDesc::kNearest || f == SamplerDesc::kLinear) return true;
  return minification && (f == SamplerDesc::kNearestMipmapNearest || f == SamplerDesc::kLinearMipmapNearest ||
                          f == SamplerDesc::kNearestMipmapLinear || f == SamplerDesc::kLinearMipmapLinear);
}
bool validWrap(int w) {
  return w == SamplerDesc::kRepeat || w == SamplerDesc::kClampToEdge || w == SamplerDesc::kMirroredRepeat;
}

// "in [0, 1]" or ">= 0" (no upper bound).
std::string rangeText(float lo, float hi) {
  std::ostringstream s;
  if (hi == kInf)
    s << ">= " << lo;
  else
    s << "in [" << lo << ", " << hi << "]";
  return s.str();
}

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

bool decodeImage(tinygltf::Image* image, const unsigned char* bytes, size_t size, std::string* err) {
  if (size == 0 || size > size_t(INT_MAX)) {
    if (err) *err += "image '" + image->name + "': " + (size == 0 ? "empty data" : "data too large") + "\n";
    return false;
  }
  if (const auto why = image_bytes::problem(bytes, size, /*allowHdr=*/false)) {
    if (err) *err += "image '" + image->name + image->uri + "': cannot decode (" + *why + ")\n";
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

bool imageCallback(tinygltf::Image* image, const int /*index*/, std::string* err, std::string* /*warn*/, int, int,
                   const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;  // decoded in decodedPixels, once its buffer view is checked
  if (size < 0) return false;
  return decodeImage(image, bytes, size_t(size), err);
}

// ------------------------------------------------------------ images and textures

const std::vector<uint8_t>& GltfLoader::decodedPixels(int gltfImage, const std::string& what) {
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
        const std::filesystem::path p = std::filesystem::path(baseDir_) / img.uri;
        msg += " (missing or unreadable file " + p.string() + ")";
      } else if (!imageWarn_.empty()) {
        msg += "; " + imageWarn_;  // tinygltf's words are the only reason given
      }
      fail(msg);
    }
  }
  if (img.width <= 0 || img.height <= 0 || img.component != 4 || img.bits != 8 ||
      img.image.size() != size_t(img.width) * size_t(img.height) * 4)
    fail(name + ": unexpected decoded pixel layout");
  return img.image;
}

int GltfLoader::sceneImage(int gltfImage, bool srgb, const std::string& what) {
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

TextureRef GltfLoader::textureRef(int gltfTexture, int texCoord, bool srgb, const std::string& what) {
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

// ------------------------------------------------------------ value ranges

float GltfLoader::checkedNumber(double v, float lo, float hi, const std::string& pointer) {
  if (!(std::isfinite(v) && v >= double(lo) && v <= double(hi)))
    failAt(pointer, "must be " + rangeText(lo, hi) + ", got " + numberText(v));
  return float(v);
}

template <size_t N>
glm::vec<N, float> GltfLoader::checkedFactor(const std::vector<double>& v, float lo, float hi, const std::string& pointer) {
  if (v.size() != N)
    failAt(pointer, "expected " + std::to_string(N) + " numbers, got " + std::to_string(v.size()));
  glm::vec<N, float> out;
  for (size_t i = 0; i < N; ++i) out[int(i)] = checkedNumber(v[i], lo, hi, pointer + "/" + std::to_string(i));
  return out;
}

// KHR_materials_specular, as the extension defines it for the PBR model
// (Material: dielectric F0 = min(0.04 * colour factor * colour texture, 1) *
// factor * texture.a, F90 = factor * texture.a; include/lighting.glsl's
// surfaceF0/surfaceF90). The Blinn-Phong path has one number instead,
// Material::specular: the strength of the highlight, 0.5 when a source says
// nothing. The mapping keeps that anchor:
//   specular = 0.5 * specularFactor * max(specularColorFactor), clamped to [0, 1]
// so the extension's defaults (1, [1, 1, 1]) look like a file without it,
// specularFactor 0 (no specular reflection) gives no highlight, and the
// brightest channel of a tinted specular colour sets the strength (Blinn-Phong
// reads no texture: the factors set it).
void GltfLoader::specularFromExtension(const tinygltf::Value& ext, const std::string& pointer, const std::string& what,
                                       Material& out) {
  if (!ext.IsObject()) failAt(pointer, "expected an object");
  const tinygltf::Value& f = ext.Get("specularFactor");
  if (f.Type() != tinygltf::NULL_TYPE) {
    if (!f.IsNumber()) failAt(pointer + "/specularFactor", "expected a number");
    out.specularFactor = checkedNumber(f.GetNumberAsDouble(), 0.0f, 1.0f, pointer + "/specularFactor");
  }
  const tinygltf::Value& c = ext.Get("specularColorFactor");
  if (c.Type() != tinygltf::NULL_TYPE) {
    const std::string cp = pointer + "/specularColorFactor";
    if (!c.IsArray() || c.ArrayLen() != 3) failAt(cp, "expected an array of 3 numbers");
    for (int i = 0; i < 3; ++i) {
      const tinygltf::Value& e = c.Get(i);
      if (!e.IsNumber()) failAt(cp + "/" + std::to_string(i), "expected a number");
      out.specularColorFactor[i] = checkedNumber(e.GetNumberAsDouble(), 0.0f, kInf, cp + "/" + std::to_string(i));
    }
  }
  auto texture = [&](const char* name, bool srgb) {
    const tinygltf::Value& t = ext.Get(name);
    if (t.Type() == tinygltf::NULL_TYPE) return TextureRef{};
    const std::string tp = pointer + "/" + name;
    if (!t.IsObject()) failAt(tp, "expected an object");
    const tinygltf::Value& index = t.Get("index");
    if (!index.IsInt()) failAt(tp + "/index", "expected an integer");
    const tinygltf::Value& texCoord = t.Get("texCoord");
    if (texCoord.Type() != tinygltf::NULL_TYPE && !texCoord.IsInt()) failAt(tp + "/texCoord", "expected an integer");
    TextureRef ref = textureRef(index.GetNumberAsInt(), texCoord.IsInt() ? texCoord.GetNumberAsInt() : 0, srgb,
                                what + " " + name);
    // Its own KHR_texture_transform, as on any textureInfo.
    if (const tinygltf::Value& e = t.Get("extensions"); e.IsObject()) {
      tinygltf::ExtensionMap extensions;
      for (const std::string& key : e.Keys()) extensions[key] = e.Get(key);
      textureTransform(ref, extensions, tp);
    }
    return ref;
  };
  out.specularTexture = texture("specularTexture", false);
  out.specularColorTexture = texture("specularColorTexture", true);
  const float color = std::max({out.specularColorFactor.r, out.specularColorFactor.g, out.specularColorFactor.b});
  out.specular = std::clamp(0.5f * out.specularFactor * color, 0.0f, 1.0f);
}

// KHR_texture_transform on a textureInfo: offset, rotation, scale and a
// texCoord that replaces the textureInfo's own. Numbers must be finite.
void GltfLoader::textureTransform(TextureRef& ref, const tinygltf::ExtensionMap& extensions, const std::string& pointer) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end() || !ref.valid()) return;
  const std::string p = pointer + "/extensions/KHR_texture_transform";
  const tinygltf::Value& ext = it->second;
  if (!ext.IsObject()) failAt(p, "expected an object");
  auto finite = [&](double v, const std::string& vp) {
    if (!(std::isfinite(v) && std::abs(v) <= double(std::numeric_limits<float>::max())))
      failAt(vp, "must be a finite number, got " + numberText(v));
    return float(v);
  };
  auto vec2 = [&](const char* key, glm::vec2& out) {
    const tinygltf::Value& v = ext.Get(key);
    if (v.Type() == tinygltf::NULL_TYPE) return;
    const std::string vp = p + "/" + key;
    if (!v.IsArray() || v.ArrayLen() != 2) failAt(vp, "expected an array of 2 numbers");
    for (int i = 0; i < 2; ++i) {
      if (!v.Get(i).IsNumber()) failAt(vp + "/" + std::to_string(i), "expected a number");
      out[i] = finite(v.Get(i).GetNumberAsDouble(), vp + "/" + std::to_string(i));
    }
  };
  vec2("offset", ref.offset);
  vec2("scale", ref.scale);
  if (const tinygltf::Value& r = ext.Get("rotation"); r.Type() != tinygltf::NULL_TYPE) {
    if (!r.IsNumber()) failAt(p + "/rotation", "expected a number");
    ref.rotation = finite(r.GetNumberAsDouble(), p + "/rotation");
  }
  if (const tinygltf::Value& t = ext.Get("texCoord"); t.Type() != tinygltf::NULL_TYPE) {
    if (!t.IsNumber()) failAt(p + "/texCoord", "expected a number");
    const double texCoord = t.GetNumberAsDouble();
    if (texCoord == 0.0 || texCoord == 1.0) {
      ref.texCoord = int(texCoord);
    } else {
      warnAt(p + "/texCoord", "texCoord " + std::to_string(texCoord) + " is not supported (only 0 and 1); using 0");
      ref.texCoord = 0;
    }
  }
}

// ------------------------------------------------------------ materials

Material GltfLoader::convertMaterial(size_t index) {
  const tinygltf::Material& m = model_.materials[index];
  const std::string what = "material " + std::to_string(index) + (m.name.empty() ? "" : " ('" + m.name + "')");
  const std::string ptr = "/materials/" + std::to_string(index);
  Material out;
  out.name = m.name;
  const auto& pbr = m.pbrMetallicRoughness;
  const std::string pbrPtr = ptr + "/pbrMetallicRoughness";
  out.baseColorFactor = checkedFactor<4>(pbr.baseColorFactor, 0.0f, 1.0f, pbrPtr + "/baseColorFactor");
  out.metallicFactor = checkedNumber(pbr.metallicFactor, 0.0f, 1.0f, pbrPtr + "/metallicFactor");
  out.roughnessFactor = checkedNumber(pbr.roughnessFactor, 0.0f, 1.0f, pbrPtr + "/roughnessFactor");
  if (!m.emissiveFactor.empty()) out.emissiveFactor = checkedFactor<3>(m.emissiveFactor, 0.0f, 1.0f, ptr + "/emissiveFactor");
  if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
    const std::string sp = ptr + "/extensions/KHR_materials_emissive_strength/emissiveStrength";
    if (!it->second.IsObject()) failAt(ptr + "/extensions/KHR_materials_emissive_strength", "expected an object");
    const tinygltf::Value& v = it->second.Get("emissiveStrength");
    if (v.Type() != tinygltf::NULL_TYPE) {
      if (!v.IsNumber()) failAt(sp, "expected a number");
      out.emissiveFactor *= checkedNumber(v.GetNumberAsDouble(), 0.0f, kInf, sp);
    }
  }
  if (auto it = m.extensions.find("KHR_materials_specular"); it != m.extensions.end())
    specularFromExtension(it->second, ptr + "/extensions/KHR_materials_specular", what, out);
  out.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true, what + " baseColorTexture");
  out.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                                            what + " metallicRoughnessTexture");
  out.normalTexture = textureRef(m.normalTexture.index, m.normalTexture.texCoord, false, what + " normalTexture");
  out.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
  out.occlusionTexture = textureRef(m.occlusionTexture.index, m.occlusionTexture.texCoord, false, what + " occlusionTexture");
  out.occlusionStrength = checkedNumber(m.occlusionTexture.strength, 0.0f, 1.0f, ptr + "/occlusionTexture/strength");
  out.emissiveTexture = textureRef(m.emissiveTexture.index, m.emissiveTexture.texCoord, true, what + " emissiveTexture");
  textureTransform(out.baseColorTexture, pbr.baseColorTexture.extensions, pbrPtr + "/baseColorTexture");
  textureTransform(out.metallicRoughnessTexture, pbr.metallicRoughnessTexture.extensions, pbrPtr + "/metallicRoughnessTexture");
  textureTransform(out.normalTexture, m.normalTexture.extensions, ptr + "/normalTexture");
  textureTransform(out.occlusionTexture, m.occlusionTexture.extensions, ptr + "/occlusionTexture");
  textureTransform(out.emissiveTexture, m.emissiveTexture.extensions, ptr + "/emissiveTexture");
  if (m.alphaMode == "OPAQUE" || m.alphaMode.empty()) {
    out.alphaMode = AlphaMode::opaque;
  } else if (m.alphaMode == "MASK") {
    out.alphaMode = AlphaMode::mask;
  } else if (m.alphaMode == "BLEND") {
    out.alphaMode = AlphaMode::blend;
  } else {
    warnAt(ptr + "/alphaMode", "unknown alphaMode '" + m.alphaMode + "'; using OPAQUE");
  }
  out.alphaCutoff = checkedNumber(m.alphaCutoff, 0.0f, 1.0f, ptr + "/alphaCutoff");
  out.doubleSided = m.doubleSided;
  if (m.extensions.count("KHR_materials_unlit")) {
    // Unlit: the base colour is all that is drawn (include/material.glsl).
    // What would shade it goes: a constant metallic 0 / roughness 1 keeps the
    // G-buffer's material target out of scenes that need it for nothing else.
    out.unlit = true;
    out.metallicFactor = 0.0f;
    out.roughnessFactor = 1.0f;
    out.metallicRoughnessTexture = out.normalTexture = out.occlusionTexture = TextureRef{};
  }
  return out;
}

int GltfLoader::defaultMaterial() {
  if (defaultMaterial_ < 0) {
    Material d;
    d.name = "default";
    defaultMaterial_ = int(scene_.materials.size());
    scene_.materials.push_back(d);
  }
  return defaultMaterial_;
}

// ------------------------------------------------------------ lights

// A spot light's cone: it points down the node's -Z; the angles are the
// extension schema's, in radians: 0 <= inner < outer <= pi/2.
void GltfLoader::spotCone(const tinygltf::Light& l, const std::string& ptr, const glm::mat4& world, PointLight& p) {
  constexpr double kHalfPi = 1.57079632679489661923;
  const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
  if (!(outer > 0.0 && outer <= kHalfPi))
    failAt(ptr + "/spot/outerConeAngle", "must be in (0, pi/2] radians, got " + numberText(outer));
  if (!(inner >= 0.0 && inner < outer))
    failAt(ptr + "/spot/innerConeAngle",
           "must be >= 0 and less than outerConeAngle (" + numberText(outer) + "), got " + numberText(inner));
  const glm::vec3 dir = glm::mat3(world) * glm::vec3(0, 0, -1);
  p.spot = true;
  p.direction = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0, 0, -1);
  p.innerConeDeg = float(glm::degrees(inner));
  p.outerConeDeg = float(glm::degrees(outer));
  // Rounding to float degrees must not break inner < outer <= 90.
  p.outerConeDeg = std::min(p.outerConeDeg, 90.0f);
  if (p.innerConeDeg >= p.outerConeDeg) p.innerConeDeg = std::nextafter(p.outerConeDeg, 0.0f);
}

void GltfLoader::addLight(int index, const glm::mat4& world, const std::string& what) {
  if (index < 0 || size_t(index) >= model_.lights.size())
    fail(what + ": light " + std::to_string(index) + " does not exist (" + std::to_string(model_.lights.size()) + " lights)");
  if (scene_.pointLights.size() + scene_.directionalLights.size() >= kMaxSceneLights)
    fail(what + ": more than " + std::to_string(kMaxSceneLights) + " light instances; at most " + std::to_string(kMaxSceneLights) +
         " are supported");
  const tinygltf::Light& l = model_.lights[size_t(index)];
  const std::string ptr = "/extensions/KHR_lights_punctual/lights/" + std::to_string(index);
  const glm::vec3 color = l.color.empty() ? glm::vec3(1.0f) : checkedFactor<3>(l.color, 0.0f, 1.0f, ptr + "/color");
  const float intensity = checkedNumber(l.intensity, 0.0f, kInf, ptr + "/intensity");
  // tinygltf reads an absent range as 0 ("infinite"); an explicit 0 is read the same way.
  if (l.range < 0.0 || !std::isfinite(l.range)) failAt(ptr + "/range", "must be > 0, got " + numberText(l.range));
  if (l.type == "directional") {
    DirectionalLight d;
    glm::vec3 dir = glm::mat3(world) * glm::vec3(0, 0, -1);
    d.direction = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0, 0, -1);
    d.color = color;
    d.intensity = intensity;
    scene_.directionalLights.push_back(d);
    return;
  }
  if (l.type != "point" && l.type != "spot") {
    warnAt(ptr + "/type", "unknown light type '" + l.type + "'; ignored");
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
  p.radius = l.range > 0.0 ? float(l.range) : lightRadius(p);
  if (l.type == "spot") spotCone(l, ptr, world, p);
  p.marker = false;  // the file's own lamp: its model draws it
  scene_.pointLights.push_back(p);
}

}  // namespace rgraph::gltf_detail
