"""A mesh series: one surface (fixed connectivity) whose nodes move, given as frames at increasing times.

The nodes move linearly in time between frames and are held at the first and last frames beyond the ends, as a
:class:`cases.model.bodies.VertexTrajectory` (a MeshSeries is one, with faces): the frame times are the breakpoints. On a
frame interval every node, and every point of a face at fixed barycentric coordinates, moves on a straight line at
constant speed, so :meth:`MeshSeries.velocity_bound` is the exact largest speed of any point of the surface there.

Read with :func:`read_mesh_series` from a ParaView series (.pvd of .vtu/.vtp frames), an XDMF time series (.xdmf,
.xmf) or an .npz (``times``, ``vertices``, ``faces``); every problem is a :class:`cases.scene.errors.SceneError` naming
the file, the key and the frame. See docs/mesh_series.md.

>>> import numpy as np
>>> s = MeshSeries([0.0, 1.0, 3.0], [[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]],
...                                  [[0.0, 0, 2], [1, 0, 2], [0, 1, 2]],
...                                  [[0.0, 0, 2], [1, 0, 2], [0, 1, 6]]], [[0, 1, 2]])
>>> s.at(0.25)[0].tolist(), s.at(9.0)[2].tolist(), s.breakpoints
([0.0, 0.0, 0.5], [0.0, 1.0, 6.0], (0.0, 1.0, 3.0))
>>> s.speed_bounds().tolist(), s.node_speeds(1).tolist()
([2.0, 2.0], [0.0, 0.0, 2.0])
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.model.bodies import VertexTrajectory
from cases.scene.errors import SceneError
from cases.model.mesh_series_checks import EDGE_RATIO, REFERENCE_RTOL, RING_MISFIT, check_frames
from cases.model.mesh_series_d3plot import is_d3plot, read_d3plot
from cases.model.mesh_series_io import SeriesInvalid, read_npz, read_pvd, read_xdmf
from cases.model.mesh_series_write import write_npz, write_pvd, write_xdmf

__all__ = ["MeshSeries", "read_mesh_series", "write_pvd", "write_xdmf", "write_npz", "is_series",
           "EDGE_RATIO", "RING_MISFIT", "REFERENCE_RTOL", "SUFFIXES"]

#: The readers by file suffix.
SUFFIXES = {".pvd": "ParaView series", ".xdmf": "XDMF time series", ".xmf": "XDMF time series", ".npz": "NumPy .npz"}


def is_series(name) -> bool:
    """A file read as a mesh series: a known suffix (:data:`SUFFIXES`) or an LS-DYNA d3plot."""
    return Path(name).suffix.lower() in SUFFIXES or is_d3plot(name)


def _frozen(values, dtype) -> np.ndarray:
    a = np.array(values, dtype=dtype)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class MeshSeries(VertexTrajectory):
    """Frames of one surface: ``times`` (k,) [s] strictly increasing, ``vertices`` (k, n, 3) [m], ``faces``
    (m, 3) or (m, 4) int (triangles in a 4-column array padded with -1, as blockage.LeakageSurface), and the
    file it came from (``source``). The arrays are copied and read-only."""

    faces: np.ndarray = None
    source: str = ""

    __eq__ = object.__eq__  # identity: arrays have no single truth value
    __hash__ = object.__hash__

    def __post_init__(self):
        times, vertices = _frozen(self.times, float), _frozen(self.vertices, float)
        faces = _frozen(np.zeros((0, 3)) if self.faces is None else self.faces, np.int64)
        if times.ndim != 1 or len(times) < 1 or vertices.shape[:1] != times.shape or vertices.ndim != 3 \
                or vertices.shape[2] != 3:
            raise ValueError(f"expected times (k,) and vertices (k, n, 3) with k >= 1, got {times.shape} and "
                             f"{vertices.shape}")
        if faces.ndim != 2 or faces.shape[1] not in (3, 4):
            raise ValueError(f"faces must have shape (m, 3) or (m, 4), got {faces.shape}")
        if not np.all(np.diff(times) > 0):
            raise ValueError("times must increase strictly")
        for name, value in (("times", times), ("vertices", vertices), ("faces", faces)):
            object.__setattr__(self, name, value)

    def __repr__(self):
        return (f"MeshSeries({len(self.times)} frames, {self.n_nodes} nodes, {len(self.faces)} faces, "
                f"t = {self.times[0]:.6g} .. {self.times[-1]:.6g} s, source={self.source!r})")

    @property
    def n_frames(self) -> int:
        return len(self.times)

    @property
    def n_nodes(self) -> int:
        return self.vertices.shape[1]

    @property
    def face_sizes(self) -> np.ndarray:
        """(m,) int: 3 or 4 nodes a face."""
        return (self.faces >= 0).sum(axis=1)

    def triangles(self) -> np.ndarray:
        """(m', 3) int: the faces as triangles, each quad [a, b, c, d] split into [a, b, c] and [a, c, d]."""
        f = self.faces
        if f.shape[1] == 3:
            return f
        quads = f[:, 3] >= 0
        return np.concatenate([f[~quads, :3], f[quads][:, [0, 1, 2]], f[quads][:, [0, 2, 3]]])

    def interval(self, t: float) -> int:
        """Index i of the frame interval [times[i], times[i+1]) holding t, clipped to 0 .. k-2 (0 for one frame)."""
        i = int(np.searchsorted(self.times, t, side="right")) - 1
        return min(max(i, 0), max(len(self.times) - 2, 0))

    def velocities(self, i: int) -> np.ndarray:
        """(n, 3) node velocities [m/s] on frame interval i (constant there: the motion is linear in time)."""
        if not 0 <= i < len(self.times) - 1:
            raise IndexError(f"frame interval {i} out of 0..{len(self.times) - 2}")
        return (self.vertices[i + 1] - self.vertices[i]) / (self.times[i + 1] - self.times[i])

    def node_speeds(self, i: int) -> np.ndarray:
        """(n,) node speeds |x_{i+1} - x_i| / (t_{i+1} - t_i) [m/s] on frame interval i."""
        return np.linalg.norm(self.velocities(i), axis=1)

    def velocity_bound(self, i: int) -> float:
        """Largest node speed [m/s] on frame interval i: exact, and a bound for every point of every face."""
        speeds = self.node_speeds(i)
        return float(speeds.max()) if speeds.size else 0.0

    def speed_bounds(self) -> np.ndarray:
        """(k-1,) :meth:`velocity_bound` of every frame interval [m/s]."""
        if self.n_nodes == 0:
            return np.zeros(len(self.times) - 1)
        step = np.linalg.norm(np.diff(self.vertices, axis=0), axis=2).max(axis=1)
        return step / np.diff(self.times)


def read_mesh_series(path, *, where: str = "", scene_path=None, reference_vertices=None, reference_faces=None,
                     reference_rtol: float = REFERENCE_RTOL, parts=(), units: str = "SI") -> MeshSeries:
    """Read and check a mesh series; the reader is chosen by the suffix (:data:`SUFFIXES`).

    Parameters
    ----------
    path : str or Path
        The .pvd, .xdmf/.xmf or .npz file.
    where : str
        The scene key it was given under, e.g. ``"body[0].mesh_series"``: the key of the SceneError.
    scene_path : str or Path, optional
        The scene file, named first in an error (then the message starts with ``path``); default ``path``.
    reference_vertices : (n, 3) float, optional
        The mesh the series belongs to, at frame 0: frame 0 must coincide with it node by node within
        ``reference_rtol`` x its bounding-box diagonal.
    reference_faces : (m, 3) or (m, 4) int, optional
        Faces for an .npz without a ``faces`` array.
    parts, units : tuple of int, str
        An LS-DYNA d3plot (:mod:`cases.model.mesh_series_d3plot`): the part ids of the surface, the unit system.

    Raises
    ------
    SceneError
        One line naming the file, ``where``, the frame (index, time, the frame's file) and what is wrong.
    """
    path = Path(path)
    kind = path.suffix.lower()

    def error(message):
        if scene_path is None:
            return SceneError(path, where, message)
        return SceneError(scene_path, where, f"{path}: {message}")

    d3plot = is_d3plot(path)
    if kind not in SUFFIXES and not d3plot:
        raise error(f"unknown mesh-series format {path.suffix!r}: expected one of "
                    f"{', '.join(f'{s} ({name})' for s, name in SUFFIXES.items())} or an LS-DYNA d3plot")
    if parts and not d3plot:
        raise error(f"parts {list(parts)} apply to an LS-DYNA d3plot only (a file named d3plot or *.d3plot)")
    if not path.is_file():
        raise error("file not found")
    try:
        if d3plot:
            frames = read_d3plot(path, parts, units)
        elif kind == ".pvd":
            frames = read_pvd(path)
        elif kind == ".npz":
            frames = read_npz(path, reference_faces)
        else:
            frames = read_xdmf(path)
        check_frames(frames, reference_vertices, reference_rtol)
    except SeriesInvalid as exc:
        raise error(str(exc)) from None
    return MeshSeries(np.array([f.time for f in frames]), np.stack([f.points for f in frames]), frames[0].faces,
                      str(path))
