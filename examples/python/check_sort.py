#!/usr/bin/env python3
"""Checks tetrender's visibility orders against brute-force rays, from Python.

Sorts a mesh's tetrahedra for random views with each method and counts, with the library's
independent verifier (rays through every pixel, ray-triangle tests, no adjacency), the pairs of
consecutive cells along a ray that an order puts the wrong way round. Exits 1 when a method that
claims an exact order has a violation or misses a cell.

    PYTHONPATH=<build>/python python3 examples/python/check_sort.py [mesh.vtu] [--views 8]

Without a file, the mesh is a square ring of hexahedra (not convex), built in numpy.
"""

import argparse
import sys

import numpy as np

import tetrender


def ring_mesh(n: int = 8, hole: int = 4) -> tetrender.Mesh:
    """n x n x 2 unit hexahedra without the middle hole x hole columns: not convex."""
    i, j, k = np.meshgrid(np.arange(n + 1), np.arange(n + 1), np.arange(3), indexing="ij")
    points = np.stack([i, j, k], axis=-1).reshape(-1, 3).astype(np.float64)
    pid = lambda a, b, c: (a * (n + 1) + b) * 3 + c
    lo, hi = (n - hole) // 2, (n + hole) // 2
    cells = [[pid(a, b, c), pid(a + 1, b, c), pid(a + 1, b + 1, c), pid(a, b + 1, c),
              pid(a, b, c + 1), pid(a + 1, b, c + 1), pid(a + 1, b + 1, c + 1), pid(a, b + 1, c + 1)]
             for a in range(n) for b in range(n) for c in range(2)
             if not (lo <= a < hi and lo <= b < hi)]
    cells = np.array(cells, dtype=np.int64)
    return tetrender.Mesh(points, cells.ravel(), None, np.full(len(cells), 12, dtype=np.uint8),
                          point_data={"s": points[:, 0]}, name="ring")


def random_camera(lo: np.ndarray, hi: np.ndarray, rng: np.random.Generator) -> dict:
    """A perspective eye outside the bounding sphere, looking at its centre."""
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    direction = rng.normal(size=3)
    direction /= np.linalg.norm(direction)
    up = [0.0, 0.0, 1.0] if abs(direction[2]) < 0.9 else [0.0, 1.0, 0.0]
    return {"position": (centre + 2.5 * radius * direction).tolist(), "focal_point": centre.tolist(),
            "view_up": up, "view_angle": 40.0}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", help="a mesh file (default: a ring built in numpy)")
    parser.add_argument("--scalar", default=None, help="any point array of the file (default: the first)")
    parser.add_argument("--views", type=int, default=6)
    parser.add_argument("--size", type=int, default=128, help="rays per side")
    parser.add_argument("--methods", default="exact,auto,mpvonc,centroid")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    mesh = tetrender.read(args.mesh) if args.mesh else ring_mesh()
    scalar = args.scalar or next(iter(mesh.point_data), None)
    if scalar is None:
        print("check_sort: the mesh has no point array", file=sys.stderr)
        return 1
    tets = tetrender.tetrahedralize(mesh)  # once; every Scene below shares it
    lo, hi = tets.points.min(axis=0), tets.points.max(axis=0)
    rng = np.random.default_rng(args.seed)
    cameras = [random_camera(lo, hi, rng) for _ in range(args.views)]

    print(f"{tets.num_cells} tets, {args.views} views of {args.size}x{args.size} rays")
    print(f"{'method':10} {'exact?':>7} {'pairs':>9} {'violations':>11} {'missing':>8}")
    failed = False
    for method in args.methods.split(","):
        scene = tetrender.Scene({
            "mesh": tets, "scalar": scalar,
            "transfer_function": {"color": [[0, 1, 1, 1]], "opacity": [[0, 0.5]], "unit_distance": 1},
            "camera": cameras[0], "image": {"width": args.size, "height": args.size},
        })
        pairs = violations = missing = 0
        claims = True
        for camera in cameras:
            scene.set_view(camera)
            order = tetrender.sort(scene, method)
            check = tetrender.verify_order(scene, order)
            pairs, violations, missing = pairs + check.pairs, violations + check.violations, missing + check.missing_cells
            claims = claims and order.exact
        print(f"{method:10} {'yes' if claims else 'no':>7} {pairs:9d} {violations:11d} {missing:8d}")
        if claims and (violations or missing):
            failed = True
            print(f"check_sort: {method} claims exact orders but has {violations} violations "
                  f"and {missing} missing cells", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
