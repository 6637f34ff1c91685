#!/usr/bin/env python3
# Copyright (c) 2026 Aniso_conformal developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""A torus (radii R, r) as a grid mesh and its exact curvature metric at a given stretch bound, in the
tool's metric-file format (IO/read_metric_file.h): the case of issue 17's "exact stretch-30 metric".

    python3 benchmark/make_torus_metric.py OUT.off OUT.metric [--R 2] [--r 1] [--nu 240] [--nv 80]
                                           [--stretch 30]

At the point (u, v), x = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v), the principal curvatures
are 1 / r along the tube (direction t_v) and cos v / (R + r cos v) around the axis (t_u). As the tool's
curvature metric does, the scales are the square roots of their absolute values, the smaller one raised
to at least the larger over `stretch`: M = s_v^2 t_v t_v^T + s_u^2 t_u t_u^T (tangent only). Python 3
standard library only.
"""
import argparse
import math


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("off")
    ap.add_argument("metric")
    ap.add_argument("--R", type=float, default=2.0)
    ap.add_argument("--r", type=float, default=1.0)
    ap.add_argument("--nu", type=int, default=240)
    ap.add_argument("--nv", type=int, default=80)
    ap.add_argument("--stretch", type=float, default=30.0)
    a = ap.parse_args()
    pts, tensors, faces = [], [], []
    for j in range(a.nv):
        v = 2 * math.pi * j / a.nv
        for i in range(a.nu):
            u = 2 * math.pi * i / a.nu
            rho = a.R + a.r * math.cos(v)
            pts.append((rho * math.cos(u), rho * math.sin(u), a.r * math.sin(v)))
            tu = (-math.sin(u), math.cos(u), 0.0)
            tv = (-math.sin(v) * math.cos(u), -math.sin(v) * math.sin(u), math.cos(v))
            k_v, k_u = 1.0 / a.r, math.cos(v) / rho
            s_v, s_u = math.sqrt(abs(k_v)), math.sqrt(abs(k_u))
            big = max(s_v, s_u)
            s_v, s_u = max(s_v, big / a.stretch), max(s_u, big / a.stretch)
            m = [[s_v * s_v * tv[p] * tv[q] + s_u * s_u * tu[p] * tu[q] for q in range(3)] for p in range(3)]
            tensors.append((m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2]))
    for j in range(a.nv):
        for i in range(a.nu):
            p = j * a.nu + i
            q = j * a.nu + (i + 1) % a.nu
            r = ((j + 1) % a.nv) * a.nu + (i + 1) % a.nu
            s = ((j + 1) % a.nv) * a.nu + i
            faces.append((p, q, r))
            faces.append((p, r, s))
    write_off_and_metric(a.off, a.metric, pts, faces, tensors)


def write_off_and_metric(off, metric, pts, faces, tensors):
    """The mesh as OFF and one tensor (m11 m12 m13 m22 m23 m33) per vertex as the tool's metric file, in
    full precision (also make_cyclide_metric.py's writer)."""
    with open(off, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(pts), len(faces)))
        for x in pts:
            f.write("%.17g %.17g %.17g\n" % x)
        for t in faces:
            f.write("3 %d %d %d\n" % t)
    with open(metric, "w") as f:
        f.write("%d\n" % len(tensors))
        for t in tensors:
            f.write(" ".join("%.17g" % x for x in t) + "\n")


if __name__ == "__main__":
    main()
