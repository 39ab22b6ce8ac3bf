#include "rgraph/passes/velocity.h"

#include "rgraph/format_sets.h"
#include "rgraph/pass_decl.h"

namespace rgraph::velocity {

SlotDecl slot() {
  return decl::slot("velocity", Access::color_attachment, false, SlotDecl::Load::never,
                    "motion vectors in UV units, uv_now - uv_prev, unjittered (0 where nothing was drawn); "
                    "needs the velocity parameter",
                    velocityFormats());
}

ParamDecl param() {
  return decl::param("velocity", ParamType::boolean, false,
                     "write motion vectors to the 'velocity' output (bind it too)");
}

bool enabled(const ParamSet& params) { return params.getBool("velocity"); }

void addDefine(const ParamSet& params, std::vector<std::string>& defines) {
  if (enabled(params)) defines.push_back("HAS_VELOCITY");
}

PassRule rule() {
  PassRule r;
  r.text = "bind the velocity output exactly when \"velocity\" is true";
  r.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const bool wanted = enabled(ctx.params());
    if (ctx.bound("velocity") == wanted) return;
    checks.slotError("velocity", wanted ? "\"velocity\": true writes motion vectors: bind the 'velocity' output"
                                        : "a 'velocity' output needs the pass parameter \"velocity\": true");
  };
  return r;
}

}  // namespace rgraph::velocity
