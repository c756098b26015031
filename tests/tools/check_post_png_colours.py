#!/usr/bin/python3
# Counts the distinct colours of PNG images and fails when one is (nearly) blank.
# Usage: check_post_png_colours.py MIN_COLOURS IMAGE.png...
# A contour plot with a colour map shows hundreds of colours; a blank or single-colour
# render shows one or two (background + text antialiasing adds a few grey levels).
import sys

import matplotlib.image
import numpy as np


def main():
    minimum = int(sys.argv[1])
    status = 0
    for path in sys.argv[2:]:
        image = matplotlib.image.imread(path)
        pixels = (np.asarray(image)[..., :3] * 255).round().astype(np.uint8).reshape(-1, 3)
        colours = len(np.unique(pixels, axis=0))
        print(f"{path}: {image.shape[1]}x{image.shape[0]}, distinct colours: {colours}")
        if colours < minimum:
            print(f"FAIL: {path} looks blank ({colours} < {minimum} colours)")
            status = 1
    sys.exit(status)


if __name__ == "__main__":
    main()
