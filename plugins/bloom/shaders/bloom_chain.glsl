// Shared by the bloom mip chain's shaders (bloom_down.frag, bloom_up.frag):
// each draw reads one mip level of the chain (u_image shows that level alone:
// a view of it, or the texture with its base and max level set to it) and
// writes another level (or 'dst'), in full. Sampling clamps to the level's
// edge, so no tap reads another level.
layout(binding = 0) uniform sampler2D u_image;
uniform vec2 u_srcSize;  // the level read, in texels
uniform vec2 u_dstSize;  // the image written, in pixels

// The source position (texels) under this fragment: by the ratio of the
// sizes, which follows GL's rounded-down odd levels (1080 rows: 135, 67, 33)
// better than the nominal factor 2 (the 1080p chain's error against the
// bench's reference: 0.70% by the ratio, 0.78% by the factor).
vec2 sourcePosition() { return gl_FragCoord.xy / u_dstSize * u_srcSize; }

vec3 tap(vec2 position, vec2 offset) { return texture(u_image, (position + offset) / u_srcSize).rgb; }
