#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 49: inserts into fairing/src/auto_strength.cpp (of a scratch checkout; never
# commit it) a print, behind FAIRING_DBG_CK, of each search checkpoint: Lanczos steps, the mean
# risk's minimizer and converged reach, whether it settled, the risk over N sigma^2 (and the trace
# over N) at every converged grid point above 100, and the later steps' minimizer where found.
# Usage: python3 debug_ck.py CHECKOUT/fairing/src/auto_strength.cpp
import sys
p = sys.argv[1]
s = open(p).read()
at = "        const bool complete = exhausted || now.reach == s.grid.size();\n"
assert at in s
s = s.replace(at, at + """        if (std::getenv("FAIRING_DBG_CK")) {
            std::fprintf(stderr, "CK later=%d steps=%d min=%g conv=%g settled=%d\\n",
                         later != nullptr, j + 1, s.minimizer, s.converged_to, (int)settled);
            for (std::size_t g = now.first; g < now.reach; ++g)
                if (s.grid[g] > 100)
                    std::fprintf(stderr, "  %g:%.6f(tr %.5f)", s.grid[g],
                                 risk[g - now.first] / (count * sigma * sigma), now.trace[g] / count);
            std::fprintf(stderr, "\\n");
        }
""", 1)
at = "            s.minimizer = s.grid[now.first + argmin(risk)];\n"
assert at in s
s = s.replace(at, at + """            if (std::getenv("FAIRING_DBG_CK")) std::fprintf(stderr, "   later-min=%g\\n", s.minimizer);
""", 1)
s = s.replace("#include <cstdint>\n", "#include <cstdint>\n#include <cstdio>\n#include <cstdlib>\n", 1)
open(p, "w").write(s)
