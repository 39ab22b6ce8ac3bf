#!/usr/bin/env python3
"""Regenerates the bench run docs/performance.md shows, and the figure tables it quotes.

    scripts/update-bench-figures.py build            # timed `rgraph bench --quick` into docs/images/bench
    scripts/update-bench-figures.py build --replot   # no rendering: tables and charts from the committed run
    scripts/update-bench-figures.py build --aa-only  # timed `rgraph bench --quick --only aa`, merged into the run
    scripts/update-bench-figures.py build --lights-only  # timed `rgraph bench --quick --only lights`, merged
    scripts/update-bench-figures.py build --pillars-only  # timed `rgraph bench --quick --only pillars`, merged

The timed run writes docs/images/bench/{results.csv,results.json,figures.md}
and the charts; then every `<!-- bench-figures:NAME -->` ...
`<!-- /bench-figures:NAME -->` block of docs/performance.md is replaced by the
table of the same name from figures.md. Review the diff before committing:
the prose around the tables quotes some of these numbers and speed ratios
(those are measured, not generated: give them as ranges over several runs).
tests/bench_cli/doc_figures_test.cpp fails while a block or the committed run
differs from what the code produces.
"""
import argparse
import csv
import json
import shutil
import tempfile
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BENCH_DIR = ROOT / "docs" / "images" / "bench"
PAGE = ROOT / "docs" / "performance.md"
BLOCK = re.compile(r"(<!-- bench-figures:(?P<name>[a-z_]+) -->\n)(?P<body>.*?)(<!-- /bench-figures:(?P=name) -->)", re.S)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build_dir", help="CMake build folder holding bin/rgraph")
    ap.add_argument("--replot", action="store_true", help="redraw from the committed results.json, render nothing")
    ap.add_argument("--aa-only", action="store_true",
                    help="rerun only the aa axis and replace its rows in the committed run (the rest is kept)")
    ap.add_argument("--lights-only", action="store_true",
                    help="rerun only the light-count axis (with the exact loop at each count) and merge its points "
                         "into the committed run (the rest is kept)")
    ap.add_argument("--pillars-only", action="store_true",
                    help="rerun only the pillars axis (tiled and clustered on many-lights:N:pillars, and on the "
                         "field at the same counts) and merge its points into the committed run")
    args = ap.parse_args()
    rgraph = pathlib.Path(args.build_dir) / "bin" / "rgraph"
    if not rgraph.exists():
        print(f"error: {rgraph} not found (build first)", file=sys.stderr)
        return 1
    if args.aa_only:
        if merge_aa_run(rgraph) != 0:
            return 1
        args.replot = True
    if args.lights_only:
        if merge_axis_run(rgraph, "lights") != 0:
            return 1
        args.replot = True
    if args.pillars_only:
        if merge_axis_run(rgraph, "pillars") != 0:
            return 1
        args.replot = True
    cmd = [str(rgraph), "bench", "--out", str(BENCH_DIR)]
    cmd += ["--replot", str(BENCH_DIR / "results.json")] if args.replot else ["--quick"]
    if subprocess.call(cmd) != 0:
        return 1
    tables = {m["name"]: m["body"] for m in BLOCK.finditer((BENCH_DIR / "figures.md").read_text())}
    page = PAGE.read_text()
    quoted = {m["name"] for m in BLOCK.finditer(page)}
    for name in sorted(set(tables) - quoted):
        print(f"note: docs/performance.md does not quote table '{name}' (add its markers)", file=sys.stderr)
    for name in sorted(quoted - set(tables)):
        print(f"error: docs/performance.md quotes '{name}', which bench no longer writes", file=sys.stderr)
    page = BLOCK.sub(lambda m: m.group(1) + tables.get(m["name"], m["body"]) + m.group(4), page)
    PAGE.write_text(page)
    print(f"updated {PAGE.relative_to(ROOT)} from {(BENCH_DIR / 'figures.md').relative_to(ROOT)}")
    return 0 if quoted <= set(tables) else 1


def merge_aa_run(rgraph: pathlib.Path) -> int:
    """Runs the aa axis alone and puts its rows into the committed results.json and results.csv."""
    with tempfile.TemporaryDirectory() as tmp:
        if subprocess.call([str(rgraph), "bench", "--quick", "--only", "aa", "--out", tmp]) != 0:
            return 1
        fresh = json.loads((pathlib.Path(tmp) / "results.json").read_text())
        run = json.loads((BENCH_DIR / "results.json").read_text())
        run["aa"] = fresh["aa"]
        run["aa_reference"] = fresh["aa_reference"]
        run["checks"] = {k: v for k, v in run["checks"].items() if not k.startswith("aa_")}
        run["checks"].update({k: v for k, v in fresh["checks"].items() if k.startswith("aa_")})
        (BENCH_DIR / "results.json").write_text(json.dumps(run, indent=2) + "\n")
        with open(pathlib.Path(tmp) / "results.csv", newline="") as f:
            fresh_rows = list(csv.reader(f))
        with open(BENCH_DIR / "results.csv", newline="") as f:
            rows = [r for r in csv.reader(f) if r and r[0] != "aa"]
        header = fresh_rows[0]  # with the aa columns
        rows = [header] + [r + [""] * (len(header) - len(r)) for r in rows[1:]] + [r for r in fresh_rows[1:] if r[0] == "aa"]
        with open(BENCH_DIR / "results.csv", "w", newline="") as f:
            csv.writer(f, lineterminator="\n").writerows(rows)
        for ext in ("svg", "png"):
            shutil.copy(pathlib.Path(tmp) / f"aa_ms_vs_error.{ext}", BENCH_DIR)
    return 0


def point_key(p: dict) -> tuple:
    return (p["method"], p["layout"], round(p["threshold"], 8), p["lights"], p["width"], p["height"],
            p.get("scene_variant", ""))


# The checks each axis's run replaces.
AXIS_CHECKS = {"lights": ("exact_reference_1024", "flat_cost_64_to_1024", "culling_vs_fullscreen_1024"),
               "pillars": ("tiles_vs_clusters_pillars",)}


def merge_axis_run(rgraph: pathlib.Path, axis: str) -> int:
    """Runs one lighting axis alone (lights: with the exact loop at each count) and merges its points into the
    committed results.json and results.csv: new points are added; a point the run already has keeps its
    other axes and takes the fresh figures (lights), or is left as it was (pillars: the field's points it
    renders only to compare with, in its own check); the axis's checks are replaced."""
    with tempfile.TemporaryDirectory() as tmp:
        if subprocess.call([str(rgraph), "bench", "--quick", "--only", axis, "--out", tmp]) != 0:
            return 1
        fresh = json.loads((pathlib.Path(tmp) / "results.json").read_text())
        run = json.loads((BENCH_DIR / "results.json").read_text())
        by_key = {point_key(p): i for i, p in enumerate(run["points"])}
        axes_of = {}
        for p in fresh["points"]:
            i = by_key.get(point_key(p))
            if i is None:
                run["points"].append(p)
            elif axis == "pillars":
                continue
            else:
                p["axes"] = run["points"][i]["axes"] + [a for a in p["axes"] if a not in run["points"][i]["axes"]]
                run["points"][i] = p
            axes_of[point_key(p)] = ";".join(p["axes"])
        for name in AXIS_CHECKS[axis]:
            if name in fresh["checks"]:
                run["checks"][name] = fresh["checks"][name]
        (BENCH_DIR / "results.json").write_text(json.dumps(run, indent=2) + "\n")
        with open(pathlib.Path(tmp) / "results.csv", newline="") as f:
            fresh_rows = list(csv.reader(f))
        with open(BENCH_DIR / "results.csv", newline="") as f:
            rows = [r for r in csv.reader(f) if r]
        header = fresh_rows[0]
        col = {name: header.index(name)
               for name in ("method", "layout", "threshold", "lights", "width", "height", "scene")}

        def row_key(r):
            return (r[col["method"]], r[col["layout"]] or None, round(float(r[col["threshold"]]), 8),
                    int(r[col["lights"]]), int(r[col["width"]]), int(r[col["height"]]), r[col["scene"]])

        fresh_by_key = {row_key(r): r for r in fresh_rows[1:] if r and r[0] != "aa" and row_key(r) in axes_of}
        merged = [header]
        for r in rows[1:]:
            r = r + [""] * (len(header) - len(r))
            k = row_key(r) if r[0] != "aa" else None
            if k in fresh_by_key:
                r = fresh_by_key.pop(k)
                r[0] = axes_of[k]
            merged.append(r)
        for k, r in fresh_by_key.items():
            r[0] = axes_of[k]
            merged.insert(len(merged) - sum(1 for x in merged if x[0] == "aa"), r)
        with open(BENCH_DIR / "results.csv", "w", newline="") as f:
            csv.writer(f, lineterminator="\n").writerows(merged)
    return 0


if __name__ == "__main__":
    sys.exit(main())
