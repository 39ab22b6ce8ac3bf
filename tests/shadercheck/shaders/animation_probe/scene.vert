#version 450
// A scene vertex shader whose SCENE_ANIMATION variant does not compile: the
// plain variant is fine, so only a check of both variants finds the error
// (ShaderCheck.SceneProgramsAreCheckedInTheirAnimatedVariantToo).
layout(location = 0) in vec3 a_position;

void main() {
#ifdef SCENE_ANIMATION
  vec3 bent = a_position * undeclaredJointScale;
#else
  vec3 bent = a_position;
#endif
  gl_Position = vec4(bent, 1.0);
}
