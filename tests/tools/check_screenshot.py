#!/usr/bin/python3
"""Checks a viewer screenshot: size, cloth pixels in the 3D view, and the ImGui panel.

usage: check_screenshot.py FILE.png WIDTH HEIGHT
The panel is the dark window at the top left (ImGui's default style); the cloth is the
bright region right of it, against the renderer's clear colour (41, 43, 51).
"""
import sys

import matplotlib.image as mpimg
import numpy as np


def main():
    path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    img = (mpimg.imread(path)[..., :3] * 255).round().astype(int)
    h, w = img.shape[:2]
    assert (w, h) == (width, height), f"{path}: size {w}x{h}, expected {width}x{height}"
    background = np.array([41, 43, 51])
    view = img[:, w // 2:]  # right half: the 3D view, clear of the panel
    cloth = np.abs(view - background).sum(axis=2) > 60
    cloth_fraction = cloth.mean()
    # ImGui's title bar: a saturated blue strip across the panel's top rows.
    panel = img[10:30, 12:200]
    title_blue = ((panel[..., 2] > panel[..., 0] + 40) & (panel[..., 2] > 90)).mean()
    print(f"{path}: {w}x{h}, cloth pixels {cloth_fraction:.1%} of the view, panel title bar {title_blue:.0%} blue")
    assert cloth_fraction > 0.02, "no cloth in the 3D view"
    assert title_blue > 0.5, "no ImGui panel at the top left"


if __name__ == "__main__":
    main()
