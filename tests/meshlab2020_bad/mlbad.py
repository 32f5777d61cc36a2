#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Bad-input meshes and checks for the MeshLab 2020.09 robustness tests (issue 6). Imports the
helpers of tests/meshlab2020/mltest.py (meshes, PLY reading/writing, parameter list) instead of
copying them. Standard library only.

  mlbad.py gen KIND OUT.ply [--quality MODE]
      KIND: empty, triangle, points, nonmanifold_edge, bowtie, degenerate, soup, dupfaces,
            nan, inf, flipped, components, sphere, far, tiny
      MODE: none, nan, negative, above1, ramp
      also writes OUT.ply.faces (one "a b c" line per face) for the volume checks
  mlbad.py mlx OUT.mlx FILTER [--pre FILTERNAME[:param=value]]... [name=value ...]
      like mltest.py mlx, with stock filters before ours, parameters after ':' separated by ';'
      (Select All:allFaces=true;allVerts=true, Conditional Vertex Selection:condSelect=vi == 17)
  mlbad.py same IN.ply OUT.ply                positions bit-identical
  mlbad.py finite OUT.ply                     no NaN/Inf
  mlbad.py onlymoved IN.ply OUT.ply I...      only the vertices I... moved (and they did)
  mlbad.py volumes IN.ply OUT.ply REL         each closed component keeps its volume (REL)
"""
import math
import os
import random
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "meshlab2020"))
import mltest  # noqa: E402

fail = mltest.fail


def grid(rng, n, size, offset=(0, 0, 0)):
    return mltest.noisy_grid(rng, n, size, offset)


def gen(kind, out, quality):
    rng = random.Random(6)
    V, F = [], []
    if kind == "empty":
        pass
    elif kind == "triangle":
        V, F = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [(0, 1, 2)]
    elif kind == "points":
        V = [[rng.random(), rng.random(), rng.random()] for _ in range(5)]
    elif kind == "nonmanifold_edge":
        V, F = grid(rng, 8, 2.0)
        for k, a in enumerate((3 * 8 + 3, 5 * 8 + 2)):   # two fins on two interior edges
            V.append([V[a][0] + 0.1, V[a][1] - 0.1, V[a][2] + 0.5 + k])
            F.append((a, a + 1, len(V) - 1))
    elif kind == "bowtie":   # two grids touching at one corner: an open bow-tie vertex
        V, F = grid(rng, 6, 1.0, (-0.5, -0.5, 0))
        V2, F2 = grid(rng, 6, 1.0, (0.5, 0.5, 0))
        corner = len(V) - 1            # (+0.5, +0.5) of the first grid
        base = len(V) - 1              # second grid's vertex 0 is glued onto it
        for v in V2[1:]:
            V.append(v)
        remap = lambda i: corner if i == 0 else base + i
        F += [tuple(remap(i) for i in f) for f in F2]
    elif kind == "degenerate":   # one zero-area face and two needles (a T-vertex 1e-3 off)
        V, F = grid(rng, 12, 11.0)
        n = 12
        a, b, c = 2 * n + 2, 2 * n + 3, 3 * n + 3
        V[a] = [V[a][0], V[a][1], 0.0]
        V[c] = [V[c][0], V[c][1], 0.0]
        V[b] = [(V[a][0] + V[c][0]) / 2, (V[a][1] + V[c][1]) / 2, 0.0]
        a, b, c = 6 * n + 6, 6 * n + 7, 7 * n + 7
        V[a] = [V[a][0], V[a][1], 0.0]
        V[c] = [V[c][0], V[c][1], 0.0]
        V[b] = [(V[a][0] + V[c][0]) / 2 + 1e-3, (V[a][1] + V[c][1]) / 2 - 1e-3, 0.0]
    elif kind == "soup":   # every face with its own vertices (as an STL is read)
        S, SF = mltest.noisy_sphere(rng, 2)
        for f in SF:
            F.append((len(V), len(V) + 1, len(V) + 2))
            V += [list(S[i]) for i in f]
    elif kind == "dupfaces":
        V, F = mltest.noisy_sphere(rng, 2)
        F = list(F) + [F[3], (F[9][1], F[9][0], F[9][2])]
    elif kind in ("nan", "inf"):
        V, F = mltest.noisy_sphere(rng, 2)
        bad = float("nan") if kind == "nan" else float("inf")
        V[10][1] = bad
        V[20][0] = bad
    elif kind == "flipped":
        V, F = mltest.noisy_sphere(rng, 2)
        F = list(F)
        for i in (5, 50):
            F[i] = (F[i][1], F[i][0], F[i][2])
    elif kind == "components":   # two closed spheres and an open grid
        V, F = mltest.noisy_sphere(rng, 2, 0.8, (-2.0, 0, 0))
        for (V2, F2) in (mltest.noisy_sphere(rng, 2, 0.3, (0, 2.0, 0)),
                         grid(rng, 10, 2.0, (1.5, 0, 0))):
            F += [tuple(i + len(V) for i in f) for f in F2]
            V += V2
    elif kind == "sphere":
        V, F = mltest.noisy_sphere(rng, 3)
    elif kind == "far":   # radius 1000 around 1e7: float spacing there is 1
        V, F = mltest.noisy_sphere(rng, 3, 1000.0, (1e7, 1e7, 1e7))
    elif kind == "tiny":
        V, F = mltest.noisy_sphere(rng, 3, 1e-7, (3e-7, 0, 0))
    else:
        fail("unknown mesh kind " + kind)
    Q = None
    if quality == "nan":
        Q = [float("nan") if i % 50 == 7 else 0.5 for i in range(len(V))]
    elif quality == "negative":
        Q = [-1.0 if i % 2 else 0.5 for i in range(len(V))]
    elif quality == "above1":
        Q = [3.0 if i % 2 else 0.5 for i in range(len(V))]
    elif quality == "ramp":
        Q = [v[0] for v in V]
    mltest.write_ply(out, V, F, Q)
    with open(out + ".faces", "w") as f:
        for t in F:
            f.write("%d %d %d\n" % tuple(t))


def read_faces(path):
    with open(path + ".faces") as f:
        return [tuple(int(x) for x in line.split()) for line in f if line.strip()]


def write_mlx(out, filt, pre, overrides):
    esc = mltest.xml_escape
    lines = []
    for p in pre:
        name, _, param = p.partition(":")
        lines.append(' <filter name="%s">' % esc(name))
        for kv in (param.split(";") if param else []):
            k, v = kv.split("=", 1)
            typ = "RichBool" if v in ("true", "false") else "RichString"
            try:
                float(v)
                typ = "RichFloat"
            except ValueError:
                pass
            lines.append('  <Param name="%s" type="%s" value="%s"/>' % (esc(k), typ, esc(v)))
        lines.append(" </filter>")
    mltest.write_script(out, lines + mltest.filter_lines(filt, overrides))


def positions(path):
    return [mltest.xyz(v) for v in mltest.read_ply_vertices(path)]


def bits(p):
    return struct.pack("<3f", *p)


def check_same(a, b):
    A, B = positions(a), positions(b)
    if len(A) != len(B):
        fail("vertex counts differ: %d vs %d" % (len(A), len(B)))
    diff = [i for i in range(len(A)) if bits(A[i]) != bits(B[i])]
    if diff:
        fail("%d vertices changed, e.g. %d: %r -> %r" % (len(diff), diff[0], A[diff[0]], B[diff[0]]))
    print("same: %d vertices bit-identical" % len(A))


def check_finite(path):
    P = positions(path)
    bad = sum(1 for p in P for c in p if not math.isfinite(c))
    if bad:
        fail("%d non-finite coordinates" % bad)
    print("finite: %d vertices" % len(P))


def check_onlymoved(a, b, idx):
    A, B = positions(a), positions(b)
    moved = {i for i in range(len(A)) if bits(A[i]) != bits(B[i])}
    if moved != set(idx):
        fail("moved %s, expected exactly %s" % (sorted(moved)[:10], sorted(idx)))
    print("onlymoved: exactly %s moved" % sorted(idx))


def components(F, n):
    parent = list(range(n))

    def root(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v
    for a, b, c in F:
        parent[root(b)] = root(a)
        parent[root(c)] = root(a)
    comps = {}
    for f in F:
        comps.setdefault(root(f[0]), []).append(f)
    return list(comps.values())


def closed(F):
    directed = set()
    for a, b, c in F:
        directed |= {(a, b), (b, c), (c, a)}
    return all((y, x) in directed for (x, y) in directed)


def volume(P, F):
    ref = P[F[0][0]]
    s = 0.0
    for a, b, c in F:
        p = [[P[i][k] - ref[k] for k in range(3)] for i in (a, b, c)]
        s += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1])
              - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0])
              + p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]))
    return s / 6.0


def check_volumes(a, b, rel):
    F = read_faces(a)
    A, B = positions(a), positions(b)
    n_closed = 0
    for comp in components(F, len(A)):
        if not closed(comp):
            continue
        n_closed += 1
        va, vb = volume(A, comp), volume(B, comp)
        print("volumes: closed component of %d faces: %.9g -> %.9g (relative change %.2g)"
              % (len(comp), va, vb, abs(vb - va) / abs(va)))
        if abs(vb - va) > rel * abs(va):
            fail("volume changed by more than %g" % rel)
    if n_closed == 0:
        fail("no closed component")


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    cmd, args = argv[1], argv[2:]
    if cmd == "gen":
        quality = "none"
        if "--quality" in args:
            i = args.index("--quality")
            quality = args[i + 1]
            args = args[:i] + args[i + 2:]
        gen(args[0], args[1], quality)
    elif cmd == "mlx":
        out, filt, rest = args[0], args[1], args[2:]
        pre, over = [], []
        i = 0
        while i < len(rest):
            if rest[i] == "--pre":
                pre.append(rest[i + 1]); i += 2
            else:
                over.append(rest[i]); i += 1
        write_mlx(out, filt, pre, over)
    elif cmd == "same":
        check_same(args[0], args[1])
    elif cmd == "finite":
        check_finite(args[0])
    elif cmd == "onlymoved":
        check_onlymoved(args[0], args[1], [int(x) for x in args[2:]])
    elif cmd == "volumes":
        check_volumes(args[0], args[1], float(args[2]))
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
