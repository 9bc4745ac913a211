"""One frozen object holding every numerical threshold of the package.

Nothing in :mod:`blockage` compares floats against a bare literal: each threshold is
a field of :class:`Tolerances`, with its meaning and unit, and :data:`TOL` is the
instance the package uses (in the spirit of ``trimesh.constants.tol``).

>>> TOL.degenerate_sin2
1e-10
>>> TOL.feature_angle_deg
20.0
"""

from dataclasses import dataclass

__all__ = ["Tolerances", "TOL"]


@dataclass(frozen=True)
class Tolerances:
    """Numerical thresholds of the proximity detector (all dimensionless).

    Attributes
    ----------
    box_margin_rel : float
        Bounding boxes of the broad phase are inflated by this fraction of the
        blocker's coordinate scale (largest absolute coordinate plus bounding-box
        diagonal). It absorbs round-off of the box and triangle distances so that
        the broad phase never prunes a face that the exact kernel would keep; it
        only ever adds candidates, so it never changes a result.
    degenerate_sin2 : float
        A triangle with ``|ab x ac|^2 <= degenerate_sin2 * |ab|^2 |ac|^2``
        (squared sine of its angle at ``a``) is treated as its three edges. Above
        this value Ericson's barycentric branch is accurate to second order in
        the in-plane error; below it the sliver is narrower than ``1e-5`` of its
        edge and its edges are the better answer.
    feature_angle_deg : float
        Edge between two blocking faces whose normals differ by more than this
        angle [deg] is a sharp (feature) edge for edge-to-edge contact. Boundary
        and non-manifold edges are always feature edges.
    rigid_rel : float
        A 4x4 ``transform`` is accepted as rigid when ``|R^T R - I|`` and the
        bottom row deviate from exact by at most this much.
    """

    box_margin_rel: float = 1e-10
    degenerate_sin2: float = 1e-10
    feature_angle_deg: float = 20.0
    rigid_rel: float = 1e-9


TOL = Tolerances()
