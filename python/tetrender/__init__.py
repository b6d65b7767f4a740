"""tetrender: volume rendering of unstructured meshes, from Python.

The library's entry points with numpy arrays in and out (docs/python.md):

- ``read(path, time_step=None)`` -> :class:`Mesh` (arrays are views of the library's mesh)
- :class:`Mesh`: points, cells (connectivity/offsets/types, VTK's layout), point_data,
  cell_data; made from numpy arrays (kept without a copy when the layout allows), a
  ``meshio.Mesh`` or anything shaped like a PyVista ``UnstructuredGrid``
- ``tetrahedralize(mesh)`` -> a tetrahedral :class:`Mesh`
- :class:`Scene` from a dict, a JSON string or a scene file (the scene format,
  ../shared/spec/scene.md); a volume's ``"mesh"`` may be an in-memory :class:`Mesh`
- ``render(scene, ...)`` -> an ``(H, W, 3)`` uint8 (or float32) array
- ``sort(scene, ...)`` -> a visibility order, ``verify_order(scene, order)`` -> its check
- ``flow_volume(scene, vectors, seed_center, seed_size, ...)`` -> the dye's picture and tets
- ``spot_noise(mesh, scalar, iso, vectors, ...)``, ``advect(mesh, vectors, ...)`` -> frames
- ``write_image(path, image)`` / ``read_image(path)``: PNG and PFM, as the CLI writes them
- ``set_max_memory("8G")`` / ``max_memory()``: the CLI's ``--max-memory``

Errors raise :class:`Error` (a ``RuntimeError``) with the library's one-line message.
The GIL is released while reading, tetrahedralizing, rendering, sorting and verifying.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from . import _core
from ._core import Error

__all__ = [
    "Error",
    "Mesh",
    "Scene",
    "SortResult",
    "OrderCheck",
    "read",
    "tetrahedralize",
    "render",
    "sort",
    "verify_order",
    "flow_volume",
    "spot_noise",
    "advect",
    "write_image",
    "read_image",
    "set_max_memory",
    "max_memory",
    "CELL_TYPES",
]

# VTK cell type ids by name (meshio's names), the layout Mesh.types holds.
CELL_TYPES = {
    "vertex": 1,
    "line": 3,
    "triangle": 5,
    "polygon": 7,
    "quad": 9,
    "tetra": 10,
    "hexahedron": 12,
    "wedge": 13,
    "pyramid": 14,
    "tetra10": 24,
    "hexahedron20": 25,
    "wedge15": 26,
    "pyramid13": 27,
}
# meshio orders a linear wedge's nodes as Gmsh does, VTK the other way round (its first
# triangle's normal points outwards): meshio/_vtk_common.py swaps nodes 1-2 and 4-5, and so do we.
_MESHIO_WEDGE_ORDER = np.array([0, 2, 1, 3, 5, 4])
_SURFACE_TYPES = {"vertex", "line", "triangle", "polygon", "quad", "line3", "triangle6", "quad8"}


def _array(values: Any, dtype: Any, name: str) -> np.ndarray:
    """``values`` as a C-contiguous array of ``dtype``; no copy when it already is one."""
    try:
        return np.ascontiguousarray(values, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise Error(f"error: {name}: not convertible to {np.dtype(dtype).name}: {exc}") from None


def _field(values: Any, name: str) -> np.ndarray:
    """A field array: float32 and float64 kept as they are, anything else as float64."""
    array = np.asarray(values)
    if array.dtype not in (np.float32, np.float64):
        return _array(array, np.float64, name)
    return np.ascontiguousarray(array)


class Mesh:
    """A mesh: points and mixed cells in VTK's layout, with point and cell arrays.

    Cell ``c`` has the nodes ``connectivity[offsets[c]:offsets[c + 1]]`` and the VTK type
    ``types[c]`` (10 tetrahedron, 12 hexahedron, 13 wedge, 14 pyramid, ...: ``CELL_TYPES``).

    Arrays are kept as given, without a copy, when they already have the layout: ``points``
    C-contiguous float64 of shape (n, 3), ``connectivity`` and ``offsets`` int64, ``types``
    uint8, fields float32 or float64 (one row per point or cell). Otherwise they are converted
    once here. The library copies them into its own storage when a Scene or tetrahedralize()
    takes the mesh (its meshes own their arrays); a mesh from read() or tetrahedralize() is
    already the library's, and its arrays are read-only views of it.

    Args:
        points: (n, 3) coordinates.
        connectivity: node ids of every cell, one after the other.
        offsets: where each cell starts in ``connectivity``, with a last entry equal to its
            length (cells + 1 entries); ``None`` when every cell has its type's node count.
        types: VTK cell type of each cell.
        point_data: name -> (n,) or (n, k) array.
        cell_data: name -> (cells,) or (cells, k) array.
        name: how errors name this mesh.
    """

    def __init__(
        self,
        points: Any,
        connectivity: Any = (),
        offsets: Any = None,
        types: Any = (),
        point_data: Mapping[str, Any] | None = None,
        cell_data: Mapping[str, Any] | None = None,
        name: str = "<in-memory mesh>",
    ) -> None:
        self.points = _array(points, np.float64, "points")
        self.connectivity = _array(connectivity, np.int64, "connectivity")
        self.types = _array(types, np.uint8, "types")
        self.offsets = None if offsets is None else _array(offsets, np.int64, "offsets")
        self.point_data = {str(k): _field(v, f"point_data['{k}']")
                           for k, v in (point_data or {}).items()}
        self.cell_data = {str(k): _field(v, f"cell_data['{k}']")
                          for k, v in (cell_data or {}).items()}
        self.name = name
        self.time_values: list = []  # a file's time series: every step's time (else empty)
        self.time_step = 0  # the step these arrays are
        self._handle: Any = None  # the library's mesh these arrays are views of, if any
        self._tets: Any = None  # the library's tetrahedral mesh, if this is one

    # --- Made by the library -----------------------------------------------------------

    @classmethod
    def _from_handle(cls, handle: Any, name: str) -> "Mesh":
        mesh = cls.__new__(cls)
        mesh.points = handle.points
        mesh.connectivity = handle.connectivity
        mesh.offsets = handle.offsets
        mesh.types = handle.types
        mesh.point_data = handle.point_data
        mesh.cell_data = handle.cell_data
        mesh.name = name
        mesh.time_values = list(handle.time_values)
        mesh.time_step = handle.time_step
        mesh._handle = handle
        mesh._tets = None
        mesh._views = mesh._snapshot()
        return mesh

    @classmethod
    def _from_tets(cls, tets: Any, name: str) -> "Mesh":
        mesh = cls(
            tets.points,
            tets.tets.reshape(-1),
            np.arange(0, 4 * len(tets.tets) + 1, 4, dtype=np.int64),
            np.full(len(tets.tets), CELL_TYPES["tetra"], dtype=np.uint8),
            tets.point_data,
            tets.cell_data,
            name=name,
        )
        mesh._tets = tets
        mesh._views = mesh._snapshot()
        return mesh

    def _snapshot(self) -> tuple:
        """The arrays this mesh holds now (compared by identity)."""
        return (self.points, self.connectivity, self.offsets, self.types,
                tuple(self.point_data.items()), tuple(self.cell_data.items()))

    def _unchanged(self) -> bool:
        """Whether the arrays are still the library mesh's own (none replaced, added or removed)."""
        views = getattr(self, "_views", None)
        if views is None:
            return False
        now = self._snapshot()
        same = lambda a, b: a is b or (isinstance(a, tuple) and len(a) == len(b) and all(
            x[0] == y[0] and x[1] is y[1] for x, y in zip(a, b)))
        return all(same(a, b) for a, b in zip(views, now))

    def _library_mesh(self) -> Any:
        """The library's copy of this mesh (made here, or the one it already is)."""
        if self._handle is not None and self._unchanged():
            return self._handle
        offsets = np.zeros(0, dtype=np.int64) if self.offsets is None else self.offsets
        return _core.mesh_from_arrays(
            self.points, self.connectivity, offsets, self.types, self.point_data, self.cell_data
        )

    # --- From other libraries ----------------------------------------------------------

    @classmethod
    def from_meshio(cls, mesh: Any, volume_only: bool = True,
                    name: str = "<meshio mesh>") -> "Mesh":
        """A Mesh from a ``meshio.Mesh`` (meshio keeps VTK's node order but for linear wedges,
        whose nodes it orders as Gmsh does: they are put back in VTK's order here).

        ``volume_only`` drops blocks of vertices, lines and surface cells (a Gmsh file's
        boundary triangles), which tetrahedralize() would refuse; their cell_data go with them.
        Cell types meshio names but CELL_TYPES does not are an Error naming the type.
        """
        blocks = [(i, b) for i, b in enumerate(mesh.cells)
                  if not (volume_only and b.type in _SURFACE_TYPES)]
        connectivity, sizes, types = [], [], []
        for _, block in blocks:
            if block.type not in CELL_TYPES:
                raise Error(f"error: {name}: cell type '{block.type}' has no VTK id here "
                            f"(known: {', '.join(CELL_TYPES)})")
            data = np.asarray(block.data, dtype=np.int64)
            if block.type == "wedge":
                data = data[:, _MESHIO_WEDGE_ORDER]
            connectivity.append(data.reshape(-1))
            sizes.append(np.full(len(data), data.shape[1], dtype=np.int64))
            types.append(np.full(len(data), CELL_TYPES[block.type], dtype=np.uint8))
        cat = lambda parts, dtype: np.concatenate(parts) if parts else np.zeros(0, dtype=dtype)
        sizes_all = cat(sizes, np.int64)
        offsets = np.concatenate([[0], np.cumsum(sizes_all)]).astype(np.int64)
        cell_data = {}
        for key, per_block in mesh.cell_data.items():
            parts = [np.asarray(per_block[i]) for i, _ in blocks]
            if parts:
                cell_data[key] = np.concatenate(parts)
        points = np.asarray(mesh.points)
        if points.ndim == 2 and points.shape[1] < 3:  # 2D meshes: z = 0
            points = np.pad(points, ((0, 0), (0, 3 - points.shape[1])))
        return cls(
            points,
            cat(connectivity, np.int64),
            offsets,
            cat(types, np.uint8),
            dict(mesh.point_data),
            cell_data,
            name=name,
        )

    @classmethod
    def from_pyvista(cls, grid: Any, name: str = "<pyvista grid>") -> "Mesh":
        """A Mesh from anything shaped like a PyVista ``UnstructuredGrid`` (PyVista not imported).

        Reads ``points``, ``celltypes``, ``point_data`` and ``cell_data`` (when present), and
        the cells from ``cell_connectivity`` and ``offset`` when the object has them (PyVista
        >= 0.33, no copy), else from ``cells`` (VTK's legacy layout: a count, then the ids).
        """
        types = np.asarray(grid.celltypes)
        if hasattr(grid, "cell_connectivity") and hasattr(grid, "offset"):
            connectivity = np.asarray(grid.cell_connectivity)
            offsets = np.asarray(grid.offset)
        else:
            cells = np.asarray(grid.cells, dtype=np.int64)
            offsets = np.zeros(len(types) + 1, dtype=np.int64)
            starts = np.zeros(len(types), dtype=np.int64)
            position = 0
            for c in range(len(types)):
                if position >= len(cells):
                    raise Error(f"error: {name}: cells ends after {c} of {len(types)} cells")
                starts[c] = position + 1
                offsets[c + 1] = offsets[c] + cells[position]
                position += 1 + int(cells[position])
            if position != len(cells):
                raise Error(f"error: {name}: cells has {len(cells)} entries, "
                            f"the counts say {position}")
            index = np.repeat(starts - offsets[:-1], np.diff(offsets)) + np.arange(offsets[-1])
            connectivity = cells[index]

        def fields(data: Any) -> dict:
            return {} if data is None else {k: np.asarray(data[k]) for k in data.keys()}

        return cls(
            grid.points,
            connectivity,
            offsets,
            types,
            fields(getattr(grid, "point_data", None)),
            fields(getattr(grid, "cell_data", None)),
            name=name,
        )

    @classmethod
    def from_any(cls, mesh: Any) -> "Mesh":
        """``mesh`` as a Mesh: a Mesh itself, a ``meshio.Mesh``, or a PyVista-shaped grid."""
        if isinstance(mesh, Mesh):
            return mesh
        if hasattr(mesh, "points") and hasattr(mesh, "cells") and not hasattr(mesh, "celltypes"):
            return cls.from_meshio(mesh)
        if hasattr(mesh, "points") and hasattr(mesh, "celltypes"):
            return cls.from_pyvista(mesh)
        raise Error(f"error: expected a tetrender.Mesh, a meshio.Mesh or a PyVista-shaped grid, "
                    f"not {type(mesh).__name__}")

    def to_meshio(self) -> Any:
        """This mesh as a ``meshio.Mesh`` (one block per run of cells of one type)."""
        import meshio

        names = {v: k for k, v in CELL_TYPES.items()}
        offsets = self.offsets
        if offsets is None:
            offsets = self._library_mesh().offsets
        blocks, block_ranges = [], []
        start = 0
        types = self.types
        while start < len(types):
            end = start
            while end < len(types) and types[end] == types[start]:
                end += 1
            nodes = offsets[start + 1] - offsets[start]
            data = self.connectivity[offsets[start]:offsets[end]].reshape(end - start, nodes)
            if types[start] == CELL_TYPES["wedge"]:
                data = data[:, _MESHIO_WEDGE_ORDER]
            blocks.append((names.get(int(types[start]), str(int(types[start]))), data))
            block_ranges.append((start, end))
            start = end
        cell_data = {k: [v[a:b] for a, b in block_ranges] for k, v in self.cell_data.items()}
        return meshio.Mesh(self.points, blocks, point_data=dict(self.point_data),
                           cell_data=cell_data)

    # --- Facts ---------------------------------------------------------------------------

    @property
    def num_points(self) -> int:
        """How many points."""
        return len(self.points)

    @property
    def num_cells(self) -> int:
        """How many cells."""
        return len(self.types)

    def __repr__(self) -> str:
        """Counts and array names."""
        return (f"tetrender.Mesh({self.num_points} points, {self.num_cells} cells, "
                f"point_data={list(self.point_data)}, cell_data={list(self.cell_data)})")


def set_max_memory(size: int | str | None) -> None:
    """The most memory the library may take (the CLI's ``--max-memory``): bytes, or a size
    like ``"8G"`` or ``"512M"``; ``None`` or 0 restores the default (80% of the machine's).

    A mesh whose tetrahedralization or a picture whose buffers would need more raise
    :class:`Error` saying what they would take, before any work.
    """
    if size is None:
        _core.set_max_memory(0)
    elif isinstance(size, str):
        _core.set_max_memory(_core.parse_byte_size(size))
    else:
        if int(size) < 0:
            raise Error(f"set_max_memory takes a size >= 0, not {size}")
        _core.set_max_memory(int(size))


def max_memory() -> int:
    """The memory budget in bytes (set_max_memory's, else 80% of the machine's memory)."""
    return int(_core.max_memory())


def read(path: str | os.PathLike, time_step: int | None = None) -> Mesh:
    """Reads a mesh file (io/read_mesh.h: .vtu .pvtu .vtk .exo .pvd .node/.ele .csv .mesh ...).

    ``time_step`` picks a step of a time series (default the first; ``mesh.time_values`` lists
    every step's time, ``mesh.time_step`` says which was read). The Mesh's arrays are
    read-only views of the library's mesh (no copy). Raises Error with the reader's message.
    """
    handle = _core.read(os.fspath(path), 0 if time_step is None else int(time_step))
    return Mesh._from_handle(handle, os.fspath(path))


def tetrahedralize(mesh: Any, merge_tolerance: float = 0.0, merge_points: bool = True) -> Mesh:
    """Splits a mixed mesh into conforming tetrahedra (mesh/tetrahedralize.h).

    ``mesh`` is a Mesh, a ``meshio.Mesh`` or a PyVista-shaped grid. Coincident points are
    merged (``merge_tolerance``: also points closer than that fraction of the shortest edge).
    Returns a Mesh of tetrahedra (type 10) whose ``report`` says what the split did; point
    fields are kept, cell fields copied to every tet of their cell. Raises Error for a
    non-finite point, an index out of range, an unsupported cell type (naming the cell).
    """
    source = Mesh.from_any(mesh)
    tets = _core.tetrahedralize(source._library_mesh(), merge_tolerance, merge_points)
    out = Mesh._from_tets(tets, source.name)
    out.report = tets.report
    return out


class Scene:
    """A scene: meshes, arrays, transfer functions, camera, image (../shared/spec/scene.md).

    Made from a dict, a JSON string (starting with ``{``) or a scene file's path, and parsed
    by the library's own scene reader (pipeline/scene.h), so every check and error is the
    CLI's. In a dict, a volume's ``"mesh"`` may be a Mesh, a ``meshio.Mesh`` or a PyVista-shaped
    grid instead of a path; paths are relative to ``base_dir`` (default: the scene file's
    folder, else the working directory).

    A Scene keeps what it loaded (meshes, sorts, tables), so rendering it again (another
    method, a changed camera through a new Scene) reuses nothing across Scenes but costs only
    the sort and raster on the same one. One render at a time per Scene.
    """

    def __init__(self, scene: Any, base_dir: str | os.PathLike | None = None) -> None:
        self._meshes: list = []  # keeps handed-over meshes' library copies alive
        if isinstance(scene, Mapping):
            self._from_dict(dict(scene), base_dir)
        elif isinstance(scene, str) and scene.lstrip().startswith("{"):
            base = os.fspath(base_dir) if base_dir is not None else os.getcwd()
            self._handle = _core.parse_scene(scene, base, "<scene string>")
        elif isinstance(scene, (str, os.PathLike)):
            self._handle = _core.read_scene(os.fspath(scene))
        else:
            raise Error(f"error: a Scene is made from a dict, a JSON string or a path, "
                        f"not {type(scene).__name__}")

    def _from_dict(self, scene: dict, base_dir: Any) -> None:
        handed: list[tuple[int, Mesh]] = []
        if "volumes" in scene and isinstance(scene["volumes"], list):
            volumes = [dict(v) if isinstance(v, Mapping) else v for v in scene["volumes"]]
            scene["volumes"] = volumes
        else:
            volumes = [scene]
        for index, volume in enumerate(volumes):
            if not isinstance(volume, dict) or "mesh" not in volume:
                continue  # the parser says what is missing
            if not isinstance(volume["mesh"], (str, os.PathLike)):
                mesh = Mesh.from_any(volume["mesh"])
                handed.append((index, mesh))
                volume["mesh"] = f"<in-memory mesh {index}>"
            elif isinstance(volume["mesh"], os.PathLike):
                volume["mesh"] = os.fspath(volume["mesh"])
        try:
            text = json.dumps(scene)
        except TypeError as exc:
            raise Error(f"error: <scene dict>: not JSON: {exc}") from None
        base = os.fspath(base_dir) if base_dir is not None else os.getcwd()
        self._handle = _core.parse_scene(text, base, "<scene dict>")
        for index, mesh in handed:
            if mesh._tets is not None and mesh._unchanged():
                self._handle.set_volume_tets(index, mesh._tets, mesh.name)
                self._meshes.append(mesh._tets)
            else:
                library = mesh._library_mesh()
                self._handle.set_volume_mesh(index, library, mesh.name)
                self._meshes.append(library)

    @classmethod
    def quick(
        cls,
        mesh: Any,
        scalar: str | None = None,
        component: int | None = None,
        width: int = 800,
        height: int = 600,
        view: str = "iso",
        colormap: str = "viridis",
        look: str = "fitted",
        range: tuple[float, float] | None = None,
        opacity: float | None = None,
        unit_distance: float | None = None,
        azimuth: float = 0.0,
        elevation: float = 0.0,
        zoom: float = 1.0,
        background: tuple[float, float, float] | None = None,
        log: bool = False,
    ) -> "Scene":
        """The CLI's quick-look scene (``tetrender render mesh --scalar NAME``) of a mesh.

        ``mesh`` is a Mesh, meshio or PyVista-shaped object, or a path; ``scalar`` None is the
        CLI's default: the mesh's first point array, else its first cell array. The keywords
        are the CLI's options of the same names (docs/quick-look.md): by default the colour map and
        opacity span the 1st to 99th percentile, the unit distance brings a typical ray through
        the object to opacity 0.8 and the camera fits the object's projected extent from
        ``view`` turned by ``azimuth`` and ``elevation``; ``look="classic"`` is the scene before
        2026-11; ``log=True`` is ``--log`` (colours over log10 of the positive range). The
        legend is the CLI's annotation: ``render(..., legend=True)`` draws it.
        """
        tets, name = _library_tets(mesh)
        scene = cls.__new__(cls)
        scene._meshes = [tets]
        scene._handle = _core.quick_scene(
            tets, name, scalar or "", -1 if component is None else int(component), int(width),
            int(height), view, colormap, look=look,
            range=None if range is None else (float(range[0]), float(range[1])),
            opacity=None if opacity is None else float(opacity),
            unit_distance=None if unit_distance is None else float(unit_distance),
            azimuth=float(azimuth), elevation=float(elevation), zoom=float(zoom),
            background=None if background is None else tuple(float(c) for c in background),
            log=bool(log))
        return scene

    @property
    def width(self) -> int:
        """Image width in pixels."""
        return self._handle.width

    @property
    def height(self) -> int:
        """Image height in pixels."""
        return self._handle.height

    @property
    def num_volumes(self) -> int:
        """How many volumes the scene has."""
        return self._handle.num_volumes

    @property
    def method(self) -> str:
        """The scene's rendering method's name."""
        return self._handle.method

    def mesh(self, volume: int = 0) -> Mesh:
        """The volume's tetrahedral mesh as the renderer loads it (cell ids of sort orders)."""
        return Mesh._from_tets(self._handle.volume_tets(volume),
                               self._handle.volume_mesh_path(volume))

    def set_view(self, camera: Mapping[str, Any], image: Mapping[str, Any] | None = None) -> None:
        """Changes the camera (and the image's size and background): the scene file's
        ``camera`` and ``image`` objects, checked by the scene parser. What the scene loaded
        and prepared is kept, so another view costs only the sort and the raster."""
        view = {
            "mesh": "-", "scalar": "-",
            "transfer_function": {"color": [[0, 0, 0, 0]], "opacity": [[0, 0]], "unit_distance": 1},
            "camera": dict(camera),
            "image": dict(image) if image is not None else
                     {"width": self.width, "height": self.height},
        }
        self._handle.set_view(_core.parse_scene(json.dumps(view), os.getcwd(), "<view>"),
                              image is not None)

    def write(self, path: str | os.PathLike) -> None:
        """Writes the scene file (in-memory meshes are named, not written)."""
        self._handle.write(os.fspath(path))

    def __repr__(self) -> str:
        """Volumes, image size and method."""
        return (f"tetrender.Scene({self.num_volumes} volume(s), {self.width}x{self.height}, "
                f"method={self.method!r})")


def _scene(scene: Any) -> Scene:
    return scene if isinstance(scene, Scene) else Scene(scene)


def _is_mesh(thing: Any) -> bool:
    """Whether render() takes `thing` as a mesh for a quick look: a path that is not a scene
    file's (.json), a Mesh, or a meshio- or PyVista-shaped object."""
    if isinstance(thing, (Scene, Mapping)):
        return False
    if isinstance(thing, str) and thing.lstrip().startswith("{"):
        return False
    if isinstance(thing, (str, os.PathLike)):
        return Path(os.fspath(thing)).suffix.lower() != ".json"
    return isinstance(thing, Mesh) or hasattr(thing, "points")


def render(
    scene: Any,
    method: str | Mapping[str, Any] | None = None,
    sort: str = "auto",
    integrator: str = "preintegrated",
    dtype: Any = np.uint8,
    return_stats: bool = False,
    legend: bool | None = None,
    bounding_box: bool = False,
    axes: bool = False,
    **quick: Any,
) -> Any:
    """Renders a scene (a Scene, or what Scene() takes) to an ``(H, W, 3)`` array, row 0 at the top.

    A mesh instead (a path that is not a ``.json`` scene file, a Mesh, a meshio or PyVista-shaped
    object) is drawn as ``tetrender render MESH`` draws it: the quick look (Scene.quick, whose
    keywords ``quick`` takes: ``scalar``, ``width``, ``height``, ``range``, ...) with its legend,
    left out with a note when the picture is too small for it, as the CLI does.

    ``method`` overrides the scene's: a name (projected-tetrahedra, pbvr-image, pbvr-object,
    splat, texture-advection, spot-noise...) keeps the scene's method keys, a mapping is a whole
    scene-file ``method`` object (``{"name": "texture-advection", "vectors": "V", "steps":
    20}``), checked as the scene file's;
    ``sort`` (auto, mpvo, mpvonc, exact, centroid) and ``integrator`` (preintegrated, exact,
    exp-texture, reference) are the CLI's ``--sort`` and ``--integrator``. ``dtype`` uint8 gives
    the PNG's bytes (linear, clamped, rounded); float32 the linear colours (the PFM's values).
    With ``return_stats`` returns ``(image, stats, notes)``. The GIL is released meanwhile.
    ``legend``, ``bounding_box``, ``axes``: the CLI's annotations (pipeline/annotations.h: a
    colour bar of each volume's array with its range and ticks, the meshes' box, an axes
    triad), drawn on the picture; the legend by default on for a mesh, off for a scene, as in
    the CLI. A picture too small for a legend asked for raises Error.
    """
    as_float = np.dtype(dtype) == np.float32
    if not as_float and np.dtype(dtype) != np.uint8:
        raise Error(f"error: dtype must be uint8 or float32, not {np.dtype(dtype).name}")
    legend_optional = False
    if _is_mesh(scene):
        scene = Scene.quick(scene, **quick)
        if legend is None:
            legend, legend_optional = quick.get("look", "fitted") != "classic", True
    elif quick:
        raise Error(f"error: {', '.join(sorted(quick))}: quick-look keywords, for a mesh; "
                    f"a scene says these itself")
    name, method_json = "", ""
    if isinstance(method, Mapping):
        method_json = json.dumps(dict(method))
    elif method is not None:
        name = str(method)
    image, stats, notes, _ = _scene(scene)._handle.render(
        name, sort, integrator, as_float, bool(legend), bounding_box, axes,
        method_json=method_json, annotations_optional=legend_optional)
    return (image, stats, notes) if return_stats else image


def _library_tets(mesh: Any) -> Any:
    """The library's tets of a Mesh, meshio or PyVista-shaped object, or a path."""
    if isinstance(mesh, (str, os.PathLike)):
        mesh = read(mesh)
    source = Mesh.from_any(mesh)
    tets = source._tets if source._tets is not None and source._unchanged() else None
    if tets is None:
        tets = _core.tetrahedralize(source._library_mesh(), 0.0, True)
    return tets, source.name


# VTK's 2D cells: triangle, polygon, pixel, quad.
_SURFACE_CELL_TYPES = (5, 7, 8, 9)


def _library_flow(mesh: Any) -> Any:
    """What the flow textures take: the library's tets, or, for a 2D mesh (triangles, quads,
    polygons only), the library's mesh itself, which they take as the flow on its plane
    (mesh/planar_slab.h)."""
    if isinstance(mesh, (str, os.PathLike)):
        mesh = read(mesh)
    source = Mesh.from_any(mesh)
    if len(source.types) > 0 and np.isin(source.types, _SURFACE_CELL_TYPES).all():
        return source._library_mesh(), source.name
    return _library_tets(source)


def spot_noise(
    mesh: Any,
    scalar: str,
    iso: float,
    vectors: str,
    steps: int = 30,
    count: int = 20000,
    dt: float = 0.0,
    band: float = 0.0,
    lifetime: int = 60,
    width: int = 512,
    height: int = 512,
    seed: int = 0x5B07,
    dtype: Any = np.uint8,
) -> tuple[list[np.ndarray], dict]:
    """Spot noise near the contour ``scalar = iso``, advected by the point array ``vectors``
    (``tetrender spotnoise``, docs/flowtex.md): the ``steps + 1`` frames as ``(H, W, 3)``
    arrays and a dict of what was chosen (band_tets, spots, band, dt, mean_speed, reseeded).

    ``dt`` 0: the spots' mean speed carries a spot 1/400 of the mesh's diagonal a frame;
    ``band`` 0: the diagonal / 100. Steady flow. The GIL is released meanwhile. On a planar
    2D mesh (triangles, quads, polygons: a 2D flow) ``scalar`` and ``iso`` are not used: the
    spots cover the mesh (docs/flowtex.md, "A 2D flow").
    """
    tets, name = _library_flow(mesh)
    as_float = np.dtype(dtype) == np.float32
    frames, info = _core.spot_noise(tets, name, scalar, float(iso), vectors, int(steps),
                                    int(count), float(dt), float(band), int(lifetime), int(width),
                                    int(height), int(seed), as_float)
    return list(frames), dict(info)


def advect(
    mesh: Any,
    vectors: str,
    point: Any = None,
    normal: Any = None,
    steps: int = 30,
    dt: float = 0.0,
    resolution: int = 256,
    method: str = "backward",
    width: int = 512,
    height: int = 512,
    dtype: Any = np.uint8,
) -> tuple[list[np.ndarray], dict]:
    """Texture advection over the slice through ``point`` with ``normal`` (default: the bounds'
    centre, across their thinnest axis) by the point array ``vectors`` (``tetrender advect``,
    docs/flowtex.md): the ``steps + 1`` frames and a dict (sheet_points, sheet_triangles, dt,
    mean_speed). ``method``: "backward" or "forward". Steady flow; the GIL is released. A
    planar 2D mesh (triangles, quads, polygons with a 2- or 3-component velocity) is the flow
    itself: the slice defaults to its plane, seen upright (docs/flowtex.md, "A 2D flow").
    """
    tets, name = _library_flow(mesh)
    as_float = np.dtype(dtype) == np.float32
    as_triple = (lambda v: None if v is None else tuple(float(c) for c in v))
    frames, info = _core.advect(tets, name, vectors, as_triple(point), as_triple(normal),
                                int(steps), float(dt), int(resolution), method, int(width),
                                int(height), as_float)
    return list(frames), dict(info)


def flow_volume(
    scene: Any,
    vectors: str,
    seed_center: Any = None,
    seed_size: Any = None,
    dtype: Any = np.uint8,
    base_dir: str | os.PathLike | None = None,
    **options: Any,
) -> tuple[np.ndarray, Mesh]:
    """Grows a flow volume through a scene's mesh and renders it (flowvol/, docs/scene-file.md).

    ``scene`` is a dict, a JSON string or a scene file's path (a volume's ``"mesh"`` may be an
    in-memory mesh); its ``"flow_volume"`` key is set from ``vectors`` (a 3-component point
    array), ``seed_center`` (3 numbers), ``seed_size`` (width, height of the dye polygon) and
    ``options`` (seed_resolution, seed_normal, steps, dt, compressible, split_threshold,
    unsteady, start_time, color, opacity, unit_distance, context: the scene file's keys).
    ``seed_center``, ``seed_size`` and ``dt`` left out are chosen from the flow as ``tetrender
    flowvol`` chooses them (the seed where the flow is fastest, an eighth of the diagonal a
    side, the front travelling 40% of the diagonal over the steps). Returns the ``(H, W, 3)`` picture and the dye's tetrahedra as a Mesh, with cell arrays
    ``concentration`` and ``age`` and point array ``concentration``.
    """
    if isinstance(scene, Scene):
        raise Error("error: flow_volume takes the scene as a dict, a JSON string or a path, "
                    "not a Scene (it adds the flow_volume key)")
    if isinstance(scene, (str, os.PathLike)) and not str(scene).lstrip().startswith("{"):
        path = Path(scene)
        try:
            text = path.read_text()
        except OSError as exc:
            raise Error(f"{path}: error: cannot read the scene file ({exc.strerror})") from None
        base_dir = path.parent if base_dir is None else base_dir
        scene = text
    if isinstance(scene, str):
        try:
            scene = json.loads(scene)
        except json.JSONDecodeError as exc:
            raise Error(f"<scene string>:{exc.lineno}:{exc.colno}: error: {exc.msg}") from None
    scene = dict(scene)
    spec: dict = {"vectors": vectors}
    if seed_center is not None:
        spec["seed_center"] = [float(v) for v in seed_center]
    if seed_size is not None:
        spec["seed_size"] = [float(v) for v in seed_size]
    spec.update({k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in options.items()})
    scene["flow_volume"] = spec
    as_float = np.dtype(dtype) == np.float32
    handle = Scene(scene, base_dir=base_dir)._handle
    image, _, _, tets = handle.render("", "auto", "preintegrated", as_float)
    return image, Mesh._from_tets(tets, "flow volume")


def write_image(path: str | os.PathLike, image: Any) -> None:
    """Writes an ``(H, W, 3)`` picture as PNG (8-bit, linear: uint8 as is, floats clamped to
    [0, 1] and rounded, as the CLI writes) or PFM (floats), by the path's extension."""
    _core.write_image(np.asarray(image), os.fspath(path))


def read_image(path: str | os.PathLike) -> np.ndarray:
    """Reads a PNG or PFM picture as an ``(H, W, 3)`` float32 array in [0, 1], row 0 at the top."""
    return _core.read_image(os.fspath(path))


@dataclass
class SortResult:
    """A visibility order of a volume's tets for the scene's camera, back to front."""

    order: np.ndarray  # uint32 tet ids of Scene.mesh(volume), back to front
    exact: bool  # the method claims exactness on this mesh and broke no cycle in this view
    note: str  # why a requested exact order is not exact ("" otherwise)
    stats: dict = field(default_factory=dict)


@dataclass
class OrderCheck:
    """The brute-force check of an order (sort/order_verifier.h)."""

    rays: int  # pixels whose ray crosses a cell
    pairs: int  # consecutive pairs along rays checked
    violations: int  # pairs in the wrong order
    missing_cells: int  # crossed cells absent from the order
    milliseconds: float

    @property
    def ok(self) -> bool:
        """No violation and no missing cell."""
        return self.violations == 0 and self.missing_cells == 0


def sort(scene: Any, method: str = "auto", volume: int = 0) -> SortResult:
    """The back-to-front order of a volume's tets for the scene's camera (sort/).

    ``method``: auto (MPVO, convexified when the mesh is not convex and TetGen is built in),
    exact, mpvo, mpvonc, centroid. Ids index ``Scene.mesh(volume)``'s tets.
    """
    order, exact, note, stats = _scene(scene)._handle.sort(volume, method)
    return SortResult(order, bool(exact), note, stats)


def verify_order(scene: Any, order: Any, volume: int = 0, min_segment: float = 1e-9) -> OrderCheck:
    """Checks ``order`` against rays through every pixel centre of the scene's camera.

    Independent of the sorter: each ray's cells are found by ray-triangle tests and every
    consecutive pair the order puts the wrong way round is counted. Segments shorter than
    ``min_segment`` times the bounds' diagonal are ignored. Raises Error for an id that is
    not a tet of the volume's mesh.
    """
    if isinstance(order, SortResult):
        order = order.order
    check = _scene(scene)._handle.check_order(volume, np.asarray(order), min_segment)
    return OrderCheck(**check)
