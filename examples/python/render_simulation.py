#!/usr/bin/env python3
"""Renders a simulation's arrays with tetrender, without writing a mesh file.

A pipe (a hollow cylinder of hexahedra, as a structured solver would store it) with a
temperature field (a hot plume rising along the pipe and turning with the swirl) and a swirling
velocity, built in numpy, handed to tetrender without a copy, rendered, and saved as a PNG.

    PYTHONPATH=<build>/python python3 examples/python/render_simulation.py -o pipe.png
"""

import argparse
import sys

import numpy as np

import tetrender


def pipe_mesh(nr: int = 8, nt: int = 48, nz: int = 40, r_in: float = 0.3, r_out: float = 1.0,
              length: float = 4.0) -> tetrender.Mesh:
    """A hollow cylinder of nr x nt x nz hexahedra (VTK node order) with point arrays
    'temperature' and 'velocity' and a cell array 'layer'."""
    r = np.linspace(r_in, r_out, nr + 1)
    t = np.linspace(0.0, 2.0 * np.pi, nt, endpoint=False)  # periodic in theta
    z = np.linspace(0.0, length, nz + 1)
    R, T, Z = np.meshgrid(r, t, z, indexing="ij")  # point (i, j, k) at index (i * nt + j) * (nz + 1) + k
    points = np.stack([R * np.cos(T), R * np.sin(T), Z], axis=-1).reshape(-1, 3)

    i, j, k = np.meshgrid(np.arange(nr), np.arange(nt), np.arange(nz), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    pid = lambda a, b, c: (a * nt + b % nt) * (nz + 1) + c
    # Bottom quad then top quad, counter-clockwise seen from +z... in (r, theta): positive volume.
    hexahedra = np.stack([pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k), pid(i, j + 1, k),
                          pid(i, j, k + 1), pid(i + 1, j, k + 1), pid(i + 1, j + 1, k + 1),
                          pid(i, j + 1, k + 1)], axis=1).astype(np.int64)

    x, y, zz = points.T
    swirl = 0.8 * zz  # the plume turns with the flow as it goes up
    cx, cy = 0.65 * np.cos(swirl), 0.65 * np.sin(swirl)
    temperature = 300.0 + 80.0 * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (0.08 + 0.03 * zz))
    velocity = np.stack([-y * 0.8, x * 0.8, np.full_like(x, 1.0)], axis=1)

    return tetrender.Mesh(
        points,  # (n, 3) float64, C-contiguous: kept without a copy
        hexahedra.ravel(),
        np.arange(0, 8 * len(hexahedra) + 1, 8, dtype=np.int64),
        np.full(len(hexahedra), tetrender.CELL_TYPES["hexahedron"], dtype=np.uint8),
        point_data={"temperature": temperature, "velocity": velocity},
        cell_data={"layer": k.astype(np.float64)},
        name="pipe",
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="pipe.png", help="the picture (.png or .pfm)")
    parser.add_argument("--size", default="640x480", help="WxH")
    args = parser.parse_args()
    width, height = map(int, args.size.split("x"))

    mesh = pipe_mesh()
    scene = {
        "mesh": mesh,
        "scalar": "temperature",
        "transfer_function": {
            "color": [[300, 0.23, 0.30, 0.75], [340, 0.87, 0.87, 0.87], [380, 0.71, 0.02, 0.15]],
            "opacity": [[300, 0.02], [330, 0.05], [380, 0.9]],
            "unit_distance": 0.2,
        },
        "camera": {"position": [5.5, -5.5, 5.0], "focal_point": [0, 0, 2.0], "view_up": [0, 0, 1],
                   "view_angle": 30},
        "image": {"width": width, "height": height, "background": [0.08, 0.08, 0.12]},
    }
    try:
        image, stats, notes = tetrender.render(scene, return_stats=True)
    except tetrender.Error as error:
        print(f"render_simulation: {error}", file=sys.stderr)
        return 1
    tetrender.write_image(args.output, image)
    background = np.array([0.08, 0.08, 0.12]) * 255
    covered = (np.abs(image - background).max(axis=2) > 2).mean()
    print(f"{mesh.num_cells} hexahedra, {mesh.num_points} points -> {args.output} "
          f"({width}x{height}, {100 * covered:.1f}% of the frame covered)")
    for note in notes:
        print(f"note: {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
