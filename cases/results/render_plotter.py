"""One off-screen pyvista plotter reused for every picture of a run.

The actors (leakage surface, active nodes, bodies, context surfaces such as the cavity) are made for the first
frame; for the next frames their points and scalars are updated in place, so each picture costs one VTK render
and one screenshot (adding meshes or text to a plotter costs a render each). A frame whose topology differs
(another leakage surface, other bodies) rebuilds the actors. pyvista is imported here only.
"""
from __future__ import annotations

import os
from functools import lru_cache

import numpy as np

from cases.results.render_annotate import annotate
from cases.results.render_style import (ACTIVE_NODE_RGB, BACKGROUND_RGB, BODY_OPACITY, BODY_RGB, CONTEXT_RGB, EDGE_RGB, LEGEND,
                                       SILHOUETTE_RGB, SILHOUETTE_WIDTH, VIEW_ANGLE, fraction_rgb, title)
from cases.results.render_vtk import frame_arrays, leak_polydata, polygon_cells

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

__all__ = ["FramePlotter", "closed", "edge_pixels"]


def _lookup_table(n_values=256):
    import pyvista as pv

    rgba = np.full((n_values, 4), 255, dtype=np.uint8)
    rgba[:, :3] = fraction_rgb(np.linspace(0.0, 1.0, n_values))
    return pv.LookupTable(values=rgba, scalar_range=(0.0, 1.0))


def _surface(vertices, faces):
    import pyvista as pv

    return pv.PolyData(np.asarray(vertices, dtype=np.float64), faces=polygon_cells(faces))


def closed(faces) -> bool:
    """True when every edge of the faces is shared by exactly two faces (a closed body: cull its back)."""
    cells = np.asarray(faces, dtype=np.int64)
    if cells.ndim != 2 or not len(cells) or (cells < 0).any():
        return False
    return _closed(cells.tobytes(), cells.shape[1])


@lru_cache(maxsize=32)
def _closed(data: bytes, corners: int) -> bool:
    cells = np.frombuffer(data, dtype=np.int64).reshape(-1, corners)
    edges = np.sort(np.stack([cells, np.roll(cells, -1, axis=1)], axis=-1).reshape(-1, 2), axis=1)
    return bool((np.unique(edges, axis=0, return_counts=True)[1] == 2).all())


def edge_pixels(frame, camera, window_size) -> float:
    """Median leakage-surface edge length projected at the focal distance [px]."""
    vertices = np.asarray(frame.leak_vertices, dtype=np.float64)
    faces = np.asarray(frame.leak_faces, dtype=np.int64)
    if not len(faces):
        return 0.0
    edge = np.median(np.linalg.norm(vertices[faces[:, 1]] - vertices[faces[:, 0]], axis=1))
    distance = np.linalg.norm(np.subtract(camera[0], camera[1]))
    return float(edge / (2.0 * distance * np.tan(np.radians(VIEW_ANGLE) / 2.0)) * window_size[1])


def _add_silhouette(plotter, mesh, width: float) -> None:
    """The outline of ``mesh`` as the plotter's camera sees it (VTK's ``vtkPolyDataSilhouette``: edges between a
    front and a back face, and boundary edges), opaque lines of ``width`` px in :data:`SILHOUETTE_RGB`. Built here
    rather than with ``Plotter.add_silhouette``, which renders the whole scene once more when it adds the actor."""
    import pyvista as pv
    from vtkmodules.vtkFiltersHybrid import vtkPolyDataSilhouette

    outline = vtkPolyDataSilhouette()
    outline.SetInputData(mesh)
    outline.SetCamera(plotter.renderer.camera)
    outline.SetEnableFeatureAngle(False)
    mapper = pv.DataSetMapper()
    mapper.SetInputConnection(outline.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = pv.Actor(mapper=mapper)
    actor.prop.color = SILHOUETTE_RGB
    actor.prop.line_width = width
    plotter.add_actor(actor, render=False, reset_camera=False)


def _topology(frame) -> tuple:
    return (np.shape(frame.leak_faces), tuple(np.shape(f) for _, f in frame.bodies),
            tuple(np.shape(f) for _, f in frame.context))


class FramePlotter:
    """Pictures of frames of one scene from one camera: ``image(frame) -> (h, w, 3) uint8``.

    Parameters
    ----------
    camera : pyvista camera position
        ``[position, focal point, view up]``, fixed for every picture.
    window_size : (int, int)
        (width, height) of the 3-D view [px].
    annotated : bool
        Add the title, legend, scale bar and the colour-bar strip (:mod:`cases.results.render_annotate`); the picture is
        then wider by :data:`cases.results.render_annotate.COLOUR_BAR_WIDTH`.
    context_opacity : float
        Opacity of the frames' context surfaces (1: opaque light grey; the whole-scene view makes the cavity
        translucent).
    """

    def __init__(self, camera, window_size=(800, 600), *, annotated=False, context_opacity=1.0):
        import pyvista as pv

        self.camera, self.window_size, self.annotated = camera, tuple(window_size), annotated
        self.context_opacity = context_opacity
        self.plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
        self.plotter.set_background(BACKGROUND_RGB)
        self._topology, self._meshes, self._points = None, {}, None

    def _build(self, frame) -> None:
        p = self.plotter
        p.clear_actors()
        self._meshes = {"context": [], "bodies": []}
        for vertices, faces in frame.context:
            mesh = _surface(vertices, faces)
            actor = p.add_mesh(mesh, color=CONTEXT_RGB, opacity=self.context_opacity, render=False,
                               culling="back" if self.context_opacity < 1.0 and closed(faces) else None)
            actor.mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0)  # behind a coincident vent
            self._meshes["context"].append(mesh)
        pixels = edge_pixels(frame, self.camera, self.window_size)
        self._meshes["leak"] = leak_polydata(frame)
        p.add_mesh(self._meshes["leak"], scalars="blocked_fraction", preference="cell", cmap=_lookup_table(),
                   clim=(0.0, 1.0), lighting=False, show_edges=pixels >= 8.0, edge_color=EDGE_RGB, line_width=1,
                   show_scalar_bar=False, interpolate_before_map=False, render=False)
        self._points = p.add_points(np.zeros((1, 3)), color=ACTIVE_NODE_RGB, render_points_as_spheres=True,
                                    point_size=float(np.clip(pixels / 3.0, 3.0, 10.0)), render=False)
        for vertices, faces in frame.bodies:
            mesh = _surface(vertices, faces)
            p.add_mesh(mesh, color=BODY_RGB, opacity=BODY_OPACITY, culling="back" if closed(faces) else None,
                       render=False)
            _add_silhouette(p, mesh, SILHOUETTE_WIDTH * max(self.window_size[1] / 600.0, 0.5))
            self._meshes["bodies"].append(mesh)
        self._topology = _topology(frame)

    def _update(self, frame) -> None:
        """Move the actors' points and set the scalars of ``frame`` (same topology as the last one)."""
        import pyvista as pv

        leak = self._meshes["leak"]
        leak.points = np.asarray(frame.leak_vertices, dtype=np.float64)
        points, cells = frame_arrays(frame)
        for name, values in cells.items():
            leak.cell_data[name] = values
        for name, values in points.items():
            leak.point_data[name] = values
        for mesh, (vertices, _) in zip(self._meshes["bodies"] + self._meshes["context"],
                                       list(frame.bodies) + list(frame.context)):
            mesh.points = np.asarray(vertices, dtype=np.float64)
        active = np.asarray(frame.leak_vertices, dtype=np.float64)[np.asarray(frame.active_nodes, dtype=bool)]
        self._points.SetVisibility(bool(len(active)))
        self._points.mapper.SetInputData(pv.PolyData(active if len(active) else np.zeros((1, 3))))

    def image(self, frame, camera=None, context_opacity=None) -> np.ndarray:
        """The picture of ``frame`` as (h, w, 3) uint8 (``camera``, ``context_opacity``: change them from now on)."""
        from vtkmodules.vtkRenderingCore import vtkMapper

        if context_opacity is not None and context_opacity != self.context_opacity:
            self.context_opacity, self._topology = context_opacity, None
        self.camera = camera if camera is not None else self.camera
        if self._topology != _topology(frame):
            self._build(frame)
        self._update(frame)
        p = self.plotter
        p.camera_position = self.camera
        p.camera.view_angle = VIEW_ANGLE
        previous = vtkMapper.GetResolveCoincidentTopology()  # a process-wide VTK setting: restore it after
        vtkMapper.SetResolveCoincidentTopologyToPolygonOffset()
        try:
            p.render()
            view = np.asarray(p.screenshot(return_img=True))[..., :3].copy()
        finally:
            vtkMapper.SetResolveCoincidentTopology(previous)
        if not self.annotated:
            return view
        return annotate(view, title(frame), LEGEND, self.camera, VIEW_ANGLE, fraction_rgb)


    def close(self) -> None:
        self.plotter.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
