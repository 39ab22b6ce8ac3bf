#version 450 core
// Copies src into the output image. Same size: texel for texel; otherwise
// bilinear. u_gamma applies the sRGB transfer (for a linear rgba8 target; an
// srgb8_alpha8 target is encoded by the hardware instead).
layout(location = 0) out vec4 o_color;
uniform sampler2D src;
uniform vec2 u_resolution;
uniform bool u_same_size;
uniform bool u_gamma;

vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  vec4 c = u_same_size ? texelFetch(src, ivec2(gl_FragCoord.xy), 0) : texture(src, gl_FragCoord.xy / u_resolution);
  if (u_gamma) c.rgb = linearToSrgb(c.rgb);
  o_color = c;
}
