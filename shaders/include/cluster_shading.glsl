// Shading with the clustered light lists (include/clusters.glsl), for every
// pass that reads them: clustered_deferred.comp per G-buffer pixel,
// forward_lit.frag per fragment (forward+). Needs the includer's lights[]
// (storage buffer 0), include/lighting.glsl and include/clusters.glsl.
// A cluster whose count passed its list's length shades every light (correct,
// slow) unless CLUSTER_OVERFLOW_TRUNCATE, which keeps the listed ones (wrong
// where the rest reach; the tests use it to show that overflow happened); so
// does every pixel when the buffer holds no lists for this viewport.

// The point lights reaching the surface `s` seen at pixel `px` and positive
// view depth `viewDepth`, out of `lightCount`.
vec3 shadeClusterLights(ivec2 px, float viewDepth, int lightCount, Surface s, vec3 V) {
  vec3 color = vec3(0.0);
  if (lightCount <= 0) return color;
  if (clusterListsFit(uint(data.length()))) {
    // A pixel past the grid (a target larger than the viewport) takes the edge tile's list.
    const ivec2 tile = min(px / TILE_SIZE, clusterTiles() - 1);
    const int cluster = clusterIndex(tile, clusterSlice(viewDepth));
    const uint count = data[cluster];
#ifndef CLUSTER_OVERFLOW_TRUNCATE
    if (count <= uint(MAX_CLUSTER_LIGHTS))
#endif
    {
      const uint base = uint(clusterCount()) + uint(cluster) * uint(MAX_CLUSTER_LIGHTS);
      for (uint i = 0u; i < min(count, uint(MAX_CLUSTER_LIGHTS)); ++i)
        color += shadePointLight(lights[data[base + i]], s, V);
      return color;
    }
  }
  for (int i = 0; i < lightCount; ++i) color += shadePointLight(lights[i], s, V);
  return color;
}
