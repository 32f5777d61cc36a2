#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Helpers of the MeshLab 2020.09 integration tests (standard library only, no numpy).

  mltest.py gen KIND OUT.ply [--seed N] [--quality none|halfx|ramp]
      KIND: sphere (closed, noisy icosphere), grid (open, noisy height field),
            twocomp (a noisy sphere and a noisy grid), nonmanifold (an edge shared by 3 faces)
  mltest.py mlx OUT.mlx FILTER [--select-x-gt V] [--old-labels] [name=value ...]
      an .mlx listing every parameter of FILTER (defaults overridden by name=value), optionally
      preceded by MeshLab's stock "Conditional Vertex Selection" (condSelect "x > V");
      --old-labels: with the enum labels of version 0.1.0 (L\u00b2 ...), as scripts saved then.
  mltest.py params [name=value ...]      the full parameter list as name=value lines
  mltest.py mlxparams FILE.mlx            the parameters of the script's last filter, one
                                          name=value per line (as engine_reference takes them)
  mltest.py compare A.ply B.ply          positions equal up to float rounding
  mltest.py fixed IN.ply OUT.ply (--x-le V | --quality-zero)
      vertices with x <= V (or quality 0 in IN) are bit-identical, and some others moved
  mltest.py moved IN.ply OUT.ply [MIN_FRACTION]   enough vertices moved (default 0.5), no NaN
"""
import math
import random
import struct
import sys

FILTERS = {
    "umbrella": "Implicit Fairing: Umbrella Diffusion",
    "scale_dependent": "Implicit Fairing: Scale-Dependent Diffusion",
    "curvature_flow": "Implicit Fairing: Curvature Flow",
}

ORDER = ["L (first order)", "L2 (second order)", "L3 (third order)", "L4 (fourth order)"]
# The labels of version 0.1.0, which .mlx scripts saved then carry (MeshLab reads the index)
OLD_ORDER = ["L (first order)", "L\u00b2 (second order, recommended)"]
# name, type, default, enum values
PARAMS = [
    ("timeStep", "RichFloat", "1", None),  # per filter: see filter_parameters.h
    ("stepSmoothNum", "RichInt", "1", None),
    ("order", "RichEnum", "1", ORDER),
    ("integration", "RichEnum", "0", ["Implicit", "Explicit",
                                      "Explicit, normalized operator (section 5.5)"]),
    ("preserveVolume", "RichBool", "true", None),
    ("openInvariant", "RichEnum", "0", ["None", "Area"]),
    ("boundaryMode", "RichEnum", "3", ["Fixed", "Smooth boundary curve", "Virtual vertex",
                                       "Automatic"]),
    ("qualityWeights", "RichBool", "false", None),
    ("invertQuality", "RichBool", "false", None),
    ("Selected", "RichBool", "false", None),
    ("tolerance", "RichFloat", "1e-08", None),
    ("maxIterations", "RichInt", "2000", None),
    ("freezeOperator", "RichBool", "false", None),
    ("acceptUnconverged", "RichBool", "false", None),
]


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


# ---------------------------------------------------------------------------------------------
# meshes

def icosphere(subdiv):
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdiv):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(V[a][k] + V[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                V.append(tuple(x / n for x in p))
                cache[key] = len(V) - 1
            return cache[key]
        G = []
        for a, b, c in F:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    return [list(v) for v in V], F


def mean_edge(V, F):
    s, n = 0.0, 0
    for f in F:
        for k in range(3):
            a, b = V[f[k]], V[f[(k + 1) % 3]]
            s += math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3)))
            n += 1
    return s / n


def noisy_sphere(rng, subdiv=3, radius=1.0, center=(0, 0, 0)):
    V, F = icosphere(subdiv)
    e = mean_edge(V, F) * radius
    out = []
    for v in V:   # v is the unit normal
        r = radius + rng.gauss(0, 0.25 * e)
        out.append([center[k] + r * v[k] for k in range(3)])
    return out, F


def noisy_grid(rng, n=24, size=2.0, offset=(0, 0, 0)):
    h = size / (n - 1)
    V, F = [], []
    for j in range(n):
        for i in range(n):
            x, y = -size / 2 + i * h, -size / 2 + j * h
            z = 0.3 * math.sin(1.5 * x) * math.cos(1.5 * y) + rng.gauss(0, 0.25 * h)
            V.append([x + offset[0], y + offset[1], z + offset[2]])
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            b, c, d = a + 1, a + n, a + n + 1
            F += [(a, b, d), (a, d, c)]
    return V, F


def gen(kind, out, seed, quality):
    rng = random.Random(seed)
    if kind == "sphere":
        V, F = noisy_sphere(rng)
    elif kind == "grid":
        V, F = noisy_grid(rng)
    elif kind == "twocomp":
        V, F = noisy_sphere(rng, 2, 0.8, (-2.0, 0, 0))
        V2, F2 = noisy_grid(rng, 16, 2.0, (1.5, 0, 0))
        F = F + [tuple(i + len(V) for i in f) for f in F2]
        V = V + V2
    elif kind == "nonmanifold":
        V, F = noisy_grid(rng, 8)
        # a fin: a third face on the interior edge (a, a+1)
        a = 3 * 8 + 3
        V.append([V[a][0] + 0.1, V[a][1] - 0.1, V[a][2] + 0.5])
        F.append((a, a + 1, len(V) - 1))
    else:
        fail("unknown mesh kind " + kind)
    Q = None
    if quality == "halfx":
        Q = [0.0 if v[0] < 0 else 1.0 for v in V]
    elif quality == "ramp":   # values outside [0, 1] exercise the clamp
        Q = [v[0] for v in V]
    write_ply(out, V, F, Q)


def write_ply(path, V, F, Q=None):
    head = ["ply", "format binary_little_endian 1.0", "element vertex %d" % len(V),
            "property float x", "property float y", "property float z"]
    if Q is not None:
        head.append("property float quality")
    head += ["element face %d" % len(F), "property list uchar int vertex_indices", "end_header"]
    with open(path, "wb") as f:
        f.write(("\n".join(head) + "\n").encode())
        for i, v in enumerate(V):
            f.write(struct.pack("<fff", *v))
            if Q is not None:
                f.write(struct.pack("<f", Q[i]))
        for t in F:
            f.write(struct.pack("<Biii", 3, *t))


# ---------------------------------------------------------------------------------------------
# PLY reading (vertex element only; binary little endian or ascii)

PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply_vertices(path):
    """Returns a list of dicts {property: value} for the vertex element (floats kept exact)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header")
    end = data.index(b"\n", end) + 1
    header = data[:end].decode("ascii", "replace").splitlines()
    fmt, elements = None, []
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            elements[-1][2].append(w[1:])
    if not elements or elements[0][0] != "vertex":
        fail(path + ": the first PLY element is not 'vertex'")
    _, n, props = elements[0]
    for p in props:
        if p[0] == "list":
            fail(path + ": list property in vertex element")
    names = [p[1] for p in props]
    out = []
    if fmt == "ascii":
        lines = data[end:].decode().splitlines()
        for i in range(n):
            vals = lines[i].split()
            out.append({names[k]: float(vals[k]) for k in range(len(names))})
        return out
    if fmt != "binary_little_endian":
        fail(path + ": unsupported PLY format " + str(fmt))
    st = struct.Struct("<" + "".join(PLY_TYPES[p[0]] for p in props))
    off = end
    for i in range(n):
        vals = st.unpack_from(data, off)
        off += st.size
        out.append(dict(zip(names, vals)))
    return out


def xyz(v):
    return (v["x"], v["y"], v["z"])


# ---------------------------------------------------------------------------------------------
# .mlx

def param_values(overrides):
    values = {p[0]: p[2] for p in PARAMS}
    for o in overrides:
        if "=" not in o:
            fail("expected name=value, got " + o)
        k, v = o.split("=", 1)
        if k not in values:
            fail("unknown parameter " + k)
        values[k] = v
    return values


def xml_escape(s):
    return (s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))


def filter_lines(filt, overrides, old_labels=False):
    """The .mlx lines of one of our filters with every parameter (defaults overridden);
    old_labels: the enum labels of version 0.1.0."""
    if filt not in FILTERS:
        fail("unknown filter " + filt)
    values = param_values(overrides)
    lines = [' <filter name="%s">' % xml_escape(FILTERS[filt])]
    for name, typ, _, enum in PARAMS:
        if old_labels and enum is ORDER:
            enum = OLD_ORDER
        attrs = 'name="%s" type="%s" value="%s"' % (name, typ, xml_escape(values[name]))
        if enum is not None:
            attrs += ' enum_cardinality="%d"' % len(enum)
            attrs += "".join(' enum_val%d="%s"' % (i, xml_escape(e)) for i, e in enumerate(enum))
        lines.append("  <Param %s/>" % attrs)
    lines.append(" </filter>")
    return lines


def write_script(out, filter_blocks):
    """Writes an .mlx holding the given filter blocks' lines, in order."""
    lines = ["<!DOCTYPE FilterScript>", "<FilterScript>"] + filter_blocks
    lines += ["</FilterScript>", ""]
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def write_mlx(out, filt, overrides, select_x_gt=None, old_labels=False):
    lines = []
    if select_x_gt is not None:
        lines += [' <filter name="Conditional Vertex Selection">',
                  '  <Param name="condSelect" type="RichString" value="%s"/>'
                  % xml_escape("x > %s" % select_x_gt),
                  " </filter>"]
    write_script(out, lines + filter_lines(filt, overrides, old_labels))


# ---------------------------------------------------------------------------------------------
# checks

def compare(a_path, b_path):
    A, B = read_ply_vertices(a_path), read_ply_vertices(b_path)
    if len(A) != len(B):
        fail("vertex counts differ: %d vs %d" % (len(A), len(B)))
    scale = max(max(abs(c) for c in xyz(v)) for v in A) or 1.0
    worst, where, identical = 0.0, -1, 0
    for i, (a, b) in enumerate(zip(A, B)):
        pa, pb = xyz(a), xyz(b)
        if any(math.isnan(c) for c in pa + pb):
            fail("NaN at vertex %d" % i)
        if pa == pb:
            identical += 1
        d = max(abs(pa[k] - pb[k]) for k in range(3))
        if d > worst:
            worst, where = d, i
    # float rounding: a few units in the last place of the largest coordinate
    tol = 4 * scale * 2.0 ** -23
    print("compare: %d vertices, %d bit-identical, max |difference| %.3g at vertex %d "
          "(tolerance %.3g)" % (len(A), identical, worst, where, tol))
    if worst > tol:
        fail("positions differ by more than float rounding")


def check_fixed(in_path, out_path, x_le=None, quality_zero=False):
    I, O = read_ply_vertices(in_path), read_ply_vertices(out_path)
    if len(I) != len(O):
        fail("vertex counts differ")
    fixed = moved_free = n_fixed = n_free = 0
    for i, (a, b) in enumerate(zip(I, O)):
        if quality_zero:
            is_fixed = a.get("quality", 1.0) == 0.0
        else:
            is_fixed = a["x"] <= x_le
        if is_fixed:
            n_fixed += 1
            if xyz(a) != xyz(b):
                fail("constrained vertex %d moved: %r -> %r" % (i, xyz(a), xyz(b)))
            fixed += 1
        else:
            n_free += 1
            if xyz(a) != xyz(b):
                moved_free += 1
    print("fixed: %d constrained vertices bit-identical; %d of %d free vertices moved"
          % (fixed, moved_free, n_free))
    if n_fixed == 0 or n_free == 0:
        fail("the test mesh has no constrained or no free vertex")
    if moved_free < n_free // 2:
        fail("too few free vertices moved")


def check_moved(in_path, out_path, min_fraction=0.5):
    I, O = read_ply_vertices(in_path), read_ply_vertices(out_path)
    if len(I) != len(O):
        fail("vertex counts differ")
    moved = sum(1 for a, b in zip(I, O) if xyz(a) != xyz(b))
    if any(math.isnan(c) or math.isinf(c) for v in O for c in xyz(v)):
        fail("non-finite output")
    print("moved: %d of %d vertices" % (moved, len(I)))
    if moved < min_fraction * len(I):
        fail("fewer than %g of the vertices moved" % min_fraction)


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    cmd, args = argv[1], argv[2:]
    if cmd == "gen":
        seed, quality = 1, "none"
        pos = []
        i = 0
        while i < len(args):
            if args[i] == "--seed":
                seed = int(args[i + 1]); i += 2
            elif args[i] == "--quality":
                quality = args[i + 1]; i += 2
            else:
                pos.append(args[i]); i += 1
        gen(pos[0], pos[1], seed, quality)
    elif cmd == "mlx":
        sel, old_labels, rest = None, False, []
        i = 2
        while i < len(args):
            if args[i] == "--select-x-gt":
                sel = args[i + 1]; i += 2
            elif args[i] == "--old-labels":
                old_labels = True; i += 1
            else:
                rest.append(args[i]); i += 1
        write_mlx(args[0], args[1], rest, sel, old_labels)
    elif cmd == "params":
        for k, v in param_values(args).items():
            print("%s=%s" % (k, v))
    elif cmd == "mlxparams":
        import xml.etree.ElementTree as ET
        filt = ET.parse(args[0]).getroot().findall("filter")[-1]
        for p in filt.findall("Param"):
            print("%s=%s" % (p.get("name"), p.get("value")))
    elif cmd == "compare":
        compare(args[0], args[1])
    elif cmd == "fixed":
        if args[2] == "--x-le":
            check_fixed(args[0], args[1], x_le=float(args[3]))
        else:
            check_fixed(args[0], args[1], quality_zero=True)
    elif cmd == "moved":
        check_moved(args[0], args[1], float(args[2]) if len(args) > 2 else 0.5)
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
