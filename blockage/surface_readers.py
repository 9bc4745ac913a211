"""Ways to make a leakage surface: a whole trimesh, a selection of a cavity surface's faces (by index, by a box
or sphere region), a meshio or pyvista mesh, a file (a mixin of :class:`blockage.surfaces.LeakageSurface`)."""

import numpy as np

from blockage.polygons import polygons
from blockage.validation import as_indices, as_points

__all__ = ["SurfaceReaders"]


class SurfaceReaders:
    """Class methods that build a leakage surface (``cls(vertices, faces, source=..., source_vertices=...)``)."""

    @classmethod
    def from_trimesh(cls, mesh):
        """Every face of a trimesh (which stays its ``source``)."""
        return cls(mesh.vertices, mesh.faces, source=mesh, source_vertices=np.arange(len(mesh.vertices)))

    @classmethod
    def from_faces(cls, mesh, face_indices):
        """A selection of faces of a cavity surface.

        Parameters
        ----------
        mesh : trimesh.Trimesh
            The cavity surface (kept as ``source`` for self-contact).
        face_indices : (k,) int
            Selected faces.
        """
        chosen = as_indices(np.ravel(face_indices), len(mesh.faces), name="face indices")
        used, local = np.unique(np.asarray(mesh.faces)[chosen], return_inverse=True)
        return cls(np.asarray(mesh.vertices)[used], local.reshape(-1, 3), source=mesh, source_vertices=used)

    @classmethod
    def from_region(cls, mesh, *, box=None, sphere=None):
        """Faces of a cavity surface whose centroid lies in a box or a sphere.

        Parameters
        ----------
        mesh : trimesh.Trimesh
            The cavity surface.
        box : ((3,) float, (3,) float), optional
            Lower and upper corners [m] (inclusive).
        sphere : ((3,) float, float), optional
            Centre [m] and radius [m] (inclusive).
        """
        if (box is None) == (sphere is None):
            raise ValueError("from_region needs exactly one of box=(lo, hi) or sphere=(centre, radius)")
        centroids = np.asarray(mesh.vertices)[np.asarray(mesh.faces)].mean(axis=1)
        if box is not None:
            lo, hi = (as_points(np.reshape(x, (1, 3)), "box corner")[0] for x in box)
            inside = ((centroids >= lo) & (centroids <= hi)).all(axis=1)
        else:
            centre = as_points(np.reshape(sphere[0], (1, 3)), "sphere centre")[0]
            inside = np.linalg.norm(centroids - centre, axis=1) <= float(sphere[1])
        if not inside.any():
            raise ValueError("no face of the mesh has its centroid in the given region")
        return cls.from_faces(mesh, np.flatnonzero(inside))

    @classmethod
    def from_meshio(cls, mesh, group=None):
        """Triangles and quads of a meshio mesh, optionally only a named cell set.

        Higher-order cells (``triangle6``, ``quad8``, ``quad9``) use their corner
        nodes. Nodes not used by the selected faces are dropped.
        """
        if group is not None and group not in mesh.cell_sets:
            raise ValueError(f"group {group!r} not found; the file has {sorted(mesh.cell_sets)}")
        rows = []
        for block_index, block in enumerate(mesh.cells):
            corners = {"triangle": 3, "triangle6": 3, "quad": 4, "quad8": 4, "quad9": 4}.get(block.type)
            if corners is None:
                continue
            data = np.asarray(block.data)[:, :corners]
            if group is not None:
                data = data[np.asarray(mesh.cell_sets[group][block_index], dtype=np.int64)]
            rows.extend(list(row) for row in data)
        if not rows:
            raise ValueError("the mesh has no triangle or quad cells" + (f" in group {group!r}" if group else ""))
        points = np.asarray(mesh.points, dtype=np.float64)
        points = np.column_stack([points, np.zeros((len(points), 3 - points.shape[1]))]) if points.shape[1] < 3 else points
        return cls._compact(points, rows)

    @classmethod
    def from_pyvista(cls, polydata):
        """Triangles and quads of a ``pyvista.PolyData``."""
        rows = [list(face) for face in polydata.irregular_faces]
        return cls._compact(np.asarray(polydata.points, dtype=np.float64), rows)

    @classmethod
    def read(cls, path, group=None):
        """Read a file with meshio (keeps quads; ``group`` names a cell set)."""
        import meshio

        return cls.from_meshio(meshio.read(path), group=group)

    @classmethod
    def _compact(cls, points, rows):
        """Surface on the nodes that the faces use."""
        faces, sizes = polygons(rows, len(points))
        used = np.unique(faces[faces >= 0])
        renumber = np.full(len(points), -1, np.int64)
        renumber[used] = np.arange(len(used))
        local = [list(renumber[face[:size]]) for face, size in zip(faces, sizes)]
        return cls(points[used], local)
