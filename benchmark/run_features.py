#!/usr/bin/env python3
# Copyright (c) 2026 Aniso_conformal developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Sharp-feature benchmark (issue 15): remeshes the crease-heavy meshes of CGAL 5.5's data set (Debian
libcgal-demo), a cube and a capped cylinder made here, with the command-line tool at a fixed number of
vertices and seed (isotropic metric), and writes a Markdown table of the report's `features` object:
the input's curves and corners, the corners kept, the share of the crease length covered by output
edges, the relative Hausdorff distance, G_avg and theta_min; then the totals.

    python3 benchmark/run_features.py --tool build/bin/aniso_remesh --data DIR [--vertices 2000]
                                      [--timeout 120] [--out benchmark/features.md]

--data is a folder holding CGAL's data/meshes/ files. Python 3 standard library only.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

MESHES = ["cube-meshed", "fandisk", "pinion", "oblong", "part", "rotor_small", "spool", "cactus", "elk",
          "patch-01", "anchor", "joint"]


def write_capped_cylinder(path, sides=48, rows=8, radius=0.5, height=1.0):
    """a closed cylinder: `sides` x `rows` quads split in two, each cap a fan around its centre"""
    pts = [(radius * math.cos(2 * math.pi * i / sides), radius * math.sin(2 * math.pi * i / sides), height * r / rows)
           for r in range(rows + 1) for i in range(sides)]
    bottom, top = len(pts), len(pts) + 1
    pts += [(0, 0, 0), (0, 0, height)]
    at = lambda r, i: r * sides + i % sides
    faces = []
    for r in range(rows):
        for i in range(sides):
            faces += [(at(r, i), at(r, i + 1), at(r + 1, i + 1)), (at(r, i), at(r + 1, i + 1), at(r + 1, i))]
    for i in range(sides):
        faces += [(bottom, at(0, i + 1), at(0, i)), (top, at(rows, i), at(rows, i + 1))]
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(pts), len(faces)))
        for p in pts:
            f.write("%.17g %.17g %.17g\n" % p)
        for t in faces:
            f.write("3 %d %d %d\n" % t)


def run(tool, path, vertices, timeout, extra):
    with tempfile.TemporaryDirectory() as d:
        report = os.path.join(d, "r.json")
        cmd = [tool, "--input", path, "--vertices", str(vertices), "--seed", "0", "--quiet", "--report", report] + extra
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return None, "time-out"
        if p.returncode != 0:
            return None, "exit %d: %s" % (p.returncode, p.stderr.strip().replace("|", "/")[:120])
        with open(report) as f:
            return json.load(f), ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tool", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--vertices", type=int, default=2000)
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--out", default=None)
    ap.add_argument("--extra", default="", help="more options for the tool, as one string")
    a = ap.parse_args()
    extra = a.extra.split()
    tmp = tempfile.mkdtemp()
    cases = [("cube (CGAL cube.off, 12 triangles)", os.path.join(a.data, "cube.off")),
             ("capped cylinder (48 sides, made here)", os.path.join(tmp, "capped_cylinder.off"))]
    write_capped_cylinder(cases[1][1])
    cases += [(m, os.path.join(a.data, m + ".off")) for m in MESHES]
    lines = ["| mesh | curves | corners | corners kept | crease covered | Hausdorff / diagonal | G_avg | theta_min | note |",
             "|---|---|---|---|---|---|---|---|---|"]
    tot = {"corners": 0, "kept": 0, "shares": []}
    for name, path in cases:
        j, note = run(a.tool, path, a.vertices, a.timeout, extra)
        if j is None:
            lines.append("| %s | | | | | | | | %s |" % (name, note))
        else:
            f = j.get("features", {})
            c, k = f.get("corners", 0), f.get("corners_kept", 0)
            tot["corners"] += c
            tot["kept"] += k
            if f.get("crease_length", 0.0) > 0:
                tot["shares"].append(f.get("covered_share", 0.0))
            lines.append("| %s | %d | %d | %d | %.1f %% | %.2e | %.4f | %.1f | |" % (
                name, f.get("curves", 0), c, k, 100 * f.get("covered_share", 0.0),
                j["output"]["hausdorff_distance_relative"], j["quality"]["G_avg"], j["quality"]["theta_min"]))
        print(lines[-1], flush=True)
    share = 100 * sum(tot["shares"]) / len(tot["shares"]) if tot["shares"] else 0.0
    lines.append("")
    lines.append("Totals over the meshes that remeshed: %d of %d corners kept; on average %.1f %% of a mesh's crease "
                 "length covered (%d meshes with creases)." % (tot["kept"], tot["corners"], share, len(tot["shares"])))
    print(lines[-1])
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
