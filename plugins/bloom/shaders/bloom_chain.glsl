// Shared by the bloom mip chain's shaders (bloom_down.frag, bloom_up.frag):
// each draw reads one rectangle of u_image and writes one rectangle of the
// target; both rectangles are in texels of their textures (origin, size). A
// tap is clamped half a texel inside the source rectangle, so bilinear
// filtering never reads a neighbouring level of the atlas.
layout(binding = 0) uniform sampler2D u_image;
uniform vec2 u_imageSize;  // u_image's size in texels
uniform vec4 u_srcRect;    // rectangle read: origin xy, size zw (texels)
uniform vec4 u_dstRect;    // rectangle written: origin xy, size zw (pixels)

// The source position (texels) under this fragment.
vec2 sourcePosition() { return u_srcRect.xy + (gl_FragCoord.xy - u_dstRect.xy) / u_dstRect.zw * u_srcRect.zw; }

vec3 tap(vec2 position, vec2 offset) {
  vec2 p = clamp(position + offset, u_srcRect.xy + 0.5, u_srcRect.xy + u_srcRect.zw - 0.5);
  return texture(u_image, p / u_imageSize).rgb;
}
