#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Adds the SPDX licence lines (GPL-3.0-or-later, see LICENSE) to every tracked source file that
# has none, after a shebang if there is one; idempotent. tests/license checks the result.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
id='SPDX-License-Identifier: GPL-3.0-or-later'
cr='SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors'
add() {  # FILE PREFIX: two comment lines
    local f=$1 pre=$2 tmp
    head -n 5 "$f" | grep -q 'SPDX-License-Identifier' && return 0
    tmp=$(mktemp)
    if head -n 1 "$f" | grep -q '^#!'; then
        { head -n 1 "$f"; printf '%s%s\n%s%s\n' "$pre" "$id" "$pre" "$cr"; tail -n +2 "$f"; } > "$tmp"
    else
        { printf '%s%s\n%s%s\n' "$pre" "$id" "$pre" "$cr"; cat "$f"; } > "$tmp"
    fi
    cat "$tmp" > "$f"; rm -f "$tmp"    # cat >: keeps the file's mode
}
git ls-files -z | while IFS= read -r -d '' f; do
    case $f in
        *.cpp|*.cc|*.h|*.hpp)              add "$f" '// ' ;;
        *.py|*.sh|*.cmake|*CMakeLists.txt) add "$f" '# ' ;;
        *) if head -n 1 "$f" 2>/dev/null | grep -q '^#!'; then add "$f" '# '; fi ;;
    esac
done
