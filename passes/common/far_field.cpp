#include "rgraph/passes/far_field.h"

#include "rgraph/error.h"
#include "rgraph/pass_decl.h"

namespace rgraph::lighting {

ParamDecl farFieldParam() {
  return decl::param("far_field", ParamType::boolean, false,
                     "add the lights a tile or cluster does not list as a low-frequency far-field term (16 "
                     "direction bins summed per tile and quarter, or per cluster with pixels, each shaded as one "
                     "light), and shade the listed ones without their cut: recovers most of the cut-off's error "
                     "(attenuation classic only)");
}

void addFarFieldDefine(const ParamSet& p, std::vector<std::string>& defines) {
  if (!p.getBool("far_field")) return;
  if (p.getString("attenuation") == "smooth")
    throw RuntimeError(
        "far_field adds the attenuation past each light's radius, and attenuation 'smooth' is zero there: use "
        "attenuation 'classic' or set far_field false");
  defines.push_back("FAR_FIELD");
}

}  // namespace rgraph::lighting
