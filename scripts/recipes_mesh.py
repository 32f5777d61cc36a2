#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The feature-preserving recipes' CAD part and its figures (Debian's python3 with numpy).

  recipes_mesh.py gen OUTDIR [--noise S]
      OUTDIR/clean.ply and OUTDIR/noisy.ply: a fandisk-like part (a block 4 x 1.6 with a flat
      top, a 45 degree chamfer, a lower flat, a cylindrical bump of radius 0.7 meeting the flats
      at 43 degree creases, and 90 degree edges all round; every crease lies on mesh edges),
      9,774 vertices on a grid of step H = 0.05 (mean edge 0.056), and the same part with
      Gaussian noise of S mean edge lengths (default 0.1) along the vertex normals.
  recipes_mesh.py measure CLEAN.ply NOISY.ply MESH.ply
      one line of JSON: RMS distance of MESH's vertices to the clean part (in mean edges), the
      same for vertices on flat faces, on creases and on the bump; the crease sharpness (mean
      dihedral angle of the crease edges, percent of the clean part's); the mean angle between
      each face's normal and the clean one (degrees); the largest distance of a flat-face vertex
      to its clean plane (edges); the share of crease vertices left exactly where NOISY had them.
  recipes_mesh.py paint MESH.ply OUT.ply (quality|inverted|unmoved NOISY.ply)
      OUT: MESH with vertex colours showing the smoothing weight, from dark red (0: fixed) to
      light grey (1): MESH's clamped vertex quality, 1 minus it, or 0 where MESH's vertex is
      bit-identical to NOISY's (hard constraints: "Affect only selection").
"""
import json
import math
import sys

import numpy as np

L, W = 4.0, 1.6         # x and y extent
H = 0.05                 # grid step (the mean edge is 0.056 with the diagonals)
TOP, MID = 1.2, 0.8      # heights of the upper and lower flats
R, XB = 0.7, 2.5         # bump radius and centre (x); it spans x in [2, 3]
SEED = 3


def g(x):
    """Height of the top surface (the profile, extruded along y)."""
    if x <= 1.0:
        return TOP
    if x <= 1.4:
        return TOP - (x - 1.0)            # the 45 degree chamfer
    if 2.0 < x < 3.0:
        return MID + math.sqrt(R * R - (x - XB) ** 2) - math.sqrt(R * R - 0.25)
    return MID


def xs():
    """Profile samples: every kink (0, 1, 1.4, 2, 3, 4) is a sample, spacing about H."""
    out = []
    for a, b in [(0, 1.0), (1.0, 1.4), (1.4, 2.0), (2.0, 3.0), (3.0, L)]:
        n = max(1, round((b - a) / H * (1.4142 if (a, b) == (1.0, 1.4) else 1)))
        out += [a + (b - a) * i / n for i in range(n)]
    return out + [L]


def part():
    """(V, F) of the closed, consistently oriented (outward) clean part."""
    X = xs()
    ny = round(W / H)
    Y = [W * k / ny for k in range(ny + 1)]
    index, V, F = {}, [], []

    def vid(p):
        key = tuple(round(c, 9) for c in p)
        if key not in index:
            index[key] = len(V)
            V.append(p)
        return index[key]

    def add(t, out):
        """Appends triangle t turned to face the outward direction out."""
        p = [np.array(V[i]) for i in t]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        F.append(t if n @ np.array(out) > 0 else (t[0], t[2], t[1]))

    def grid(P, out):
        """P[i][j] points of a patch facing direction out; two triangles per cell."""
        for i in range(len(P) - 1):
            for j in range(len(P[0]) - 1):
                a, b = vid(P[i][j]), vid(P[i + 1][j])
                c, d = vid(P[i + 1][j + 1]), vid(P[i][j + 1])
                add((a, b, c), out)
                add((a, c, d), out)

    def levels(z):
        m = max(1, round(z / H))
        return [z * k / m for k in range(m + 1)]
    # one column count per profile sample, shared by both end walls
    col = [levels(g(x)) for x in X]
    grid([[(x, y, g(x)) for y in Y] for x in X], (0, 0, 1))                  # top
    grid([[(x, y, 0.0) for y in Y] for x in X], (0, 0, -1))                  # bottom
    grid([[(0.0, y, z) for z in col[0]] for y in Y], (-1, 0, 0))             # x = 0
    grid([[(L, y, z) for z in col[-1]] for y in Y], (1, 0, 0))               # x = L
    # End walls y = 0 and y = W: neighbouring columns may have different level counts, so
    # each strip between two columns is zipped bottom-up, always advancing the lower side.
    for y, out in [(0.0, (0, -1, 0)), (W, (0, 1, 0))]:
        for i in range(len(X) - 1):
            a = [vid((X[i], y, z)) for z in col[i]]
            b = [vid((X[i + 1], y, z)) for z in col[i + 1]]
            # walk both columns bottom-up, advancing the one whose next point is lower
            p = q = 0
            while p < len(a) - 1 or q < len(b) - 1:
                za = col[i][p + 1] if p < len(a) - 1 else math.inf
                zb = col[i + 1][q + 1] if q < len(b) - 1 else math.inf
                if za <= zb:
                    t = (a[p], b[q], a[p + 1])
                    p += 1
                else:
                    t = (a[p], b[q], b[q + 1])
                    q += 1
                add(t, out)
    return np.array(V), np.array(F, dtype=np.int64)


# ---------------------------------------------------------------------------------------------
# geometry

def face_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    return n / np.linalg.norm(n, axis=1)[:, None], 0.5 * np.linalg.norm(n, axis=1)


def vertex_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    vn = np.zeros_like(V)
    for k in range(3):
        np.add.at(vn, F[:, k], n)
    return vn / np.linalg.norm(vn, axis=1)[:, None]


def edges(F):
    """Interior edges (all, on a closed mesh) as (v0, v1, face_a, face_b)."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    f = np.tile(np.arange(len(F)), 3)
    key = np.sort(e, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, f = key[order], f[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    i = np.nonzero(same)[0]
    return key[i], f[i], f[i + 1]


def mean_edge(V, F):
    k, _, _ = edges(F)
    return float(np.linalg.norm(V[k[:, 0]] - V[k[:, 1]], axis=1).mean())


def dihedral(V, F, ea, fa, fb):
    """Angle between the normals of the two faces of each edge (degrees)."""
    n, _ = face_normals(V, F)
    return np.degrees(np.arccos(np.clip((n[fa] * n[fb]).sum(1), -1, 1)))


def distance_to_part(P):
    """Unsigned distance of points to the clean part (an extruded profile), exact."""
    X = np.array(xs())
    prof = np.array([[x, g(x)] for x in X])
    poly = np.concatenate([[[0.0, 0.0]], prof, [[L, 0.0]]])    # closed profile in (x, z)
    q = P[:, [0, 2]]
    d2 = np.full(len(P), np.inf)
    for a, b in zip(poly, np.roll(poly, -1, axis=0)):
        ab = b - a
        t = np.clip(((q - a) @ ab) / (ab @ ab), 0, 1)
        d2 = np.minimum(d2, np.linalg.norm(q - (a + t[:, None] * ab), axis=1))
    inside = (q[:, 0] > 0) & (q[:, 0] < L) & (q[:, 1] > 0) & \
        (q[:, 1] < np.interp(q[:, 0], X, prof[:, 1]))
    sd2 = np.where(inside, -d2, d2)                 # signed distance in the profile plane
    dy = np.abs(P[:, 1] - W / 2) - W / 2
    outside = np.hypot(np.maximum(sd2, 0), np.maximum(dy, 0))
    return np.abs(np.minimum(np.maximum(sd2, dy), 0) + outside)


# ---------------------------------------------------------------------------------------------
# PLY

def write_ply(path, V, F, colours=None):
    vt = [("p", "<f4", 3)] + ([("c", "u1", 3)] if colours is not None else [])
    with open(path, "wb") as out:
        out.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                   "property float x\nproperty float y\nproperty float z\n%s"
                   "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                   % (len(V), "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                      if colours is not None else "", len(F))).encode())
        v = np.zeros(len(V), dtype=vt)
        v["p"] = V
        if colours is not None:
            v["c"] = colours
        f = np.zeros(len(F), dtype=[("n", "u1"), ("i", "<i4", 3)])
        f["n"], f["i"] = 3, F
        out.write(v.tobytes())
        out.write(f.tobytes())


def read_vertex_quality(path):
    """The 'quality' vertex property of a binary little-endian PLY (as meshlabserver -m vq
    writes it)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    fields, n, in_vertex = [], 0, False
    for line in data[:end].decode().splitlines():
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            n, in_vertex = int(w[2]), True
        elif w and w[0] == "element":
            in_vertex = False
        elif in_vertex and w[0] == "property":
            fields.append((w[2], {"float": "<f4", "double": "<f8", "uchar": "u1", "char": "i1",
                                  "int": "<i4", "uint": "<u4", "short": "<i2",
                                  "ushort": "<u2"}[w[1]]))
    dt = np.dtype(fields)
    return np.frombuffer(data, dtype=dt, count=n, offset=end)["quality"].astype(float)


def read_ply(path):
    sys.path.insert(0, __file__.rsplit("/", 1)[0])
    import demo_mesh   # the project's PLY reader (ASCII and binary, any properties)
    V, F = demo_mesh.read_ply(path)
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int64)


# ---------------------------------------------------------------------------------------------

def gen(outdir, noise):
    V, F = part()
    e = mean_edge(V, F)
    rng = np.random.default_rng(SEED)
    noisy = V + rng.normal(0.0, noise * e, len(V))[:, None] * vertex_normals(V, F)
    write_ply(outdir + "/clean.ply", V, F)
    write_ply(outdir + "/noisy.ply", noisy, F)


def classes(V, F):
    """Per vertex: 0 flat (all faces coplanar), 1 crease (on an edge of dihedral > 20 deg),
    2 on the bump (curved, no crease); and the crease edges with their clean angles."""
    k, fa, fb = edges(F)
    ang = dihedral(V, F, k, fa, fb)
    crease = ang > 20
    cls = np.zeros(len(V), dtype=int)
    on_bump = (V[:, 0] > 2.0 + 1e-9) & (V[:, 0] < 3.0 - 1e-9) & (V[:, 2] > MID - 1e-9)
    cls[on_bump] = 2
    cls[np.unique(k[crease])] = 1
    return cls, (k[crease], fa[crease], fb[crease], ang[crease])


def paint(path, out, mode, noisy_path=None):
    V, F = read_ply(path)
    if mode == "unmoved":
        Vn, _ = read_ply(noisy_path)
        w = np.where(np.all(V == Vn, axis=1), 0.0, 1.0)
    else:
        w = np.clip(read_vertex_quality(path), 0, 1)
        w = 1 - w if mode == "inverted" else w
    fixed, free = np.array([170, 20, 20]), np.array([215, 215, 215])
    write_ply(out, V, F, np.rint((1 - w)[:, None] * fixed + w[:, None] * free))


def measure(clean_path, noisy_path, path):
    V0, F0 = read_ply(clean_path)
    Vn, _ = read_ply(noisy_path)
    V, F = read_ply(path)
    if len(V) != len(V0) or not np.array_equal(F, F0):
        raise SystemExit("measure: %s is not the clean part's mesh" % path)
    e = mean_edge(V0, F0)
    cls, (ck, cfa, cfb, cang) = classes(V0, F0)
    d = distance_to_part(V) / e
    n0, _ = face_normals(V0, F0)
    n, _ = face_normals(V, F)
    normal_err = np.degrees(np.arccos(np.clip((n0 * n).sum(1), -1, 1)))
    ang = dihedral(V, F, ck, cfa, cfb)
    rms = lambda a: float(np.sqrt(np.mean(a ** 2)))
    print(json.dumps({
        "rms_edges": round(rms(d), 4),
        "rms_flat": round(rms(d[cls == 0]), 4),
        "rms_crease": round(rms(d[cls == 1]), 4),
        "rms_bump": round(rms(d[cls == 2]), 4),
        "max_flat": round(float(d[cls == 0].max()), 4),
        "crease_sharpness_pct": round(100 * float(ang.mean() / cang.mean()), 1),
        "normal_error_deg": round(float(normal_err.mean()), 2),
        "crease_unmoved_pct": round(100 * float(np.all(V == Vn, axis=1)[cls == 1].mean()), 1),
        "vertices": int(len(V)), "faces": int(len(F)),
        "crease_edges": int(len(ck))}))


def main(argv):
    if len(argv) >= 2 and argv[0] == "gen":
        noise = float(argv[3]) if len(argv) >= 4 and argv[2] == "--noise" else 0.1
        gen(argv[1], noise)
        return 0
    if len(argv) == 4 and argv[0] == "measure":
        measure(argv[1], argv[2], argv[3])
        return 0
    if len(argv) in (4, 5) and argv[0] == "paint" and argv[3] in ("quality", "inverted",
                                                                    "unmoved"):
        paint(argv[1], argv[2], argv[3], argv[4] if len(argv) == 5 else None)
        return 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
