// Shading with the clustered light lists (include/clusters.glsl), for every
// pass that reads them: clustered_deferred.comp per G-buffer pixel,
// forward_lit.frag per fragment (forward+). Needs the includer's lights[]
// (storage buffer 0), include/lighting.glsl, include/shadows.glsl (each
// light times its visibility) and include/clusters.glsl.
// A cluster whose count passed its list's length shades every light (correct,
// slow; with FAR_FIELD, exact) unless CLUSTER_OVERFLOW_TRUNCATE, which keeps the listed ones (wrong
// where the rest reach; the tests use it to show that overflow happened); so
// does every pixel when the buffer holds no lists for this viewport.

// Light i as shaded: with FAR_FIELD (clustered_deferred's far field, which
// adds the unlisted lights' tails) without its cut, so that no tail is lost.
PointLight clusterLight(uint i) {
#if defined(FAR_FIELD)
  return farFieldUncut(lights[i]);
#else
  return lights[i];
#endif
}

// The point lights reaching the surface `s` seen at pixel `px` and positive
// view depth `viewDepth`, out of `lightCount`.
vec3 shadeClusterLights(ivec2 px, float viewDepth, int lightCount, Surface s, vec3 V) {
  vec3 color = vec3(0.0);
  if (lightCount <= 0) return color;
  if (clusterListsFit(uint(data.length()))) {
    const int cluster = clusterAt(px, viewDepth);
    const uint count = data[cluster];
#ifndef CLUSTER_OVERFLOW_TRUNCATE
    if (count <= uint(MAX_CLUSTER_LIGHTS))
#endif
    {
      const uint base = uint(clusterCount()) + uint(cluster) * uint(MAX_CLUSTER_LIGHTS);
      for (uint i = 0u; i < min(count, uint(MAX_CLUSTER_LIGHTS)); ++i) {
        const uint light = data[base + i];
        color += shadePointLight(clusterLight(light), s, V) * lightVisibility(int(light), s);
      }
      return color;
    }
  }
  for (int i = 0; i < lightCount; ++i) color += shadePointLight(clusterLight(uint(i)), s, V) * lightVisibility(i, s);
  return color;
}
