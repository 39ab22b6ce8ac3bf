#version 450 core
// The hazard harness's read-back of a multisampled texture
// (core/src/renderer/texture_snapshot.cpp): each sample's four components as
// their bits (floats through floatBitsToUint) at
// ((layer * height + y) * width + x) * samples + sample.
// Defines: ARRAYED (a 2D multisample array), INT_TEXELS or UINT_TEXELS (an
// integer format; neither: float, normalized and depth formats).
layout(local_size_x = 8, local_size_y = 8) in;

#if defined(INT_TEXELS)
#define SAMPLER isampler2DMS
#define SAMPLER_ARRAY isampler2DMSArray
#define TEXEL ivec4
#define BITS(v) uvec4(v)
#elif defined(UINT_TEXELS)
#define SAMPLER usampler2DMS
#define SAMPLER_ARRAY usampler2DMSArray
#define TEXEL uvec4
#define BITS(v) (v)
#else
#define SAMPLER sampler2DMS
#define SAMPLER_ARRAY sampler2DMSArray
#define TEXEL vec4
#define BITS(v) floatBitsToUint(v)
#endif

#if defined(ARRAYED)
layout(binding = 0) uniform SAMPLER_ARRAY u_src;
#else
layout(binding = 0) uniform SAMPLER u_src;
#endif
layout(std430, binding = 0) writeonly buffer Words { uvec4 words[]; };
uniform int u_samples;

void main() {
  const ivec3 p = ivec3(gl_GlobalInvocationID);
  const ivec2 size = textureSize(u_src).xy;
  if (p.x >= size.x || p.y >= size.y) return;
  for (int s = 0; s < u_samples; ++s) {
#if defined(ARRAYED)
    const TEXEL v = texelFetch(u_src, p, s);
#else
    const TEXEL v = texelFetch(u_src, p.xy, s);
#endif
    words[((p.z * size.y + p.y) * size.x + p.x) * u_samples + s] = BITS(v);
  }
}
