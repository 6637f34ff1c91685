#!/usr/bin/env python3
# Writes test/data/cases/pyramid_grid.off to stdout (CC0 1.0, ours): the square [-1,1]^2, 16 x 16 cells,
# lifted to the pyramid z = 2 (1 - max(|x|, |y|)), each cell split along the diagonal that points to the
# apex, so the pyramid is exact on the mesh: a disk whose 4 creases (dihedral angle 78.5 degrees) run from
# an interior corner (the apex, 4 creases) to the 4 corners of the boundary (issue 15, creases in the plane).
# Usage: scripts/make_pyramid_grid.py > test/data/cases/pyramid_grid.off

m = 16
pts = []
for j in range(m + 1):
    for i in range(m + 1):
        x, y = -1 + 2 * i / m, -1 + 2 * j / m
        pts.append((x, y, 2 * (1 - max(abs(x), abs(y)))))
def v(i, j):
    return j * (m + 1) + i
faces = []
h = m // 2
for j in range(m):
    for i in range(m):
        a, b, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
        # the diagonals x = y (cells with (i < h) == (j < h)) and x = -y (the others) are edges
        if (i < h) == (j < h): faces += [(a, b, c), (a, c, d)]
        else: faces += [(a, b, d), (b, c, d)]
print("OFF"); print(len(pts), len(faces), 0)
for p in pts: print("%.17g %.17g %.17g" % p)
for f in faces: print(3, *f)
