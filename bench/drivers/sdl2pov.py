#!/usr/bin/env python3
"""Translate a scene in Hill's SDL (the language hitray reads) into POV-Ray 3.7.

    bench/drivers/sdl2pov.py SCENE.sdl -o SCENE.pov [--camera EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE]
                     [--size WxH] [--mask MASK.sdl]

The translation follows hitray's reading of the language (docs/sdl.md): macros
are expanded, the transform stack is kept as 4x4 matrices (M <- M.T, the
transform written last acts first), and every object is written with its full
object-to-world matrix, so the geometry is exactly the same.

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

--mask MASK.sdl also writes a flat SDL scene (macros expanded, no lights, no
materials but one `emissive` colour per object, black background) and makes
the .pov the same: each leaf object shows only its id colour, so the two
renders can be compared pixel by pixel for "the same objects in the same
places" (bench/drivers/compare_images.py).
"""
import argparse
import math
import os
import sys

OBJECT_WORDS = {"sphere", "cube", "square", "plane", "taperedCylinder", "cylinder", "cone",
                "torus", "mesh", "union", "intersection", "difference"}
MATERIAL_ARGS = {"ambient": 3, "diffuse": 3, "specular": 3, "emissive": 3,
                 "specularExponent": 1, "reflectivity": 1, "transparency": 1,
                 "speedOfLight": 1, "specularFraction": 1, "surfaceRoughness": 1, "texture": 1}
GLOBAL_ARGS = {"background": 3, "globalAmbient": 3, "minReflectivity": 1,
               "minTransparency": 1, "maxRecursionDepth": 1}


class SdlError(Exception):
    pass


def tokenize(text):
    tokens = []
    for line in text.splitlines():
        line = line.split("!", 1)[0]
        for word in line.replace("{", " { ").replace("}", " } ").split():
            tokens.append(word)
    return tokens


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def translation(dx, dy, dz):
    m = identity()
    m[0][3], m[1][3], m[2][3] = dx, dy, dz
    return m


def scaling(sx, sy, sz):
    m = identity()
    m[0][0], m[1][1], m[2][2] = sx, sy, sz
    return m


def rotation(angle, ux, uy, uz):
    n = math.sqrt(ux * ux + uy * uy + uz * uz)
    if n == 0:
        raise SdlError("rotate: zero axis")
    x, y, z = ux / n, uy / n, uz / n
    a = math.radians(angle)
    c, s, t = math.cos(a), math.sin(a), 1 - math.cos(a)
    m = identity()
    m[0][:3] = [t * x * x + c, t * x * y - s * z, t * x * z + s * y]
    m[1][:3] = [t * x * y + s * z, t * y * y + c, t * y * z - s * x]
    m[2][:3] = [t * x * z - s * y, t * y * z + s * x, t * z * z + c]
    return m


def default_material():
    return {"ambient": [0.1] * 3, "diffuse": [0.8] * 3, "specular": [0.0] * 3,
            "emissive": [0.0] * 3, "specularExponent": 1.0, "reflectivity": 0.0,
            "transparency": 0.0, "speedOfLight": 1.0}


class Scene:
    def __init__(self):
        self.globals = {"background": [0, 0, 0.6], "globalAmbient": [0.1] * 3,
                        "minReflectivity": 0.5, "minTransparency": 0.5, "maxRecursionDepth": 3}
        self.lights = []
        self.camera = None
        self.objects = []      # top-level objects, file order
        self.flat = []         # the expanded token stream for the mask SDL
        self.leaf_count = 0


class Reader:
    """Hill's SDL as hitray reads it, producing object records."""

    def __init__(self, tokens, base_dir, scene):
        self.tokens = list(reversed(tokens))  # a stack: pop() is the next token
        self.base_dir = base_dir
        self.scene = scene
        self.defs = {}
        self.stack = [identity()]
        self.material = default_material()

    def next(self):
        if not self.tokens:
            raise SdlError("unexpected end of the scene")
        return self.tokens.pop()

    def numbers(self, n):
        return [float(self.next()) for _ in range(n)]

    def emit(self, *words):
        self.scene.flat.append(" ".join(str(w) for w in words))

    def run(self):
        while self.tokens:
            obj = self.read_until_object(top=True)
            if obj is not None:
                self.scene.objects.append(obj)

    def read_until_object(self, top=False):
        """Process state commands up to the next object and read it."""
        while self.tokens:
            word = self.next()
            if word in OBJECT_WORDS:
                return self.read_object(word)
            self.state_command(word)
        if top:
            return None
        raise SdlError("a boolean operand is missing at the end of the scene")

    def state_command(self, word):
        top = self.stack[-1]
        if word == "translate":
            a = self.numbers(3)
            self.stack[-1] = matmul(top, translation(*a))
            self.emit(word, *a)
        elif word == "scale":
            a = self.numbers(3)
            self.stack[-1] = matmul(top, scaling(*a))
            self.emit(word, *a)
        elif word == "rotate":
            a = self.numbers(4)
            self.stack[-1] = matmul(top, rotation(*a))
            self.emit(word, *a)
        elif word == "push":
            self.stack.append([row[:] for row in top])
            self.emit(word)
        elif word == "pop":
            if len(self.stack) == 1:
                raise SdlError("pop of the last transform")
            self.stack.pop()
            self.emit(word)
        elif word == "identityAffine":
            self.stack[-1] = identity()
            self.emit(word)
        elif word in MATERIAL_ARGS:
            a = self.numbers(MATERIAL_ARGS[word])
            if word in self.material:
                self.material[word] = a if len(a) == 3 else a[0]
        elif word == "parameters":
            n = int(float(self.next()))
            self.numbers(n)
        elif word == "defaultMaterials":
            self.material = default_material()
        elif word in GLOBAL_ARGS:
            a = self.numbers(GLOBAL_ARGS[word])
            self.scene.globals[word] = a if len(a) == 3 else a[0]
        elif word == "light":
            self.scene.lights.append(self.numbers(6))
        elif word == "camera":
            self.scene.camera = self.numbers(10)
        elif word == "def":
            name = self.next()
            if self.next() != "{":
                raise SdlError(f"def {name}: expected '{{'")
            body = []
            while True:
                w = self.next()
                if w == "}":
                    break
                body.append(w)
            self.defs[name] = body
        elif word == "use":
            name = self.next()
            if name not in self.defs:
                raise SdlError(f"use of unknown macro '{name}'")
            self.tokens.extend(reversed(self.defs[name]))
        else:
            raise SdlError(f"unknown word '{word}'")

    def read_object(self, word):
        if word in ("union", "intersection", "difference"):
            self.emit(word)
            a = self.read_until_object()
            b = self.read_until_object()
            return {"kind": word, "children": [a, b]}
        obj = {"kind": word, "matrix": [row[:] for row in self.stack[-1]],
               "material": {k: (v[:] if isinstance(v, list) else v)
                            for k, v in self.material.items()}}
        if word == "taperedCylinder":
            obj["s"] = float(self.next())
        elif word == "cylinder":
            obj["kind"], obj["s"] = "taperedCylinder", 1.0
        elif word == "cone":
            obj["kind"], obj["s"] = "taperedCylinder", 0.0
        elif word == "mesh":
            obj["file"] = self.next()
        self.scene.leaf_count += 1
        obj["id"] = self.scene.leaf_count
        self.emit("emissive", *id_colour(obj["id"]))
        self.emit(word, *([obj["s"]] if word == "taperedCylinder" else
                          [obj["file"]] if word == "mesh" else []))
        return obj


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
    cols = [[m[r][c] for r in range(3)] for c in range(4)]
    return "matrix <" + ", ".join(num(x) for col in cols for x in col) + ">"


class PovWriter:
    def __init__(self, scene, mask, out_dir):
        self.scene = scene
        self.mask = mask
        self.out_dir = out_dir
        self.textures = {}
        self.meshes = {}
        self.decls = []

    def texture(self, mat, ident):
        if self.mask:
            return f"texture {{ pigment {{ rgb {vec(id_colour(ident))} }} finish {{ ambient 0 diffuse 0 emission 1 }} }}"
        g = self.scene.globals
        pig = [d if d > 0 else 1e-4 for d in mat["diffuse"]]
        amb = [a * ga / p for a, ga, p in zip(mat["ambient"], g["globalAmbient"], pig)]
        emi = [e / p for e, p in zip(mat["emissive"], pig)]
        spec = sum(mat["specular"]) / 3.0
        finish = f"ambient rgb {vec(amb)} emission rgb {vec(emi)} diffuse 1"
        if spec > 0:
            rough = min(1.0, max(1e-4, 1.0 / max(mat["specularExponent"], 1e-9)))
            finish += f" specular {num(spec)} roughness {num(rough)}"
        if mat["reflectivity"] >= g["minReflectivity"] and mat["reflectivity"] > 0:
            finish += f" reflection {{ rgb {num(mat['reflectivity'])} }}"
        transmit = mat["transparency"] if (mat["transparency"] >= g["minTransparency"] and
                                           mat["transparency"] > 0) else 0.0
        pigment = f"rgbt <{num(pig[0])}, {num(pig[1])}, {num(pig[2])}, {num(transmit)}>"
        text = f"texture {{ pigment {{ {pigment} }} finish {{ {finish} }} }}"
        if transmit > 0:
            text += f" interior {{ ior {num(1.0 / mat['speedOfLight'])} }}"
        name = self.textures.get(text)
        if name is None:
            name = f"T{len(self.textures) + 1}"
            self.textures[text] = name
            self.decls.append(f"#declare {name}_tex = {text.split(' interior ')[0]}")
            if transmit > 0:
                self.decls.append(f"#declare {name}_int = interior {{ ior {num(1.0 / mat['speedOfLight'])} }}")
        return f"texture {{ {name}_tex }}" + (f" interior {{ {name}_int }}" if transmit > 0 else "")

    def mesh(self, file):
        if file in self.meshes:
            return self.meshes[file]
        path = os.path.join(self.scene_dir, file)
        with open(path) as f:
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

    def shape(self, obj):
        kind = obj["kind"]
        if kind in ("union", "intersection", "difference"):
            a, b = (self.shape(c) for c in obj["children"])
            return f"{kind} {{\n {a}\n {b}\n}}"
        if kind == "sphere":
            body = "sphere { <0, 0, 0>, 1"
        elif kind == "cube":
            body = "box { <-1, -1, -1>, <1, 1, 1>"
        elif kind == "square":
            body = "mesh { triangle { <-1, -1, 0>, <1, -1, 0>, <1, 1, 0> } triangle { <-1, -1, 0>, <1, 1, 0>, <-1, 1, 0> }"
        elif kind == "plane":
            body = "plane { z, 0"
        elif kind == "taperedCylinder":
            s = obj["s"]
            body = ("cylinder { <0, 0, 0>, <0, 0, 1>, 1" if s == 1.0 else
                    f"cone {{ <0, 0, 0>, 1, <0, 0, 1>, {num(s)}")
        elif kind == "torus":
            body = "torus { 1, 0.2 rotate 90*x"
        elif kind == "mesh":
            body = f"object {{ {self.mesh(obj['file'])}"
        else:
            raise SdlError(f"no POV-Ray shape for '{kind}'")
        return f"{body} {self.texture(obj['material'], obj['id'])} {pov_matrix(obj['matrix'])} }}"

    def write(self, path, width, height):
        s = self.scene
        g = s.globals
        eye, look, up, angle = s.camera[0:3], s.camera[3:6], s.camera[6:9], s.camera[9]
        aspect = width / height
        hfov = math.degrees(2 * math.atan(math.tan(math.radians(angle) / 2) * aspect))
        body = [self.shape(o) for o in s.objects]
        out = ["#version 3.7;",
               "// generated by bench/drivers/sdl2pov.py: see its header for the mapping",
               "global_settings {",
               " assumed_gamma 1.0",
               f" max_trace_level {int(g['maxRecursionDepth']) + 1}",
               " adc_bailout 0",
               " ambient_light rgb <1, 1, 1>",
               "}",
               f"background {{ rgb {vec([0, 0, 0] if self.mask else g['background'])} }}",
               "camera {",
               " perspective",
               f" location {vec(eye)}",
               f" sky {vec(up)}",
               f" up y right -x*{num(aspect)}",
               f" angle {num(hfov)}",
               f" look_at {vec(look)}",
               "}"]
        if not self.mask:
            for x, y, z, r, gg, b in s.lights:
                out.append(f"light_source {{ {vec([x, y, z])} color rgb {vec([r, gg, b])} }}")
        out += self.decls
        out += body
        with open(path, "w") as f:
            f.write("\n".join(out) + "\n")


def write_mask_sdl(scene, path):
    g = scene.globals
    cam = " ".join(f"{num(x)}" for x in scene.camera)
    head = ["! flat id-colour version, generated by bench/drivers/sdl2pov.py --mask",
            f"camera {cam}", "background 0 0 0", "globalAmbient 0 0 0",
            f"maxRecursionDepth {int(g['maxRecursionDepth'])}",
            "ambient 0 0 0 diffuse 0 0 0 specular 0 0 0"]
    with open(path, "w") as f:
        f.write("\n".join(head + scene.flat) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--camera", help="EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE (overrides the scene's)")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--mask", help="also write the flat id-colour SDL here; the .pov is flat too")
    args = ap.parse_args(argv)
    width, height = (int(x) for x in args.size.split("x"))
    with open(args.scene) as f:
        tokens = tokenize(f.read())
    scene = Scene()
    try:
        Reader(tokens, os.path.dirname(args.scene), scene).run()
        if args.camera:
            scene.camera = [float(x) for x in args.camera.split(",")]
        if scene.camera is None or len(scene.camera) != 10:
            raise SdlError("the scene has no camera: give --camera")
        writer = PovWriter(scene, args.mask is not None,
                           os.path.dirname(os.path.abspath(args.output)))
        writer.scene_dir = os.path.dirname(os.path.abspath(args.scene))
        writer.write(args.output, width, height)
        if args.mask:
            write_mask_sdl(scene, args.mask)
    except (SdlError, ValueError, OSError) as e:
        print(f"sdl2pov: {args.scene}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
