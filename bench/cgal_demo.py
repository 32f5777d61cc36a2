# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Real scans for the benchmarks: data/meshes/*.off of Debian's libcgal-demo package, fetched with
apt-get download into the meshes folder (never committed)."""
import os
import shutil
import subprocess
import tarfile


def cgal_demo_off(meshes_dir, name, also=()):
    """meshes_dir/NAME.off (and the meshes named in `also`), extracted on first use."""
    dst = os.path.join(meshes_dir, name + ".off")
    if os.path.exists(dst):
        return dst
    d = os.path.join(meshes_dir, "deb-" + name)
    os.makedirs(d, exist_ok=True)
    subprocess.run(["apt-get", "download", "libcgal-demo"], cwd=d, check=True, capture_output=True)
    deb = [f for f in os.listdir(d) if f.startswith("libcgal-demo") and f.endswith(".deb")][0]
    x = os.path.join(d, "x")
    subprocess.run(["dpkg", "-x", os.path.join(d, deb), x], check=True)
    with tarfile.open(os.path.join(x, "usr/share/doc/libcgal-dev/data.tar.gz")) as t:
        for n in [name, *also]:
            out = os.path.join(meshes_dir, n + ".off")
            if not os.path.exists(out):
                with open(out, "wb") as f:
                    f.write(t.extractfile("data/meshes/%s.off" % n).read())
    shutil.rmtree(d)
    return dst
