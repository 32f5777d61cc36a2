#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# One MeshLab 2025.07 or 2022.02 integration test (registered in CTest by host_tests.cmake, labels
# meshlab2025, meshlab2022):
# the plugin run the way pymeshlab 2025.7 runs it, by pymeshlab_host (no Python, no display).
#   run_test.sh list                      python names, types and defaults of every parameter
#   run_test.sh run FILTER MESH[+QUALITY] [python_name=value ...]
#       generated noisy MESH (mltest.py gen MESH --quality QUALITY) -> host (load through
#       io_base, apply_filter with the keyword arguments, save) -> compared with engine_reference
#       run on the same file with the parameter values the filter received; the returned
#       figures match the reference's. SELECT_X_GT=V in the environment selects x > V first.
#   run_test.sh quality-fixed FILTER      quality 0 vertices stay bit-identical
#   run_test.sh selection FILTER          selected x > 0.25, only those move
#   run_test.sh failure                   non-manifold input: the error comes back, mesh unchanged,
#                                         the repair filter named in this host's words
#   run_test.sh warnings                  an explicit step past its bound: flagged in the dict
#   run_test.sh reject                    OTHER_PLUGIN (the other precision's or the other MeshLab
#                                         version's binary) is refused with the host's message
#                                         "... has different $REJECT_REASON from the running ..."
# Environment (set by CMake): PREC (float|double), HOST, ENGINE_REFERENCE, PLUGIN, OTHER_PLUGIN,
# REJECT_REASON ("floating point precision" or "version"), PLUGINS_DIR, WORK_DIR.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mltest() { python3 "$here/../meshlab2020/mltest.py" "$@"; }
host() { "$HOST" "$PLUGINS_DIR" "$PLUGIN" "$@"; }
work=${WORK_DIR:?}
rm -rf "$work"; mkdir -p "$work"; cd "$work"

declare -A PYNAME=(
    [umbrella]=apply_coord_implicit_fairing_umbrella
    [scale_dependent]=apply_coord_implicit_fairing_scale_dependent
    [curvature_flow]=apply_coord_implicit_fairing_curvature_flow)

# the figures returned by apply_filter, checked against the reference's own count
check_figures() {   # host.log ref.log
    python3 - "$1" "$2" <<'EOF'
import math, re, sys
out = {}
for line in open(sys.argv[1], encoding="utf-8"):
    w = line.split()
    if len(w) == 4 and w[0] == "output":
        out[w[1]] = (w[2], w[3])
# every key the docs list, of a type pymeshlab's toPyDict turns into a Python value
expect = {"iterations": "int", "inner_iterations": "int", "steps": "int", "vertices_moved": "int", "vertices_fixed": "int",
          "residual": "double", "volume_before": "double", "volume_after": "double",
          "lambda_dt": "double", "seconds": "double", "engine_seconds": "double",
          "warnings": "int", "unconverged_solves": "int", "explicit_unstable": "bool",
          "time_step": "double", "boundary_time_step": "double",
          "automatic_time_step": "bool", "noise_level": "double",
          "noise_level_edges": "double", "mean_edge_length": "double",
          "strength_seconds": "double", "operator_frozen": "bool"}
if sorted(out) != sorted(expect):
    print("FAIL: the output map has %s, expected %s" % (sorted(out), sorted(expect))); sys.exit(1)
for k, t in expect.items():
    if out[k][0] != t:
        print("FAIL: %s is a %s, expected %s" % (k, out[k][0], t)); sys.exit(1)
    if t != "bool" and not math.isfinite(float(out[k][1])):
        print("FAIL: %s is not finite" % k); sys.exit(1)
ref = open(sys.argv[2], encoding="utf-8").read()
m = re.search(r"engine_reference: (\d+) vertices moved, (\d+) fixed, (\d+) CG iterations, "
              r"lambda_dt (\S+)", ref)
if not m:
    print("FAIL: no figures in the reference's output"); sys.exit(1)
moved, fixed, its, ldt = int(m.group(1)), int(m.group(2)), int(m.group(3)), float(m.group(4))
got = (int(out["vertices_moved"][1]), int(out["vertices_fixed"][1]), int(out["iterations"][1]))
if got != (moved, fixed, its):
    print("FAIL: moved/fixed/iterations %r, reference %r" % (got, (moved, fixed, its))); sys.exit(1)
if abs(float(out["lambda_dt"][1]) - ldt) > 1e-5 * abs(ldt):
    print("FAIL: lambda_dt %s, reference %g" % (out["lambda_dt"][1], ldt)); sys.exit(1)
print("figures: " + ", ".join("%s=%s" % (k, out[k][1]) for k in sorted(expect)))
EOF
}

# run FILTER MESH[+QUALITY] [kwargs...]: host vs reference; both select x > $SELECT_X_GT if set
sel=()
[ -n "${SELECT_X_GT:-}" ] && sel=(--select-x-gt "$SELECT_X_GT")
run_case() {
    local filter=$1 spec=$2; shift 2
    local quality=none
    [[ $spec == *+* ]] && quality=${spec#*+}
    mltest gen "${spec%%+*}" in.ply --quality "$quality"
    local kw=""
    [ $# -gt 0 ] && kw=$(printf ", %s" "$@")
    echo "--- host ($PREC): apply_filter('${PYNAME[$filter]}'$kw)"
    host apply "$work/in.ply" "$work/out.ply" "${PYNAME[$filter]}" "${sel[@]}" \
        --params-out "$work/params.txt" "$@" | tee host.log
    echo "--- parameters the filter received"; cat params.txt
    echo "--- engine_reference ($PREC)"
    local params
    mapfile -t params < params.txt
    "$ENGINE_REFERENCE" in.ply ref.ply "$filter" "${sel[@]}" "${params[@]}" | tee ref.log
    mltest compare out.ply ref.ply
    check_figures host.log ref.log
}

case ${1:?case} in
list)
    host list | tee list.log
    python3 - list.log <<'EOF'
import keyword, sys
lines = open(sys.argv[1], encoding="utf-8").read().splitlines()
filters = [l.split()[1] for l in lines if l.startswith("filter ")]
want = ["apply_coord_implicit_fairing_curvature_flow", "apply_coord_implicit_fairing_scale_dependent",
        "apply_coord_implicit_fairing_umbrella"]
if sorted(filters) != want:
    print("FAIL: filters %r" % filters); sys.exit(1)
types = {"timestep": "float", "stepsmoothnum": "int", "order": "str", "integration": "str",
         "preservevolume": "bool", "openinvariant": "str", "boundarymode": "str",
         "qualityweights": "bool", "invertquality": "bool", "selected": "bool",
         "tolerance": "float", "maxiterations": "int", "freezeoperator": "bool",
         "acceptunconverged": "bool"}
current = None
seen = {}
for l in lines:
    w = l.split()
    if w and w[0] == "filter":
        current = w[1]; seen[current] = {}
    elif w and w[0] == "param":
        name, typ = w[1], w[2]
        if keyword.iskeyword(name) or keyword.iskeyword(name.rstrip("_")) or name.endswith("_"):
            print("FAIL: %s: python name %s is (or was mangled from) a keyword" % (current, name)); sys.exit(1)
        if not name.isidentifier():
            print("FAIL: %s: %s is not an identifier" % (current, name)); sys.exit(1)
        seen[current][name] = typ
for f, params in seen.items():
    if params != types:
        print("FAIL: %s parameters %r" % (f, params)); sys.exit(1)
print("list: 3 filters, each with the 14 parameters %s" % ", ".join(sorted(types)))
# pymeshlab matches an enum string exactly: every label must be typeable (printable ASCII), and
# the labels keep their index order (.mlx scripts store the index)
labels = {}
for l in lines:
    if l.startswith("labels "):
        _, name, rest = l.split(" ", 2)
        labels[name] = rest.split("|")
want = {"order": ["L (first order)", "L2 (second order)", "L3 (third order)",
                  "L4 (fourth order)"],
        "integration": ["Implicit", "Explicit", "Explicit, normalized operator (section 5.5)"],
        "openinvariant": ["None", "Area"],
        "boundarymode": ["Fixed", "Smooth boundary curve", "Virtual vertex", "Automatic"]}
if labels != want:
    print("FAIL: enum labels %r, expected %r" % (labels, want)); sys.exit(1)
for name, ls in labels.items():
    for label in ls:
        if not all(32 <= ord(c) < 127 for c in label):
            print("FAIL: %s label %r is not plain ASCII" % (name, label)); sys.exit(1)
print("labels: all plain ASCII, in index order")
EOF
    ;;
run)
    shift
    run_case "$@"
    # quality weights or a selection fix some vertices on purpose
    if [[ $2 == *+* || ${#sel[@]} -gt 0 ]]; then fraction=0.25; else fraction=0.5; fi
    mltest moved in.ply out.ply $fraction
    ;;
quality-fixed)
    run_case "$2" grid+halfx qualityweights=True
    grep -q "vertex quality" host.log || { echo "FAIL: io_base did not load the quality"; exit 1; }
    mltest fixed in.ply out.ply --quality-zero
    ;;
selection)
    sel=(--select-x-gt 0.25)
    run_case "$2" sphere selected=True
    mltest fixed in.ply out.ply --x-le 0.25
    ;;
failure)
    mltest gen nonmanifold in.ply
    cp in.ply in.orig.ply
    host apply "$work/in.ply" "$work/out.ply" "${PYNAME[umbrella]}" --expect-failure | tee host.log
    if ! cmp -s in.ply in.orig.ply || [ -e out.ply ]; then
        echo "FAIL: the input changed or an output was written"; exit 1
    fi
    # pymeshlab's message with the plugin's MLException text; the host compared the mesh
    # the repair filter named as this host names it: pymeshlab (double) its python name, the
    # GUI (float) its menu entry
    if [ "$PREC" = double ]; then
        repair="; run ms\.meshing_repair_non_manifold_edges() first\$"
    else
        repair="; run MeshLab's 'Repair non Manifold Edges' filter (Filters > Cleaning and Repairing) first\$"
    fi
    for line in "^PyMeshLabException: Failed to apply filter: ${PYNAME[umbrella]}\$" \
                "^Details: 1 non-manifold edge .*$repair" "^mesh unchanged after the failure"; do
        grep -q "$line" host.log || { echo "FAIL: no line matching '$line'"; exit 1; }
    done
    if grep -q "^output " host.log; then echo "FAIL: figures returned by a failed run"; exit 1; fi
    ;;
warnings)
    # a warning that changes the result reaches a non-verbose pymeshlab user (whose log and
    # stderr pymeshlab silences) through the returned dict: explicit steps past their bound
    mltest gen sphere in.ply
    host apply "$work/in.ply" "$work/out.ply" "${PYNAME[umbrella]}" integration=Explicit \
        order=0 timestep=3 stepsmoothnum=1 | tee host.log
    for line in "^output explicit_unstable bool true\$" "^output warnings int [1-9][0-9]*\$" \
                "^output unconverged_solves int 0\$"; do
        grep -q "$line" host.log || { echo "FAIL: no line matching '$line'"; exit 1; }
    done
    host apply "$work/in.ply" "$work/out.ply" "${PYNAME[umbrella]}" | tee clean.log
    for line in "^output explicit_unstable bool false\$" "^output warnings int 0\$"; do
        grep -q "$line" clean.log || { echo "FAIL: a clean run: no line matching '$line'"; exit 1; }
    done
    ;;
reject)
    host reject "$OTHER_PLUGIN" | tee host.log
    grep -qx "rejected: libfilter_implicit_fairing.so has different ${REJECT_REASON:-floating point precision} from the running MeshLab version." host.log \
        || { echo "FAIL: not the host's message about a different ${REJECT_REASON:-floating point precision}"; exit 1; }
    ;;
*)
    echo "unknown case $1"; exit 2 ;;
esac
echo PASS
