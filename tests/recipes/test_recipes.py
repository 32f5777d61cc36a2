#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Test of scripts/recipes.sh (label recipes): the feature-preserving recipes through the real
meshlabserver keep the CAD part's creases while the filter alone rounds them.

  test_recipes.py --recipes scripts/recipes.sh --work DIR

What a user of the recipes needs, on the generated part with noise of 0.1 edge:
- our filter alone rounds the creases (their dihedral angles drop below 60 % of the clean
  part's) while it denoises the flats (error at most half the noise's);
- every recipe keeps the creases (at least 85 % of the clean angles), and still halves the
  error on the flats and on the bump against the noisy input, and beats the filter alone on
  the whole part and on the creases;
- the hard-constraint recipe leaves the vertices it did not select bit-identical (most crease
  vertices); the pictures exist and are small enough to commit (< 150 KB).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print("ok: " + msg)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--recipes", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)   # no stale picture or figure can pass for new
    r = subprocess.run([a.recipes, "--out", a.work])
    if r.returncode != 0:
        fail("recipes.sh exited %d" % r.returncode)
    with open(os.path.join(a.work, "figures.json")) as f:
        fig = {row["recipe"]: row for row in json.load(f)}
    noisy, uniform = fig["noisy"], fig["uniform"]
    check(uniform["crease_sharpness_pct"] < 60,
          "the filter alone rounds the creases: %.1f %% of the clean dihedral angles"
          % uniform["crease_sharpness_pct"])
    check(uniform["rms_flat"] <= 0.5 * noisy["rms_flat"],
          "the filter alone denoises the flats: %.4f -> %.4f edges"
          % (noisy["rms_flat"], uniform["rms_flat"]))
    for name in ("selection", "geodesic", "curvature"):
        r = fig[name]
        check(r["crease_sharpness_pct"] >= 85,
              "%s keeps the creases: %.1f %% of the clean angles"
              % (name, r["crease_sharpness_pct"]))
        for part in ("rms_flat", "rms_bump"):
            check(r[part] <= 0.5 * noisy[part], "%s: %s %.4f <= half the noisy %.4f"
                  % (name, part, r[part], noisy[part]))
        check(r["rms_edges"] < uniform["rms_edges"] and r["rms_crease"] < uniform["rms_crease"],
              "%s beats the filter alone: error %.4f < %.4f, on creases %.4f < %.4f"
              % (name, r["rms_edges"], uniform["rms_edges"], r["rms_crease"],
                 uniform["rms_crease"]))
    check(fig["selection"]["crease_unmoved_pct"] >= 50,
          "selection: %.1f %% of the crease vertices bit-identical (hard constraints)"
          % fig["selection"]["crease_unmoved_pct"])
    check(uniform["crease_unmoved_pct"] == 0, "the filter alone moves every crease vertex")
    for name in ("uniform", "selection", "geodesic", "curvature"):
        png = os.path.join(a.work, "recipe_%s.png" % name)
        size = os.path.getsize(png) if os.path.exists(png) else 0
        check(10000 < size < 150000, "%s: %d bytes" % (os.path.basename(png), size))
    print("PASS")


if __name__ == "__main__":
    main()
