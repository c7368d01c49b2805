#!/usr/bin/env python3
"""Writes the collision meshes of my_robot_description (tests/urdf_real.rs).

Run from this folder: `python3 make_meshes.py`. The tests compare the loaded meshes with the
parameters below (restated in tests/urdf_real.rs), not with the files.

- base_link.stl: ASCII STL, a box in millimetres (the URDF scales it by 0.001):
  x in [-100, 100], y in [-80, 80], z in [0, 100]; 12 triangles, 8 vertices.
- link_1.stl: binary STL whose header starts with "solid " (as SolidWorks exports do), in
  metres: a tube around z with 12 sides, outer radius 0.05, inner radius 0.04 (both at the
  corners), z in [0, 0.3]; 96 triangles, 48 vertices.
- link_2.STL (upper-case extension, as SolidWorks exports): binary STL, in metres: a prism
  along y, 0.12 long (y in [-0.06, 0.06]), over the triangle (0, 0), (0.08, 0), (0, 0.2) in
  (x, z); 8 triangles, 6 vertices.
"""

import math
import struct


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return [x / length for x in n]


def quad(a, b, c, d):
    """Two triangles of the quadrilateral a b c d (counter-clockwise seen from outside)."""
    return [(a, b, c), (a, c, d)]


def box(x0, x1, y0, y1, z0, z1):
    p = lambda i, j, k: ((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])
    return (
        quad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0))  # bottom, -z
        + quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1))  # top, +z
        + quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1))  # -y
        + quad(p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0))  # +y
        + quad(p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0))  # -x
        + quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1))  # +x
    )


def tube(sides, outer, inner, length):
    # k modulo sides: the last side closes on the first corners exactly (sin 2π ≠ 0).
    ring = lambda r, k, z: (
        r * math.cos(2 * math.pi * (k % sides) / sides),
        r * math.sin(2 * math.pi * (k % sides) / sides),
        z,
    )
    triangles = []
    for k in range(sides):
        o0, o1 = ring(outer, k, 0.0), ring(outer, k + 1, 0.0)
        O0, O1 = ring(outer, k, length), ring(outer, k + 1, length)
        i0, i1 = ring(inner, k, 0.0), ring(inner, k + 1, 0.0)
        I0, I1 = ring(inner, k, length), ring(inner, k + 1, length)
        triangles += quad(o0, o1, O1, O0)  # outer wall
        triangles += quad(i1, i0, I0, I1)  # inner wall, facing the axis
        triangles += quad(O0, O1, I1, I0)  # top annulus
        triangles += quad(o1, o0, i0, i1)  # bottom annulus
    return triangles


def prism(width, base, height):
    y0, y1 = -width / 2, width / 2
    corners = [(0.0, 0.0), (base, 0.0), (0.0, height)]  # (x, z)
    near = [(x, y0, z) for x, z in corners]
    far = [(x, y1, z) for x, z in corners]
    triangles = [(near[0], near[1], near[2]), (far[0], far[2], far[1])]
    for k in range(3):
        triangles += quad(near[k], far[k], far[(k + 1) % 3], near[(k + 1) % 3])
    return triangles


def write_ascii(path, name, triangles):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for t in triangles:
            f.write("  facet normal {:g} {:g} {:g}\n    outer loop\n".format(*normal(*t)))
            for v in t:
                f.write("      vertex {:g} {:g} {:g}\n".format(*v))
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def write_binary(path, header, triangles):
    with open(path, "wb") as f:
        f.write(header.encode("ascii").ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            f.write(struct.pack("<3f", *normal(*t)))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))


if __name__ == "__main__":
    folder = "my_robot_description/meshes/collision/"
    write_ascii(folder + "base_link.stl", "base_link", box(-100, 100, -80, 80, 0, 100))
    write_binary(
        folder + "link_1.stl",
        "solid link_1 (binary STL, metres)",
        tube(12, 0.05, 0.04, 0.3),
    )
    write_binary(folder + "link_2.STL", "link_2 (binary STL, metres)", prism(0.12, 0.08, 0.2))
