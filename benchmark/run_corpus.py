#!/usr/bin/env python3
# Copyright (c) 2026 Aniso_conformal developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Corpus benchmark (issue 14): remeshes every mesh of benchmark/corpus_60.txt (CGAL 5.5's data set,
Debian libcgal-demo) with the command-line tool at a fixed number of vertices and seed, isotropic and
with the curvature metric (stretch 5), and writes a Markdown table: exit code, wall time, G_avg,
theta_min, % of angles below 30 degrees, relative Hausdorff distance, repairs, and whether the output
has the requested vertex count, the input's genus and boundary count and no inverted triangle; then the
totals.

    python3 benchmark/run_corpus.py --tool build/bin/aniso_remesh [--data DIR] [--vertices 2000]
                                    [--timeout 60] [--out benchmark/corpus.md] [--only NAME...]
                                    [--metrics isotropic|curvature ...] [--tool-args "--iterations 40"]

--data is a folder holding CGAL's data/meshes/ files; without it the script unpacks
/usr/share/doc/libcgal-dev/data.tar.gz (Debian package libcgal-demo: `apt-get install libcgal-demo`)
into a temporary folder. Python 3 standard library only. The timings are wall seconds of the whole
process (reading, all stages, writing), one run each.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
METRICS = {"isotropic": ["--metric", "isotropic"], "curvature": ["--metric", "curvature", "--stretch-max", "5"]}


def read_list(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            name, v, fcount, loops, genus = line.split()[:5]
            rows.append((name, int(v), int(fcount), int(loops), int(genus)))
    return rows


def topology_of_off(path):
    """(vertices, genus, boundary loops) of a triangle mesh in OFF; None if unreadable"""
    try:
        with open(path) as f:
            tokens = [t for line in f for t in line.split("#", 1)[0].split()]
    except OSError:
        return None
    if not tokens or tokens[0] != "OFF":
        return None
    nv, nf = int(tokens[1]), int(tokens[2])
    pos = 4 + 3 * nv
    edges = {}
    for _ in range(nf):
        k = int(tokens[pos])
        face = [int(x) for x in tokens[pos + 1:pos + 1 + k]]
        pos += 1 + k
        for i in range(k):
            a, b = face[i], face[(i + 1) % k]
            key = (min(a, b), max(a, b))
            edges[key] = edges.get(key, 0) + 1
    boundary = [e for e, c in edges.items() if c == 1]
    # boundary loops: components of the boundary edges
    parent = {}

    def find(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in boundary:
        parent[find(a)] = find(b)
    loops = len({find(a) for a, _ in boundary})
    euler = nv - len(edges) + nf
    genus = (2 - euler - loops) // 2
    return nv, genus, loops


def data_dir(arg):
    if arg:
        return arg, None
    archive = "/usr/share/doc/libcgal-dev/data.tar.gz"
    if not os.path.exists(archive):
        sys.exit("run_corpus.py: %s not found; install Debian's libcgal-demo or pass --data DIR" % archive)
    tmp = tempfile.TemporaryDirectory()
    with tarfile.open(archive) as t:
        members = [m for m in t.getmembers() if m.name.startswith("data/meshes/") and m.isfile()]
        t.extractall(tmp.name, members=members)
    return os.path.join(tmp.name, "data", "meshes"), tmp


def run_one(tool, mesh, metric, n, seed, timeout, workdir, extra=()):
    base = os.path.join(workdir, os.path.basename(mesh) + "." + metric)
    cmd = [tool, "--input", mesh, *METRICS[metric], "--vertices", str(n), "--seed", str(seed), "--quiet",
           "--output", base + ".off", "--report", base + ".json", *extra]
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        rc, err = p.returncode, p.stderr.strip().replace("\n", " ")
    except subprocess.TimeoutExpired:
        rc, err = "timeout", "no result within %d s" % timeout
    seconds = time.monotonic() - start
    report = None
    if rc == 0:
        with open(base + ".json") as f:
            report = json.load(f)
    return rc, seconds, err, report, base + ".off"


def repairs_text(report):
    rep = report.get("repairs") if report else None
    if not rep:
        return ""
    return ", ".join("%s %s" % (k, v) for k, v in rep.items()
                     if not k.startswith("input_") and isinstance(v, (int, float)) and not isinstance(v, bool) and v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tool", required=True)
    ap.add_argument("--data")
    ap.add_argument("--list", default=os.path.join(HERE, "corpus_60.txt"))
    ap.add_argument("--vertices", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--out", default=os.path.join(HERE, "corpus.md"))
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--metrics", nargs="*", choices=list(METRICS), help="run only these metrics (default: all)")
    ap.add_argument("--tool-args", default="", help="more options for the tool, one string (e.g. \"--iterations 40\")")
    a = ap.parse_args()
    meshes, keep = data_dir(a.data)
    rows = read_list(a.list)
    if a.only:
        rows = [r for r in rows if r[0] in a.only or r[0].replace(".off", "") in a.only]
    work = tempfile.TemporaryDirectory()
    metrics = [m for m in METRICS if not a.metrics or m in a.metrics]
    lines, results = [], {m: [] for m in metrics}
    for name, nv, nf, loops, genus in rows:
        for metric in metrics:
            rc, sec, err, rep, out = run_one(a.tool, os.path.join(meshes, name), metric, a.vertices, a.seed, a.timeout,
                                             work.name, a.tool_args.split())
            ok = False
            if rep is not None:
                topo = topology_of_off(out)
                q = rep["quality"]
                exact = topo is not None and topo[0] == a.vertices
                welded = (rep.get("repairs") or {}).get("points_welded", 0) > 0
                # welding coincident points can close a seam (CGAL's oblong-shuffled: a sphere opened by 2
                # duplicated points): the expected topology is then the welded surface's, not the list's
                same = topo is not None and (welded or (topo[1] == genus and topo[2] == loops))
                inverted = rep["output"]["inverted_triangles"]
                ok = exact and same and inverted == 0
                cells = ["%.2f" % sec, "%.4f" % q["G_avg"], "%.1f" % q["theta_min"], "%.2f" % q["percent_below_30"],
                         "%.2e" % rep["output"]["hausdorff_distance_relative"], repairs_text(rep),
                         "yes" if ok else "no (V %s, genus %s, loops %s, inverted %d)" % (
                             topo[0] if topo else "?", topo[1] if topo else "?", topo[2] if topo else "?", inverted)]
                results[metric].append((name, True, ok, sec, q["G_avg"], q["theta_min"]))
            else:
                cells = ["%.2f" % sec, "", "", "", "", "", "exit %s: %s" % (rc, err[:160].replace("|", "/"))]
                results[metric].append((name, False, False, sec, None, None))
            lines.append("| %s | %d | %d/%d | %s | %s |" % (name, nv, genus, loops, metric, " | ".join(cells)))
            print(lines[-1], flush=True)
    with open(a.out, "w") as f:
        f.write("# Corpus benchmark: CGAL 5.5's meshes at %d vertices (issue 14)\n\n" % a.vertices)
        f.write("Written by `benchmark/run_corpus.py` (seed %d, timeout %d s; wall seconds of the whole tool "
                "process, one run, this machine as it was). A result counts as a success when the tool "
                "exits 0 with exactly %d vertices, the input's genus and boundary count and no inverted "
                "triangle.\n\n" % (a.seed, a.timeout, a.vertices))
        f.write("## Totals\n\n| metric | meshes | remeshed | successes | median G_avg | min G_avg | "
                "median theta_min | median s | max s |\n|---|---|---|---|---|---|---|---|---|\n")
        for metric, res in results.items():
            done = [r for r in res if r[1]]
            good = [r for r in res if r[2]]
            g = [r[4] for r in good]
            th = [r[5] for r in good]
            t = [r[3] for r in res]
            f.write("| %s | %d | %d | %d | %s | %s | %s | %s | %s |\n" % (
                metric, len(res), len(done), len(good), "%.4f" % statistics.median(g) if g else "-",
                "%.4f" % min(g) if g else "-", "%.1f" % statistics.median(th) if th else "-",
                "%.2f" % statistics.median(t) if t else "-", "%.2f" % max(t) if t else "-"))
        f.write("\n## Per mesh\n\n| mesh | input V | genus/loops | metric | s | G_avg | theta_min | %<30 | "
                "Hausdorff / diagonal | repairs | success |\n|---|---|---|---|---|---|---|---|---|---|---|\n")
        f.write("\n".join(lines) + "\n")
    print("written", a.out)
    if keep:
        keep.cleanup()


if __name__ == "__main__":
    main()
