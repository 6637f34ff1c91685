#!/usr/bin/env python3
# Writes data/meshes/plate_two_holes.off to stdout (CC0 1.0, ours): the unit square, 24 x 24 cells, with
# two rectangular holes, triangulated: a planar plate with 3 boundary loops (issue 15; doc/fig/plate_two_holes_mesh.svg).
# Usage: scripts/make_plate_two_holes.py > data/meshes/plate_two_holes.off

m = 24
holes = [(4, 4, 10, 12), (14, 9, 20, 19)]  # cells [i0, i1) x [j0, j1) removed
def inside(i, j):
    return any(i0 <= i < i1 and j0 <= j < j1 for (i0, j0, i1, j1) in holes)
idx = {}
pts = []
faces = []
def v(i, j):
    if (i, j) not in idx:
        idx[(i, j)] = len(pts); pts.append((i / m, j / m, 0.0))
    return idx[(i, j)]
for i in range(m):
    for j in range(m):
        if inside(i, j): continue
        a, b, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
        if (i + j) % 2 == 0: faces += [(a, b, c), (a, c, d)]
        else: faces += [(a, b, d), (b, c, d)]
print("OFF"); print(len(pts), len(faces), 0)
for p in pts: print("%.17g %.17g %.17g" % p)
for f in faces: print(3, *f)
