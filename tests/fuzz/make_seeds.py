#!/usr/bin/env python3
"""Writes the hand-made seeds of the binary harnesses (fuzz_shapes.c,
fuzz_csg.c) into corpus/<harness>/seed_*: one input per shape class with a
few rays (inside, outside, tangent, along an axis with zero and negative-zero
direction components, from far away), and CSG trees of coincident cubes and
mixed solids. Run it again after changing how a harness reads its input;
the fuzzers' own finds are merged into the same folders (FUZZING.md)."""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def raw(value):
    """fuzz_double kind 3: the bit pattern, big-endian."""
    return bytes([3]) + struct.pack(">d", value)


def ray(origin, direction, interval=None):
    out = b"".join(raw(v) for v in origin) + b"".join(raw(v) for v in direction)
    if interval is None:
        return out + bytes([0])  # (0, inf)
    if interval == "line":
        return out + bytes([1])  # (-inf, inf)
    return out + bytes([2]) + raw(interval[0]) + raw(interval[1])


# The classes fuzz_shapes.c finds in the built-in modules, in its order
# (module by module, each module's classes in its own order).
CLASSES = ["sphere", "plane", "square", "cube", "taperedCylinder", "cylinder", "cone",
           "openTaperedCylinder", "torus", "mesh", "tetrahedron", "octahedron", "dodecahedron", "icosahedron",
           "triangleMesh", "buckyball", "teapot"]
RAYS = [
    ray((0, 0, 5), (0, 0, -1)),
    ray((0.5, 0.25, 0.5), (1, 0.5, -0.25), "line"),
    ray((-3, 1, 0.5), (1, -0.0, 0.0)),  # tangent / along faces, signed zeros
    ray((1e6, 2e5, -3e5), (-1e6, -2e5, 3e5 + 0.5), (0.5, 2.0)),
    ray((0, 0, 0.5), (5e-324, -5e-324, 1)),
]


def shape_seeds():
    seeds = {}
    for index, name in enumerate(CLASSES):
        params = b""
        variants = [b""]
        if name in ("taperedCylinder", "openTaperedCylinder"):
            variants = [raw(0.5), raw(0.0), raw(3.0), raw(-1.0), raw(2e6)]
        elif name == "torus":
            # tube, then the solver (0 default, 1 ferrari, 2 ferrari-newton,
            # 3 bracketing, 4 an unknown name)
            variants = [raw(0.2) + bytes([0]), raw(0.5) + bytes([1]), raw(1e-6) + bytes([2]),
                        raw(0.999) + bytes([3]), raw(0.2) + bytes([4]), raw(1.0) + bytes([3])]
        elif name == "mesh":
            variants = [bytes([k]) for k in range(5)]
        elif name == "teapot":
            # steps a side: the coarsest, the default, then refused ones
            # (a fraction, below and above the range)
            variants = [raw(2.0), raw(12.0), raw(2.5), raw(1.0), raw(129.0)]
        elif name == "triangleMesh":
            continue  # arrays from the input: fuzzed from the seeds of others
        for k, params in enumerate(variants):
            seeds["seed_%s_%d" % (name, k)] = bytes([index]) + params + b"".join(RAYS)
    return seeds


def csg_seeds():
    rng = random.Random(12345)
    seeds = {}
    # Root: difference (kind 2) of cube minus a cube moved by 1 along x
    # (sharing a face), rays along and across the shared face. Leaf bytes:
    # kind (>= 3: a leaf), leaf class, then offsets and scales through
    # grid_or_any (1: on the 1/8 grid, then the step).
    def grid(value, lo):
        return bytes([1, int(round((value - lo) * 8))])

    def leaf(cls, offset, scale, param=None):
        out = bytes([3, cls])
        if param is not None:
            out += grid(param, 0.0)
        return out + b"".join(grid(v, -2.0) for v in offset) + b"".join(
            grid(v - 0.25, 0.0) for v in scale)

    def csg_ray(origin, direction):
        return b"".join(grid(v, -4.0) for v in origin) + b"".join(
            grid(v, -1.0) for v in direction) + bytes([0, 1])

    rays = csg_ray((-3, 0, 0), (1, 0, 0)) + csg_ray((-3, 1, 0), (1, 0, 0)) + csg_ray(
        (0, 0, -3), (0.25, 0.125, 1))
    for op in range(3):
        seeds["seed_cubes_face_%d" % op] = bytes([op]) + leaf(1, (0, 0, 0), (1, 1, 1)) + leaf(
            1, (1, 0, 0), (1, 1, 1)) + rays
        seeds["seed_mixed_%d" % op] = bytes([op]) + bytes([(op + 1) % 3]) + leaf(
            0, (0, 0, 0), (1, 1, 1)) + leaf(5, (0.5, 0, 0), (1, 1, 1), 0.25) + leaf(
            4, (0, 0, -0.5), (0.5, 0.5, 2), 0.5) + rays
    seeds["seed_open_operand"] = bytes([0]) + leaf(0, (0, 0, 0), (1, 1, 1)) + bytes(
        [3, 7, 0]) + rays
    for k in range(6):
        seeds["seed_random_%d" % k] = bytes(rng.randrange(256) for _ in range(160))
    return seeds


def main():
    for harness, seeds in (("shapes", shape_seeds()), ("csg", csg_seeds())):
        folder = os.path.join(HERE, "corpus", harness)
        os.makedirs(folder, exist_ok=True)
        for name, data in seeds.items():
            with open(os.path.join(folder, name), "wb") as f:
                f.write(data)


if __name__ == "__main__":
    main()
