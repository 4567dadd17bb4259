"""Polygon area (shoelace) and polar helpers for the exact-profile volumes.

Examples
--------
>>> shoelace_area([0, 2, 2, 0], [0, 0, 1, 1])
2.0
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def shoelace_area(x: ArrayLike, y: ArrayLike) -> float:
    """Area of the simple polygon with vertices ``(x[i], y[i])`` (closed implicitly).

    Parameters
    ----------
    x, y : array_like
        Vertex coordinates, in order (either orientation); the last vertex joins the first.

    Returns
    -------
    float
        The (positive) area, in the square of the coordinates' unit.

    Examples
    --------
    >>> shoelace_area([0, 1, 0], [0, 0, 1])      # right triangle, legs 1
    0.5
    >>> shoelace_area([0, 0, 1], [0, 1, 0])      # clockwise: same area
    0.5
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1 or x.size < 3:
        raise ValueError("a polygon needs two 1-D arrays of the same length >= 3")
    # Shift to the centroid of the vertices: same area, less cancellation for large shapes.
    x = x - x.mean()
    y = y - y.mean()
    return float(abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2)


def polar_to_xy(radius: ArrayLike, angle: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Cartesian points of polar ``(radius, angle)``; angle in radians from the x axis.

    Examples
    --------
    >>> x, y = polar_to_xy([2.0], [np.pi / 2])
    >>> float(round(x[0], 12)), float(y[0])
    (0.0, 2.0)
    """
    radius = np.asarray(radius, dtype=float)
    angle = np.asarray(angle, dtype=float)
    return radius * np.cos(angle), radius * np.sin(angle)
