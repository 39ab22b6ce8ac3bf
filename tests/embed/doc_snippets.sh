#!/usr/bin/env bash
# The C++ in docs/embedding.md and README.md's "Embedding" section compiles
# against the INSTALLED headers, README's usage is docs/embedding.md's, and
# docs/embedding.md quotes renderer.h's GL state contract word for word:
#   doc_snippets.sh PREFIX CXX SOURCE_DIR
# Each ```cpp block becomes the body of a function; the names a block takes
# from the program around it (pipelinePath, camera, renderer...) are declared
# once below, and a block's own declarations hide them.
set -uo pipefail
prefix=$1; cxx=$2; src=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
blocks() { awk '/^```cpp$/ {on = 1; n++; print "// block " n; next} /^```$/ {on = 0} on' "$1"; }
section() { awk -v h="$2" '$0 == h {on = 1; next} /^## / {on = 0} on' "$1"; }

usage_doc=$(section "$src/docs/embedding.md" "## Usage" | awk '/^```cpp$/ {on = 1; next} /^```$/ {exit} on')
usage_readme=$(section "$src/README.md" "## Embedding" | awk '/^```cpp$/ {on = 1; next} /^```$/ {exit} on')
[[ -n "$usage_doc" ]] || fail "docs/embedding.md has no \`\`\`cpp block under '## Usage'"
[[ -n "$usage_readme" ]] || fail "README.md has no \`\`\`cpp block under '## Embedding'"
[[ "$usage_doc" == "$usage_readme" ]] ||
  { diff <(echo "$usage_doc") <(echo "$usage_readme") >&2; fail "README.md's usage differs from docs/embedding.md's"; }

# The GL state contract: docs/embedding.md quotes renderer.h's comment word for word.
flat() { tr '\n' ' ' | sed 's/  */ /g; s/^ //; s/ $//'; }
contract_h=$(awk '/^\/\/ GL state contract\./,/See docs\/embedding.md\./' "$src/core/include/rgraph/renderer.h" |
  sed 's|^// \{0,1\}||; s/^GL state contract\. //; s/ See docs\/embedding.md\.$//' | flat)
contract_doc=$(section "$src/docs/embedding.md" "## The GL state contract" | sed -n 's/^> \{0,1\}//p' | flat)
[[ -n "$contract_h" ]] || fail "renderer.h has no 'GL state contract.' comment ending 'See docs/embedding.md.'"
[[ "$contract_h" == "$contract_doc" ]] ||
  { printf 'renderer.h: %s\ndocs:       %s\n' "$contract_h" "$contract_doc" >&2;
    fail "docs/embedding.md's quoted GL state contract differs from renderer.h's comment"; }

tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
{
  cat <<'PRELUDE'
#include <GL/glcorearb.h>
#include <iostream>
#include <memory>
#include <string>
#include <vector>
#include <rgraph/gl/fullscreen.h>
#include <rgraph/pass_decl.h>
#include <rgraph/registry.h>
#include <rgraph/renderer.h>
namespace given {  // what the snippets take from the program around them
std::string pipelinePath, deferred, gbufferDebug;
rgraph::Camera camera, playerCamera, topDownCamera;
rgraph::PointLight movedLight;
rgraph::RendererOptions options, insetOptions;
rgraph::Diagnostics diags;
std::unique_ptr<rgraph::Renderer> renderer;
}  // namespace given
using namespace given;
PRELUDE
  blocks "$src/docs/embedding.md" | awk '/^\/\/ block / {if (n++) print "  return 0;\n}"; print "int snippet" n "() {"; next} {print "  " $0} END {if (n) print "  return 0;\n}"}'
  echo "int main() { return 0; }"
} >"$tmp/snippets.cpp"
count=$(grep -c '^int snippet' "$tmp/snippets.cpp")
[[ $count -ge 3 ]] || fail "expected at least 3 \`\`\`cpp blocks in docs/embedding.md, found $count"
"$cxx" -std=c++20 -fsyntax-only -Wall -DGL_GLEXT_PROTOTYPES -I"$prefix/include" "$tmp/snippets.cpp" ||
  { cat -n "$tmp/snippets.cpp" >&2; fail "docs/embedding.md's C++ does not compile against $prefix/include"; }
echo "ok: $count C++ blocks of docs/embedding.md compile against the installed headers; README's usage is the same; the GL state contract is quoted as renderer.h states it"
