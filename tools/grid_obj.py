#!/usr/bin/env python3
"""A square grid mesh with UVs as OBJ text: the small test mesh of the Python tools (bench/soak.py's
wave sheets, tools/hostile_cli.py's planes); one copy so both write the same file format.

    /usr/bin/python3 tools/grid_obj.py OUT.obj [N] [SIZE]   # writes a flat N x N-quad grid

grid_obj(n, size, z): (n + 1)^2 vertices at x, y in [0, size] with z(x, y) (x, y in metres),
UVs (i / n, j / n), two triangles per quad, counter-clockwise seen from +z."""
import sys


def grid_obj(n=4, size=1.0, z=lambda x, y: 0.0):
    if n < 1:
        raise ValueError(f"grid_obj: n must be at least 1 quad, got {n}")
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n * size, j / n * size
            lines.append(f"v {x!r} {y!r} {z(x, y)!r}")
    for j in range(n + 1):
        for i in range(n + 1):
            lines.append(f"vt {i / n!r} {j / n!r}")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            lines.append(f"f {a}/{a} {b}/{b} {c}/{c}")
            lines.append(f"f {a}/{a} {c}/{c} {d}/{d}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: grid_obj.py OUT.obj [N] [SIZE]")
    with open(sys.argv[1], "w") as f:
        f.write(grid_obj(int(sys.argv[2]) if len(sys.argv) > 2 else 4,
                         float(sys.argv[3]) if len(sys.argv) > 3 else 1.0))
