// What a glTF file asks for and the loader does not draw: said once per
// feature per file, naming the feature and what is drawn instead (the table
// in scenes/README.md lists every feature). Draco compression is looked for
// before tinygltf parses the file: tinygltf fails on a compressed primitive's
// accessors (they have no buffer view) without naming the extension.
#include <string>

#include <nlohmann/json.hpp>

#include "gltf_internal.h"

namespace rgraph::gltf_detail {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// Extensions listed in extensionsUsed that change how a material looks, and
// what is drawn without them.
struct IgnoredExtension {
  const char* name;
  const char* instead;
};
constexpr IgnoredExtension kIgnoredExtensions[] = {
    {"KHR_materials_clearcoat", "drawn without the clear coat"},
    {"KHR_materials_transmission", "drawn opaque"},
    {"KHR_materials_diffuse_transmission", "drawn opaque"},
    {"KHR_materials_volume", "drawn as a thin surface"},
    {"KHR_materials_sheen", "drawn without sheen"},
    {"KHR_materials_ior", "index of refraction 1.5"},
    {"KHR_materials_iridescence", "drawn without iridescence"},
    {"KHR_materials_anisotropy", "drawn isotropic"},
    {"KHR_materials_dispersion", "drawn without dispersion"},
    {"KHR_materials_pbrSpecularGlossiness", "the metallic-roughness values (defaults where absent)"},
    {"KHR_materials_variants", "the default materials"},
};

}  // namespace

void GltfLoader::warnIgnored(const std::string& feature, const std::string& instead) {
  if (!ignoredFeatures_.insert(feature).second) return;
  warn(feature + " ignored: " + instead);
}

void GltfLoader::checkDraco() {
  if (json_.find(kDraco) == std::string_view::npos) return;  // the common case: no second parse
  const nlohmann::json doc = nlohmann::json::parse(json_.data(), json_.data() + json_.size(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return;  // tinygltf says what is wrong
  if (auto r = doc.find("extensionsRequired"); r != doc.end() && r->is_array())
    for (size_t i = 0; i < r->size(); ++i)
      if ((*r)[i] == kDraco)
        failAt("/extensionsRequired/" + std::to_string(i),
               "requires KHR_draco_mesh_compression (Draco-compressed meshes), which is not supported; export the file "
               "without Draco compression");
  const auto accessors = doc.find("accessors");
  // An accessor with data of its own (a buffer view), as the uncompressed
  // fallback of a compressed primitive must have.
  auto plain = [&](const nlohmann::json& index) {
    if (!index.is_number_unsigned() || accessors == doc.end() || !accessors->is_array()) return false;
    const size_t i = index.get<size_t>();
    return i < accessors->size() && (*accessors)[i].is_object() && (*accessors)[i].contains("bufferView");
  };
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return;
  for (size_t mi = 0; mi < meshes->size(); ++mi) {
    const nlohmann::json& m = (*meshes)[mi];
    if (!m.is_object() || !m.contains("primitives") || !m["primitives"].is_array()) continue;
    const nlohmann::json& prims = m["primitives"];
    for (size_t pi = 0; pi < prims.size(); ++pi) {
      const nlohmann::json& p = prims[pi];
      if (!p.is_object() || !p.contains("extensions") || !p["extensions"].is_object() || !p["extensions"].contains(kDraco))
        continue;
      bool fallback = p.contains("attributes") && p["attributes"].is_object() && !p["attributes"].empty();
      if (fallback)
        for (const auto& a : p["attributes"].items()) fallback = fallback && plain(a.value());
      if (p.contains("indices")) fallback = fallback && plain(p["indices"]);
      const std::string ptr = "/meshes/" + std::to_string(mi) + "/primitives/" + std::to_string(pi) + "/extensions/" + kDraco;
      if (!fallback)
        failAt(ptr, "the primitive is Draco-compressed (KHR_draco_mesh_compression), which is not supported, and has no "
                    "uncompressed accessors to draw instead");
      warnIgnored(kDraco, "the primitives' uncompressed accessors are drawn");
    }
  }
}

void GltfLoader::warnIgnoredFeatures() {
  // (Animations, skins and morph targets are drawn: RenderScene::setTime
  // poses them, GpuScene deforms them in scene.vert. No warning.)
  for (const std::string& used : model_.extensionsUsed)
    for (const IgnoredExtension& e : kIgnoredExtensions)
      if (used == e.name) warnIgnored(e.name, e.instead);
}

}  // namespace rgraph::gltf_detail
