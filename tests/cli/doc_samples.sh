#!/usr/bin/env bash
# Samples of rgraph's output shown in markdown are the program's output.
#
#   doc_samples.sh check|update RGRAPH FILE.md [PLUGIN_DIR...]
#
# A sample is a line
#   <!-- output of: rgraph ARGS; plugin folder shown as DIR -->
# ("; plugin folder shown as DIR" is optional) followed by a fenced block
# (```text) holding what `rgraph ARGS` prints. `check` runs the command (the
# PLUGIN_DIRs in $RGRAPH_PLUGIN_PATH) and fails on any difference, printing
# it; `update` rewrites the blocks. A plugin's folder in the output
# ("(/some/build/lib/rgraph/plugins/librgraph_bloom.so)") is shown as DIR, so
# the sample does not name the machine it was made on. A file without any
# sample fails: the marker must not get lost in an edit.
#
# After changing what `rgraph passes` prints:
#   bash tests/cli/doc_samples.sh update build/bin/rgraph docs/writing-a-pass.md
set -uo pipefail
mode=$1 rgraph=$2 file=$3
shift 3
[[ $mode == check || $mode == update ]] || { echo "usage: doc_samples.sh check|update RGRAPH FILE [PLUGIN_DIR...]" >&2; exit 2; }
plugin_path=$(IFS=:; echo "$*")
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT

mapfile -t lines <"$file"
samples=0 fail=0 i=0 n=${#lines[@]}
: >"$tmp/new"
while ((i < n)); do
  line=${lines[i]}
  echo "$line" >>"$tmp/new"
  i=$((i + 1))
  [[ $line =~ ^'<!-- output of: rgraph '(.*)' -->'$ ]] || continue
  spec=${BASH_REMATCH[1]}
  args=${spec%%; plugin folder shown as *}
  shown=""
  [[ $spec == *'; plugin folder shown as '* ]] && shown=${spec##*; plugin folder shown as }
  samples=$((samples + 1))
  # shellcheck disable=SC2086  # ARGS are words, as on a command line
  RGRAPH_PLUGIN_PATH=$plugin_path "$rgraph" $args >"$tmp/now" 2>"$tmp/err"
  rc=$?
  if ((rc != 0)); then
    echo "FAIL: $file:$i: rgraph $args: exit $rc: $(cat "$tmp/err")" >&2
    exit 1
  fi
  [[ -n $shown ]] && sed -i -E "s#\\(/[^()]*/(librgraph_[A-Za-z0-9_]+\\.so)\\)#(${shown}/\\1)#" "$tmp/now"
  # The old block: blank lines, ```text, its lines, ```.
  while ((i < n)) && [[ -z ${lines[i]} ]]; do echo "" >>"$tmp/new"; i=$((i + 1)); done
  if ((i >= n)) || [[ ${lines[i]} != '```text' ]]; then
    echo "FAIL: $file:$((i + 1)): the marker '$line' must be followed by a \`\`\`text block" >&2
    exit 1
  fi
  i=$((i + 1))
  : >"$tmp/old"
  while ((i < n)) && [[ ${lines[i]} != '```' ]]; do echo "${lines[i]}" >>"$tmp/old"; i=$((i + 1)); done
  ((i < n)) || { echo "FAIL: $file: the sample block of 'rgraph $args' is not closed" >&2; exit 1; }
  i=$((i + 1))
  { echo '```text'; cat "$tmp/now"; echo '```'; } >>"$tmp/new"
  [[ $mode == check ]] || continue
  if diff -u --label "$file: rgraph $args (as shown)" --label "rgraph $args (as it prints now)" \
      "$tmp/old" "$tmp/now" >&2; then
    echo "ok: $file: rgraph $args ($(wc -l <"$tmp/now") lines)"
  else
    echo "FAIL: $file: the sample of 'rgraph $args' is not what it prints (regenerate: bash tests/cli/doc_samples.sh update RGRAPH $file)" >&2
    fail=1
  fi
done

((samples > 0)) || { echo "FAIL: $file has no '<!-- output of: rgraph ... -->' sample" >&2; exit 1; }
if [[ $mode == update ]]; then
  cp "$tmp/new" "$file"
  echo "updated $samples sample(s) in $file"
fi
exit $fail
