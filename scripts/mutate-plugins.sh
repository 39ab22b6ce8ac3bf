#!/usr/bin/env bash
# Mutation check of the plugin oracle tests (issue 9, OracleSsao and
# OracleBloom in tests/plugin/plugin_oracle_*_test.cpp; issue 15,
# OracleSsaoUpsample and BloomChainStability): applies single changes to the
# bloom and ssao plugins' shaders, one at a time, runs rgraph_plugin_tests
# --gtest_filter='Oracle*:BloomChain*' on each and prints which changes the
# tests caught (and by which tests).
#
#   scripts/mutate-plugins.sh [BUILD_DIR]     (default: build)
#
# A plugin reads its shaders at run time from share/rgraph/plugins/<name>
# above its library. The script copies the built plugin libraries and the
# source shaders into a temporary install-like folder that RGRAPH_PLUGIN_PATH
# puts first in the plugin search path, and mutates only that copy: neither
# the working tree nor the build folder is modified. Before the mutations, the
# unchanged copy must pass and a copy with a syntax error must fail (proof
# that the copy is what the tests read).
#
# Exit status: 0 when every mutation compiles and is caught, 1 otherwise or on
# a setup error.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
tests="$build_dir/bin/rgraph_plugin_tests"
libs="$build_dir/lib/rgraph/plugins"
if [[ ! -x "$tests" || ! -f "$libs/librgraph_bloom.so" || ! -f "$libs/librgraph_ssao.so" ]]; then
  echo "mutate-plugins.sh: $tests or the plugins in $libs not found: build rgraph_plugin_tests in $build_dir first" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export RGRAPH_PLUGIN_PATH="$work/lib/rgraph/plugins"

fresh_copy() {
  rm -rf "$work/lib" "$work/share"
  mkdir -p "$work/lib/rgraph/plugins" "$work/share/rgraph/plugins"
  cp "$libs/librgraph_bloom.so" "$libs/librgraph_ssao.so" "$work/lib/rgraph/plugins/"
  for p in bloom ssao; do cp -r "plugins/$p/shaders" "$work/share/rgraph/plugins/$p"; done
}
run_tests() { "$tests" --gtest_filter='Oracle*:BloomChain*' >"$work/log" 2>&1; }

# plugin/shader@name@original text@replacement (each original must occur exactly once)
mutations=$(cat <<'EOF'
bloom/bloom_blur.frag@blur weight w1 0.1945945946 -> 0.1946@0.1945945946@0.1946
bloom/bloom_blur.frag@blur weight w4 0.016 -> 0.026@0.0162162162@0.0262162162
bloom/bloom_blur.frag@blur 7 taps instead of 9@for (int i = 1; i < 5; ++i)@for (int i = 1; i < 4; ++i)
bloom/bloom_blur.frag@blur positive taps one texel farther@uv + u_step * float(i)@uv + u_step * float(i + 1)
bloom/bloom_composite.frag@composite ignores intensity@.rgb * u_intensity;@.rgb;
bloom/bloom_composite.frag@composite bloom x 0.99@base + bloom@base + bloom * 0.99
bloom/bloom_bright.frag@bright threshold x 0.9@brightness - u_threshold)@brightness - u_threshold * 0.9)
bloom/bloom_bright.frag@bright knee 4k -> 2k@soft * soft / (4.0@soft * soft / (2.0
bloom/bloom_bright.frag@bright leaks 1e-3 below the threshold@max(soft, brightness - u_threshold)@max(soft, brightness - u_threshold + 1e-3)
bloom/bloom_bright.frag@bright point-samples (no 2x2 average)@vec3 c = texture(u_hdr, v_uv).rgb;@vec3 c = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
ssao/ssao.frag@ssao bias sign flipped@scene.z >= s.z + u_bias@scene.z >= s.z - u_bias
ssao/ssao.frag@ssao bias dropped@scene.z >= s.z + u_bias@scene.z >= s.z
ssao/ssao.frag@ssao bias x 4@scene.z >= s.z + u_bias@scene.z >= s.z + 4.0 * u_bias
ssao/ssao.frag@ssao comparison reversed@scene.z >= s.z + u_bias ? 1.0 : 0.0@scene.z <= s.z + u_bias ? 1.0 : 0.0
ssao/ssao.frag@ssao radius x 0.7@vec3 s = P + TBN * u_kernel[i] * u_radius;@vec3 s = P + TBN * u_kernel[i] * u_radius * 0.7;
ssao/ssao.frag@ssao radius x 1.4@vec3 s = P + TBN * u_kernel[i] * u_radius;@vec3 s = P + TBN * u_kernel[i] * u_radius * 1.4;
ssao/ssao.frag@ssao range check dropped@float range = smoothstep(0.0, 1.0, u_radius / max(abs(P.z - scene.z), 1e-4));@float range = 1.0;
ssao/ssao.frag@ssao range check halved@u_radius / max(abs(P.z - scene.z), 1e-4)@0.5 * u_radius / max(abs(P.z - scene.z), 1e-4)
ssao/ssao.frag@ssao occlusion halved@occlusion / float(n)@occlusion / float(2 * n)
ssao/ssao.frag@ssao power ignored@, u_power);@, 1.0);
ssao/ssao.frag@ssao hemisphere below the surface@mat3 TBN = mat3(T, cross(N, T), N);@mat3 TBN = mat3(T, cross(N, T), -N);
ssao/ssao_blur.frag@ssao_blur normalisation off@sum / float(4 * u_size * u_size)@sum / float(4 * u_size * u_size + 1)
ssao/ssao_blur.frag@ssao_blur one row short@for (int y = -u_size; y < u_size; ++y)@for (int y = -u_size; y < u_size - 1; ++y)
ssao/ssao_upsample.frag@ssao_upsample depth weight off@ * exp(-d * d);@;
bloom/bloom_down.frag@chain downsample point-sampled@outColor = vec4(sum / total, 1.0);@outColor = vec4(texelFetch(u_image, ivec2(c), 0).rgb, 1.0);
bloom/bloom_up.frag@chain tent centre weight halved@vec3 sum = 4.0 * tap(c, vec2(0.0));@vec3 sum = 2.0 * tap(c, vec2(0.0));
EOF
)

fresh_copy
if ! run_tests; then
  echo "mutate-plugins.sh: the oracle tests fail on the unchanged plugins; fix that first:" >&2
  tail -20 "$work/log" >&2
  exit 1
fi
echo 'this is not GLSL' >>"$work/share/rgraph/plugins/ssao/ssao.frag"
if run_tests; then
  echo "mutate-plugins.sh: a broken ssao.frag copy under $work did not fail the tests: they do not read it" >&2
  exit 1
fi

missed=0
printf '%-44s  %s\n' mutation result
while IFS='@' read -r file name from to; do
  fresh_copy
  path="$work/share/rgraph/plugins/${file%%/*}/${file#*/}"
  if ! python3 - "$path" "$from" "$to" <<'PY'
import sys
path, old, new = sys.argv[1:4]
text = open(path).read()
if text.count(old) != 1:
    sys.exit(f"'{old}' occurs {text.count(old)} times in {path} (expected once): update the mutation list")
open(path, "w").write(text.replace(old, new))
PY
  then
    exit 1
  fi
  if run_tests; then
    result=MISSED
    missed=$((missed + 1))
  elif grep -q '\.frag:[0-9]*: error' "$work/log"; then
    # A mutation that does not compile proves nothing about the tests.
    result="INVALID (does not compile)"
    missed=$((missed + 1))
  else
    result="caught by $(grep -E '^\[  FAILED  \] (Oracle|BloomChain)' "$work/log" | sed 's/^\[  FAILED  \] //; s/ (.*//' | sort -u |
      sed 's/^Oracle//' | paste -sd, -)"
  fi
  printf '%-44s  %s\n' "$name" "$result"
done <<<"$mutations"

if ((missed > 0)); then
  echo "$missed mutation(s) not caught" >&2
  exit 1
fi
echo "every mutation caught"
