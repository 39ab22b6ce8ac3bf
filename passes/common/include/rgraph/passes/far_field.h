// The far-field option of the compute lighting passes (tiled_deferred,
// clustered_deferred): the lights a tile/cluster does not list are added as
// a low-frequency diffuse term (shaders/include/far_field.glsl), and the
// listed ones are shaded without their cut, so that the cut-off's error is
// recovered at the cost of one evaluation per light and tile (or cluster
// with pixels), and one shading per direction bin and pixel. Both passes
// take the far field of the lights far from a 64-pixel bin from the bins
// (rgraph/passes/light_bins.h).
#pragma once

#include <string>
#include <vector>

#include "rgraph/pass.h"

namespace rgraph::lighting {

// The "far_field" boolean parameter.
ParamDecl farFieldParam();
// Appends FAR_FIELD when the param is set. Throws RuntimeError (the message
// validate and render report at the pass) when it is set with attenuation
// 'smooth', which has no tail past the radius to recover.
void addFarFieldDefine(const ParamSet& params, std::vector<std::string>& defines);

}  // namespace rgraph::lighting
