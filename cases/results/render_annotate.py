"""What a picture of a run says besides the 3-D view: time and pressure, a colour bar with its unit, a scale bar.

The annotations are drawn with Pillow on the rendered view (no VTK text or scalar-bar actors, which would cost a
render each): the title at the top (scene, exchange and cavity on a first line when given, then
``t = 12.50 ms, p = 135.2 kPa``), the orientation axes (x, y, z arrows as the camera sees them) at the top left, a
one-line legend at the bottom left, a scale bar (its length in mm is true at the camera's focal point) at the
bottom right, and to the right of the view a
strip of :data:`COLOUR_BAR_WIDTH` pixels holding the colour bar of the blocked fraction ``A_eb / A_e [-]``
(red 1 at the top, blue 0 at the bottom).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

__all__ = ["COLOUR_BAR_WIDTH", "annotate", "scale_bar_length", "view_part", "pixels_per_metre", "screen_axes"]

COLOUR_BAR_WIDTH = 130
"""Width [px] of the strip to the right of the view that holds the colour bar."""
BAR_MARGIN = 0.12
"""Top and bottom margins of the colour bar, as a fraction of the picture's height."""


def view_part(image: np.ndarray) -> np.ndarray:
    """The 3-D view of an annotated picture (without the colour-bar strip)."""
    return np.asarray(image)[:, :-COLOUR_BAR_WIDTH]


def pixels_per_metre(camera, view_angle: float, height: int) -> float:
    """Screen pixels per metre at the camera's focal point [px/m]: ``h / (2 d tan(view_angle / 2))``.

    >>> round(pixels_per_metre([(0, 0, 1.0), (0, 0, 0), (0, 1, 0)], 90.0, 600), 6)
    300.0
    """
    distance = float(np.linalg.norm(np.subtract(camera[0], camera[1])))
    return height / (2.0 * distance * math.tan(math.radians(view_angle) / 2.0))


def screen_axes(camera) -> np.ndarray:
    """(3, 2) screen directions (right, up; unit length for an axis across the view) of the world x, y, z axes as
    seen by ``camera`` (a pyvista camera position ``[position, focal point, view up]``).

    >>> screen_axes([(0, 0, 1.0), (0, 0, 0), (0, 1, 0)]).round(6).tolist()  # looking down -z, y up
    [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]
    """
    position, focal, up = (np.asarray(v, dtype=np.float64) for v in camera)
    forward = (focal - position) / np.linalg.norm(focal - position)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    return np.column_stack([right, np.cross(right, forward)])


def _axes(draw, camera, origin, length: float, font) -> None:
    """The orientation axes: an arrow per world axis from ``origin`` [px], its end labelled x, y or z."""
    from cases.results.render_style import AXIS_RGB

    x0, y0 = origin
    directions = screen_axes(camera)
    for k in np.argsort([-d @ d for d in directions]):  # the shortest (pointing at the viewer) drawn last
        dx, dy = directions[k] * length
        end = (x0 + dx, y0 - dy)
        draw.line([origin, end], fill=AXIS_RGB[k], width=3)
        size = math.hypot(dx, dy)
        if size > 4.0:
            ux, uy = dx / size, -dy / size
            draw.polygon([end, (end[0] - 7 * ux - 4 * uy, end[1] - 7 * uy + 4 * ux),
                          (end[0] - 7 * ux + 4 * uy, end[1] - 7 * uy - 4 * ux)], fill=AXIS_RGB[k])
        label = (x0 + dx * (1.0 + 9.0 / max(size, 1e-9)), y0 - dy * (1.0 + 9.0 / max(size, 1e-9)))
        draw.text(label, "xyz"[k], fill=AXIS_RGB[k], font=font, anchor="mm")


def scale_bar_length(metres_per_pixel: float, target_pixels: float = 120.0) -> float:
    """A round length (1, 2 or 5 times a power of ten) [m] closest below ``target_pixels`` pixels.

    >>> scale_bar_length(1e-4), scale_bar_length(2.5e-4)
    (0.01, 0.02)
    """
    target = target_pixels * metres_per_pixel
    power = 10.0 ** math.floor(math.log10(target))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= target * (1 + 1e-12))


@lru_cache(maxsize=8)
def default_font(size: int):
    """Pillow's default font at ``size`` pixels (one bitmap size before Pillow 10.1), kept per size."""
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1: one bitmap size
        return ImageFont.load_default()


def _colour_bar(canvas, draw, width: int, height: int, colours, font) -> None:
    """The blocked-fraction bar in the strip starting at x = ``width`` (the view's width)."""
    top, bottom = int(BAR_MARGIN * height), int((1.0 - BAR_MARGIN) * height)
    x0, x1 = width + 20, width + 45
    rows = colours((bottom - np.arange(top, bottom + 1)) / max(bottom - top, 1))
    canvas.paste(_bar_image(rows.tobytes(), len(rows), x1 - x0 + 1), (x0, top))
    draw.rectangle([x0 - 1, top - 1, x1 + 1, bottom + 1], outline=(0, 0, 0))
    for f in (0.0, 0.25, 0.5, 0.75, 1.0):
        y = bottom - f * (bottom - top)
        draw.line([(x1 + 1, y), (x1 + 6, y)], fill=(0, 0, 0))
        draw.text((x1 + 9, y), f"{f:g}", fill=(0, 0, 0), font=font, anchor="lm")
    draw.text((x0 - 8, top - 12), "blocked fraction", fill=(0, 0, 0), font=font, anchor="ls")
    draw.text((x0 - 8, bottom + 20), "A_eb / A_e [-]", fill=(0, 0, 0), font=font, anchor="ls")


@lru_cache(maxsize=8)
def _bar_image(rows: bytes, n: int, width: int):
    from PIL import Image

    column = np.frombuffer(rows, dtype=np.uint8).reshape(n, 1, 3)
    return Image.fromarray(np.ascontiguousarray(np.repeat(column, width, axis=1)))


def _scale_bar(draw, width: int, height: int, px_per_m: float, font) -> None:
    length = scale_bar_length(1.0 / px_per_m, target_pixels=0.18 * width)
    pixels = length * px_per_m
    x1, y = width - 20, height - 22
    x0 = x1 - pixels
    draw.line([(x0, y), (x1, y)], fill=(0, 0, 0), width=3)
    for x in (x0, x1):
        draw.line([(x, y - 6), (x, y + 6)], fill=(0, 0, 0), width=2)
    label = f"{length * 1e3:g} mm" if length < 1.0 else f"{length:g} m"
    draw.text(((x0 + x1) / 2, y - 8), label, fill=(0, 0, 0), font=font, anchor="mb")


def annotate(view: np.ndarray, title: str, legend: str, camera, view_angle: float, colours) -> np.ndarray:
    """The annotated picture: ``view`` (h, w, 3) uint8 with the title, legend and scale bar, and the colour-bar
    strip appended on the right; ``colours(fraction) -> (3,) uint8`` is the colour scale."""
    from PIL import Image, ImageDraw

    height, width = view.shape[:2]
    canvas = Image.new("RGB", (width + COLOUR_BAR_WIDTH, height), (255, 255, 255))
    canvas.paste(Image.fromarray(np.ascontiguousarray(view[..., :3])), (0, 0))
    draw = ImageDraw.Draw(canvas)
    scale = min(width / 800.0, height / 600.0)
    big, small = default_font(max(round(20 * scale), 9)), default_font(max(round(12 * scale), 8))
    lines = title.split("\n")
    for k, line in enumerate(lines):
        draw.text((width / 2, 8 + k * round(24 * scale)), line, fill=(0, 0, 0),
                  font=big if k == len(lines) - 1 else default_font(max(round(15 * scale), 8)), anchor="mt")
    top = 8 + len(lines) * round(24 * scale)
    _axes(draw, camera, (round(45 * scale), top + round(45 * scale)), 32 * scale, small)
    draw.text((8, height - 8), legend, fill=(0, 0, 0), font=small, anchor="ls")
    _scale_bar(draw, width, height - round(14 * scale), pixels_per_metre(camera, view_angle, height), small)
    _colour_bar(canvas, draw, width, height, colours, small)
    return np.asarray(canvas)
