// What a light can reach, for the passes that cull lights against screen
// tiles and clusters (tiled_deferred.comp, clustered_build.comp), stated
// once for all of them. Needs include/frame.glsl first.

// A sphere (xyz world centre, w radius) holding every point the light
// lights. A point light: its cut-off sphere. A spot light: the smallest
// sphere around the part of that sphere inside its cone (a spherical
// sector of radius r and half-angle a): up to 45 degrees the sphere through
// the apex and the rim circle (centre r / (2 cos a) along the axis, that
// radius); wider, the rim circle's own (centre r cos a along the axis,
// radius r sin a). w negative: no cut-off, the light reaches everything.
vec4 lightBounds(PointLight l) {
  const vec4 pr = l.positionRadius;
  const float c = l.spot.w;  // cos(outer cone angle); -2 for a point light
  if (pr.w < 0.0 || c <= 0.0) return pr;
  if (c >= 0.70710678) {
    const float h = pr.w / (2.0 * c);
    return vec4(pr.xyz + l.spot.xyz * h, h);
  }
  return vec4(pr.xyz + l.spot.xyz * (pr.w * c), pr.w * sqrt(1.0 - c * c));
}

// Whether a cone (apex, unit axis, cos of its half-angle, at most 90
// degrees) may reach a sphere, all in one space: false only when the sphere
// lies wholly outside the cone's side. across cos - along sin is the
// distance from the centre to the side's line in their common plane; behind
// the apex the true distance (to the apex) is larger, so the test stays
// conservative there.
bool coneMeetsSphere(vec3 apex, vec3 axis, float cosAngle, vec3 centre, float radius) {
  const vec3 v = centre - apex;
  const float along = dot(v, axis);
  const float across = sqrt(max(dot(v, v) - along * along, 0.0));
  return across * cosAngle - along * sqrt(max(1.0 - cosAngle * cosAngle, 0.0)) <= radius;
}

// Whether light l may light a point of the view-space box [lo, hi], beyond
// what lightBounds() already says: true for a point light; for a spot light,
// whether its cone meets the box's bounding sphere (with the same slack as
// the sphere tests, so that rounding never drops a light a pixel can see).
bool spotMayReachViewBox(PointLight l, vec3 lo, vec3 hi) {
  if (l.spot.w < -1.0) return true;
  const vec3 apex = (u_view * vec4(l.positionRadius.xyz, 1.0)).xyz;
  const vec3 axis = mat3(u_view) * l.spot.xyz;
  const float radius = 0.5 * length(hi - lo);
  return coneMeetsSphere(apex, axis, l.spot.w, 0.5 * (lo + hi), radius * 1.001 + 1e-4);
}
