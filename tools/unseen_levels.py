#!/usr/bin/env python3
"""Held-out level-like glTF scenes for checking ISM (and later techniques) beyond the suite.

Written independently of the suite's Rust generator (src/suite/levels.rs) and never used to
tune anything: walls, floors and ceilings are solid slabs with outward normals, as level
geometry is modelled. Four scenes, the kinds issue 10's "done when" names:

- apartment: four rooms of different sizes in a 2 x 2 grid, 0.25 m walls, three doorways in an
  L (so no straight line joins the lit rooms and the camera's room), a ceiling lamp in one room
  and a spot in the next; the camera stands in the fourth, unlit, room.
- sunroom: a 5 x 2.8 x 7 m room with two windows in one long wall, a sun shining in, a lamp
  and a spot.
- storeroom: a 7 x 3 x 9 m room with two shelving units (thin slabs on posts), forty boxes
  and a spot and a lamp.
- offices: a corridor with a lamp and three offices behind 0.15 m partitions, a spot in the
  first; the camera in the unlit third (added later, see `offices`).
- cluttered: a 6.5 x 3.2 x 5.5 m room with thirty boxes and cylinders and a spot (issue 13's
  "done when" room for DRT, written after its parameters were fixed).
- three_rooms_b / three_rooms_c: three box rooms in a row joined by doorways, a spot in the
  first; the camera in the second / third room (issue 12's "done when" level for MRT).

Usage: python3 tools/unseen_levels.py OUT_DIR  (writes OUT_DIR/<name>.gltf)
"""

import base64
import json
import math
import random
import struct
from pathlib import Path


class Writer:
    def __init__(self):
        self.data = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "bouncelab tools/unseen_levels.py"},
            # Intensities are W/sr and W/m^2; Bounce Lab reads unrecorded files as candela/lux.
            "extras": {"bouncelab": {"light_units": "radiometric"}},
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": []}},
            "scenes": [{"nodes": []}],
            "scene": 0,
            "nodes": [],
            "meshes": [],
            "materials": [],
            "accessors": [],
            "bufferViews": [],
            "buffers": [],
            "cameras": [],
        }
        self.box_meshes = {}

    def material(self, name, rgb):
        self.doc["materials"].append(
            {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        )
        return len(self.doc["materials"]) - 1

    def _view(self, payload, target):
        while len(self.data) % 4:
            self.data.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload), "target": target})
        self.data.extend(payload)
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, view, ctype, count, kind, lo=None, hi=None):
        a = {"bufferView": view, "componentType": ctype, "count": count, "type": kind}
        if lo is not None:
            a["min"], a["max"] = lo, hi
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def box_mesh(self, size, material):
        """A cuboid of full size `size` centred on the origin: 24 vertices, outward normals."""
        key = (tuple(round(s, 6) for s in size), material)
        if key in self.box_meshes:
            return self.box_meshes[key]
        hx, hy, hz = (s / 2 for s in size)
        pos, nrm, idx = [], [], []
        for axis in range(3):
            for sign in (1.0, -1.0):
                n = [0.0, 0.0, 0.0]
                n[axis] = sign
                u, v = (axis + 1) % 3, (axis + 2) % 3
                base = len(pos)
                for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = sign
                    p[u], p[v] = a, b
                    pos.append([p[0] * hx, p[1] * hy, p[2] * hz])
                    nrm.append(n)
                # Counter-clockwise seen from outside: (u x v) = axis for the + face.
                if sign > 0:
                    idx += [base, base + 1, base + 2, base, base + 2, base + 3]
                else:
                    idx += [base, base + 2, base + 1, base, base + 3, base + 2]
        pv = self._view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        nv = self._view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        iv = self._view(b"".join(struct.pack("<H", i) for i in idx), 34963)
        pa = self._accessor(pv, 5126, len(pos), "VEC3", [-hx, -hy, -hz], [hx, hy, hz])
        na = self._accessor(nv, 5126, len(nrm), "VEC3")
        ia = self._accessor(iv, 5123, len(idx), "SCALAR")
        self.doc["meshes"].append(
            {"name": f"box{len(self.doc['meshes'])}", "primitives": [{"attributes": {"POSITION": pa, "NORMAL": na}, "indices": ia, "material": material}]}
        )
        self.box_meshes[key] = len(self.doc["meshes"]) - 1
        return self.box_meshes[key]

    def cylinder_mesh(self, radius, height, material, sides=16):
        """A closed cylinder of `radius` and `height` standing on the origin (y up), flat
        normals on the caps, smooth on the side."""
        pos, nrm, idx = [], [], []
        ring = [(math.cos(2 * math.pi * k / sides), math.sin(2 * math.pi * k / sides)) for k in range(sides)]
        for k, (c, s) in enumerate(ring):  # side: two vertices per ring point
            pos += [[radius * c, 0.0, radius * s], [radius * c, height, radius * s]]
            nrm += [[c, 0.0, s], [c, 0.0, s]]
        for k in range(sides):
            a, b = 2 * k, 2 * ((k + 1) % sides)
            # Counter-clockwise seen from outside.
            idx += [a, a + 1, b + 1, a, b + 1, b]
        for y, ny in ((height, 1.0), (0.0, -1.0)):
            centre = len(pos)
            pos.append([0.0, y, 0.0])
            nrm.append([0.0, ny, 0.0])
            for c, s in ring:
                pos.append([radius * c, y, radius * s])
                nrm.append([0.0, ny, 0.0])
            for k in range(sides):
                a, b = centre + 1 + k, centre + 1 + (k + 1) % sides
                idx += [centre, b, a] if ny > 0 else [centre, a, b]
        pv = self._view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        nv = self._view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        iv = self._view(b"".join(struct.pack("<H", i) for i in idx), 34963)
        pa = self._accessor(pv, 5126, len(pos), "VEC3", [-radius, 0.0, -radius], [radius, height, radius])
        na = self._accessor(nv, 5126, len(nrm), "VEC3")
        ia = self._accessor(iv, 5123, len(idx), "SCALAR")
        self.doc["meshes"].append(
            {"name": f"cylinder{len(self.doc['meshes'])}", "primitives": [{"attributes": {"POSITION": pa, "NORMAL": na}, "indices": ia, "material": material}]}
        )
        return len(self.doc["meshes"]) - 1

    def node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def slab(self, name, lo, hi, material):
        size = [h - l for l, h in zip(lo, hi)]
        centre = [(l + h) / 2 for l, h in zip(lo, hi)]
        self.node({"name": name, "mesh": self.box_mesh(size, material), "translation": centre})

    def light(self, name, kind, intensity, position, direction, colour=(1.0, 0.95, 0.9), cone=None):
        light = {"name": name, "type": kind, "color": list(colour), "intensity": intensity}
        if cone:
            light["spot"] = {"innerConeAngle": cone[0], "outerConeAngle": cone[1]}
        lights = self.doc["extensions"]["KHR_lights_punctual"]["lights"]
        lights.append(light)
        self.node({"name": name, "translation": list(position), "rotation": look_rotation(direction),
                   "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})

    def camera(self, eye, target, yfov, znear):
        self.doc["cameras"].append({"type": "perspective", "perspective": {"yfov": yfov, "znear": znear, "aspectRatio": 16 / 9}})
        d = [t - e for t, e in zip(target, eye)]
        self.node({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_rotation(d)})

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.data), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.data)).decode()}]
        doc = {k: v for k, v in self.doc.items() if v != []}
        Path(path).write_text(json.dumps(doc, indent=1))


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def look_rotation(direction):
    """The quaternion (x, y, z, w) turning -Z onto `direction` with +Y kept up."""
    f = normalize(direction)
    up = [0.0, 1.0, 0.0] if abs(f[1]) < 0.999 else [1.0, 0.0, 0.0]
    r = normalize(cross(f, up))
    u = cross(r, f)
    b = [-c for c in f]
    m = [[r[0], u[0], b[0]], [r[1], u[1], b[1]], [r[2], u[2], b[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    if m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        return [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    if m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        return [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
    return [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]


WALL, FLOOR, CEILING = (0.75, 0.72, 0.66), (0.5, 0.38, 0.28), (0.85, 0.85, 0.85)


def apartment():
    w = Writer()
    wall, floor, ceil = w.material("plaster", WALL), w.material("parquet", FLOOR), w.material("ceiling", CEILING)
    blue = w.material("blue_wall", (0.3, 0.4, 0.65))
    t, h = 0.25, 2.6
    xs = [0.0, 4.5, 4.5 + t, 4.5 + t + 3.5]  # room columns: [0, 4.5] and [4.75, 8.25]
    zs = [0.0, 3.5, 3.5 + t, 3.5 + t + 5.0]  # room rows: [0, 3.5] and [3.75, 8.75]
    x0, x1 = -t, xs[3] + t
    z0, z1 = -t, zs[3] + t
    w.slab("floor", [x0, -t, z0], [x1, 0.0, z1], floor)
    w.slab("ceiling", [x0, h, z0], [x1, h + t, z1], ceil)
    # Outer walls.
    w.slab("outer_south", [x0, 0, z0], [x1, h, 0.0], wall)
    w.slab("outer_north", [x0, 0, zs[3]], [x1, h, z1], wall)
    w.slab("outer_west", [x0, 0, 0.0], [0.0, h, zs[3]], blue)
    w.slab("outer_east", [xs[3], 0, 0.0], [x1, h, zs[3]], wall)
    door_h = 2.05
    # Interior wall along x (between the rows), z in [3.5, 3.75]: doorway A->C at x 1.0..1.9 only.
    w.slab("inner_x_a", [0.0, 0, zs[1]], [1.0, h, zs[2]], wall)
    w.slab("inner_x_b", [1.9, 0, zs[1]], [xs[3], h, zs[2]], wall)
    w.slab("inner_x_lintel", [1.0, door_h, zs[1]], [1.9, h, zs[2]], wall)
    # Interior wall along z (between the columns), x in [4.5, 4.75]: doorway A->B at z 2.2..3.1,
    # doorway C->D at z 7.5..8.4 (so D, the camera's room, is two doorways from the lamp).
    w.slab("inner_z_a", [xs[1], 0, 0.0], [xs[2], h, 2.2], wall)
    w.slab("inner_z_b", [xs[1], 0, 3.1], [xs[2], h, 7.5], wall)
    w.slab("inner_z_c", [xs[1], 0, 8.4], [xs[2], h, zs[3]], wall)
    w.slab("inner_z_lintel_ab", [xs[1], door_h, 2.2], [xs[2], h, 3.1], wall)
    w.slab("inner_z_lintel_cd", [xs[1], door_h, 7.5], [xs[2], h, 8.4], wall)
    # Room B (x 4.75..8.25, z 0..3.5) has no door to D: the wall between B and D is inner_x_b.
    w.slab("table", [1.5, 0.72, 0.9], [2.7, 0.76, 1.8], floor)
    w.slab("sofa", [5.2, 0.0, 0.3], [7.6, 0.8, 1.1], blue)
    w.light("lamp", "point", 6.0, [2.2, 2.3, 1.7], [0, -1, 0])
    w.light("spot", "spot", 25.0, [7.8, 2.45, 3.2], [-0.4, -1.0, -0.5], cone=(0.4, 0.7))
    w.camera([8.0, 1.6, 8.5], [4.0, 1.0, 6.5], 1.15, 0.05)
    return w


def sunroom():
    w = Writer()
    wall, floor, ceil = w.material("plaster", WALL), w.material("tiles", (0.35, 0.33, 0.3)), w.material("ceiling", CEILING)
    green = w.material("green", (0.3, 0.55, 0.3))
    t, h = 0.3, 2.8
    X, Z = 5.0, 7.0
    w.slab("floor", [-t, -t, -t], [X + t, 0, Z + t], floor)
    w.slab("ceiling", [-t, h, -t], [X + t, h + t, Z + t], ceil)
    w.slab("south", [0, 0, -t], [X, h, 0], wall)
    w.slab("north", [0, 0, Z], [X, h, Z + t], green)
    w.slab("east", [X, 0, -t], [X + t, h, Z + t], wall)
    # The west wall (x in [-t, 0]) with two 1.4 x 1.5 m windows, sills at 0.8 m.
    win = [(1.0, 2.4), (4.2, 5.6)]
    sill, head = 0.8, 2.3
    edges = [0.0] + [e for a in win for e in a] + [Z]
    for i in range(0, len(edges), 2):
        w.slab(f"west_pier_{i}", [-t, 0, edges[i] - (t if i == 0 else 0)], [0, h, edges[i + 1] + (t if i + 2 == len(edges) else 0)], wall)
    for k, (a, b) in enumerate(win):
        w.slab(f"west_sill_{k}", [-t, 0, a], [0, sill, b], wall)
        w.slab(f"west_head_{k}", [-t, head, a], [0, h, b], wall)
    w.slab("bench", [3.6, 0.0, 2.5], [4.6, 0.45, 4.5], green)
    w.light("sun", "directional", 5.0, [-3.0, 5.0, 3.0], [1.0, -0.6, 0.35])
    w.light("lamp", "point", 3.0, [4.2, 2.2, 6.3], [0, -1, 0])
    w.light("spot", "spot", 15.0, [0.5, 2.6, 6.6], [0.6, -0.8, -0.9], cone=(0.3, 0.55))
    w.camera([4.6, 1.6, 0.4], [1.5, 1.0, 5.0], 1.2, 0.05)
    return w


def closed_room(w, t, h, X, Z, wall, floor, ceil):
    """A closed X x h x Z m room of t m slabs (floor, ceiling, four walls) from the origin."""
    w.slab("floor", [-t, -t, -t], [X + t, 0, Z + t], floor)
    w.slab("ceiling", [-t, h, -t], [X + t, h + t, Z + t], ceil)
    w.slab("south", [0, 0, -t], [X, h, 0], wall)
    w.slab("north", [0, 0, Z], [X, h, Z + t], wall)
    w.slab("west", [-t, 0, -t], [0, h, Z + t], wall)
    w.slab("east", [X, 0, -t], [X + t, h, Z + t], wall)


def storeroom():
    w = Writer()
    wall, floor, ceil = w.material("concrete", (0.55, 0.55, 0.52)), w.material("floor", (0.4, 0.4, 0.42)), w.material("ceiling", CEILING)
    metal = w.material("shelf", (0.6, 0.5, 0.35))
    colours = [(0.7, 0.55, 0.35), (0.6, 0.2, 0.15), (0.2, 0.35, 0.6), (0.75, 0.75, 0.7)]
    stuff = [w.material(f"crate_{i}", c) for i, c in enumerate(colours)]
    t, h, X, Z = 0.2, 3.0, 7.0, 9.0
    closed_room(w, t, h, X, Z, wall, floor, ceil)
    for s, x in enumerate([1.5, 4.5]):
        for k, y in enumerate([0.1, 0.9, 1.7]):
            w.slab(f"shelf_{s}_{k}", [x, y, 2.0], [x + 1.0, y + 0.04, 7.0], metal)
        for px in [x, x + 0.96]:
            for pz in [2.0, 4.48, 6.96]:
                w.slab(f"post_{s}_{px}_{pz}", [px, 0, pz], [px + 0.04, 2.0, pz + 0.04], metal)
    rng = random.Random(20261123)
    for i in range(40):
        size = 0.2 + 0.35 * rng.random()
        if i < 24:  # on the shelves
            s, k = i % 2, (i // 2) % 3
            x = [1.5, 4.5][s] + 0.1 + rng.random() * (0.9 - size)
            y = [0.14, 0.94, 1.74][k]
            z = 2.1 + rng.random() * (4.8 - size)
            hy = min(size, 0.7)
        else:  # on the floor along the walls
            x = rng.choice([0.2, 6.2]) + rng.random() * 0.4
            y = 0.0
            z = 0.3 + rng.random() * 8.2
            hy = size
        w.slab(f"crate_{i}", [x, y, z], [x + size, y + hy, z + size], stuff[i % len(stuff)])
    w.light("spot", "spot", 60.0, [3.5, 2.9, 1.0], [0.0, -1.0, 0.9], cone=(0.5, 0.8))
    w.light("lamp", "point", 4.0, [3.5, 2.7, 8.0], [0, -1, 0])
    w.camera([6.6, 2.2, 0.4], [3.2, 0.8, 5.0], 1.1, 0.05)
    return w


def cluttered():
    """Issue 13's "done when" room: 6.5 x 3.2 x 5.5 m, thirty boxes and cylinders, a spot."""
    w = Writer()
    wall, floor, ceil = w.material("plaster", (0.72, 0.7, 0.66)), w.material("boards", (0.45, 0.35, 0.25)), w.material("ceiling", CEILING)
    colours = [(0.8, 0.3, 0.2), (0.25, 0.45, 0.7), (0.8, 0.75, 0.35), (0.35, 0.6, 0.35), (0.7, 0.7, 0.7)]
    stuff = [w.material(f"thing_{i}", c) for i, c in enumerate(colours)]
    t, h, X, Z = 0.2, 3.2, 6.5, 5.5
    closed_room(w, t, h, X, Z, wall, floor, ceil)
    rng = random.Random(13131313)
    for i in range(30):
        size = 0.25 + 0.45 * rng.random()
        x, z = 0.4 + rng.random() * (X - 0.8 - size), 0.4 + rng.random() * (Z - 0.8 - size)
        material = stuff[rng.randrange(len(stuff))]
        if i % 5 in (1, 3):
            r, hh = size / 2, size * (0.8 + 0.8 * rng.random())
            w.node({"name": f"cylinder_{i}", "mesh": w.cylinder_mesh(r, hh, material), "translation": [x + r, 0.0, z + r]})
        else:
            w.slab(f"box_{i}", [x, 0, z], [x + size, size * (0.5 + rng.random()), z + size], material)
    w.light("spot", "spot", 70.0, [0.6, 3.0, 0.6], [1.0, -0.9, 0.8], cone=(0.45, 0.75))
    w.camera([6.1, 2.4, 5.1], [2.6, 0.2, 2.0], 1.1, 0.05)
    return w


def cornell_b():
    """Issue 14's "done when" box, never used for tuning: a 2.4 x 2.2 x 2.6 m Cornell-style box
    (open front, 5 cm slabs), blue and yellow side walls, a rotated tall box and a cylinder, a
    point light under the ceiling and a spot on the back wall (the digest's record demo)."""
    w = Writer()
    white, blue, yellow = w.material("white", (0.73, 0.73, 0.7)), w.material("blue", (0.15, 0.3, 0.7)), w.material("yellow", (0.75, 0.65, 0.2))
    t, X, h, Z = 0.05, 2.4, 2.2, 2.6
    w.slab("floor", [-t, -t, -t], [X + t, 0, Z], white)
    w.slab("ceiling", [-t, h, -t], [X + t, h + t, Z], white)
    w.slab("back", [-t, 0, -t], [X + t, h, 0], white)
    w.slab("left", [-t, 0, 0], [0, h, Z], blue)
    w.slab("right", [X, 0, 0], [X + t, h, Z], yellow)
    angle = math.radians(-20.0)
    w.node({"name": "tall box", "mesh": w.box_mesh([0.6, 1.3, 0.6], white), "translation": [0.75, 0.65, 0.9],
            "rotation": [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]})
    w.node({"name": "drum", "mesh": w.cylinder_mesh(0.3, 0.6, white), "translation": [1.65, 0.0, 1.5]})
    w.light("lamp", "point", 6.0, [1.2, 2.0, 1.4], [0, -1, 0])
    w.light("spot", "spot", 25.0, [1.9, 1.8, 2.4], [-0.3, -0.2, -1.0], cone=(0.2, 0.35))
    w.camera([1.2, 1.1, 4.4], [1.2, 1.0, 0.0], 0.75, 0.05)
    return w


def outer_shell(w, t, h, X, Z, floor, ceil, south, north, west, east):
    """Floor, ceiling and four outer walls of t m slabs around [0, X] x [0, Z], h m high; the
    south and north walls run the full width, the west and east walls fit between them."""
    w.slab("floor", [-t, -t, -t], [X + t, 0, Z + t], floor)
    w.slab("ceiling", [-t, h, -t], [X + t, h + t, Z + t], ceil)
    w.slab("south", [-t, 0, -t], [X + t, h, 0], south)
    w.slab("north", [-t, 0, Z], [X + t, h, Z + t], north)
    w.slab("west", [-t, 0, 0], [0, h, Z], west)
    w.slab("east", [X, 0, 0], [X + t, h, Z], east)


def offices():
    """Added at stop 15, after the apartment had been used to diagnose ISM's holes: a second
    held-out multi-room level, never used for tuning. Thin (0.15 m) partitions, a 12 m corridor
    with a lamp at its west end, three offices off it, a spot in the first; the camera stands
    in the third office, lit only through its door (and by bounces off the corridor)."""
    w = Writer()
    wall, floor, ceil = w.material("paint", (0.7, 0.7, 0.62)), w.material("carpet", (0.3, 0.32, 0.4)), w.material("tiles", CEILING)
    desk = w.material("desk", (0.55, 0.4, 0.25))
    accent = w.material("accent", (0.65, 0.3, 0.25))
    t, h = 0.15, 2.7
    X = 12.3  # corridor x in [0, X], z in [0, 2]; offices z in [2 + t, 6 + t]
    zc, zo = 2.0, 2.0 + t
    Z = zo + 4.0
    outer_shell(w, t, h, X, Z, floor, ceil, wall, wall, accent, wall)
    # Office partitions along z at x = 4 and 8.15 (each t thick).
    parts = [(4.0, 4.0 + t), (8.15, 8.15 + t)]
    for i, (a, b) in enumerate(parts):
        w.slab(f"partition_{i}", [a, 0, zo], [b, h, Z], wall)
    # The corridor wall (z in [2, 2.15]) with one 0.9 m door per office, at different places.
    doors = [(2.8, 3.7), (4.6, 5.5), (11.0, 11.9)]
    door_h = 2.1
    edges = [0.0] + [e for d in doors for e in d] + [X]
    for i in range(0, len(edges), 2):
        w.slab(f"corridor_wall_{i}", [edges[i], 0, zc], [edges[i + 1], h, zo], wall)
    for k, (a, b) in enumerate(doors):
        w.slab(f"lintel_{k}", [a, door_h, zc], [b, h, zo], wall)
    # Desks (a top on two side panels) in each office, and a cabinet in the third.
    for k, x in enumerate([1.0, 5.2, 9.4]):
        w.slab(f"desk_top_{k}", [x, 0.72, Z - 1.0], [x + 1.6, 0.75, Z - 0.2], desk)
        for px in [x, x + 1.55]:
            w.slab(f"desk_side_{k}_{px}", [px, 0, Z - 1.0], [px + 0.05, 0.72, Z - 0.2], desk)
    w.slab("cabinet", [11.4, 0, 4.0], [12.2, 1.3, 5.0], accent)
    w.light("lamp", "point", 5.0, [0.8, 2.4, 1.0], [0, -1, 0])
    w.light("spot", "spot", 30.0, [2.0, 2.6, 4.5], [0.3, -1.0, 0.4], cone=(0.35, 0.6))
    w.camera([8.7, 1.7, 5.7], [11.2, 0.9, 2.3], 1.2, 0.05)
    return w


def three_rooms(view):
    """Added for issue 12 (MRT), never used for tuning: three box rooms of different sizes in a
    row along x, 0.2 m slab walls, one 1.0 x 2.1 m doorway between each pair at different
    places along z, a spot in the first room aimed at its floor; no other light. `view` "b" puts
    the camera in the second room, "c" in the third (the same level, two files)."""
    w = Writer()
    wall, floor, ceil = w.material("plaster", WALL), w.material("oak", FLOOR), w.material("ceiling", CEILING)
    green = w.material("green_wall", (0.35, 0.55, 0.35))
    t, h = 0.2, 2.8
    # Rooms along x: A [0, 4], B [4.2, 10.2], C [10.4, 14.9]; all z in [0, 5].
    xa, xb, xc = (0.0, 4.0), (4.0 + t, 10.0 + t), (10.0 + 2 * t, 14.5 + 2 * t)
    Z = 5.0
    x0, x1 = -t, xc[1] + t
    w.slab("floor", [x0, -t, -t], [x1, 0.0, Z + t], floor)
    w.slab("ceiling", [x0, h, -t], [x1, h + t, Z + t], ceil)
    w.slab("south", [x0, 0, -t], [x1, h, 0.0], wall)
    w.slab("north", [x0, 0, Z], [x1, h, Z + t], wall)
    w.slab("west", [x0, 0, 0.0], [0.0, h, Z], green)
    w.slab("east", [xc[1], 0, 0.0], [x1, h, Z], wall)
    door_h = 2.1
    # Wall A|B at x [4, 4.2] with a doorway at z 3.2..4.2; wall B|C at x [10.2, 10.4], z 0.8..1.8.
    for k, (xw, (za, zb)) in enumerate([((xa[1], xb[0]), (3.2, 4.2)), ((xb[1], xc[0]), (0.8, 1.8))]):
        w.slab(f"partition_{k}_a", [xw[0], 0, 0.0], [xw[1], h, za], wall)
        w.slab(f"partition_{k}_b", [xw[0], 0, zb], [xw[1], h, Z], wall)
        w.slab(f"lintel_{k}", [xw[0], door_h, za], [xw[1], h, zb], wall)
    w.light("spot", "spot", 40.0, [1.0, 2.6, 1.2], [0.5, -1.0, 0.6], cone=(0.3, 0.55))
    if view == "b":
        w.camera([9.6, 1.6, 4.5], [5.5, 0.8, 1.5], 1.2, 0.05)
    else:
        w.camera([14.3, 1.6, 4.6], [11.0, 0.7, 1.2], 1.2, 0.05)
    return w


def maisonette():
    """Added at stop 37, never used for tuning: five rooms off a 1.6 m hall, 0.3 m walls (thicker
    than any suite level), 3.0 m ceilings, doors of different widths; a spot in the first room,
    a lamp in the second; the camera stands in the room across the hall from them, lit only by
    light that has turned two corners."""
    w = Writer()
    wall, floor, ceil = w.material("plaster", (0.78, 0.74, 0.7)), w.material("oak", (0.55, 0.42, 0.3)), w.material("ceiling", CEILING)
    ochre = w.material("ochre", (0.7, 0.55, 0.25))
    t, h = 0.3, 3.0
    # Hall: x in [0, 13], z in [4, 5.6]. South rooms z in [0, 4]: x [0,4], [4.3,8.3], [8.6,13].
    # North rooms z in [5.9, 10.4]: x [0,6], [6.3,13].
    zs, zh0, zh1, zn = 4.0, 4.0 + t, 4.0 + t + 1.6, 4.0 + 2 * t + 1.6
    Z = zn + 4.5
    X = 13.0
    outer_shell(w, t, h, X, Z, floor, ceil, wall, ochre, wall, wall)
    door_h = 2.2
    def wall_x(name, z0, z1, doors):
        edges = [0.0] + [e for d in doors for e in d] + [X]
        for i in range(0, len(edges), 2):
            w.slab(f"{name}_{i}", [edges[i], 0, z0], [edges[i + 1], h, z1], wall)
        for k, (a, b) in enumerate(doors):
            w.slab(f"{name}_head_{k}", [a, door_h, z0], [b, h, z1], wall)
    wall_x("hall_s", zs, zh0, [(2.6, 3.5), (5.0, 6.2), (11.8, 12.6)])
    wall_x("hall_n", zh1, zn, [(1.0, 1.8), (9.0, 10.1)])
    for k, x in enumerate([4.0, 8.3]):
        w.slab(f"part_s_{k}", [x, 0, 0], [x + t, h, zs], wall)
    w.slab("part_n", [6.0, 0, zn], [6.0 + t, h, Z], wall)
    w.slab("bed", [0.4, 0, 0.4], [2.4, 0.5, 2.4], ochre)
    w.slab("wardrobe", [5.0, 0, 0.0], [7.2, 2.2, 0.6], wall)
    w.slab("table", [9.5, 0.74, 7.0], [11.5, 0.78, 8.2], floor)
    w.light("spot", "spot", 35.0, [1.2, 2.9, 3.4], [0.3, -1.0, -0.5], cone=(0.35, 0.6))
    w.light("lamp", "point", 5.0, [6.2, 2.6, 2.0], [0, -1, 0])
    w.camera([12.6, 1.7, 9.9], [8.0, 0.8, 6.4], 1.15, 0.05)
    return w


def studio():
    """Added at stop 37, never used for tuning: an 8 x 3.4 x 6 m studio with a window in each of
    two walls (0.35 m reveals), a low sun through them, a lamp and a spot on the back wall, and a
    half-height partition; the camera looks at the partition's shadowed side."""
    w = Writer()
    wall, floor, ceil = w.material("plaster", (0.8, 0.78, 0.72)), w.material("concrete", (0.45, 0.44, 0.42)), w.material("ceiling", CEILING)
    teal = w.material("teal", (0.2, 0.5, 0.5))
    t, h, X, Z = 0.35, 3.4, 8.0, 6.0
    w.slab("floor", [-t, -t, -t], [X + t, 0, Z + t], floor)
    w.slab("ceiling", [-t, h, -t], [X + t, h + t, Z + t], ceil)
    w.slab("west", [-t, 0, -t], [0, h, Z + t], wall)
    w.slab("north", [0, 0, Z], [X + t, h, Z + t], teal)
    # South wall (z in [-t, 0]) with a window x 2.0..4.0, sill 1.0, head 2.6.
    w.slab("south_a", [0, 0, -t], [2.0, h, 0], wall)
    w.slab("south_b", [4.0, 0, -t], [X + t, h, 0], wall)
    w.slab("south_sill", [2.0, 0, -t], [4.0, 1.0, 0], wall)
    w.slab("south_head", [2.0, 2.6, -t], [4.0, h, 0], wall)
    # East wall (x in [X, X + t]) with a window z 2.5..4.5, sill 0.9, head 2.5.
    w.slab("east_a", [X, 0, 0], [X + t, h, 2.5], wall)
    w.slab("east_b", [X, 0, 4.5], [X + t, h, Z], wall)
    w.slab("east_sill", [X, 0, 2.5], [X + t, 0.9, 4.5], wall)
    w.slab("east_head", [X, 2.5, 2.5], [X + t, h, 4.5], wall)
    w.slab("partition", [3.0, 0, 3.2], [6.5, 1.5, 3.32], teal)
    w.slab("plinth", [1.0, 0, 4.2], [2.0, 0.9, 5.2], wall)
    w.light("sun", "directional", 4.0, [10.0, 6.0, -4.0], [-0.8, -0.45, 0.55])
    w.light("lamp", "point", 4.0, [1.5, 2.9, 1.0], [0, -1, 0])
    w.light("spot", "spot", 20.0, [4.0, 3.2, 5.8], [0.0, -0.7, -1.0], cone=(0.3, 0.5))
    w.camera([7.5, 1.8, 5.6], [3.5, 0.8, 1.8], 1.2, 0.05)
    return w


def workshop():
    """Added at stop 37, never used for tuning: a 9 x 3.5 x 7 m workshop, 0.25 m slabs, two
    workbenches (tops on legs), fifty boxes and cylinders of many sizes on the floor and the
    benches, a spot and a lamp."""
    w = Writer()
    wall, floor, ceil = w.material("brick", (0.6, 0.45, 0.38)), w.material("screed", (0.5, 0.5, 0.48)), w.material("ceiling", CEILING)
    wood = w.material("wood", (0.6, 0.45, 0.3))
    colours = [(0.75, 0.7, 0.6), (0.2, 0.3, 0.55), (0.7, 0.25, 0.2), (0.3, 0.5, 0.3), (0.85, 0.8, 0.3), (0.5, 0.5, 0.5)]
    stuff = [w.material(f"item_{i}", c) for i, c in enumerate(colours)]
    t, h, X, Z = 0.25, 3.5, 9.0, 7.0
    closed_room(w, t, h, X, Z, wall, floor, ceil)
    benches = [(1.0, 1.0, 4.0, 1.8), (5.0, 4.5, 8.2, 5.4)]
    for k, (x0, z0, x1, z1) in enumerate(benches):
        w.slab(f"bench_top_{k}", [x0, 0.85, z0], [x1, 0.9, z1], wood)
        for px in [x0, x1 - 0.06]:
            for pz in [z0, z1 - 0.06]:
                w.slab(f"bench_leg_{k}_{px}_{pz}", [px, 0, pz], [px + 0.06, 0.85, pz + 0.06], wood)
    rng = random.Random(37373737)
    for i in range(50):
        size = 0.12 + 0.5 * rng.random()
        material = stuff[rng.randrange(len(stuff))]
        if i < 14:
            x0, z0, x1, z1 = benches[i % 2]
            size = min(size, 0.5)
            x, z, y = x0 + 0.05 + rng.random() * (x1 - x0 - 0.1 - size), z0 + 0.05 + rng.random() * (z1 - z0 - 0.1 - size), 0.9
        else:
            while True:
                x, z = 0.2 + rng.random() * (X - 0.4 - size), 0.2 + rng.random() * (Z - 0.4 - size)
                if not any(x0 - size < x < x1 and z0 - size < z < z1 for x0, z0, x1, z1 in benches):
                    break
            y = 0.0
        if i % 3 == 2:
            r, hh = size / 2, size * (0.6 + 1.2 * rng.random())
            w.node({"name": f"drum_{i}", "mesh": w.cylinder_mesh(r, hh, material), "translation": [x + r, y, z + r]})
        else:
            w.slab(f"box_{i}", [x, y, z], [x + size, y + size * (0.4 + 0.9 * rng.random()), z + size], material)
    w.light("spot", "spot", 80.0, [2.5, 3.4, 5.5], [0.5, -1.0, -0.7], cone=(0.4, 0.7))
    w.light("lamp", "point", 5.0, [7.0, 3.0, 1.5], [0, -1, 0])
    w.camera([0.5, 2.3, 6.6], [5.0, 0.4, 2.5], 1.15, 0.05)
    return w


def slab_corridors():
    """Added at stop 52 (issue 46's corridor level, rebuilt from its description), never used for
    tuning: three 5 x 3 x 4 m rooms of 0.2 m slabs in a row, a 0.6 m corridor of slabs (floor,
    2.4 m ceiling, side walls) between each pair with 1.8 x 2.4 m doorways at its ends; a spot in
    the first room, the camera in the second looking back through the corridor."""
    w = Writer()
    wall, floor, ceil = w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING)
    t, h, X, Z, gap = 0.2, 3.0, 5.0, 4.0, 0.6
    dz0, dz1, dh = 1.1, 2.9, 2.4
    for k in range(3):
        x0 = k * (X + 2 * t + gap)
        w.slab(f"floor{k}", [x0 - t, -t, -t], [x0 + X + t, 0, Z + t], floor)
        w.slab(f"ceiling{k}", [x0 - t, h, -t], [x0 + X + t, h + t, Z + t], ceil)
        w.slab(f"south{k}", [x0 - t, 0, -t], [x0 + X + t, h, 0], wall)
        w.slab(f"north{k}", [x0 - t, 0, Z], [x0 + X + t, h, Z + t], wall)
        for side, xa in (("west", x0 - t), ("east", x0 + X)):
            if (side == "east" and k < 2) or (side == "west" and k > 0):
                w.slab(f"{side}{k}_a", [xa, 0, 0], [xa + t, h, dz0], wall)
                w.slab(f"{side}{k}_b", [xa, 0, dz1], [xa + t, h, Z], wall)
                w.slab(f"{side}{k}_lintel", [xa, dh, dz0], [xa + t, h, dz1], wall)
            else:
                w.slab(f"{side}{k}", [xa, 0, 0], [xa + t, h, Z], wall)
    for k in range(2):
        xa = k * (X + 2 * t + gap) + X + t
        w.slab(f"corridor{k}_floor", [xa, -t, dz0 - t], [xa + gap, 0, dz1 + t], floor)
        w.slab(f"corridor{k}_ceiling", [xa, dh, dz0 - t], [xa + gap, dh + t, dz1 + t], ceil)
        w.slab(f"corridor{k}_south", [xa, 0, dz0 - t], [xa + gap, dh, dz0], wall)
        w.slab(f"corridor{k}_north", [xa, 0, dz1], [xa + gap, dh, dz1 + t], wall)
    w.light("spot", "spot", 40.0, [1.0, 2.7, 1.2], [0.5, -1.0, 0.6], cone=(0.35, 0.6))
    x1 = X + 2 * t + gap
    w.camera([x1 + 4.6, 1.6, 3.6], [x1 + 0.5, 0.9, 1.0], 1.2, 0.05)
    return w


def main():
    import argparse

    parser = argparse.ArgumentParser(description="Write the held-out level-like glTF scenes.")
    parser.add_argument("out", nargs="?", default="unseen", help="output folder (default: unseen)")
    out = Path(parser.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    levels = [("apartment", apartment), ("sunroom", sunroom), ("storeroom", storeroom), ("offices", offices)]
    levels += [("cluttered", cluttered), ("cornell_b", cornell_b)]
    levels += [("three_rooms_b", lambda: three_rooms("b")), ("three_rooms_c", lambda: three_rooms("c"))]
    levels += [("maisonette", maisonette), ("studio", studio), ("workshop", workshop)]
    levels += [("slab_corridors", slab_corridors)]
    for name, make in levels:
        make().write(out / f"{name}.gltf")
        print(out / f"{name}.gltf")


if __name__ == "__main__":
    main()
