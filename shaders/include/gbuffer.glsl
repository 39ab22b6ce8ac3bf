// G-buffer layouts. Exactly one of these is defined by the pass that includes
// this file: GBUFFER_LEARNOPENGL, GBUFFER_PBR, GBUFFER_COMPACT, GBUFFER_FP32.
// What each stores, in which formats, is the layout table in
// passes/common/include/rgraph/passes/gbuffer_layout.h (compact: no position,
// rebuilt from depth; octahedral normal rg; fp32: the pbr layout in rgba32f,
// the reference; optional emissive and reflectance targets, HAS_EMISSIVE_TARGET
// and HAS_REFLECTANCE_TARGET). gbuffer.frag writes the targets in the table's slot order.
// include/gbuffer_read.glsl reads them back.

struct Surface {
  vec3 position;   // world space
  vec3 normal;     // world space, unit length
  vec3 albedo;
  float specular;  // Blinn-Phong specular intensity
  float metallic;
  float roughness;
  float ao;
  vec3 emissive;   // emitted radiance, added once after lighting (emissiveTerm)
  vec3 f0;         // dielectric reflectance at normal incidence (KHR_materials_specular; 0.04 by default)
  float f90;       // dielectric reflectance at grazing angles, the specular weight (1 by default)
  bool covered;    // false where no geometry was drawn
};

// Octahedral normal encoding (unit vector <-> [-1,1]^2): two half floats keep
// normals to about 1e-3, where rgb16 x 3 costs half as much again.
vec2 octWrap(vec2 v) { return (1.0 - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
vec2 encodeOctahedral(vec3 n) {
  n /= (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z >= 0.0 ? n.xy : octWrap(n.xy);
}
vec3 decodeOctahedral(vec2 e) {
  vec3 n = vec3(e.xy, 1.0 - abs(e.x) - abs(e.y));
  float t = clamp(-n.z, 0.0, 1.0);
  n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
  return normalize(n);
}

// World position from a depth-buffer value at a pixel (compact layout).
vec3 positionFromDepth(vec2 uv, float depth, mat4 invProj, mat4 invView) {
  vec4 clip = vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  vec4 view = invProj * clip;
  view /= view.w;
  return (invView * view).xyz;
}

// A normal that is zero or not finite would poison every light with NaN:
// fall back to "facing the viewer" so the pixel stays finite.
vec3 safeNormal(vec3 n, vec3 fallback) {
  float len2 = dot(n, n);
  if (!(len2 > 1e-12) || isinf(len2) || isnan(len2)) return fallback;
  return n * inversesqrt(len2);
}

// Motion vector in UV units from a point's clip positions this frame and the
// last (both unjittered): uv_now - uv_prev, so the point was at uv - velocity.
vec2 screenVelocity(vec4 clipNow, vec4 clipPrev) {
  return (clipNow.xy / clipNow.w - clipPrev.xy / clipPrev.w) * 0.5;
}
