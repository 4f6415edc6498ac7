#!/usr/bin/env python3
"""Writes the building meshes of scenes/mesh_buildings.json (scenes/meshes/*.obj).

Closed surfaces, faces counter-clockwise seen from outside, metres, +Z up,
each building's origin at the middle of its footprint on the ground. Convex
faces are written as polygons (assimp triangulates them); the L-shaped
block's concave top and bottom as triangles.
Run from the repository root: python3 tools/make_mesh_buildings.py
"""
import math
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "scenes" / "meshes"


def write_obj(name, comment, vertices, faces):
    lines = [f"# {comment}", "# written by tools/make_mesh_buildings.py; metres, +Z up", f"o {Path(name).stem}"]
    lines += [f"v {x:g} {y:g} {z:g}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces]
    (OUT / name).write_text("\n".join(lines) + "\n")


def prism(footprint, height, cap_triangles=None):
    """A vertical prism over a counter-clockwise footprint: bottom ring, then top ring."""
    n = len(footprint)
    vertices = [(x, y, 0.0) for x, y in footprint] + [(x, y, height) for x, y in footprint]
    faces = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]  # walls
    if cap_triangles is None:
        faces.append(list(reversed(range(n))))  # bottom, seen from below
        faces.append([n + i for i in range(n)])  # top
    else:
        for a, b, c in cap_triangles:
            faces.append([c, b, a])
            faces.append([n + a, n + b, n + c])
    return vertices, faces


def l_block():
    # An L of 12 m x 4 m and 4 m x 10 m arms, 7 m tall, centred on its bounding box.
    pts = [(0, 0), (12, 0), (12, 4), (4, 4), (4, 10), (0, 10)]
    pts = [(x - 6, y - 5) for x, y in pts]
    # Fan from the reflex corner (index 3) covers the L.
    fan = [(3, 4, 5), (3, 5, 0), (3, 0, 1), (3, 1, 2)]
    v, f = prism(pts, 7.0, fan)
    write_obj("l_block.obj", "An L-shaped block, 12 m x 10 m, 7 m tall", v, f)


def gable_house():
    # 8 m along x, 6 m along y, walls 3.5 m, ridge along x at 6 m.
    hx, hy, eave, ridge = 4.0, 3.0, 3.5, 6.0
    v = [(-hx, -hy, 0), (hx, -hy, 0), (hx, hy, 0), (-hx, hy, 0),
         (-hx, -hy, eave), (hx, -hy, eave), (hx, hy, eave), (-hx, hy, eave),
         (-hx, 0, ridge), (hx, 0, ridge)]
    f = [[3, 2, 1, 0],              # floor
         [0, 1, 5, 4],              # south wall (y = -hy)
         [2, 3, 7, 6],              # north wall
         [1, 2, 6, 9, 5],           # east gable (x = +hx)
         [3, 0, 4, 8, 7],           # west gable
         [4, 5, 9, 8],              # south roof
         [6, 7, 8, 9]]              # north roof
    write_obj("gable_house.obj", "A house with a gable roof, 8 m x 6 m, ridge 6 m", v, f)


def tower():
    # An octagonal tower, 2.5 m to its corners, 16 m tall.
    pts = [(2.5 * math.cos(math.pi / 8 + k * math.pi / 4), 2.5 * math.sin(math.pi / 8 + k * math.pi / 4)) for k in range(8)]
    v, f = prism([(round(x, 6), round(y, 6)) for x, y in pts], 16.0)
    write_obj("tower.obj", "An octagonal tower, 5 m across its corners, 16 m tall", v, f)


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    l_block()
    gable_house()
    tower()
