#version 450 core
// Vignette: darkens the image towards its corners.
//   colour * clamp(1 - strength * r^2, 0, 1), r = 0 at the centre, 1 at a corner.
in vec2 v_uv;                                   // from rgraph's fullscreen.vert: 0..1, (0,0) bottom left
layout(binding = 0) uniform sampler2D u_src;    // the "src" slot, bound to unit 0 by the pass
uniform float u_strength;                       // the "strength" parameter
layout(location = 0) out vec4 outColor;         // the "dst" slot (colour attachment 0)

void main() {
  vec4 color = texelFetch(u_src, ivec2(gl_FragCoord.xy), 0);
  float r = length(v_uv - 0.5) * 1.41421356;
  outColor = vec4(color.rgb * clamp(1.0 - u_strength * r * r, 0.0, 1.0), color.a);
}
