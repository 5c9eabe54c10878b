"""Whether a PNG of vtkdf (--png) explains itself: check_legend.py KIND PICTURE.png.

Finds the colour bar, a row of at least 300 pixels whose colours are those of the
picture's colour map in order, from one end of the map to the other (within 5 % of it);
KIND: signed or unsigned (the linfac slice's blue-white-red), grey (the medial slice's
radius) or region (a segmented slice's lightness in region 0's hue); then, below the slice, the text
around it: dark pixels above the bar (its title) and below it (its range and the lines
saying what the lines mean and where the slice is). Exit status 0 when both are there.
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def signed(t):
    """linfac: t in [-1, 1], blue inside, white at 0, warm outside."""
    a = np.minimum(1, np.abs(t))
    inside = np.stack([1 - 0.8 * a, 1 - 0.6 * a, 1 - 0.1 * a], axis=-1)
    outside = np.stack([1 - 0.1 * a, 1 - 0.7 * a, 1 - 0.85 * a], axis=-1)
    return np.where((t < 0)[..., None], inside, outside)


def grey(t):
    """medial: radius over the largest radius, t in [0, 1]."""
    v = (255 - 200 * t) / 255
    return np.stack([v, v, v], axis=-1)


def region(t):
    """segment: region 0's hue (red), distance over Delta, t in [0, 1]."""
    light = 0.45 + 0.5 * np.clip(t, 0, 1)
    base = np.array([1.0, 0.65, 0.65])  # hue 0: (1, 0, 0) mixed 0.35 : 0.65 with white
    return base * light[..., None]


MAPS = {"signed": (signed, -1.0, 1.0), "unsigned": (signed, 0.0, 1.0), "grey": (grey, 0.0, 1.0), "region": (region, 0.0, 1.0)}


def main(kind, path):
    colour, lo, hi = MAPS[kind]
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)[::-1, :, :3]
    rgb = rgb.astype(np.int32)  # rows top to bottom, as the picture is seen
    # As many entries as a bar has pixels at most: neighbours differ by about a level.
    ts = np.linspace(lo, hi, 513)
    table = np.round(255 * colour(ts)).astype(np.int32)

    bar = None
    for y in range(h // 2, h):  # the legend is below the slice
        row = rgb[y]
        # The map's parameter of each pixel, when its colour is the map's (within 3 levels).
        if not (row.max(axis=1) - row.min(axis=1) > 0).any() and kind != "grey":
            continue
        difference = np.abs(row[:, None, :] - table[None, :, :]).max(axis=2)
        best = difference.argmin(axis=1)
        match = difference[np.arange(w), best] <= 3
        t = ts[best]
        x = 0
        while x < w:
            if not match[x]:
                x += 1
                continue
            end = x
            while end + 1 < w and match[end + 1] and t[end + 1] >= t[end] - 0.02 * (hi - lo):
                end += 1
            if end - x + 1 >= 300 and t[x] <= lo + 0.05 * (hi - lo) and t[end] >= hi - 0.05 * (hi - lo):
                bar = (y, x, end)
                break
            x = end + 1
        if bar:
            break
    if bar is None:
        print(f"{path}: no colour bar of the {kind} map")
        return 1
    y, x0, x1 = bar
    dark = rgb.max(axis=2) < 110
    above = np.argwhere(dark[max(0, y - 30):y, x0:x1 + 1])
    below = np.argwhere(dark[y + 1:, :])
    ok = len(above) > 20 and len(below) > 100
    if ok:
        rows = below[:, 0].max() - below[:, 0].min() + 1
        cols = below[:, 1].max() - below[:, 1].min() + 1
        ok = rows >= 40 and cols >= 150
    else:
        rows = cols = 0
    print(f"{path}: colour bar of the {kind} map at row {y} of {h}, columns {x0}..{x1}; "
          f"title {'found' if len(above) > 20 else 'missing'}; text below it {cols} x {rows} pixels")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
