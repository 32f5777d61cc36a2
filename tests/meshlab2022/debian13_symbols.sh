#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The 2022.02 plugin fits the MeshLab that Debian 13 users install: Debian 13's own
# libmeshlab-common.so (from meshlab_2022.02+dfsg1-1_amd64.deb, unpacked, never run: it needs
# trixie's glibc and Qt) is float MeshLab 2022.02 and exports every symbol that the plugin
# imports from the libmeshlab-common.so it was linked against (built here from the same source
# package). A symbol missing there would make Debian 13's MeshLab refuse the plugin at load time.
# (The version and precision the plugin reports are checked by MeshLab 2022.02's own loader in
# the host tests; these 26 or so symbols alone would not tell a 2022.02 from a 2025.07 binary.)
# Environment (set by CTest): PLUGIN, SDK_LIB, DEBIAN_DEB, WORK_DIR.
set -euo pipefail
work=${WORK_DIR:?}
rm -rf "$work"; mkdir -p "$work"; cd "$work"

dpkg-deb --fsys-tarfile "$DEBIAN_DEB" \
    | tar -x ./usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so
deb_lib=$work/usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so
[ -f "$deb_lib" ] || { echo "FAIL: no libmeshlab-common.so in $DEBIAN_DEB"; exit 1; }

# the version string getMLVersion() compares: "2022.02" (a double build says "2022.02d")
strings "$deb_lib" > strings.txt
grep -qx "2022.02" strings.txt || { echo "FAIL: Debian 13's libmeshlab-common.so is not 2022.02"; exit 1; }
if grep -qx "2022.02d" strings.txt; then echo "FAIL: Debian 13's MeshLab is a double build"; exit 1; fi

defined() { nm -D --defined-only "$1" | awk '{ print $NF }' | sort -u; }
nm -D --undefined-only "$PLUGIN" | awk '{ print $NF }' | sed 's/@.*//' | sort -u > imports.txt
defined "$SDK_LIB" > sdk.txt
defined "$deb_lib" > debian13.txt
comm -12 imports.txt sdk.txt > from_meshlab.txt
comm -23 from_meshlab.txt debian13.txt > missing.txt
n=$(wc -l < from_meshlab.txt)
[ "$n" -gt 20 ] || { echo "FAIL: only $n symbols imported from libmeshlab-common (expected the plugin API)"; exit 1; }
if [ -s missing.txt ]; then
    echo "FAIL: $(wc -l < missing.txt) of the $n symbols the plugin imports from libmeshlab-common are not exported by Debian 13's:"
    c++filt < missing.txt | head -n 20
    exit 1
fi
echo "Debian 13's libmeshlab-common.so (MeshLab 2022.02, float) exports all $n symbols the plugin imports from libmeshlab-common"
echo PASS
