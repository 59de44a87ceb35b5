#!/usr/bin/env python3
"""Translate a scene in Hill's SDL (the language hitray reads) into POV-Ray 3.7.

    bench/drivers/sdl2pov.py SCENE.sdl -o SCENE.pov [--camera EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE]
                     [--size WxH] [--mask MASK.sdl]

The scene is read by hitray itself (hitray.load_sdl, so macros, the transform
stack and every keyword mean what they mean to the renderer) and walked
through the scene's introspection (Scene.objects: each object's class, the
parameters it was made with, its matrix and its material): no SDL is parsed
here. Every object is written with its own matrix (an operand's relative to
its boolean's), so the geometry is exactly the same. Needs the hitray package
(make python-install).

Camera. Hill's camera is eye/look/up and a *vertical* view angle; hitray shoots
through pixel centres of an image plane at distance 1. POV-Ray is left-handed
and its `angle` is horizontal, so the camera gets `right -x*aspect` (which
makes POV-Ray right-handed, as hitray is), `sky` = up and the horizontal angle
2 atan(tan(v/2) aspect): the same rays through the same pixels.

Materials. Hill: colour = emissive + ambient*globalAmbient
  + sum over unshadowed lights of light*(diffuse*max(0, s.m) + specular*max(0, h.m)^exp)
  + reflectivity*(reflected) + transparency*(transmitted).
POV-Ray multiplies ambient and emission by the pigment, so the pigment is
Hill's diffuse colour (`diffuse 1`), and `ambient` / `emission` are Hill's
ambient*globalAmbient / emissive divided by it channel by channel
(`ambient_light` 1): exact. A diffuse channel of 0 becomes 1e-4 (POV-Ray could
not divide by it), adding at most 1e-4 of the light: negligible.
Approximate: the highlight. POV-Ray's `specular` is a grey Blinn term,
specular*(h.n)^(1/roughness); Hill's specular colour becomes its mean and
`roughness` = 1/specularExponent. Approximate: transparency. POV-Ray's
`transmit` t blends (1-t)*surface + t*behind where Hill adds t*behind to the
full surface colour; `ior` = 1/speedOfLight (speedOfLight is the relative
speed inside). POV-Ray lets light through transmitting objects to the
shadowed point; Hill's shadows stop at the first hit. Reflection (and
transmission) are written only where they reach minReflectivity
(minTransparency), as hitray spawns those rays only there.
Depth: Hill counts bounces after the primary ray (maxRecursionDepth d), POV-Ray
counts the primary ray as level 1: max_trace_level d+1, adc_bailout 0 (hitray
never cuts a ray tree short by its weight).

Shapes: sphere, cube (box -1..1), square (two triangles), plane (plane z),
taperedCylinder/cylinder/cone (capped cone or cylinder from z=0 to z=1),
torus (torus 1, 0.2 turned from POV-Ray's xz-plane to Hill's xy-plane), mesh
(Hill's .3vn file as a mesh2 with its vertex normals), union / intersection /
difference (POV-Ray's CSG of the same names, each leaf with its own texture).

--mask MASK.sdl also writes a flat SDL scene (no macros, no lights, no
materials but one `emissive` colour per object, black background; each
object's matrix written as translate, rotate, scale, rotate from its singular
value decomposition) and makes
the .pov the same: each leaf object shows only its id colour, so the two
renders can be compared pixel by pixel for "the same objects in the same
places" (bench/drivers/compare_images.py).
"""
import argparse
import math
import os
import sys

import numpy as np

import hitray

BOOLEANS = {"union", "intersection", "difference"}


class SdlError(Exception):
    pass


# 4 levels per channel (0, 1/3, 2/3, 1) minus black: 63 colours, far apart
# even after sRGB encoding and 8-bit rounding.
def id_colour(ident):
    k = (ident - 1) % 63 + 1
    return [round((k >> s & 3) / 3.0, 6) for s in (0, 2, 4)]


def num(x):
    return repr(float(x))  # the shortest text that reads back as the same double


def vec(v):
    return "<" + ", ".join(num(x) for x in v) + ">"


def pov_matrix(m):
    # POV-Ray multiplies row vectors: p' = p M, so its 12 numbers are the
    # transpose of hitray's column-vector matrix, translation last.
    return "matrix <" + ", ".join(num(m[r][c]) for c in range(4) for r in range(3)) + ">"


class Node:
    """One object of the scene: a leaf, or a boolean with its two operands."""

    def __init__(self, obj, children):
        self.obj = obj
        self.shape = obj.shape
        self.params = obj.params
        self.matrix = obj.matrix
        self.material = obj.material
        self.children = children
        self.id = 0


def tree(scene):
    """The top-level objects in the order they were written, each with its
    operands; leaves numbered 1, 2, ... in that order (their mask ids)."""
    def node(obj):
        kids = [node(v) for v in obj.params.values() if isinstance(v, hitray.SceneObject)]
        return Node(obj, kids)
    roots = [node(o) for o in scene.objects if o.top_level]
    count = 0

    def number(n):
        nonlocal count
        if n.children:
            for c in n.children:
                number(c)
        else:
            count += 1
            n.id = count
    for r in roots:
        number(r)
    return roots


class PovWriter:
    def __init__(self, scene, mask, out_dir, scene_dir):
        self.scene = scene
        self.mask = mask
        self.out_dir = out_dir
        self.scene_dir = scene_dir
        self.textures = {}
        self.meshes = {}
        self.decls = []

    def texture(self, mat, ident):
        if self.mask:
            return f"texture {{ pigment {{ rgb {vec(id_colour(ident))} }} finish {{ ambient 0 diffuse 0 emission 1 }} }}"
        s = self.scene
        pig = [d if d > 0 else 1e-4 for d in mat["diffuse"]]
        amb = [a * ga / p for a, ga, p in zip(mat["ambient"], s.global_ambient, pig)]
        emi = [e / p for e, p in zip(mat["emissive"], pig)]
        spec = sum(mat["specular"]) / 3.0
        finish = f"ambient rgb {vec(amb)} emission rgb {vec(emi)} diffuse 1"
        if spec > 0:
            rough = min(1.0, max(1e-4, 1.0 / max(mat["specular_exponent"], 1e-9)))
            finish += f" specular {num(spec)} roughness {num(rough)}"
        if mat["reflectivity"] >= s.min_reflectivity and mat["reflectivity"] > 0:
            finish += f" reflection {{ rgb {num(mat['reflectivity'])} }}"
        transmit = mat["transparency"] if (mat["transparency"] >= s.min_transparency and
                                           mat["transparency"] > 0) else 0.0
        pigment = f"rgbt <{num(pig[0])}, {num(pig[1])}, {num(pig[2])}, {num(transmit)}>"
        text = f"texture {{ pigment {{ {pigment} }} finish {{ {finish} }} }}"
        ior = num(1.0 / mat["speed_of_light"])
        name = self.textures.get(text)
        if name is None:
            name = f"T{len(self.textures) + 1}"
            self.textures[text] = name
            self.decls.append(f"#declare {name}_tex = {text}")
            if transmit > 0:
                self.decls.append(f"#declare {name}_int = interior {{ ior {ior} }}")
        return f"texture {{ {name}_tex }}" + (f" interior {{ {name}_int }}" if transmit > 0 else "")

    def mesh(self, file):
        if file in self.meshes:
            return self.meshes[file]
        if file.lower().endswith(".obj"):
            raise SdlError(f"mesh {file}: only Hill's format (.3vn) is translated")
        with open(os.path.join(self.scene_dir, file)) as f:
            nums = f.read().split()
        pos = 0

        def take(n):
            nonlocal pos
            out = nums[pos:pos + n]
            if len(out) < n:
                raise SdlError(f"{file}: the mesh file ends early")
            pos += n
            return out
        nv, nn, nf = (int(x) for x in take(3))
        verts = take(3 * nv)
        norms = take(3 * nn)
        faces, fnorms = [], []
        for _ in range(nf):
            k = int(take(1)[0])
            vi = take(k)
            ni = take(k)
            for j in range(1, k - 1):  # a fan of triangles
                faces.append((vi[0], vi[j], vi[j + 1]))
                fnorms.append((ni[0], ni[j], ni[j + 1]))
        name = f"M{len(self.meshes) + 1}"
        inc = os.path.splitext(os.path.basename(file))[0] + ".inc"
        with open(os.path.join(self.out_dir, inc), "w") as f:
            f.write(f"// {file} ({len(faces)} triangles), generated by sdl2pov.py\n")
            f.write(f"#declare {name} = mesh2 {{\n vertex_vectors {{ {nv}\n")
            f.write(",\n".join(f"<{verts[3*i]},{verts[3*i+1]},{verts[3*i+2]}>" for i in range(nv)))
            f.write(f"\n }}\n normal_vectors {{ {nn}\n")
            f.write(",\n".join(f"<{norms[3*i]},{norms[3*i+1]},{norms[3*i+2]}>" for i in range(nn)))
            f.write(f"\n }}\n face_indices {{ {len(faces)}\n")
            f.write(",\n".join(f"<{a},{b},{c}>" for a, b, c in faces))
            f.write(f"\n }}\n normal_indices {{ {len(fnorms)}\n")
            f.write(",\n".join(f"<{a},{b},{c}>" for a, b, c in fnorms))
            f.write("\n }\n}\n")
        self.decls.append(f'#include "{inc}"')
        self.meshes[file] = name
        return name

    def shape(self, n):
        kind, p = n.shape, n.params
        if kind in BOOLEANS:
            a, b = (self.shape(c) for c in n.children)
            own = "" if np.array_equal(n.matrix, np.eye(4)) else f" {pov_matrix(n.matrix)}"
            return f"{kind} {{\n {a}\n {b}{own}\n}}"
        if kind == "sphere":
            body = "sphere { <0, 0, 0>, 1"
        elif kind == "cube":
            body = "box { <-1, -1, -1>, <1, 1, 1>"
        elif kind == "square":
            body = "mesh { triangle { <-1, -1, 0>, <1, -1, 0>, <1, 1, 0> } triangle { <-1, -1, 0>, <1, 1, 0>, <-1, 1, 0> }"
        elif kind == "plane":
            body = "plane { z, 0"
        elif kind in ("taperedCylinder", "cylinder", "cone"):
            s = p["s"] if kind == "taperedCylinder" else 1.0 if kind == "cylinder" else 0.0
            body = ("cylinder { <0, 0, 0>, <0, 0, 1>, 1" if s == 1.0 else
                    f"cone {{ <0, 0, 0>, 1, <0, 0, 1>, {num(s)}")
        elif kind == "torus":
            body = f"torus {{ 1, {num(p['tube'])} rotate 90*x"
        elif kind == "mesh":
            body = f"object {{ {self.mesh(p['file'])}"
        else:
            raise SdlError(f"no POV-Ray shape for '{kind}'")
        return f"{body} {self.texture(n.material, n.id)} {pov_matrix(n.matrix)} }}"

    def write(self, path, roots, camera, width, height):
        s = self.scene
        aspect = width / height
        hfov = math.degrees(2 * math.atan(math.tan(math.radians(camera.angle) / 2) * aspect))
        body = [self.shape(r) for r in roots]
        out = ["#version 3.7;",
               "// generated by bench/drivers/sdl2pov.py: see its header for the mapping",
               "global_settings {",
               " assumed_gamma 1.0",
               f" max_trace_level {int(s.max_recursion_depth) + 1}",
               " adc_bailout 0",
               " ambient_light rgb <1, 1, 1>",
               "}",
               f"background {{ rgb {vec([0, 0, 0] if self.mask else s.background)} }}",
               "camera {",
               " perspective",
               f" location {vec(camera.eye)}",
               f" sky {vec(camera.up)}",
               f" up y right -x*{num(aspect)}",
               f" angle {num(hfov)}",
               f" look_at {vec(camera.look)}",
               "}"]
        if not self.mask:
            for light in s.lights:
                out.append(f"light_source {{ {vec(light.position)} color rgb {vec(light.color)} }}")
        out += self.decls
        out += body
        with open(path, "w") as f:
            f.write("\n".join(out) + "\n")


def rotation_words(r):
    """SDL's `rotate ANGLE X Y Z` for a rotation matrix (det +1); none for
    the identity."""
    cos = max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0))
    angle = math.acos(cos)
    if angle < 1e-15:
        return []
    if math.pi - angle < 1e-6:  # near a half turn: the axis from R + I
        axis = np.sqrt(np.maximum(np.diag(r) + 1.0, 0.0) / 2.0)
        k = int(np.argmax(axis))
        for j in range(3):
            if j != k:
                axis[j] = (r[k][j] + r[j][k]) / (4.0 * axis[k])
    else:
        axis = np.array([r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]])
    return ["rotate", num(math.degrees(angle)), *(num(x) for x in axis)]


def transform_words(m):
    """SDL transforms whose product is the 4x4 matrix m (to rounding):
    translate, then the linear part's SVD U S V^T as rotate U, scale S,
    rotate V^T (the transform written last acts first)."""
    words = []
    if any(m[i][3] != 0 for i in range(3)):
        words += ["translate", *(num(m[i][3]) for i in range(3))]
    lin = np.array(m, dtype=np.float64)[:3, :3]
    if np.count_nonzero(lin - np.diag(np.diag(lin))) == 0:
        if not np.array_equal(lin, np.eye(3)):
            words += ["scale", *(num(x) for x in np.diag(lin))]
        return words
    u, sv, vt = np.linalg.svd(lin)
    if np.linalg.det(lin) > 0 and sv[0] - sv[2] <= 1e-12 * sv[0]:
        # A rotation and one scale: the SVD's two turns are one.
        return words + rotation_words(u @ vt) + (["scale", *[num(sv[0])] * 3] if sv[0] != 1.0 else [])
    if np.linalg.det(u) < 0:
        u[:, 2], sv[2] = -u[:, 2], -sv[2]
    if np.linalg.det(vt) < 0:
        vt[2, :], sv[2] = -vt[2, :], -sv[2]
    scale = [] if np.array_equal(sv, np.ones(3)) else ["scale", *(num(x) for x in sv)]
    return words + rotation_words(u) + scale + rotation_words(vt)


def write_mask_sdl(scene, roots, camera, path):
    """The scene flat: each leaf alone under its own transform with its id
    colour, each boolean with its operands, no lights and no shading."""
    lines = ["! flat id-colour version, generated by bench/drivers/sdl2pov.py --mask",
             "camera " + " ".join(num(x) for x in (*camera.eye, *camera.look, *camera.up, camera.angle)),
             "background 0 0 0", "globalAmbient 0 0 0",
             f"maxRecursionDepth {int(scene.max_recursion_depth)}",
             "ambient 0 0 0 diffuse 0 0 0 specular 0 0 0"]

    def leaf_lines(n, above):
        """A boolean's line and its operands', or a leaf's three: its
        transform, its id colour and its keyword, the pop."""
        world = above @ n.matrix
        if n.children:
            return [n.shape] + [line for c in n.children for line in leaf_lines(c, world)]
        args = []
        for value in n.params.values():
            if isinstance(value, str):
                if value:  # an empty string is the parameter left out (the torus's solver)
                    args.append(value)
            elif isinstance(value, float):
                args.append(num(value))
            else:
                raise SdlError(f"'{n.shape}': an array parameter has no SDL word")
        return [" ".join(["push", "identityAffine", *transform_words(world)]),
                " ".join(["emissive", *(num(c) for c in id_colour(n.id)), n.shape, *args]), "pop"]
    for r in roots:
        lines += leaf_lines(r, np.eye(4))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--camera", help="EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE (overrides the scene's)")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--mask", help="also write the flat id-colour SDL here; the .pov is flat too")
    args = ap.parse_args(argv)
    width, height = (int(x) for x in args.size.split("x"))
    try:
        scene, camera = hitray.load_sdl(args.scene)
        if args.camera:
            c = [float(x) for x in args.camera.split(",")]
            if len(c) != 10:
                raise SdlError("--camera takes 10 numbers")
            camera = hitray.Camera(c[0:3], c[3:6], c[6:9], c[9])
        if camera is None:
            raise SdlError("the scene has no camera: give --camera")
        roots = tree(scene)
        writer = PovWriter(scene, args.mask is not None, os.path.dirname(os.path.abspath(args.output)),
                           os.path.dirname(os.path.abspath(args.scene)))
        writer.write(args.output, roots, camera, width, height)
        if args.mask:
            write_mask_sdl(scene, roots, camera, args.mask)
    except (hitray.Error, SdlError, ValueError, OSError) as e:
        print(f"sdl2pov: {args.scene}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
