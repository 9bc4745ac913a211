"""The history figure of a run (``history.png``) drawn with Pillow: one panel per quantity against time.

What it shows is :func:`history_panels`: pressure, temperature, mass flows (exchanges and inflators), exchange
areas and, where the scene has them, blocked fractions, body displacements and peak contact pressure, with an FE
run's pressure dashed in black over ventsim's (:mod:`cases.results.fe_pressure`). The look follows matplotlib's
defaults (its ``tab10`` line colours, light grid, a legend in the emptiest corner, 5% margins around the data);
:func:`cases.results.output.history_figure` draws the same panels as a matplotlib ``Figure`` for interactive use.

Drawing it here costs a few hundredths of a second; importing matplotlib alone costs about 0.3 s of CPU, more than
the whole figure is worth to a command-line run. The picture is drawn at twice its size and averaged down, so that
lines and text are antialiased.
"""
from __future__ import annotations

import math

import numpy as np

from cases.results.render_annotate import default_font

__all__ = ["history_panels", "draw_history", "nice_ticks", "tick_labels", "PANEL_HEIGHT", "WIDTH"]

WIDTH = 800
"""Width of the picture [px]."""
PANEL_HEIGHT = 230
"""Height of one panel with its share of the spacing [px]."""
COLOURS = ((31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189), (140, 86, 75),
           (227, 119, 194), (127, 127, 127), (188, 189, 34), (23, 190, 207))
"""Line colours in order (matplotlib's ``tab10``)."""
GRID_RGB = (223, 223, 223)
SCALE = 2
"""Drawn this many times larger and averaged down."""
LEFT, RIGHT, TOP, BOTTOM, GAP = 80, 16, 45, 50, 55
"""Margins of the axes [px]: left, right, above the first panel, below the last, between panels."""

_PANELS = [("pressure [Pa]", "pressure [kPa]", 1e-3), ("temperature [K]", "temperature [K]", 1.0),
           ("mass_flow [kg/s]", "mass flow [kg/s]", 1.0), (".area [m^2]", "exchange area [mm^2]", 1e6)]
_OPTIONAL = [(".blocked_fraction [-]", "blocked fraction [-]", 1.0),
             (".displacement [m]", "body displacement [mm]", 1e3), ("max_cpress [Pa]", "max CPRESS [kPa]", 1e-3)]


def history_panels(columns: list, history: np.ndarray, overlay: dict | None = None) -> list:
    """[(y label, [(series name, time [ms] (k,), values (k,), dashed)])] of the history figure, one per panel.

    A panel is there when a column ends with its suffix (blocked fractions, displacements and CPRESS only when
    not all zero); gauge pressures are left out (the pressure panel shows absolute pressures). ``overlay``
    {cavity: FePressure} adds the FE runs' pressures, dashed, to the pressure panel.
    """
    t = history[:, 0] * 1e3
    panels = [p for p in _PANELS if any(c.endswith(p[0]) for c in columns)]
    panels += [p for p in _OPTIONAL if any(c.endswith(p[0]) and np.any(history[:, i]) for i, c in enumerate(columns))]
    out = []
    for suffix, label, factor in panels:
        series = [(c.split(" [")[0], t, history[:, i] * factor, False) for i, c in enumerate(columns)
                  if c.endswith(suffix) and not c.endswith("gauge_pressure [Pa]")]
        if suffix == "pressure [Pa]":
            series += [(f"{name} (FE run)", fe.times * 1e3, fe.pressures * factor, True)
                       for name, fe in (overlay or {}).items()]
        out.append((label, series))
    return out


def nice_ticks(low: float, high: float, most: int = 6) -> np.ndarray:
    """At most ``most`` round ticks (1, 2, 2.5 or 5 times a power of ten apart) within [low, high].

    >>> nice_ticks(112.8, 263.0).tolist()
    [125.0, 150.0, 175.0, 200.0, 225.0, 250.0]
    >>> nice_ticks(0.0, 1.0).tolist()
    [0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
    """
    span = high - low
    if not span > 0.0 or not math.isfinite(span):
        return np.array([low])
    power = 10.0 ** math.floor(math.log10(span / most))
    for step in (m * power for m in (1.0, 2.0, 2.5, 5.0, 10.0, 20.0, 25.0, 50.0, 100.0)):
        first, last = math.ceil(low / step - 1e-9), math.floor(high / step + 1e-9)
        if last - first + 1 <= most:
            break
    return np.arange(first, last + 1) * step


def tick_labels(ticks) -> tuple[list, str]:
    """(labels, multiplier): the ticks' labels with as many decimals as their spacing needs; when the values are
    very large or small, labels of the values divided by a power of ten, given as ``"1e-5"`` (else "").

    >>> tick_labels(np.array([0.0, 0.4, 0.8, 1.2]))
    (['0.0', '0.4', '0.8', '1.2'], '')
    >>> tick_labels(np.array([0.0, 2e-5, 4e-5]))
    (['0', '2', '4'], '1e-5')
    """
    ticks = np.asarray(ticks, dtype=np.float64)
    big = float(np.max(np.abs(ticks))) if len(ticks) else 0.0
    exponent = math.floor(math.log10(big)) if big > 0.0 else 0
    multiplier = ""
    if exponent >= 5 or exponent <= -4:
        ticks, multiplier = ticks / 10.0 ** exponent, f"1e{exponent}"
    step = float(np.min(np.diff(ticks))) if len(ticks) > 1 else 1.0
    decimals = 0 if step <= 0 else max(0, -math.floor(math.log10(step) + 1e-9))
    if decimals < 4 and any(abs(round(v, decimals) - v) > 1e-9 * max(abs(step), 1e-300) for v in ticks):
        decimals += 1  # a step of 2.5 x 10^k
    return [f"{v:.{decimals}f}" for v in ticks], multiplier


def _range(values_list) -> tuple[float, float]:
    """(low, high) of all finite values with matplotlib's 5% margins; a flat series gets +-1 (or +-5%)."""
    finite = [v[np.isfinite(v)] for v in values_list]
    finite = np.concatenate(finite) if finite else np.zeros(0)
    if not len(finite):
        return 0.0, 1.0
    low, high = float(finite.min()), float(finite.max())
    if high - low <= 1e-12 * max(abs(low), abs(high)):
        pad = 0.05 * abs(low) if low else 1.0
        return low - pad, high + pad
    pad = 0.05 * (high - low)
    return low - pad, high + pad


def _wrap(text: str, font, width: float) -> list:
    """``text`` broken at spaces into lines no wider than ``width`` [px] (a longer word stays whole)."""
    lines, line = [], ""
    for word in text.split():
        trial = f"{line} {word}".strip()
        if line and font.getlength(trial) > width:
            lines.append(line)
            line = word
        else:
            line = trial
    return lines + ([line] if line else [])


def _dashes(points: np.ndarray, on: float, off: float) -> list:
    """The pieces (each (k, 2)) of the polyline ``points`` drawn by a dash pattern ``on``, ``off`` [px]."""
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(steps)])
    if s[-1] <= 0.0:
        return []
    starts = np.arange(0.0, s[-1], on + off)
    out = []
    for a in starts:
        b = min(a + on, s[-1])
        inside = (s > a) & (s < b)
        piece = np.vstack([[np.interp(a, s, points[:, 0]), np.interp(a, s, points[:, 1])], points[inside],
                           [np.interp(b, s, points[:, 0]), np.interp(b, s, points[:, 1])]])
        out.append(piece)
    return out


def _text_vertical(image, text: str, centre, font) -> None:
    """``text`` rotated a quarter turn (reading upwards), centred on ``centre`` [px]."""
    from PIL import Image, ImageDraw

    left, top, right, bottom = font.getbbox(text)
    label = Image.new("L", (right - left + 4, bottom - top + 4), 0)
    ImageDraw.Draw(label).text((2 - left, 2 - top), text, fill=255, font=font)
    label = label.rotate(90, expand=True)
    image.paste((0, 0, 0), (int(centre[0] - label.width / 2), int(centre[1] - label.height / 2)), label)


class _Axes:
    """One panel's box [px] and its data limits: maps data to pixels."""

    def __init__(self, box, xlim, ylim):
        self.box, self.xlim, self.ylim = box, xlim, ylim

    def pixels(self, x, y) -> np.ndarray:
        (x0, y0, x1, y1), (a, b), (c, d) = self.box, self.xlim, self.ylim
        return np.column_stack([x0 + (np.asarray(x) - a) / (b - a) * (x1 - x0),
                                y1 - (np.asarray(y) - c) / (d - c) * (y1 - y0)])


def _legend(draw, ax: _Axes, series, font, s: int) -> None:
    """The series' names with a line sample each, in the corner of the panel that covers the fewest data points."""
    names = [name for name, *_ in series]
    rows = round(font.size * 1.4)
    width = max(font.getlength(n) for n in names) + 40 * s
    height = rows * len(names) + 8 * s
    x0, y0, x1, y1 = ax.box
    corners = [(x1 - width - 6 * s, y0 + 6 * s), (x0 + 6 * s, y0 + 6 * s), (x0 + 6 * s, y1 - height - 6 * s),
               (x1 - width - 6 * s, y1 - height - 6 * s)]  # matplotlib's order: upper right, upper left, ...
    points = np.concatenate([ax.pixels(t, v) for _, t, v, _ in series])

    def covered(corner):
        (a, b) = corner
        return int(np.count_nonzero((points[:, 0] >= a) & (points[:, 0] <= a + width) & (points[:, 1] >= b)
                                    & (points[:, 1] <= b + height)))

    a, b = min(corners, key=covered)
    draw.rounded_rectangle([a, b, a + width, b + height], radius=3 * s, fill=(255, 255, 255), outline=(204, 204, 204),
                           width=s)
    for k, (name, _, _, dashed) in enumerate(series):
        y = b + 4 * s + rows * k + rows / 2
        colour = (0, 0, 0) if dashed else COLOURS[k % len(COLOURS)]
        draw.line([(a + 6 * s, y), (a + 30 * s, y)], fill=colour, width=(s if dashed else 2 * s))
        draw.text((a + 36 * s, y), name, fill=(0, 0, 0), font=font, anchor="lm")


def _panel(image, draw, ax: _Axes, label: str, series, xticks, bottom: bool, s: int) -> None:
    """Grid, lines, frame, ticks, labels and legend of one panel."""
    fonts = default_font(13 * s), default_font(11 * s)
    x0, y0, x1, y1 = ax.box
    yticks = nice_ticks(*ax.ylim)
    xs = ax.pixels(xticks, np.full(len(xticks), ax.ylim[0]))[:, 0]
    ys = ax.pixels(np.full(len(yticks), ax.xlim[0]), yticks)[:, 1]
    for x in xs:
        draw.line([(x, y0), (x, y1)], fill=GRID_RGB, width=s)
    for y in ys:
        draw.line([(x0, y), (x1, y)], fill=GRID_RGB, width=s)
    for k, (_, t, v, dashed) in enumerate(series):
        good = np.isfinite(t) & np.isfinite(v)
        points = ax.pixels(t[good], v[good])
        if dashed:
            for piece in _dashes(points, 5.0 * s, 2.2 * s):
                draw.line([tuple(p) for p in piece], fill=(0, 0, 0), width=s)
        elif len(points):
            draw.line([tuple(p) for p in points], fill=COLOURS[k % len(COLOURS)], width=2 * s, joint="curve")
    draw.rectangle([x0, y0, x1, y1], outline=(0, 0, 0), width=s)
    labels, multiplier = tick_labels(yticks)
    for y, text in zip(ys, labels):
        draw.line([(x0 - 5 * s, y), (x0, y)], fill=(0, 0, 0), width=s)
        draw.text((x0 - 8 * s, y), text, fill=(0, 0, 0), font=fonts[0], anchor="rm")
    if multiplier:
        draw.text((x0, y0 - 3 * s), multiplier, fill=(0, 0, 0), font=fonts[0], anchor="ld")
    for x, text in zip(xs, tick_labels(xticks)[0]):
        draw.line([(x, y1), (x, y1 + 5 * s)], fill=(0, 0, 0), width=s)
        if bottom:
            draw.text((x, y1 + 8 * s), text, fill=(0, 0, 0), font=fonts[0], anchor="mt")
    _text_vertical(image, label, (16 * s, (y0 + y1) / 2), fonts[0])
    if series:
        _legend(draw, ax, series, fonts[1], s)


def draw_history(columns: list, history: np.ndarray, title: str = "", overlay: dict | None = None):
    """The history figure (:func:`history_panels`) as a Pillow RGB image :data:`WIDTH` px wide."""
    from PIL import Image, ImageDraw

    panels = history_panels(columns, history, overlay) or [("", [])]
    s = SCALE
    lines = _wrap(title, default_font(13 * s), (WIDTH - 20) * s) if title else []
    top = (TOP + 17 * max(len(lines) - 1, 0)) * s
    height = (PANEL_HEIGHT * len(panels) + 17 * max(len(lines) - 1, 0)) * s
    image = Image.new("RGB", (WIDTH * s, height), (255, 255, 255))
    draw = ImageDraw.Draw(image)
    for k, line in enumerate(lines):
        draw.text((WIDTH * s / 2, (10 + 17 * k) * s), line, fill=(0, 0, 0), font=default_font(13 * s), anchor="mt")
    xlim = _range([t for _, series in panels for _, t, _, _ in series] or [history[:, 0] * 1e3])
    xticks = nice_ticks(*xlim, most=8)
    size = (height - top - BOTTOM * s - GAP * s * (len(panels) - 1)) / len(panels)
    for k, (label, series) in enumerate(panels):
        y0 = top + k * (size + GAP * s)
        ax = _Axes((LEFT * s, y0, (WIDTH - RIGHT) * s, y0 + size), xlim, _range([v for _, _, v, _ in series]))
        _panel(image, draw, ax, label, series, xticks, k == len(panels) - 1, s)
    y = height - BOTTOM * s + 30 * s
    draw.text(((LEFT + WIDTH - RIGHT) * s / 2, y), "time [ms]", fill=(0, 0, 0), font=default_font(13 * s), anchor="mm")
    return image.reduce(s)
