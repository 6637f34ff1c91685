#!/usr/bin/env python3
# Copyright (c) 2026 Aniso_conformal developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Table 2 Dupin cyclide as a grid mesh and a user-specified metric field whose stretch spans the
paper's [2, 29] exactly, in the tool's metric-file format (IO/read_metric_file.h).

    python3 benchmark/make_cyclide_metric.py OUT.off OUT.metric [--nu 180] [--nv 144]
                                             [--stretch-min 2] [--stretch-max 29]

The mesh is `make_dupin_cyclide(nu, nv)`'s (a = 1, b = 0.95, mu = 0.5; the same points in the same order,
the same triangles). The paper (section 2.1, eq. 4) builds its metric from two user-specified stretching
factors s1 <= s2 along the principal directions and gives Fig. 11's stretch s2 / s1 as [2, 29]; its exact
field is not published. The tool's curvature metric (scales the square roots of the principal curvatures,
bound 29) spans [1, 29] unsmoothed but reaches 29 only on bands one or two vertices wide. This field is a
continuous one that does span [2, 29] on bands a user would see:

  the parameter lines of a Dupin cyclide are its lines of curvature; with kappa_v the normal curvature
  across the tube (along x_v, never zero) and kappa_u the one along it (along x_u, zero on two circles),
  the length scale across the tube is s_v = sqrt(|kappa_v|) and along it s_u = s_v / r with the stretch
  r = clamp(|kappa_v / kappa_u|, stretch_min, stretch_max);
  M = s_v^2 t_v t_v^T + s_u^2 t_u t_u^T (tangent only; t_u, t_v the unit parameter directions).

The frame is the same everywhere (the long axis of the ellipses always along the tube), so the field is
continuous where the two curvatures are equal, which the principal-direction field of a curvature
metric with a lower bound above 1 would not be. The curvatures come from central differences of the
exact parameterisation (step 1e-4: errors near 1e-8). Python 3 standard library only (and
make_torus_metric.py's writer, beside it).
"""
import argparse
import math

from make_torus_metric import write_off_and_metric  # the same directory

A, B, MU = 1.0, 0.95, 0.5
C = math.sqrt(A * A - B * B)


def point(u, v):
    den = A - C * math.cos(u) * math.cos(v)
    return ((MU * (C - A * math.cos(u) * math.cos(v)) + B * B * math.cos(u)) / den,
            B * math.sin(u) * (A - MU * math.cos(v)) / den,
            B * math.sin(v) * (C * math.cos(u) - MU) / den)


def sub(p, q):
    return tuple(a - b for a, b in zip(p, q))


def add(p, q):
    return tuple(a + b for a, b in zip(p, q))


def scale(p, s):
    return tuple(a * s for a in p)


def dot(p, q):
    return sum(a * b for a, b in zip(p, q))


def cross(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def frame(u, v, h=1e-4):
    """Unit tangents t_u, t_v and the normal curvatures along them (the principal curvatures)."""
    p = point(u, v)
    pu_p, pu_m, pv_p, pv_m = point(u + h, v), point(u - h, v), point(u, v + h), point(u, v - h)
    xu = scale(sub(pu_p, pu_m), 0.5 / h)
    xv = scale(sub(pv_p, pv_m), 0.5 / h)
    xuu = scale(sub(add(pu_p, pu_m), scale(p, 2.0)), 1.0 / (h * h))
    xvv = scale(sub(add(pv_p, pv_m), scale(p, 2.0)), 1.0 / (h * h))
    n = cross(xu, xv)
    n = scale(n, 1.0 / math.sqrt(dot(n, n)))
    E, G = dot(xu, xu), dot(xv, xv)
    return scale(xu, 1 / math.sqrt(E)), scale(xv, 1 / math.sqrt(G)), dot(xuu, n) / E, dot(xvv, n) / G


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("off")
    ap.add_argument("metric")
    ap.add_argument("--nu", type=int, default=180)
    ap.add_argument("--nv", type=int, default=144)
    ap.add_argument("--stretch-min", type=float, default=2.0)
    ap.add_argument("--stretch-max", type=float, default=29.0)
    a = ap.parse_args()
    if not (1 <= a.stretch_min <= a.stretch_max):
        ap.error("need 1 <= --stretch-min <= --stretch-max")
    pts, tensors, faces = [], [], []
    ratios = []
    for i in range(a.nu):
        u = 2 * math.pi * i / a.nu
        for j in range(a.nv):
            v = 2 * math.pi * j / a.nv
            pts.append(point(u, v))
            tu, tv, k_u, k_v = frame(u, v)
            ratio = abs(k_v) / max(abs(k_u), 1e-300)
            r = min(max(ratio, a.stretch_min), a.stretch_max)
            ratios.append(r)
            s_v = math.sqrt(abs(k_v))
            s_u = s_v / r
            m = [[s_v * s_v * tv[p] * tv[q] + s_u * s_u * tu[p] * tu[q] for q in range(3)] for p in range(3)]
            tensors.append((m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2]))
    for i in range(a.nu):
        for j in range(a.nv):
            A_ = i * a.nv + j
            B_ = ((i + 1) % a.nu) * a.nv + j
            C_ = ((i + 1) % a.nu) * a.nv + (j + 1) % a.nv
            D_ = i * a.nv + (j + 1) % a.nv
            faces.append((A_, B_, C_))
            faces.append((A_, C_, D_))
    write_off_and_metric(a.off, a.metric, pts, faces, tensors)
    s = sorted(ratios)
    print("stretch of the field at the %d vertices: min %.2f, median %.2f, 95%% %.2f, max %.2f; %.1f%% at the upper bound"
          % (len(s), s[0], s[len(s) // 2], s[int(0.95 * (len(s) - 1))], s[-1],
             100.0 * sum(1 for x in s if x >= a.stretch_max) / len(s)))


if __name__ == "__main__":
    main()
