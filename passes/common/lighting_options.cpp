#include "rgraph/passes/lighting_options.h"

#include <GL/glcorearb.h>

#include <cctype>
#include <utility>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/gbuffer_layout.h"
#include "rgraph/scene.h"

namespace rgraph::lighting {

const char* hdrImageQualifier(Format f) {
  switch (f) {
    case Format::rgba32f: return "rgba32f";
    case Format::r11g11b10f: return "r11f_g11f_b10f";
    default: return "rgba16f";
  }
}

uint32_t hdrImageFormat(Format f) {
  switch (f) {
    case Format::rgba32f: return GL_RGBA32F;
    case Format::r11g11b10f: return GL_R11F_G11F_B10F;
    default: return GL_RGBA16F;
  }
}

std::vector<ParamDecl> params(double defaultThreshold, bool allowNoCutoff) {
  using namespace rgraph::decl;
  return {
      param("model", ParamType::enumeration, std::string("blinn_phong"),
            "lighting model: blinn_phong (LearnOpenGL) or cook_torrance (GGX, Smith, Schlick)",
            {"blinn_phong", "cook_torrance"}),
      param("attenuation", ParamType::enumeration, std::string("classic"),
            "classic: 1/(kc + kl d + kq d^2) cut at the radius; smooth: max(1 - (d/r)^2, 0)", {"classic", "smooth"}),
      ranged("threshold", ParamType::number, defaultThreshold, allowNoCutoff ? 0.0 : 1e-4, 1.0,
             allowNoCutoff ? "brightness at which a light's radius is cut, as a share of its brightest channel "
                             "(LearnOpenGL: 5/256); 0: no cut-off"
                           : "brightness at which a light's radius is cut, as a share of its brightest channel "
                             "(LearnOpenGL: 5/256)"),
  };
}

ParamDecl layoutParam() {
  return decl::param("layout", ParamType::enumeration, std::string(gbuffer::kDefaultLayout),
                     "G-buffer layout it reads: " + gbuffer::nameList(false), gbuffer::names());
}

std::vector<std::string> defines(const ParamSet& p) {
  // The smooth falloff reaches zero at each light's radius, and threshold 0
  // ("no cut-off") leaves the lights without one: the shader would light
  // nothing. Refused here, where validate (through the pass's programs) and
  // setup at render time both build the defines.
  if (p.getString("attenuation") == "smooth" && p.has("threshold") && !(threshold(p) > 0.0f))
    throw RuntimeError(
        "attenuation 'smooth' falls to zero at each light's radius, and threshold 0 (no cut-off) gives the lights "
        "none: set threshold above 0 (5/256 = 0.01953125 is LearnOpenGL's) or use attenuation 'classic'");
  return {p.getString("model") == "cook_torrance" ? "LIGHTING_COOK_TORRANCE" : "LIGHTING_BLINN_PHONG",
          p.getString("attenuation") == "smooth" ? "ATTENUATION_SMOOTH" : "ATTENUATION_CLASSIC"};
}

std::string layoutDefine(const ParamSet& p) { return gbuffer::of(p).define; }

std::vector<std::string> gbufferDefines(const ParamSet& p) {
  std::vector<std::string> d = {layoutDefine(p)};
  if (p.getBool("constant_material")) {
    d.push_back("CONSTANT_MATERIAL");
    d.push_back("CONSTANT_METALLIC=" + std::to_string(p.getNumber("metallic")));
    d.push_back("CONSTANT_ROUGHNESS=" + std::to_string(p.getNumber("roughness")));
  }
  // HAS_EMISSIVE_TARGET, HAS_REFLECTANCE_TARGET: the optional targets on.
  const gbuffer::Layout& layout = gbuffer::of(p);
  for (const auto& slot : gbuffer::optionalSlots())
    if (layout.writes(slot) && p.getBool(slot)) {
      std::string define = "HAS_" + slot + "_TARGET";
      for (char& c : define) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      d.push_back(std::move(define));
    }
  return d;
}

std::vector<ShaderProgramSpec> normalMapVariants(const ShaderProgramSpec& spec) {
  std::vector<ShaderProgramSpec> v = {spec, spec};
  v[1].defines.push_back("HAS_NORMAL_MAPS");
  return v;
}

size_t normalMapVariant(const PassContext& ctx) { return ctx.scene() && ctx.scene()->hasNormalMaps() ? 1 : 0; }

std::vector<std::string> shadingDefines(const ParamSet& p) {
  std::vector<std::string> d = defines(p);
  for (auto& def : gbufferDefines(p)) d.push_back(std::move(def));
  return d;
}

std::vector<ParamDecl> constantMaterialParams() {
  using namespace rgraph::decl;
  return {param("constant_material", ParamType::boolean, false,
                "the scene has one metallic/roughness: no material target, values below (set by scene adaptation)"),
          ranged("metallic", ParamType::number, 0.0, 0.0, 1.0, "metallic when constant_material"),
          ranged("roughness", ParamType::number, 1.0, 0.0, 1.0, "roughness when constant_material"),
          param("emissive", ParamType::boolean, false,
                "the G-buffer has an emissive target (bind 'emissive'); scene adaptation turns it off, unbinding "
                "the slot, when no material emits"),
          param("reflectance", ParamType::boolean, false,
                "the G-buffer has a reflectance target (KHR_materials_specular F0 and F90; bind 'reflectance'); "
                "scene adaptation turns it off, unbinding the slot, when every material has the default")};
}

namespace {
// Optional targets (gbuffer::Target::optional) the scene does not need: off and unbound.
void adaptOptionalTargets(const SceneFeatures& f, PassAdaptation& a) {
  const std::pair<const char*, bool> needed[] = {{"emissive", f.emissive}, {"reflectance", f.reflectance}};
  for (const auto& [slot, need] : needed) {
    if (need || !a.params.getBool(slot)) continue;
    a.params.set(slot, false);
    a.unbindSlots.push_back(slot);
    a.notes.push_back(std::string(slot == std::string("emissive") ? "no emitting material"
                                                                  : "every material has the default reflectance") +
                      ": no " + slot + " target");
  }
}
}  // namespace

void adaptGBuffer(const SceneFeatures& f, PassAdaptation& a) {
  adaptOptionalTargets(f, a);
  if (f.metallicRoughnessVariation || !gbuffer::of(a.params).writes("material") ||
      a.params.getBool("constant_material"))
    return;
  a.params.set("constant_material", true);
  a.params.set("metallic", static_cast<double>(f.metallic));
  a.params.set("roughness", static_cast<double>(f.roughness));
  a.unbindSlots.push_back("material");
  a.notes.push_back("one metallic/roughness in the scene: no material target (metallic " +
                    std::to_string(f.metallic) + ", roughness " + std::to_string(f.roughness) + ")");
}

void adaptPointLightShading(const SceneFeatures& f, PassAdaptation& a) {
  adaptGBuffer(f, a);
  if (!f.pointLights && a.params.getBool("point_lights")) {
    a.params.set("point_lights", false);
    a.notes.push_back("no point lights: ambient and directional light only");
  }
}

float threshold(const ParamSet& p) { return static_cast<float>(p.getNumber("threshold")); }

PassRule gbufferReaderRule() {
  PassRule rule;
  rule.text = "bind the inputs \"layout\" reads:";
  for (const auto& layout : gbuffer::layouts()) {
    const auto slots = layout.readerSlots(false);
    rule.text += std::string(&layout == &gbuffer::layouts().front() ? " " : ", ") + layout.name + " (";
    for (size_t i = 0; i < slots.size(); ++i) rule.text += (i ? ", " : "") + slots[i];
    rule.text += ")";
  }
  rule.text += "; no material with constant_material; emissive and reflectance exactly when their parameter is on";
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const gbuffer::Layout& layout = gbuffer::of(ctx.params());
    for (const auto& slot : layout.readerSlots(ctx.params().getBool("constant_material")))
      if (!ctx.bound(slot))
        checks.slotError(slot, "input '" + slot + "' is required by layout '" + layout.name + "' but not bound");
    checkOptionalTargets(ctx, checks, /*writes=*/false);
  };
  return rule;
}

void checkOptionalTargets(const PassCheckContext& ctx, PassChecks& checks, bool writes) {
  const gbuffer::Layout& layout = gbuffer::of(ctx.params());
  for (const auto& slot : gbuffer::optionalSlots()) {
    const bool wanted = layout.uses(slot, ctx.params());
    if (ctx.bound(slot) == wanted) continue;
    if (wanted)
      checks.slotError(slot, "\"" + slot + "\": true " + (writes ? "writes" : "reads") + " a '" + slot +
                                 "' target: bind it in " + (writes ? "outputs" : "inputs"));
    else
      checks.slotError(slot, (writes ? "a '" + slot + "' output" : "input '" + slot + "'") +
                                 " needs the pass parameter \"" + slot + "\": true" +
                                 (layout.writes(slot) ? "" : " and a layout with that target (not '" + layout.name + "')"));
  }
}

std::vector<std::string> materialSamplers() {
  return {"u_baseColorTex", "u_metallicRoughnessTex", "u_normalTex",          "u_occlusionTex",
          "u_emissiveTex",  "u_specularTex",          "u_specularColorTex"};
}

std::vector<SamplerSlot> gbufferSamplers() {
  return {{"position", "g_position", 0}, {"normal", "g_normal", 1}, {"albedo", "g_albedo", 2},
          {"material", "g_material", 3}, {"depth", "g_depth", 4},   {"emissive", "g_emissive", 9},
          {"reflectance", "g_reflectance", 10}};
}

PassTypeDesc gbufferReader(std::string name, std::string description) {
  PassTypeDesc d = decl::passType(std::move(name), std::move(description));
  d.slots = gbufferSlots();
  d.rules = {gbufferReaderRule(), gbuffer::sameLayoutAsWriterRule()};
  d.needsScene = true;
  d.adapt = adaptGBuffer;
  return d;
}

PassTypeDesc computeLightingPass(std::string name, std::string description) {
  using namespace rgraph::decl;
  PassTypeDesc d = gbufferReader(std::move(name), std::move(description));
  d.slots.push_back(slot("color", Access::storage_write, true, SlotDecl::Load::optional,
                         "HDR lighting target written with image stores; when loaded, the lights are added to it; "
                         "background pixels keep its clear value",
                         hdrFormats()));
  d.params = params();
  d.params.push_back(layoutParam());
  d.params.push_back(param("point_lights", ParamType::boolean, true, "shade the point lights"));
  d.params.push_back(param("ambient_and_sun", ParamType::boolean, true,
                           "also add ambient and the directional light (false when another pass adds them)"));
  d.adapt = adaptPointLightShading;
  return d;
}

std::vector<SlotDecl> gbufferSlots() {
  using namespace rgraph::decl;
  return {
      slot("position", Access::sampled, false, SlotDecl::Load::never, "G-buffer world position (not in compact)"),
      slot("normal", Access::sampled, true, SlotDecl::Load::never, "G-buffer normal"),
      slot("albedo", Access::sampled, true, SlotDecl::Load::never, "G-buffer albedo + specular"),
      slot("material", Access::sampled, false, SlotDecl::Load::never, "G-buffer metallic/roughness (pbr, compact, fp32)"),
      slot("depth", Access::sampled, false, SlotDecl::Load::never, "G-buffer depth (compact: rebuilds position)",
           depthFormats()),
      slot("emissive", Access::sampled, false, SlotDecl::Load::never,
           "G-buffer emitted radiance (with the \"emissive\" parameter)"),
      slot("reflectance", Access::sampled, false, SlotDecl::Load::never,
           "G-buffer dielectric F0 + specular weight (with the \"reflectance\" parameter)"),
  };
}

}  // namespace rgraph::lighting
