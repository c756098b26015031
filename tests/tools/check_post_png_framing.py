#!/usr/bin/python3
# Measures how much of a picture of mppm-postprocess the body fills: the bounding box of the
# pixels that are not background, outside the strip of the colour bar (the right 210 of every
# 1600 pixels of width) and the band of the time label (the top 56 of every 1600), as a
# fraction of the picture's width and height. Fails unless one of them reaches MIN_FRACTION.
# Usage: check_post_png_framing.py MIN_FRACTION IMAGE.png...
# Background: white; a pixel counts as the body when a channel is more than 8 of 255 below
# white (antialiasing at the body's rim is kept, compression noise has none on a PNG).
import sys

import numpy
from PIL import Image

COLOUR_BAR_STRIP, LABEL_BAND = 210 / 1600, 56 / 1600


def coverage(path):
    pixels = numpy.asarray(Image.open(path).convert("RGB")).astype(int)
    height, width, _ = pixels.shape
    body = (pixels < 255 - 8).any(axis=2)
    body[:, width - int(round(COLOUR_BAR_STRIP * width)):] = False
    body[:int(round(LABEL_BAND * width)), :] = False
    rows, columns = numpy.nonzero(body)
    if len(rows) == 0:
        return width, height, 0.0, 0.0
    return width, height, (columns.max() - columns.min() + 1) / width, (rows.max() - rows.min() + 1) / height


def main():
    minimum = float(sys.argv[1])
    status = 0
    for path in sys.argv[2:]:
        width, height, across, down = coverage(path)
        print(f"{path}: {width}x{height}, body covers {across:.3f} of the width and {down:.3f} of the height")
        if max(across, down) < minimum:
            print(f"FAIL: {path}: the body fills less than {minimum} of the width and of the height")
            status = 1
    sys.exit(status)


if __name__ == "__main__":
    main()
