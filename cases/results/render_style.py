"""The look of ventsim's pictures: colours of the blocked-fraction scale, bodies and text, the view angle, the
title line (see ``docs/rendering.md``)."""
from __future__ import annotations

import numpy as np

__all__ = ["UNBLOCKED_RGB", "HALF_BLOCKED_RGB", "BLOCKED_RGB", "BLOCKED_TOLERANCE", "BACKGROUND_RGB", "EDGE_RGB",
           "ACTIVE_NODE_RGB", "BODY_RGB", "BODY_OPACITY", "SILHOUETTE_RGB", "SILHOUETTE_WIDTH", "AXIS_RGB", "CONTEXT_RGB", "CAVITY_OPACITY", "VIEW_ANGLE", "LEGEND",
           "fraction_rgb", "title"]

UNBLOCKED_RGB = (43, 131, 186)
"""Face colour for ``A_eb / A_e = 0`` (ColorBrewer RdYlBu blue)."""
HALF_BLOCKED_RGB = (255, 255, 191)
"""Face colour for ``A_eb / A_e = 0.5`` (pale yellow); linear in between."""
BLOCKED_RGB = (215, 25, 28)
"""Face colour for ``A_eb / A_e = 1`` (ColorBrewer RdYlBu red): "the blocked colour"."""
BLOCKED_TOLERANCE = 70.0
"""Euclidean RGB distance counted as "the blocked colour": fractions >= 0.88, or red behind one body layer."""
BACKGROUND_RGB = (255, 255, 255)
EDGE_RGB = (64, 64, 64)
ACTIVE_NODE_RGB = (0, 0, 0)
BODY_RGB = (102, 189, 99)
"""Fill of the blocking bodies (ColorBrewer RdYlGn green: on no colour of the blocked-fraction scale)."""
BODY_OPACITY = 0.25
"""Translucent, so that the faces behind a body keep their colour (blended with one layer)."""
SILHOUETTE_RGB = (0, 104, 55)
"""Outline of the blocking bodies (their silhouette from the camera, drawn opaque): dark green."""
SILHOUETTE_WIDTH = 3.0
"""Width of the bodies' outline [px] (at an 800 x 600 view)."""
AXIS_RGB = ((197, 27, 125), (51, 160, 44), (106, 61, 154))
"""Colours of the x, y and z arrows of the orientation axes (magenta, green, purple: none on the blocked-fraction
scale, so that nothing but faces is red or blue)."""
CONTEXT_RGB = (211, 211, 211)
CAVITY_OPACITY = 0.18
"""Opacity of the cavity surface in the whole-scene view (translucent: the bodies and the vent show through)."""
VIEW_ANGLE = 30.0
"""Vertical view angle of the camera [deg] (pyvista's default)."""
LEGEND = "faces: blocked fraction A_eb/A_e, blue 0 - yellow 0.5 - red 1; dots: active nodes; green outline: bodies"



def fraction_rgb(fraction):
    """RGB (uint8) of the fixed blocked-fraction colour scale: blue -> pale yellow -> red.

    Parameters
    ----------
    fraction : float or (k,) float
        ``A_eb / A_e``, clipped to [0, 1].

    Returns
    -------
    (3,) or (k, 3) uint8

    >>> fraction_rgb(0.0).tolist(), fraction_rgb(0.5).tolist(), fraction_rgb(1.0).tolist()
    ([43, 131, 186], [255, 255, 191], [215, 25, 28])
    """
    anchors = np.array([UNBLOCKED_RGB, HALF_BLOCKED_RGB, BLOCKED_RGB], dtype=np.float64)
    f = np.clip(np.asarray(fraction, dtype=np.float64), 0.0, 1.0)
    rgb = np.stack([np.interp(f, [0.0, 0.5, 1.0], anchors[:, c]) for c in range(3)], axis=-1)
    return np.rint(rgb).astype(np.uint8)


def title(frame):
    """``"t = 12.50 ms, p = 135.2 kPa"``, after the frame's ``label`` line (scene, exchange, cavity) when it has one.

    >>> from types import SimpleNamespace
    >>> title(SimpleNamespace(time=0.0125, pressure=135.2e3))
    't = 12.50 ms, p = 135.2 kPa'
    >>> print(title(SimpleNamespace(time=0.0125, pressure=135.2e3, label="bag: exchange vent, cavity cushion")))
    bag: exchange vent, cavity cushion
    t = 12.50 ms, p = 135.2 kPa
    """
    line = f"t = {frame.time * 1e3:.2f} ms, p = {frame.pressure / 1e3:.1f} kPa"
    label = getattr(frame, "label", "")
    return f"{label}\n{line}" if label else line
