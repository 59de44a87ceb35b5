#!/usr/bin/env python3
"""Write the benchmark's terrain mesh in Hill's chapter-6 mesh format (.3vn).

    bench/drivers/make_terrain.py OUT.3vn [--grid N]

A height field over [-1, 1]^2 in the xz-plane (y up), heights a sum of a few
sines (deterministic, so every run benchmarks the same mesh), N x N vertices
(default 230: 2 (N-1)^2 = 104,882 triangles) with one normal per vertex from
the height field's gradient. Format: `numVerts numNorms numFaces`, the
vertices, the normals, then per face `3 a b c a b c` (0-based vertex indices,
then the normal indices, which are the same here)."""
import argparse
import math


def height(x, z):
    return (0.06 * math.sin(3.1 * x + 0.4) * math.cos(2.3 * z - 0.2) +
            0.03 * math.sin(7.7 * x * z + 1.0) + 0.015 * math.cos(13.0 * x - 9.0 * z))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("output")
    ap.add_argument("--grid", type=int, default=230)
    args = ap.parse_args()
    n = args.grid
    step = 2.0 / (n - 1)
    verts, norms = [], []
    for j in range(n):
        z = -1.0 + j * step
        for i in range(n):
            x = -1.0 + i * step
            y = height(x, z)
            h = 1e-5  # central differences for the gradient
            dx = (height(x + h, z) - height(x - h, z)) / (2 * h)
            dz = (height(x, z + h) - height(x, z - h)) / (2 * h)
            length = math.sqrt(dx * dx + 1.0 + dz * dz)
            verts.append(f"{x:.9g} {y:.9g} {z:.9g}")
            norms.append(f"{-dx / length:.9g} {1.0 / length:.9g} {-dz / length:.9g}")
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i, (j + 1) * n + i + 1
            # counter-clockwise seen from above (+y), so the face normal is up
            faces.append(f"3 {a} {c} {b} {a} {c} {b}")
            faces.append(f"3 {b} {c} {d} {b} {c} {d}")
    with open(args.output, "w") as f:
        f.write(f"{len(verts)} {len(norms)} {len(faces)}\n")
        f.write("\n".join(verts) + "\n")
        f.write("\n".join(norms) + "\n")
        f.write("\n".join(faces) + "\n")


if __name__ == "__main__":
    main()
