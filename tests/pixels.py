"""Colours of rendered pictures, for the tests that judge what a picture shows."""

from __future__ import annotations

import numpy as np


def hsv(image: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hue (degrees), saturation and value (0-1) of every pixel of an RGB image of 0-255 integers."""
    rgb = image.astype(float) / 255.0
    high, low = rgb.max(axis=2), rgb.min(axis=2)
    span = np.where(high > low, high - low, 1.0)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    hue = np.where(high == r, ((g - b) / span) % 6, np.where(high == g, (b - r) / span + 2, (r - g) / span + 4)) * 60
    saturation = np.where(high > 0, (high - low) / np.where(high > 0, high, 1), 0)
    return hue, saturation, high
