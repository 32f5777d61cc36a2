#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's restoration fields for the umbrella L^2 filter on the man (auto-gap.md section 26),
# a measurement aid, not part of the product. The filter's unrestored result y (fairing-bench-tool
# fair ... volume=0), then offsets t w_i n_i (n: y's vertex normals) whose t restores the noisy
# input's volume exactly (Newton), scored by fairing-denoise-tool eval. Needs numpy (apt
# python3-numpy: /usr/bin/python3) and the bench tools in TOOLS (cmake --build BUILD --target
# fairing-bench-tool fairing-denoise-tool; TOOLS=BUILD/bin).
#   man_fields.py fields NOISY CLEAN TIME_STEP TOOLS KIND,... PASSES,...
#       KIND: H (cotangent mean curvature), H3 (h^4 H^3), HA2 (h^4 H |A|^2, the continuum normal
#       shrink of the uniform L^2 operator), UM (n.Lx times n.Ln, uniform L), L2 (n.L^2 x);
#       each smoothed by PASSES umbrella half-passes, signed and positive part
#   man_fields.py ideal NOISY CLEAN TIME_STEP TOOLS   the same filter's shrink of the clean mesh
#   man_fields.py twice NOISY CLEAN TIME_STEP TOOLS   its shrink of its own result y, at 0.5, 1
#       and 2 times the step, as a field and as a vector extrapolation y + s (y - F(y))
# The filter is the umbrella L^2 x4 throughout (the study's default).
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "../../../../scripts"))
sys.path.insert(0, os.path.join(here, "../session23-prototype"))
from recipes_mesh import read_ply, vertex_normals, write_ply  # noqa: E402
from restoration_field import mean_curvature, smoothed  # noqa: E402  2H, umbrella half-passes


def vertex_areas(v, f):
    face_area = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    area = np.zeros(len(v))
    for a in range(3):
        np.add.at(area, f[:, a], face_area / 3)
    return area


def angle_deficit(v, f):
    angle = np.zeros(len(v))
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        i, j, k = f[:, a], f[:, b], f[:, c]
        u, w = v[j] - v[i], v[k] - v[i]
        cos = np.einsum('ij,ij->i', u, w) / np.maximum(np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1), 1e-300)
        np.add.at(angle, i, np.arccos(np.clip(cos, -1, 1)))
    return 2 * np.pi - angle


def edges_of(f):
    return np.unique(np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1), axis=0)


def volume(v, f):
    return np.einsum('ij,ij->i', v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum() / 6


def field(v, f, passes, kind):
    e = edges_of(f)
    n = vertex_normals(v, f)
    degree = np.maximum(np.bincount(e.ravel(), minlength=len(v)), 1)

    def umbrella(x):
        s = np.zeros_like(x)
        np.add.at(s, e[:, 0], x[e[:, 1]])
        np.add.at(s, e[:, 1], x[e[:, 0]])
        return s / degree[:, None] - x

    if kind == 'L2':
        return smoothed(np.einsum('ij,ij->i', n, umbrella(umbrella(v))), f, passes), n
    if kind == 'UM':
        u = np.einsum('ij,ij->i', n, umbrella(v))
        m = np.einsum('ij,ij->i', n, umbrella(n))
        return smoothed(u, f, passes) * smoothed(m, f, passes), n
    area = vertex_areas(v, f)
    H = mean_curvature(v, f) / 2
    K = angle_deficit(v, f) / np.maximum(area, 1e-300)
    A2 = np.maximum(4 * H * H - 2 * K, 0)
    lengths = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    h = np.zeros(len(v))
    np.add.at(h, e[:, 0], lengths)
    np.add.at(h, e[:, 1], lengths)
    h = smoothed((h / degree) ** 4, f, passes)
    if kind == 'H':
        return smoothed(H, f, passes), n
    if kind == 'H3':
        return h * smoothed(H, f, passes) ** 3, n
    return h * smoothed(H, f, passes) * smoothed(A2, f, passes), n  # HA2


def restore(y, f, target, w, n):
    w = w / np.mean(np.abs(w))
    s = 0.0
    for _ in range(30):
        moved = y + s * w[:, None] * n
        s += (target - volume(moved, f)) / np.sum(vertex_areas(moved, f) * w)
    return y + s * w[:, None] * n


def fair(tools, src, out, time_step, volume_kept):
    subprocess.run([os.path.join(tools, 'fairing-bench-tool'), 'fair', src, out, 'umbrella', '2',
                    str(time_step), '4'] + ([] if volume_kept else ['volume=0']),
                   check=True, capture_output=True)


def evaluate(tools, clean, noisy, named):
    out = subprocess.run([os.path.join(tools, 'fairing-denoise-tool'), 'eval', clean, 'mesh', noisy]
                         + [p for _, p in named], check=True, capture_output=True, text=True).stdout
    rows = [json.loads(line) for line in out.splitlines() if line.startswith('{')]
    for (name, _), r in zip(named, rows):
        print('%-24s %.5f' % (name, r['rms']))


def main():
    what, noisy, clean, time_step, tools = sys.argv[1:6]
    vn, fn = read_ply(noisy)
    target = volume(vn, fn)
    with tempfile.TemporaryDirectory() as d:
        y_path, engine_path = d + '/y.ply', d + '/engine.ply'
        fair(tools, noisy, y_path, time_step, False)
        fair(tools, noisy, engine_path, time_step, True)
        y, f = read_ply(y_path)
        n = vertex_normals(y, f)
        named = [('not restored', y_path), ('uniform (the engine)', engine_path)]

        def add(name, z):
            path = '%s/%d.ply' % (d, len(named))
            write_ply(path, z, f)
            named.append((name, path))

        if what == 'fields':
            for kind in sys.argv[6].split(','):
                for passes in map(int, sys.argv[7].split(',')):
                    w, n = field(y, f, passes, kind)
                    add('%s/%d signed' % (kind, passes), restore(y, f, target, w, n))
                    add('%s/%d positive' % (kind, passes), restore(y, f, target, np.maximum(w, 0), n))
        elif what == 'ideal':
            x, _ = read_ply(clean)
            fair(tools, clean, d + '/yc.ply', time_step, False)
            yc, _ = read_ply(d + '/yc.ply')
            shrink = -np.einsum('ij,ij->i', vertex_normals(x, f), yc - x)
            for passes in (0, 4, 16):
                w = smoothed(shrink, f, passes)
                add('clean shrink/%d signed' % passes, restore(y, f, target, w, n))
                add('clean shrink/%d positive' % passes, restore(y, f, target, np.maximum(w, 0), n))
        else:  # twice
            for k in (0.5, 1, 2):
                fair(tools, y_path, d + '/yy.ply', float(time_step) * k, False)
                yy, _ = read_ply(d + '/yy.ply')
                dv = y - yy
                shrink = np.einsum('ij,ij->i', n, dv)
                add('own shrink x%g signed' % k, restore(y, f, target, shrink, n))
                add('own shrink x%g positive' % k, restore(y, f, target, np.maximum(shrink, 0), n))
                s = 0.0
                for _ in range(30):
                    slope = (volume(y + (s + 1e-3) * dv, f) - volume(y + s * dv, f)) / 1e-3
                    s += (target - volume(y + s * dv, f)) / slope
                add('own shrink x%g vector' % k, y + s * dv)
        evaluate(tools, clean, noisy, named)


if __name__ == '__main__':
    main()
