#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Writes the feature-preserving recipes' .mlx scripts (MeshLab 2020.09's stock filters, then
ours). Every parameter is listed, as Debian's meshlabserver requires; our filter's block comes
from tests/meshlab2020/mltest.py, the project's one writer of it.

  recipes_mlx.py OUTDIR     writes OUTDIR/recipe_<name>.mlx for every recipe of RECIPES

Numbers are in the part's units (scripts/recipes_mesh.py: grid step H = 0.05, mean edge 0.056).
"""
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location(
    "mltest", os.path.join(HERE, "..", "tests", "meshlab2020", "mltest.py"))
ML = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ML)

H = 0.05
TIME_STEP = "22.5"          # curvature flow's default, explicit: the recipes depend on it
# Crease measure per face: 1 - cos of the largest angle between the face's normal and its
# vertices' normals. MeshLab 2020.09 hands the expression un-normalized vertex normals (the sum
# of the adjacent faces' unit normals), hence the divisions.
def _cos(k):
    dot = "nx{0}*fnx + ny{0}*fny + nz{0}*fnz".format(k)
    return "({}) / sqrt(nx{k}^2 + ny{k}^2 + nz{k}^2)".format(dot, k=k)


CREASE = "1 - min(%s, %s, %s) / sqrt(fnx^2 + fny^2 + fnz^2)" % (_cos(0), _cos(1), _cos(2))
CREASE_MIN = 0.15           # face crease measure: about 0.3 on a 90 degree crease, 0.08 on 45
CREASE_VOTE = 0.6           # share of selected neighbours (after three smoothings) to keep
GEODESIC_RAMP = 3 * H       # weight 0 on a crease, 1 from three grid steps away
CURVATURE_FULL = 15.0       # RMS curvature (1/units; 1/0.7 on the bump) giving weight 0


def esc(s):
    return ML.xml_escape(str(s))


def block(name, *params):
    """A stock filter's block; params are (name, type, value[, extra attributes])."""
    lines = [' <filter name="%s">' % esc(name)]
    for p in params:
        extra = p[3] if len(p) > 3 else ""
        lines.append('  <Param name="%s" type="%s" value="%s"%s/>' % (p[0], p[1], esc(p[2]),
                                                                      extra))
    lines.append(" </filter>")
    return lines


def bool_(v):
    return "true" if v else "false"


def face_quality(expr):
    return block("Per Face Quality Function", ("q", "RichString", expr),
                 ("normalize", "RichBool", "false"), ("map", "RichBool", "false"),
                 ("onselected", "RichBool", "false"))


def vertex_quality(expr):
    return block("Per Vertex Quality Function", ("q", "RichString", expr),
                 ("normalize", "RichBool", "false"), ("map", "RichBool", "false"),
                 ("onselected", "RichBool", "false"))


def select_by_face_quality(lo, hi, inclusive):
    rng = ' min="0" max="%g"' % hi
    return block("Select by Face Quality", ("minQ", "RichDynamicFloat", lo, rng),
                 ("maxQ", "RichDynamicFloat", hi, rng), ("Inclusive", "RichBool", bool_(inclusive)))


def invert_selection():
    return block("Invert Selection", ("InvFaces", "RichBool", "true"),
                 ("InvVerts", "RichBool", "true"))


def select_none():
    return block("Select None", ("allFaces", "RichBool", "true"),
                 ("allVerts", "RichBool", "true"))


def geodesic_from_selection():
    return block("Colorize by geodesic distance from the selected points",
                 ("maxDistance", "RichAbsPerc", "10", ' min="0" max="20"'))


def discrete_curvature(kind):
    labels = ["Mean Curvature", "Gaussian Curvature", "RMS Curvature", "ABS Curvature"]
    enum = ' enum_cardinality="4"' + "".join(' enum_val%d="%s"' % (i, l)
                                             for i, l in enumerate(labels))
    return block("Discrete Curvatures", ("CurvatureType", "RichEnum", labels.index(kind), enum))


def ours(**overrides):
    args = ["timeStep=" + TIME_STEP] + ["%s=%s" % kv for kv in overrides.items()]
    return ML.filter_lines("curvature_flow", args)


def select_by_vertex_quality(lo, hi, inclusive):
    rng = ' min="0" max="%g"' % hi
    return block("Select by Vertex Quality", ("minQ", "RichDynamicFloat", lo, rng),
                 ("maxQ", "RichDynamicFloat", hi, rng), ("Inclusive", "RichBool", bool_(inclusive)))


def crease_selection():
    """The vertices along the creases, selected (with the faces touching them).

    Faces whose crease measure passes CREASE_MIN select their vertices; noise selects a few
    scattered ones too, so the selection becomes a vertex quality (1 selected, 0 not), is
    smoothed three times over the neighbours, and only vertices where at least CREASE_VOTE of the
    neighbourhood agreed stay selected: lines survive, isolated spots do not. (A "Dilate
    Selection" after it widens the band: measured worse here, 0.061 against 0.051 edges.)
    """
    smooth = block("Smooth Vertex Quality")
    return (face_quality(CREASE) + select_by_face_quality(CREASE_MIN, 2, inclusive=False)
            + vertex_quality("vsel") + smooth + smooth + smooth
            + select_by_vertex_quality(CREASE_VOTE, 1, inclusive=False))


RECIPES = {
    # name: (title, .mlx blocks)
    "uniform": ("our filter alone", ours()),
    "selection": ("crease selection, inverted + Affect only selection",
                  crease_selection() + invert_selection() + ours(Selected="true")),
    "geodesic": ("geodesic distance from the creases as weight",
                 crease_selection() + geodesic_from_selection() + select_none()
                 + vertex_quality("q / %g" % GEODESIC_RAMP) + ours(qualityWeights="true")),
    "curvature": ("RMS curvature as weight, inverted",
                  discrete_curvature("RMS Curvature") + block("Smooth Vertex Quality")
                  + block("Smooth Vertex Quality")
                  + vertex_quality("min(q / %g, 1)" % CURVATURE_FULL)
                  + ours(qualityWeights="true", invertQuality="true")),
}


def main(argv):
    if len(argv) != 1:
        sys.stderr.write(__doc__)
        return 2
    os.makedirs(argv[0], exist_ok=True)
    for name, (_, blocks) in RECIPES.items():
        ML.write_script(os.path.join(argv[0], "recipe_%s.mlx" % name), blocks)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
