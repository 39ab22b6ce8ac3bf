#include "rgraph/gl/lighting_options.h"

#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/pass_decl.h"

namespace rgraph::lighting {

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
  return decl::param("layout", ParamType::enumeration, std::string("pbr"),
                     "G-buffer layout it reads: learnopengl, pbr, compact, fp32",
                     {"learnopengl", "pbr", "compact", "fp32"});
}

std::vector<std::string> defines(const ParamSet& p) {
  return {p.getString("model", "blinn_phong") == "cook_torrance" ? "LIGHTING_COOK_TORRANCE" : "LIGHTING_BLINN_PHONG",
          p.getString("attenuation", "classic") == "smooth" ? "ATTENUATION_SMOOTH" : "ATTENUATION_CLASSIC"};
}

std::string layoutDefine(const ParamSet& p) {
  const std::string layout = p.getString("layout", "pbr");
  if (layout == "learnopengl") return "GBUFFER_LEARNOPENGL";
  if (layout == "compact") return "GBUFFER_COMPACT";
  if (layout == "fp32") return "GBUFFER_FP32";
  return "GBUFFER_PBR";
}

float threshold(const ParamSet& p) { return static_cast<float>(p.getNumber("threshold", 5.0 / 256.0)); }

namespace {
constexpr const char* kSlots[] = {"position", "normal", "albedo", "material", "depth"};
}

void bindGBuffer(PassContext& ctx) {
  for (GLuint unit = 0; unit < 5; ++unit)
    glBindTextureUnit(unit, ctx.bound(kSlots[unit]) ? ctx.texture(kSlots[unit]) : 0);
}

void requireGBuffer(PassContext& ctx, const std::string& passKind) {
  const std::string layout = ctx.params().getString("layout", "pbr");
  std::vector<std::string> needed = {"normal", "albedo"};
  if (layout == "compact") {
    needed.push_back("depth");
    needed.push_back("material");
  } else {
    needed.push_back("position");
    if (layout != "learnopengl") needed.push_back("material");
  }
  for (const auto& slot : needed)
    if (!ctx.bound(slot))
      throw RuntimeError(passKind + " pass '" + ctx.passName() + "': input '" + slot + "' is required by layout '" +
                         layout + "' but not bound");
}

std::vector<SlotDecl> gbufferSlots() {
  using namespace rgraph::decl;
  return {
      slot("position", Access::sampled, false, SlotDecl::Load::never, "G-buffer world position (not in compact)"),
      slot("normal", Access::sampled, true, SlotDecl::Load::never, "G-buffer normal"),
      slot("albedo", Access::sampled, true, SlotDecl::Load::never, "G-buffer albedo + specular"),
      slot("material", Access::sampled, false, SlotDecl::Load::never, "G-buffer metallic/roughness (pbr, compact, fp32)"),
      slot("depth", Access::sampled, false, SlotDecl::Load::never, "G-buffer depth (compact: rebuilds position)",
           {Format::depth24, Format::depth32f, Format::depth24_stencil8, Format::depth32f_stencil8}),
  };
}

}  // namespace rgraph::lighting
