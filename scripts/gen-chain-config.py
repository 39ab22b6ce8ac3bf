#!/usr/bin/env python3
"""Writes a pipeline config that is a chain of N passes, to time loading.

    scripts/gen-chain-config.py 50000 > /tmp/chain-50k.json
    time build/bin/rgraph validate /tmp/chain-50k.json

Modes (--mode):
  resources  (default) N resources r0..r{N-1}: a clear writes r0, then pass i
             blits r{i-1} into r{i}; the output is the last one.
  fullscreen the same chain with fullscreen passes running one shader
             (invert.frag): many passes, one distinct program for glslang.
  versions   one resource, N versions: a clear writes "img", then each
             fullscreen pass loads the previous version and writes the next
             ("img_1", "img_2", ...).
--reverse declares the passes last to first (the graph order does not change).
"""
import argparse
import json
import sys


def chain(n, mode):
    passes = []
    if mode == "versions":
        resources = {"img": {"format": "rgba8", "size": "output"}}
        passes.append({"name": "p0", "type": "clear", "outputs": {"color": "img"}})
        prev = "img"
        for i in range(1, n):
            cur = "img_%d" % i
            passes.append({"name": "p%d" % i, "type": "fullscreen", "params": {"shader": "gradient.frag"},
                           "inputs": {"color": prev}, "outputs": {"color": cur}})
            prev = cur
        return resources, passes, prev
    resources = {"r%d" % i: {"format": "rgba8", "size": "output"} for i in range(n)}
    passes.append({"name": "p0", "type": "clear", "outputs": {"color": "r0"}})
    for i in range(1, n):
        if mode == "fullscreen":
            passes.append({"name": "p%d" % i, "type": "fullscreen", "params": {"shader": "invert.frag"},
                           "inputs": {"input0": "r%d" % (i - 1)}, "outputs": {"color": "r%d" % i}})
        else:
            passes.append({"name": "p%d" % i, "type": "blit",
                           "inputs": {"src": "r%d" % (i - 1)}, "outputs": {"dst": "r%d" % i}})
    return resources, passes, "r%d" % (n - 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("passes", type=int, help="number of passes (>= 1)")
    ap.add_argument("--mode", choices=["resources", "fullscreen", "versions"], default="resources")
    ap.add_argument("--reverse", action="store_true", help="declare the passes in reverse order")
    args = ap.parse_args()
    if args.passes < 1:
        ap.error("passes must be at least 1")
    resources, passes, output = chain(args.passes, args.mode)
    if args.reverse:
        passes.reverse()
    out = sys.stdout
    # One pass / resource per line, so positions in messages stay readable.
    out.write('{\n  "version": 1,\n  "description": "chain of %d passes (%s)",\n  "resources": {\n'
              % (args.passes, args.mode))
    out.write(",\n".join("    %s: %s" % (json.dumps(k), json.dumps(v)) for k, v in resources.items()))
    out.write('\n  },\n  "passes": [\n')
    out.write(",\n".join("    " + json.dumps(p) for p in passes))
    out.write('\n  ],\n  "output": %s\n}\n' % json.dumps(output))


if __name__ == "__main__":
    main()
