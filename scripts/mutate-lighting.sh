#!/usr/bin/env bash
# Mutation check of the lighting oracle tests (issue 9): applies single changes
# to shaders/include/lighting.glsl, one at a time, runs rgraph_oracle_tests on
# each and prints which changes the tests caught.
#
#   scripts/mutate-lighting.sh [BUILD_DIR]     (default: build)
#
# The mutations are applied to a copy of shaders/ in a temporary folder that
# RGRAPH_SHADER_DIR puts first in the shader search path (shaders are read at
# run time, so no rebuild is needed), not to the source tree: the working tree
# is never modified, even when the script is interrupted, and other test runs
# in the same tree are not disturbed. Before the mutations, the unchanged copy
# must pass and a copy with a syntax error must fail (proof that the copy, not
# the source tree, is what the tests read).
#
# Exit status: 0 when every "term" mutation compiles and is caught, 1 otherwise or on a
# setup error. "guard" mutations (the small epsilons that only keep degenerate
# points finite) are reported but may survive.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
tests="$build_dir/bin/rgraph_oracle_tests"
if [[ ! -x "$tests" ]]; then
  echo "mutate-lighting.sh: $tests not found: build the target rgraph_oracle_tests in $build_dir first" >&2
  exit 1
fi
src=shaders/include/lighting.glsl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export RGRAPH_SHADER_DIR="$work/shaders"

fresh_copy() { rm -rf "$work/shaders"; cp -r shaders "$work/shaders"; }
run_tests() { "$tests" --gtest_filter='Oracle*' >"$work/log" 2>&1; }

# kind@name@original text@replacement (each original must occur exactly once)
mutations=$(cat <<'EOF'
term@blinn-phong exponent 16 -> 17@pow(max(dot(N, H), 0.0), 16.0)@pow(max(dot(N, H), 0.0), 17.0)
term@blinn-phong specular intensity dropped@16.0) * specular * radiance@16.0) * radiance
term@blinn-phong specular term dropped@return diffuse + spec;@return diffuse;
term@blinn-phong diffuse albedo dropped@max(dot(N, L), 0.0) * albedo * radiance@max(dot(N, L), 0.0) * radiance
term@blinn-phong diffuse N.L dropped@vec3 diffuse = max(dot(N, L), 0.0) *@vec3 diffuse = 1.0 *
term@half vector L+V -> L+N@vec3 h = L + V;@vec3 h = L + N;
term@PI 3.14159 -> 3.2@3.14159265359@3.2
term@cook-torrance diffuse 1/pi dropped@kD * albedo / PI@kD * albedo
term@F0 0.04 -> 0.05@mix(vec3(0.04)@mix(vec3(0.05)
term@geometry k /8 -> /2@r * r / 8.0@r * r / 2.0
term@geometry r+1 -> r@float r = roughness + 1.0;@float r = roughness;
term@geometry Schlick-GGX -> N.X@return NdotX / (NdotX * (1.0 - k) + k);@return NdotX;
term@geometry NdotL factor dropped@geometrySchlickGGX(NdotV, roughness) * geometrySchlickGGX(NdotL, roughness)@geometrySchlickGGX(NdotV, roughness)
term@fresnel power 5 -> 4@0.0, 1.0), 5.0)@0.0, 1.0), 4.0)
term@fresnel at N.V instead of H.V@fresnelSchlick(max(dot(H, V), 0.0), F0)@fresnelSchlick(max(dot(N, V), 0.0), F0)
term@fresnel F0 term dropped@return F0 + (1.0 - F0) *@return (1.0 - F0) *
term@GGX alpha = roughness (not squared)@float a = roughness * roughness;@float a = roughness;
term@GGX a2 = a@float a2 = a * a;@float a2 = a;
term@GGX 1/pi dropped@a2 / max(PI * d * d, 1e-7)@a2 / max(d * d, 1e-7)
term@GGX denominator d^2 -> d@a2 / max(PI * d * d, 1e-7)@a2 / max(PI * d, 1e-7)
term@GGX denominator +1 dropped@float d = NdotH * NdotH * (a2 - 1.0) + 1.0;@float d = NdotH * NdotH * (a2 - 1.0);
term@specular denominator 4 -> 2@4.0 * NdotV * NdotL@2.0 * NdotV * NdotL
term@specular denominator guard 0.001 -> 0.0001@NdotL, 0.001)@NdotL, 0.0001)
term@specular denominator guard 0.001 -> 0.01@NdotL, 0.001)@NdotL, 0.01)
term@kD metallic term dropped@* (1.0 - metallic);@;
term@kD (1 - F) dropped@vec3 kD = (vec3(1.0) - F) *@vec3 kD = vec3(1.0) *
term@cook-torrance N.L factor dropped@* radiance * NdotL;@* radiance;
term@N.V clamp -> 1@float NdotV = max(dot(N, V), 0.0);@float NdotV = 1.0;
term@N.L clamp removed@float NdotL = max(dot(N, L), 0.0);@float NdotL = dot(N, L);
term@attenuation constant term dropped@k.x + k.y * d + k.z * d * d@k.y * d + k.z * d * d
term@attenuation linear term dropped@k.x + k.y * d + k.z * d * d@k.x + k.z * d * d
term@attenuation quadratic term dropped@k.x + k.y * d + k.z * d * d@k.x + k.y * d
term@attenuation quadratic d^2 -> d@k.x + k.y * d + k.z * d * d@k.x + k.y * d + k.z * d
term@classic no-cut-off (negative radius) ignored@(radius < 0.0 || d <= radius) ? a : 0.0@(d <= radius) ? a : 0.0
term@classic cut-off at the radius ignored@(radius < 0.0 || d <= radius) ? a : 0.0@a
term@smooth x*x -> x@max(1.0 - x * x, 0.0)@max(1.0 - x, 0.0)
term@smooth radius doubled@float x = d / max(radius, 1e-6);@float x = d / max(2.0 * radius, 1e-6);
term@point light attenuation dropped@light.color.rgb * att@light.color.rgb
term@point light colour dropped@light.color.rgb * att@vec3(att)
term@ambient AO factor dropped@u_ambient.rgb * s.albedo * s.ao@u_ambient.rgb * s.albedo
term@ambient albedo dropped@u_ambient.rgb * s.albedo * s.ao@u_ambient.rgb * s.ao
term@ambient dropped@u_ambient.rgb * s.albedo * s.ao@vec3(0.0)
term@directional light dropped@if (u_dirLightDir.w <= 0.0) return vec3(0.0);@return vec3(0.0);
term@directional light direction negated@normalize(-u_dirLightDir.xyz)@normalize(u_dirLightDir.xyz)
term@spot cone dropped@attenuate(light, d) * spotCone(light, L)@attenuate(light, d)
term@spot cone not squared@  return t * t;@  return t;
term@spot cone axis reversed@dot(light.spot.xyz, -L)@dot(light.spot.xyz, L)
term@spot cone scale dropped@ - light.spot.w) * light.attenuation.w, 0.0@ - light.spot.w), 0.0
term@spot cone outer cosine dropped@(dot(light.spot.xyz, -L) - light.spot.w)@dot(light.spot.xyz, -L)
term@directional light colour dropped@u_dirLightColor.rgb, s)@vec3(1.0), s)
guard@half-vector guard 1e-12 -> 1e-6@dot(h, h) > 1e-12@dot(h, h) > 1e-6
guard@GGX guard 1e-7 -> 1e-5@PI * d * d, 1e-7)@PI * d * d, 1e-5)
guard@attenuation guard 1e-6 -> 1e-3@d * d, 1e-6)@d * d, 1e-3)
EOF
)

fresh_copy
if ! run_tests; then
  echo "mutate-lighting.sh: the oracle tests fail on the unchanged shaders; fix that first:" >&2
  tail -20 "$work/log" >&2
  exit 1
fi
echo 'this is not GLSL' >>"$work/$src"
if run_tests; then
  echo "mutate-lighting.sh: a broken $src copy in $RGRAPH_SHADER_DIR did not fail the tests: they do not read it" >&2
  exit 1
fi

missed=0
printf '%-6s  %-52s  %s\n' kind mutation result
while IFS='@' read -r kind name from to; do
  fresh_copy
  if ! python3 - "$work/$src" "$from" "$to" <<'PY'
import sys
path, old, new = sys.argv[1:4]
text = open(path).read()
if text.count(old) != 1:
    sys.exit(f"'{old}' occurs {text.count(old)} times in lighting.glsl (expected once): update the mutation list")
open(path, "w").write(text.replace(old, new))
PY
  then
    exit 1
  fi
  if run_tests; then
    result=MISSED
    [[ "$kind" == term ]] && missed=$((missed + 1))
  elif grep -q 'lighting.glsl:[0-9]*: error' "$work/log"; then
    # A mutation that does not compile proves nothing about the tests.
    result="INVALID (does not compile)"
    [[ "$kind" == term ]] && missed=$((missed + 1))
  else
    failed=$(grep '^\[  FAILED  \] Oracle' "$work/log" | sed 's/ (.*//' | sort -u | wc -l)
    result="caught (${failed} failing tests)"
  fi
  printf '%-6s  %-52s  %s\n' "$kind" "$name" "$result"
done <<<"$mutations"

if ((missed > 0)); then
  echo "$missed term mutation(s) not caught" >&2
  exit 1
fi
echo "every term mutation caught"
