#version 450 core
// One instance per light: for point lights (u_spotVolumes 0) the unit
// icosphere scaled to enclose the light's radius (u_volumeScale makes its
// flat faces reach the sphere); for spot lights (1) GpuScene's spot volume
// (scene.h, makeSpotVolume) bent to the light's cone: its apex at the light,
// its ring z = 1 at r cos(outer) along the axis and radius r sin(outer), its
// cap at r, so that it holds the part of the light's sphere inside the cone
// (the same radius r, from the same cut-off, as a point light's sphere).
// Instance i shades light u_firstLight + i.
#include "include/frame.glsl"

layout(location = 0) in vec3 a_position;
#include "include/lights.glsl"
uniform float u_volumeScale;
uniform int u_firstLight;
uniform int u_spotVolumes;

flat out int v_light;

void main() {
  v_light = u_firstLight + gl_InstanceID;
  PointLight l = lights[v_light];
  float r = max(l.positionRadius.w, 0.0);
  vec3 p;
  if (u_spotVolumes == 0) {
    p = l.positionRadius.xyz + a_position * (r * u_volumeScale);
  } else {
    vec3 axis = l.spot.xyz;
    vec3 t1 = normalize(cross(axis, abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 t2 = cross(axis, t1);  // (t1, t2, axis) right-handed: the mesh keeps its winding
    float c = clamp(l.spot.w, 0.0, 1.0), s = sqrt(1.0 - c * c);
    float z = a_position.z;
    float along = z <= 1.0 ? z * r * c : r * c + (z - 1.0) * r * (1.0 - c);
    vec2 across = a_position.xy * (r * s * u_volumeScale);
    p = l.positionRadius.xyz + axis * along + t1 * across.x + t2 * across.y;
  }
  gl_Position = u_viewProj * vec4(p, 1.0);
}
