// Shared by the bloom mip chain's shaders (bloom_down.frag, bloom_up.frag):
// each draw reads the chain's level at the origin of one mip level (u_image
// shows that mip level alone: a view of it, or the texture with its base and
// max level set to it; or the source image) and writes the next level (or
// 'dst'). Every level is exactly half the one above (bloom_chain.cpp), so a
// pixel's source position is its own times a fixed factor: 2 down, 1/2 up,
// which keeps each level's grid aligned with the source's pixels (a ratio of
// GL's rounded-down level sizes, 1080 rows: 135, 67, 33, stretched the coarse
// levels by up to 5.5%). Taps are clamped half a texel inside the part of
// the level the chain covers, as a sampler clamps to a texture's edge.
layout(binding = 0) uniform sampler2D u_image;
uniform vec2 u_srcScale;  // source texels per pixel written: 2 down, 0.5 up
uniform vec2 u_srcLimit;  // the part of u_image's level the chain covers, in texels from the origin
uniform vec2 u_srcSize;   // u_image's level, in texels

vec2 sourcePosition() { return gl_FragCoord.xy * u_srcScale; }

vec3 tap(vec2 position, vec2 offset) {
  return texture(u_image, clamp(position + offset, vec2(0.5), u_srcLimit - 0.5) / u_srcSize).rgb;
}
