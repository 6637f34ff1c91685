#!/usr/bin/env python3
# Writes test/data/cases/hip_roof.off to stdout (CC0 1.0, ours): a hip roof over the square [-1,1]^2,
# z = H (1 - max(|y|, (|x| - a) / (1 - a))) with a ridge of length 2a along the x axis, each of its 4
# planar faces (2 trapezoids, 2 triangles) meshed in m rows, so the roof is exact on the mesh: a disk with
# 5 creases, the short ridge between two interior corners (3 creases each) and 4 hips from them to the
# corners of the boundary (issue 15: two fixed corners closer together than an output edge, with a free
# vertex across their short edge, made a thin triangle). Usage: scripts/make_hip_roof.py > test/data/cases/hip_roof.off
import sys

a, H, m = 0.12, 2.0, 12
if len(sys.argv) > 1: a = float(sys.argv[1])
pts, index, faces = [], {}, []

def vid(x, y):
    key = (round(x, 12), round(y, 12))
    if key not in index:
        index[key] = len(pts)
        pts.append((x, y, H * (1 - max(abs(y), (abs(x) - a) / (1 - a)))))
    return index[key]

def lerp(p, q, t):
    return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))

def add(i, j, k):
    # counter-clockwise seen from above (z up): the roof is a graph over the square
    (x0, y0), (x1, y1), (x2, y2) = (pts[i][:2], pts[j][:2], pts[k][:2])
    if (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0) < 0: j, k = k, j
    faces.append((i, j, k))

for s in (1, -1):
    # trapezoid between the ridge (-a, 0)-(a, 0) and the edge y = s, m + 1 points a row
    rows = []
    for r in range(m + 1):
        t = r / m
        left, right = lerp((-a, 0), (-1, s), t), lerp((a, 0), (1, s), t)
        rows.append([vid(*lerp(left, right, c / m)) for c in range(m + 1)])
    for r in range(m):
        for c in range(m):
            add(rows[r][c], rows[r][c + 1], rows[r + 1][c + 1])
            add(rows[r][c], rows[r + 1][c + 1], rows[r + 1][c])
    # triangle between the ridge's end (s a, 0) and the edge x = s, row r has r + 1 points
    rows = []
    for r in range(m + 1):
        t = r / m
        p, q = lerp((s * a, 0), (s, -1), t), lerp((s * a, 0), (s, 1), t)
        rows.append([vid(*lerp(p, q, c / r)) if r > 0 else vid(s * a, 0) for c in range(r + 1)])
    for r in range(m):
        for c in range(r + 1):
            add(rows[r][c], rows[r + 1][c], rows[r + 1][c + 1])
            if c < r: add(rows[r][c], rows[r + 1][c + 1], rows[r][c + 1])

print("OFF"); print(len(pts), len(faces), 0)
for p in pts: print("%.17g %.17g %.17g" % p)
for f in faces: print(3, *f)
