// Motion vectors from the scene-drawing passes (geometry, forward_lit): the
// optional "velocity" output and the "velocity" parameter that selects the
// HAS_VELOCITY shader variant. Programs see parameters only, and `rgraph
// validate` checks exactly the programs that run, so the parameter chooses
// the variant and the check holds the binding to it. The velocity is
// uv_now - uv_prev in UV units, both unjittered (docs/writing-a-pass.md,
// "The Frame block"); 0 where nothing was drawn.
#pragma once

#include <string>
#include <vector>

#include "rgraph/pass.h"
#include "rgraph/pass_check.h"

namespace rgraph::velocity {

// The output slot: declare it after the pass's other colour slots so theirs
// keep their attachment indices.
SlotDecl slot();
ParamDecl param();
bool enabled(const ParamSet& params);
// Appends HAS_VELOCITY when the parameter is on.
void addDefine(const ParamSet& params, std::vector<std::string>& defines);
// Rule: the output is bound exactly when the parameter is on.
PassRule rule();

}  // namespace rgraph::velocity
