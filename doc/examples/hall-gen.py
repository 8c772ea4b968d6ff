#!/usr/bin/env python3
"""Writes the example level "hall" (doc/examples/hall.scene):

    python3 hall-gen.py [DIR]

writes DIR/hall.gltf, DIR/hall.bin, DIR/hall.obj, DIR/hall.mtl and
DIR/hall-textures/{plaster,tiles}.png (DIR defaults to this script's
directory).  The output is the same bytes on every run and machine:
the committed files are this script's output, and
tests/t1015-hall-generator.sh in reflect's source tree checks that they
still are.

The hall is L-shaped, in metres, +Y up, floor at y = 0, 4.5 m high:

  main wing  x -6 .. 6, z -3 .. 3      (12 x 6 m)
  side wing  x  0 .. 6, z 3.4 .. 11.4  (6 x 8 m)

joined through a wall 0.4 m thick (z 3 .. 3.4) by an arched doorway
3 m wide, its round arch springing at 2.5 m (apex 4 m).  In the main
wing: three windows in the -z wall, open below (the sun comes through)
with an emissive fanlight above; a large emissive window in the +x end
wall; a row of four 16-sided columns at z = -1.8; a table turned by 30
degrees with a lamp hanging above it (an emissive disc in a shade and a
spot light).  In the side wing: an emissive window in the far wall and
two sconces (an emissive face and a point light each).  The floor is
glossy: the material the scene reflects with ("mirror-floor", with
extras reflect.mirror = true).

Only the standard library: the PNGs are written with stored (not
compressed) deflate blocks so that no zlib version can change a byte,
and every sine and cosine is rounded to 12 decimals before use so that
no libm can either.
"""

import json
import math
import os
import re
import struct
import sys
import zlib

H = 4.5           # ceiling height
WALL = 0.3        # depth of the window reveals
SIDES = 16        # sides of a column
ARCH_SEGMENTS = 24

# Light intensities in glTF's units (candela for point and spot lights,
# lux for the directional one); reflect divides them by 683 lm/W
# (reflect-scene(5)), so that beside windows of radiance 12 (a bright
# overcast sky, some 8000 cd/m2) the sun is a low winter sun through
# glass (40000 lux: irradiance 59), the lamp a strong reading spot and
# the sconces bright bulbs.
SUN_LUX = 40000.0
LAMP_CD = 3000.0
SCONCE_CD = 1500.0
# Emissive surfaces: emissiveFactor times KHR_materials_emissive_strength
WINDOW_STRENGTH = 12.0
LAMP_STRENGTH = 20.0


def cs(a):
    """cos and sin of a, rounded so that every libm gives the same."""
    return round(math.cos(a), 12), round(math.sin(a), 12)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


# ---------------------------------------------------------------------
# Meshes: per material, a list of vertices (position, normal, uv) and
# triangles.  Front faces are counter-clockwise seen from the normal's
# side, as glTF has them.

class Mesh:
    def __init__(self, name):
        self.name = name
        self.prims = {}  # material name -> [vertices, triangles]

    def prim(self, material):
        return self.prims.setdefault(material, [[], []])

    def polygon(self, material, points, normal, uv):
        """A flat convex polygon, fanned from its first point; uv(p)
        gives each corner's texture coordinates."""
        verts, tris = self.prim(material)
        g = cross(sub(points[1], points[0]), sub(points[2], points[0]))
        if dot(g, normal) < 0:
            points = points[::-1]
        base = len(verts)
        for p in points:
            verts.append((p, normal, uv(p)))
        for k in range(1, len(points) - 1):
            tris.append((base, base + k, base + k + 1))

    def strip(self, material, rows):
        """A smooth surface: rows of (position, normal, uv), each row as
        long as the others, joined by quads; winding follows the
        normals."""
        verts, tris = self.prim(material)
        base = len(verts)
        width = len(rows[0])
        for row in rows:
            verts.extend(row)
        for j in range(len(rows) - 1):
            for i in range(width - 1):
                a = base + j * width + i
                b, c, d = a + 1, a + width + 1, a + width
                g = cross(sub(verts[b][0], verts[a][0]),
                          sub(verts[c][0], verts[a][0]))
                if dot(g, verts[a][1]) < 0:
                    tris.append((a, c, b))
                    tris.append((a, d, c))
                else:
                    tris.append((a, b, c))
                    tris.append((a, c, d))


# uv in metres: along a vertical face, u runs along the face and v down
# (glTF's v points down the image); floors and ceilings take x and z.
def uv_x(p):
    return (p[0], -p[1])


def uv_z(p):
    return (p[2], -p[1])


def uv_xz(p):
    return (p[0], p[2])


def box(mesh, material, lo, hi, skip=()):
    """An axis-aligned box's faces, facing out; skip names faces left
    out ("+y" for a face against the ceiling, ...)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = {
        "+x": ([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)], (1, 0, 0), uv_z),
        "-x": ([(x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (x0, y0, z1)], (-1, 0, 0), uv_z),
        "+y": ([(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)], (0, 1, 0), uv_xz),
        "-y": ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0), uv_xz),
        "+z": ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1), uv_x),
        "-z": ([(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)], (0, 0, -1), uv_x),
    }
    for name in ("+x", "-x", "+y", "-y", "+z", "-z"):
        if name not in skip:
            points, normal, uv = faces[name]
            mesh.polygon(material, points, normal, uv)


def wall(mesh, material, axis, value, normal, lo, hi, holes=()):
    """A vertical wall in the plane axis = value ("x" or "z"), spanning
    lo .. hi along the other horizontal axis and 0 .. H up, with
    rectangular holes (a0, a1, y0, y1) that do not overlap along it.
    It is cut into strips at the holes' edges."""
    if axis == "x":
        def at(a, y):
            return (value, y, a)
        uv = uv_z
    else:
        def at(a, y):
            return (a, y, value)
        uv = uv_x
    cuts = sorted({lo, hi} | {h[0] for h in holes} | {h[1] for h in holes})
    for a0, a1 in zip(cuts, cuts[1:]):
        spans = [(0.0, H)]
        for h in holes:
            if h[0] <= a0 and a1 <= h[1]:
                spans = [(0.0, h[2]), (h[3], H)]
        for y0, y1 in spans:
            if y1 > y0:
                mesh.polygon(material, [at(a0, y0), at(a1, y0), at(a1, y1), at(a0, y1)],
                             normal, uv)


def reveal(mesh, material, axis, value, normal, hole, depth, closed_by=None):
    """The four faces lining a hole of a wall (see wall()) back to
    depth behind its face; closed_by, a material, puts a pane at the
    back, facing into the room."""
    a0, a1, y0, y1 = hole
    back = value - depth * (normal[0] if axis == "x" else normal[2])
    if axis == "x":
        def at(a, y, w):
            return (w, y, a)
        side, uv, uvh = (0, 0, 1), uv_x, uv_xz
    else:
        def at(a, y, w):
            return (a, y, w)
        side, uv, uvh = (1, 0, 0), uv_z, uv_xz
    neg = (-side[0], -side[1], -side[2])
    mesh.polygon(material, [at(a0, y0, value), at(a0, y1, value), at(a0, y1, back), at(a0, y0, back)], side, uv)
    mesh.polygon(material, [at(a1, y0, value), at(a1, y1, value), at(a1, y1, back), at(a1, y0, back)], neg, uv)
    mesh.polygon(material, [at(a0, y0, value), at(a1, y0, value), at(a1, y0, back), at(a0, y0, back)], (0, 1, 0), uvh)
    mesh.polygon(material, [at(a0, y1, value), at(a1, y1, value), at(a1, y1, back), at(a0, y1, back)], (0, -1, 0), uvh)
    if closed_by:
        mesh.polygon(closed_by, [at(a0, y0, back), at(a1, y0, back), at(a1, y1, back), at(a0, y1, back)],
                     normal, uv)


# The doorway between the wings: centre x, half width, springing height.
ARCH_X, ARCH_R, ARCH_SPRING = 3.0, 1.5, 2.5
ARCH_Z0, ARCH_Z1 = 3.0, 3.4


def arch_points():
    """The arch's intrados from its left springing to its right one."""
    pts = []
    for k in range(ARCH_SEGMENTS + 1):
        c, s = cs(math.pi * (1 - k / ARCH_SEGMENTS))
        pts.append((ARCH_X + ARCH_R * c, ARCH_SPRING + ARCH_R * s, c, s))
    return pts


def arched_wall(mesh, material, z, normal, lo, hi):
    """The wall z = const between the wings, lo .. hi along x, with the
    arched doorway cut out: the full-height parts beside it, and above
    the arch one quad per arch segment up to the ceiling."""
    x0, x1 = ARCH_X - ARCH_R, ARCH_X + ARCH_R
    for a0, a1 in ((lo, x0), (x1, hi)):
        mesh.polygon(material, [(a0, 0, z), (a1, 0, z), (a1, H, z), (a0, H, z)], normal, uv_x)
    pts = arch_points()
    for (xa, ya, _, _), (xb, yb, _, _) in zip(pts, pts[1:]):
        mesh.polygon(material, [(xa, ya, z), (xb, yb, z), (xb, H, z), (xa, H, z)], normal, uv_x)


def shell():
    m = Mesh("shell")
    # floors, split where the doorway's floor meets them
    for x0, x1 in ((-6, ARCH_X - ARCH_R), (ARCH_X - ARCH_R, ARCH_X + ARCH_R), (ARCH_X + ARCH_R, 6)):
        m.polygon("mirror-floor", [(x0, 0, -3), (x1, 0, -3), (x1, 0, 3), (x0, 0, 3)], (0, 1, 0), uv_xz)
    m.polygon("mirror-floor", [(ARCH_X - ARCH_R, 0, ARCH_Z0), (ARCH_X + ARCH_R, 0, ARCH_Z0),
                               (ARCH_X + ARCH_R, 0, ARCH_Z1), (ARCH_X - ARCH_R, 0, ARCH_Z1)],
              (0, 1, 0), uv_xz)
    for x0, x1 in ((0, ARCH_X - ARCH_R), (ARCH_X - ARCH_R, ARCH_X + ARCH_R), (ARCH_X + ARCH_R, 6)):
        m.polygon("mirror-floor", [(x0, 0, 3.4), (x1, 0, 3.4), (x1, 0, 11.4), (x0, 0, 11.4)],
                  (0, 1, 0), uv_xz)
    # ceilings
    m.polygon("ceiling", [(-6, H, -3), (6, H, -3), (6, H, 3), (-6, H, 3)], (0, -1, 0), uv_xz)
    m.polygon("ceiling", [(0, H, 3.4), (6, H, 3.4), (6, H, 11.4), (0, H, 11.4)], (0, -1, 0), uv_xz)

    # main wing: windows open below, a fanlight above, in the -z wall
    windows = [(cx - 0.8, cx + 0.8, 0.9, 3.7) for cx in (-3.0, 0.0, 3.0)]
    wall(m, "plaster", "z", -3, (0, 0, 1), -6, 6, windows)
    for a0, a1, y0, y1 in windows:
        reveal(m, "plaster", "z", -3, (0, 0, 1), (a0, a1, y0, y1), WALL)
        # the transom, a stone bar through the wall under the fanlight
        box(m, "stone", (a0, 2.82, -3 - WALL), (a1, 2.9, -3), skip=("+x", "-x", "+y"))
        m.polygon("window-glow", [(a0, 2.9, -3.15), (a1, 2.9, -3.15), (a1, y1, -3.15), (a0, y1, -3.15)],
                  (0, 0, 1), uv_x)
        m.polygon("stone", [(a0, 2.9, -3.0), (a1, 2.9, -3.0), (a1, 2.9, -3.15), (a0, 2.9, -3.15)],
                  (0, 1, 0), uv_xz)
    wall(m, "plaster", "x", -6, (1, 0, 0), -3, 3)
    east = (-1.5, 1.5, 1.0, 3.6)
    wall(m, "plaster", "x", 6, (-1, 0, 0), -3, 3, [east])
    reveal(m, "plaster", "x", 6, (-1, 0, 0), east, WALL, "window-glow")
    arched_wall(m, "plaster", ARCH_Z0, (0, 0, -1), -6, 6)

    # side wing
    arched_wall(m, "plaster", ARCH_Z1, (0, 0, 1), 0, 6)
    wall(m, "plaster", "x", 0, (1, 0, 0), 3.4, 11.4)
    wall(m, "plaster", "x", 6, (-1, 0, 0), 3.4, 11.4)
    north = (1.8, 4.2, 1.2, 3.6)
    wall(m, "plaster", "z", 11.4, (0, 0, -1), 0, 6, [north])
    reveal(m, "plaster", "z", 11.4, (0, 0, -1), north, WALL, "window-glow")

    # the doorway: jambs up to the springing, then the round soffit,
    # its normals towards the arch's axis
    x0, x1 = ARCH_X - ARCH_R, ARCH_X + ARCH_R
    m.polygon("stone", [(x0, 0, ARCH_Z0), (x0, ARCH_SPRING, ARCH_Z0), (x0, ARCH_SPRING, ARCH_Z1),
                        (x0, 0, ARCH_Z1)], (1, 0, 0), uv_z)
    m.polygon("stone", [(x1, 0, ARCH_Z0), (x1, ARCH_SPRING, ARCH_Z0), (x1, ARCH_SPRING, ARCH_Z1),
                        (x1, 0, ARCH_Z1)], (-1, 0, 0), uv_z)
    rows = []
    for z in (ARCH_Z0, ARCH_Z1):
        row = []
        for k, (x, y, c, s) in enumerate(arch_points()):
            row.append(((x, y, z), (-c, -s, 0.0), (ARCH_R * math.pi * k / ARCH_SEGMENTS, z)))
        rows.append(row)
    m.strip("stone", rows)
    return m


def column():
    """A column standing at the origin: a square plinth, a 16-sided
    shaft with smooth normals, a square capital against the ceiling."""
    m = Mesh("column")
    box(m, "stone", (-0.4, 0, -0.4), (0.4, 0.25, 0.4), skip=("-y",))
    box(m, "stone", (-0.38, H - 0.3, -0.38), (0.38, H, 0.38), skip=("+y",))
    r = 0.28
    rows = []
    for y in (0.25, H - 0.3):
        row = []
        for k in range(SIDES + 1):
            c, s = cs(2 * math.pi * k / SIDES)
            row.append(((r * c, y, -r * s), (c, 0.0, -s), (r * 2 * math.pi * k / SIDES, -y)))
        rows.append(row)
    m.strip("stone", rows)
    return m


def table():
    """A table 2 x 1 m, its top 0.75 m high, centred on the origin."""
    m = Mesh("table")
    box(m, "wood", (-1.0, 0.72, -0.5), (1.0, 0.78, 0.5))
    for x in (-0.88, 0.81):
        for z in (-0.38, 0.31):
            box(m, "wood", (x, 0, z), (x + 0.07, 0.72, z + 0.07), skip=("+y", "-y"))
    return m


def lamp():
    """A hanging lamp, its origin 2.8 m above the floor (as the table's
    child): a rod to the ceiling, a conical shade and, inside it, an
    emissive disc facing down."""
    m = Mesh("lamp")
    rod = 0.02
    rows = []
    for y in (0.25, H - 2.8):
        row = []
        for k in range(9):
            c, s = cs(2 * math.pi * k / 8)
            row.append(((rod * c, y, -rod * s), (c, 0.0, -s), (k / 8, -y)))
        rows.append(row)
    m.strip("metal", rows)
    # the shade: a cone from r 0.12 at y 0.25 to r 0.3 at y 0; its
    # normal leans up by the cone's half angle
    slope = (0.3 - 0.12) / 0.25
    ny = slope / math.sqrt(1 + slope * slope)
    nr = 1 / math.sqrt(1 + slope * slope)
    rows = []
    for y, r in ((0.0, 0.3), (0.25, 0.12)):
        row = []
        for k in range(SIDES + 1):
            c, s = cs(2 * math.pi * k / SIDES)
            row.append(((r * c, y, -r * s), (nr * c, ny, -nr * s), (k / SIDES, y)))
        rows.append(row)
    m.strip("metal", rows)
    m.polygon("metal", [(0.12 * c, 0.25, -0.12 * s) for c, s in
                        (cs(2 * math.pi * k / SIDES) for k in range(SIDES))], (0, 1, 0),
              lambda p: (p[0], p[2]))
    m.polygon("lamp-glow", [(0.22 * c, 0.1, -0.22 * s) for c, s in
                            (cs(2 * math.pi * k / SIDES) for k in range(SIDES))], (0, -1, 0),
              lambda p: (p[0], p[2]))
    return m


def sconce():
    """A wall light on a wall at x = 0 facing +x: a metal box 0.12 m
    deep whose front face glows."""
    m = Mesh("sconce")
    box(m, "metal", (0, -0.15, -0.1), (0.12, 0.15, 0.1), skip=("-x", "+x"))
    m.polygon("lamp-glow", [(0.12, -0.15, -0.1), (0.12, 0.15, -0.1), (0.12, 0.15, 0.1),
                            (0.12, -0.15, 0.1)], (1, 0, 0), uv_z)
    return m


# ---------------------------------------------------------------------
# Materials, glTF's metallic-roughness; the MTL lines say the same.

MATERIALS = [
    ("plaster", dict(colour=(1, 1, 1), metallic=0, roughness=0.9, texture="plaster")),
    ("mirror-floor", dict(colour=(0.9, 0.9, 0.9), metallic=0, roughness=0.15,
                          texture="tiles", tiling=0.5, mirror=True)),
    ("ceiling", dict(colour=(0.85, 0.85, 0.82), metallic=0, roughness=1)),
    ("stone", dict(colour=(0.7, 0.66, 0.6), metallic=0, roughness=0.7)),
    ("wood", dict(colour=(0.45, 0.28, 0.15), metallic=0, roughness=0.6)),
    ("metal", dict(colour=(0.8, 0.8, 0.8), metallic=1, roughness=0.4)),
    ("window-glow", dict(colour=(0, 0, 0), metallic=0, roughness=1,
                         emission=(1.0, 0.96, 0.88), strength=WINDOW_STRENGTH)),
    ("lamp-glow", dict(colour=(0, 0, 0), metallic=0, roughness=1,
                       emission=(1.0, 0.85, 0.6), strength=LAMP_STRENGTH)),
]
MATERIAL_INDEX = {name: k for k, (name, _) in enumerate(MATERIALS)}


# ---------------------------------------------------------------------
# Nodes: translation, rotation (a unit quaternion x y z w), children.

def quat_axis(axis, degrees):
    c, s = cs(math.radians(degrees) / 2)
    a = unit(axis)
    return [round(a[0] * s, 9), round(a[1] * s, 9), round(a[2] * s, 9), round(c, 9)]


def quat_from_minus_z(d):
    """The rotation taking -Z (where glTF lights point) to d."""
    d = unit(d)
    axis = cross((0, 0, -1), d)
    angle = math.degrees(math.acos(-d[2]))
    return quat_axis(axis, angle)


SUN_DIRECTION = (0.35, -0.55, 0.76)  # where the sunlight goes

LIGHTS = [
    {"name": "sun", "type": "directional", "color": [1.0, 0.95, 0.85], "intensity": SUN_LUX},
    {"name": "lamp", "type": "spot", "color": [1.0, 0.85, 0.6], "intensity": LAMP_CD,
     "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.85}},
]
# one light a node: assimp, for one, names a light after the node that
# holds it, and would keep one of two nodes sharing it
for side in ("west", "east"):
    LIGHTS.append({"name": "sconce." + side, "type": "point", "color": [1.0, 0.8, 0.55],
                   "intensity": SCONCE_CD, "range": 12.0})


def scene_nodes():
    """The node tree, as (name, mesh, light, translation, rotation,
    children)."""
    columns = [("column.%d" % k, "column", None, [x, 0, 0], None, [])
               for k, x in enumerate((-4.5, -1.5, 1.5, 4.5))]
    spot = ("lamp.light", None, "lamp", [0, 0.08, 0], quat_axis((1, 0, 0), -90), [])
    return [
        ("shell", "shell", None, None, None, []),
        ("colonnade", None, None, [0, 0, -1.8], None, columns),
        ("table", "table", None, [1.0, 0, 1.0], quat_axis((0, 1, 0), 30),
         [("lamp", "lamp", None, [0, 2.8, 0], None, [spot])]),
        ("sun", None, "sun", [0, 6, -8], quat_from_minus_z(SUN_DIRECTION), []),
        ("sconce.west", "sconce", None, [0, 2.2, 7.4], None,
         [("sconce.west.light", None, "sconce.west", [0.25, 0, 0], None, [])]),
        ("sconce.east", "sconce", None, [6, 2.2, 7.4], quat_axis((0, 1, 0), 180),
         [("sconce.east.light", None, "sconce.east", [0.25, 0, 0], None, [])]),
    ]


def quat_matrix(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def compose(parent, translation, rotation):
    """parent (R, t) times this node's (R, t)."""
    pr, pt = parent
    r = quat_matrix(rotation) if rotation else [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    t = translation or [0, 0, 0]
    rr = [[sum(pr[i][k] * r[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    tt = [sum(pr[i][k] * t[k] for k in range(3)) + pt[i] for i in range(3)]
    return rr, tt


def apply(xf, p):
    r, t = xf
    return tuple(sum(r[i][k] * p[k] for k in range(3)) + t[i] for i in range(3))


def rotate(xf, n):
    r, _ = xf
    return tuple(sum(r[i][k] * n[k] for k in range(3)) for i in range(3))


# ---------------------------------------------------------------------
# PNG, with stored deflate blocks.

def png(width, height, rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    blocks = []
    for k in range(0, len(raw), 65535):
        part = raw[k:k + 65535]
        last = 1 if k + 65535 >= len(raw) else 0
        blocks.append(struct.pack("<BHH", last, len(part), 0xFFFF ^ len(part)) + part)
    data = b"\x78\x01" + b"".join(blocks) + struct.pack(">I", zlib.adler32(raw))

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body
                + struct.pack(">I", zlib.crc32(kind + body)))
    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", data) + chunk(b"IEND", b""))


def hash01(x, y, seed):
    """A value in [0, 1) from integer coordinates (an integer hash)."""
    h = (x * 374761393 + y * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65536.0


def plaster_png():
    """64 x 64, tiling: warm plaster with value noise at two scales."""
    n = 64

    def noise(x, y, cell, seed):
        cx, cy = x // cell, y // cell
        fx, fy = (x % cell) / cell, (y % cell) / cell
        m = n // cell

        def v(i, j):
            return hash01(i % m, j % m, seed)
        a = v(cx, cy) + (v(cx + 1, cy) - v(cx, cy)) * fx
        b = v(cx, cy + 1) + (v(cx + 1, cy + 1) - v(cx, cy + 1)) * fx
        return a + (b - a) * fy
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            t = 0.6 * noise(x, y, 16, 1) + 0.4 * noise(x, y, 4, 2)
            k = int(round(-14 + 28 * t))
            row += [205 + k, 196 + k, 180 + k]
        rows.append(row)
    return png(n, n, rows)


def tiles_png():
    """64 x 64, tiling: 2 x 2 tiles in two tones, 2-pixel grout."""
    n = 64
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            if x % 32 < 2 or y % 32 < 2:
                row += [70, 66, 60]
            elif (x // 32 + y // 32) % 2:
                row += [214, 206, 188]
            else:
                row += [120, 132, 126]
        rows.append(row)
    return png(n, n, rows)


# ---------------------------------------------------------------------
# Writers

def f32(x):
    """x as the float32 the .bin holds, as a Python float."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def write_gltf(meshes, nodes):
    binary = bytearray()
    views, accessors = [], []

    def add_view(data, target, stride=None):
        while len(binary) % 4:
            binary.append(0)
        view = {"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        view["target"] = target
        views.append(view)
        binary.extend(data)
        return len(views) - 1

    def add_vectors(values, kind, bounds=False):
        n = len(values[0])
        data = b"".join(struct.pack("<%df" % n, *v) for v in values)
        view = add_view(data, 34962, 4 * n)
        acc = {"bufferView": view, "componentType": 5126, "count": len(values), "type": kind}
        if bounds:
            stored = [[f32(c) for c in v] for v in values]
            acc["min"] = [min(v[k] for v in stored) for k in range(n)]
            acc["max"] = [max(v[k] for v in stored) for k in range(n)]
        accessors.append(acc)
        return len(accessors) - 1

    def add_indices(tris, nverts):
        flat = [i for t in tris for i in t]
        if nverts <= 65535:
            data, ctype = struct.pack("<%dH" % len(flat), *flat), 5123
        else:
            data, ctype = struct.pack("<%dI" % len(flat), *flat), 5125
        view = add_view(data, 34963)
        accessors.append({"bufferView": view, "componentType": ctype, "count": len(flat),
                          "type": "SCALAR"})
        return len(accessors) - 1

    gmeshes, mesh_index = [], {}
    for mesh in meshes:
        prims = []
        for material, (verts, tris) in mesh.prims.items():
            pos = add_vectors([v[0] for v in verts], "VEC3", bounds=True)
            nrm = add_vectors([unit(v[1]) for v in verts], "VEC3")
            uv = add_vectors([v[2] for v in verts], "VEC2")
            idx = add_indices(tris, len(verts))
            prims.append({"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv},
                          "indices": idx, "material": MATERIAL_INDEX[material], "mode": 4})
        mesh_index[mesh.name] = len(gmeshes)
        gmeshes.append({"name": mesh.name, "primitives": prims})

    gmaterials, images = [], ["plaster", "tiles"]
    for name, m in MATERIALS:
        pbr = {"baseColorFactor": [m["colour"][0], m["colour"][1], m["colour"][2], 1.0],
               "metallicFactor": float(m["metallic"]), "roughnessFactor": float(m["roughness"])}
        if "texture" in m:
            info = {"index": images.index(m["texture"]), "texCoord": 0}
            if "tiling" in m:
                info["extensions"] = {"KHR_texture_transform": {
                    "scale": [m["tiling"], m["tiling"]]}}
            pbr["baseColorTexture"] = info
        mat = {"name": name, "pbrMetallicRoughness": pbr}
        if "emission" in m:
            mat["emissiveFactor"] = list(m["emission"])
            mat["extensions"] = {"KHR_materials_emissive_strength": {
                "emissiveStrength": m["strength"]}}
        if m.get("mirror"):
            mat["extras"] = {"reflect": {"mirror": True}}
        gmaterials.append(mat)

    gnodes = []

    def add_node(node):
        name, mesh, light, translation, rotation, children = node
        g = {"name": name}
        k = len(gnodes)
        gnodes.append(g)
        kids = [add_node(c) for c in children]
        if kids:
            g["children"] = kids
        if mesh:
            g["mesh"] = mesh_index[mesh]
        if light:
            g["extensions"] = {"KHR_lights_punctual": {
                "light": [l["name"] for l in LIGHTS].index(light)}}
        if translation:
            g["translation"] = [float(v) for v in translation]
        if rotation:
            g["rotation"] = rotation
        return k
    hall = {"name": "hall"}
    gnodes.append(hall)
    hall["children"] = [add_node(n) for n in nodes]

    doc = {
        "asset": {"version": "2.0", "generator": "reflect doc/examples/hall-gen.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength",
                           "KHR_texture_transform"],
        "extensions": {"KHR_lights_punctual": {"lights": LIGHTS}},
        "scene": 0,
        "scenes": [{"name": "hall", "nodes": [0]}],
        "nodes": gnodes,
        "meshes": gmeshes,
        "materials": gmaterials,
        "textures": [{"sampler": 0, "source": 0}, {"sampler": 0, "source": 1}],
        "images": [{"uri": "hall-textures/%s.png" % n, "mimeType": "image/png"} for n in images],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "buffers": [{"uri": "hall.bin", "byteLength": len(binary)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    text = json.dumps(doc, indent=1, ensure_ascii=True)
    # arrays of numbers and names on one line each
    text = re.sub(r"\[\s+([^][{}]*?)\s+\]", lambda m: "[" + " ".join(m.group(1).split()) + "]", text)
    text += "\n"
    return text.encode("ascii"), bytes(binary)


def world_triangles(meshes, nodes):
    """Every node's mesh in world space: (node name, material,
    [(position, normal, uv)], triangles)."""
    by_name = {m.name: m for m in meshes}
    out = []
    identity = ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0])

    def walk(node, parent):
        name, mesh, _, translation, rotation, children = node
        xf = compose(parent, translation, rotation)
        if mesh:
            for material, (verts, tris) in by_name[mesh].prims.items():
                wv = [(apply(xf, p), unit(rotate(xf, n)), uv) for p, n, uv in verts]
                out.append((name, material, wv, tris))
        for c in children:
            walk(c, xf)
    for n in nodes:
        walk(n, identity)
    return out


def fmt(x):
    s = "%.6f" % x
    return "0.000000" if s == "-0.000000" else s


def write_obj(meshes, nodes):
    """The same triangles in world space (OBJ has no node tree), each
    node an object; positions, normals and uvs shared where equal."""
    lines = ["# The example level of hall.scene as hall.gltf has it, written by",
             "# hall-gen.py.  Metres, +Y up, the glTF's node transforms applied.",
             "mtllib hall.mtl"]
    body = []
    tables = [{}, {}, {}]
    heads = ["v", "vt", "vn"]
    decl = [[], [], []]

    def ref(k, text):
        t = tables[k]
        if text not in t:
            t[text] = len(t) + 1
            decl[k].append("%s %s" % (heads[k], text))
        return t[text]
    tiling = {name: m.get("tiling", 1.0) for name, m in MATERIALS}
    for name, material, verts, tris in world_triangles(meshes, nodes):
        body.append("o %s.%s" % (name, material))
        body.append("usemtl %s" % material)
        # KHR_texture_transform's scale, folded into the uvs: MTL's
        # "map_Kd -s" is not read by every loader
        k = tiling[material]
        refs = []
        for p, n, uv in verts:
            refs.append((ref(0, " ".join(fmt(c) for c in p)),
                         ref(1, "%s %s" % (fmt(uv[0] * k), fmt(-uv[1] * k))),
                         ref(2, " ".join(fmt(c) for c in n))))
        for t in tris:
            body.append("f " + " ".join("%d/%d/%d" % refs[i] for i in t))
    text = "\n".join(lines + decl[0] + decl[1] + decl[2] + body) + "\n"
    return text.encode("ascii")


def write_mtl():
    out = ["# Materials of hall.obj, as hall.gltf's: Kd base colour, Pm metallic,",
           "# Pr roughness and Ns = 1000 (1 - roughness)^2 for loaders without them,",
           "# Ke emission (emissiveFactor times emissive strength).  The floor",
           "# is the reflective one, by its name (mirror-...); its texture of",
           "# 2 x 2 tiles repeats every 2 m through hall.obj's uvs, which hold",
           "# the glTF's KHR_texture_transform."]
    for name, m in MATERIALS:
        c = m["colour"]
        r = m["roughness"]
        out.append("")
        out.append("newmtl %s" % name)
        out.append("Kd %s %s %s" % tuple(fmt(v) for v in c))
        # a metal's specular colour is its base colour, a dielectric's 4 %
        ks = c if m["metallic"] else (0.04, 0.04, 0.04)
        out.append("Ks %s %s %s" % tuple(fmt(v) for v in ks))
        out.append("Ns %s" % fmt(1000 * (1 - r) ** 2))
        out.append("Pm %s" % fmt(m["metallic"]))
        out.append("Pr %s" % fmt(r))
        if "emission" in m:
            out.append("Ke %s %s %s" % tuple(fmt(v * m["strength"]) for v in m["emission"]))
        if "texture" in m:
            out.append("map_Kd hall-textures/%s.png" % m["texture"])
        out.append("illum %d" % (3 if m.get("mirror") else 2))
    return ("\n".join(out) + "\n").encode("ascii")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else here
    meshes = [shell(), column(), table(), lamp(), sconce()]
    nodes = scene_nodes()
    gltf, binary = write_gltf(meshes, nodes)
    files = {
        "hall.gltf": gltf,
        "hall.bin": binary,
        "hall.obj": write_obj(meshes, nodes),
        "hall.mtl": write_mtl(),
        "hall-textures/plaster.png": plaster_png(),
        "hall-textures/tiles.png": tiles_png(),
    }
    os.makedirs(os.path.join(out, "hall-textures"), exist_ok=True)
    for name, data in files.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
