// clustered_deferred's far field (FAR_FIELD): per cluster, what its pixels
// shade for the lights its list leaves out, written by clustered_far.comp
// (CLUSTER_FAR_FIELD_WRITER) and read by clustered_deferred.comp.
// Storage buffer 3: one record of CLUSTER_FAR_RECORD uints per cluster (the
// clusters' order of include/clusters.glsl): a bit per direction bin that
// holds light (0: nothing to add: no pixel, an overflowed list, no lights),
// the point it was summed at (xyz floats), then per direction bin
// (far_field.glsl) its radiance, weighted direction, gradient of the weight
// and mean light offset from the point (vec3 each, as floats).
// Needs include/clusters.glsl and include/far_field.glsl first.
#define CLUSTER_FAR_RECORD (4 + FAR_FIELD_BINS * 12)

#ifdef CLUSTER_FAR_FIELD_WRITER
layout(std430, binding = 3) writeonly buffer ClusterFarFields { uint farFields[]; };
#else
layout(std430, binding = 3) readonly buffer ClusterFarFields { uint farFields[]; };
#endif

// false when the bound buffer is smaller than the viewport's clusters need
// (a viewport larger than the target the pass sized it for): no far field.
bool clusterFarFieldsFit(uint bufferUints) { return uint(clusterCount()) * uint(CLUSTER_FAR_RECORD) <= bufferUints; }

#ifndef CLUSTER_FAR_FIELD_WRITER
vec3 clusterFarValue(uint record, int b, int j) {
  const uint at = record + 4u + uint(b * 12 + j * 3);
  return uintBitsToFloat(uvec3(farFields[at], farFields[at + 1u], farFields[at + 2u]));
}

// The far field at surface s in `cluster`: each direction bin shaded as one
// light at its mean light position, scaled by its gradient (as
// tiled_deferred.comp's pixels do with their quarter's bins).
vec3 shadeClusterFarField(int cluster, Surface s, vec3 V) {
  vec3 color = vec3(0.0);
  if (!clusterFarFieldsFit(uint(farFields.length()))) return color;
  const uint record = uint(cluster) * uint(CLUSTER_FAR_RECORD);
  const vec3 offset = s.position - uintBitsToFloat(uvec3(farFields[record + 1u], farFields[record + 2u], farFields[record + 3u]));
  for (uint bits = farFields[record]; bits != 0u; bits &= bits - 1u) {
    const int b = findLSB(bits);
    const vec3 radiance = clusterFarValue(record, b, 0);
    color += farFieldShadeBin(radiance, farFieldScaleAt(radiance, clusterFarValue(record, b, 2), offset),
                              clusterFarValue(record, b, 1), clusterFarValue(record, b, 3) - offset, s, V);
  }
  return color;
}
#endif
