#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Find text on a screenshot (GUI smoke test): tesseract on a 3x grey upscale.

  ocr.py IMG [--crop WxH+X+Y]        print every text line
  ocr.py IMG TEXT [--crop WxH+X+Y]   print "x y" (screen coordinates), the centre of the first
                        occurrence of TEXT (a sequence of whole words inside one line); exit 1
                        when it is not found. --crop reads only that part of the screenshot.
"""
import os
import subprocess
import sys

SCALE = 2
CROP = None   # (w, h, x, y)


def lines(img):
    big = img + ".ocr.png"
    crop = []
    if CROP:
        crop = ["-crop", "%dx%d+%d+%d" % CROP, "+repage"]
    subprocess.run(["convert", img] + crop + ["-resize", "%d%%" % (100 * SCALE),
                    "-colorspace", "Gray", big], check=True)
    env = dict(os.environ, OMP_THREAD_LIMIT="1")   # tesseract's threads only slow it down here
    tsv = subprocess.run(["tesseract", big, "-", "--psm", "3", "tsv"], capture_output=True,
                         text=True, check=True, env=env).stdout
    out = {}
    for row in tsv.splitlines()[1:]:
        r = row.split("\t")
        if len(r) == 12 and r[11].strip():
            box = [int(v) // SCALE for v in r[6:10]]   # left top width height
            if CROP:
                box[0] += CROP[2]
                box[1] += CROP[3]
            out.setdefault((r[1], r[2], r[3], r[4]), []).append((r[11], box))
    return list(out.values())


def find(img, text):
    want = text.split()
    for words in lines(img):
        toks = [w for w, _ in words]
        for i in range(len(toks) - len(want) + 1):
            if toks[i:i + len(want)] == want:
                boxes = [b for _, b in words[i:i + len(want)]]
                x0 = min(b[0] for b in boxes)
                y0 = min(b[1] for b in boxes)
                x1 = max(b[0] + b[2] for b in boxes)
                y1 = max(b[1] + b[3] for b in boxes)
                return (x0 + x1) // 2, (y0 + y1) // 2
    return None


def main():
    global CROP
    if "--crop" in sys.argv:
        i = sys.argv.index("--crop")
        g = sys.argv[i + 1]
        del sys.argv[i:i + 2]
        wh, x, y = g.split("+")
        w, h = (int(v) for v in wh.split("x"))
        x, y = int(x), int(y)
        # A window partly off the screen (a dialog taller than the space left for it starts at
        # a negative y): read its visible part, in screen coordinates.
        w, h = w + min(x, 0), h + min(y, 0)
        CROP = (w, h, max(x, 0), max(y, 0))
    if len(sys.argv) == 2:
        for words in lines(sys.argv[1]):
            print(" ".join(w for w, _ in words))
        return 0
    pos = find(sys.argv[1], sys.argv[2])
    if pos is None:
        return 1
    print("%d %d" % pos)
    return 0


if __name__ == "__main__":
    sys.exit(main())
