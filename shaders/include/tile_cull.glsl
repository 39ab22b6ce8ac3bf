// Culling a point light's sphere against a screen rectangle's frustum between
// two view depths: shared by tiled_deferred.comp (tiles, half rows, quarters)
// and tiled_bin.comp (the groups of tiles it lists lights for). Needs
// include/frame.glsl first.

// A light's radius with a little slack, so that rounding never drops a light
// a pixel can see.
float slackRadius(float radius) { return radius * 1.001 + 1e-4; }

// Where the pixel rectangle [pxMin, pxMax) (clamped to the viewport) is in
// view space per unit of depth: a point at view depth d is inside its
// frustum when x / d lies in [perDepth0.x, perDepth1.x] (and y likewise),
// since ndc.x = (P00 x + P20 z) / -z with z = -d.
void frustumPerDepth(uvec2 pxMin, uvec2 pxMax, out vec2 perDepth0, out vec2 perDepth1) {
  const vec2 ndc0 = vec2(pxMin) * u_viewport.zw * 2.0 - 1.0;
  const vec2 ndc1 = min(vec2(pxMax), u_viewport.xy) * u_viewport.zw * 2.0 - 1.0;
  const vec2 p = vec2(u_proj[0][0], u_proj[1][1]), pz = vec2(u_proj[2][0], u_proj[2][1]);
  perDepth0 = (ndc0 + pz) / p;
  perDepth1 = (ndc1 + pz) / p;
}

// Whether a sphere (centre: view x, y and depth) meets the box bounding the
// frustum between depths [minDepth, maxDepth] clipped to the sphere's own
// depth range. The frustum's sides are linear in depth, so the box's extremes
// are at the clipped range's ends; clipping first keeps the box small. It is
// tight for lights small against the tile, which sphere-against-plane tests
// pass near the tile's corners. Conservative: any point of the frustum slice
// within the sphere is in the box.
bool sphereMeetsFrustumBox(vec3 c, float r, float minDepth, float maxDepth, vec2 perDepth0, vec2 perDepth1) {
  const float z0 = max(c.z - r, minDepth), z1 = min(c.z + r, maxDepth);
  if (z0 > z1) return false;
  const vec2 boxMin = min(perDepth0 * z0, perDepth0 * z1), boxMax = max(perDepth1 * z0, perDepth1 * z1);
  const vec2 dxy = max(max(boxMin - c.xy, c.xy - boxMax), vec2(0.0));
  const float dz = max(max(z0 - c.z, c.z - z1), 0.0);
  return dot(dxy, dxy) + dz * dz <= r * r;
}

// The world point on the ray through the middle of a frustum (frustumPerDepth),
// halfway through its depth range: where a far field is summed.
vec3 frustumMidPoint(vec2 perDepth0, vec2 perDepth1, float minDepth, float maxDepth) {
  const float d = 0.5 * (minDepth + maxDepth);
  return (u_invView * vec4(0.5 * (perDepth0 + perDepth1) * d, -d, 1.0)).xyz;
}
