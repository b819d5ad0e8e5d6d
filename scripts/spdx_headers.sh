#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Puts "SPDX-License-Identifier: Apache-2.0" in the first comment line of
# every source file of the project (the licence: LICENSE, NOTICE), in the
# file's own comment syntax:
#
#   /* ... */  C and headers (*.c, *.h), the linker version script (*.map)
#   !          Fortran (*.f90)
#   #          Python (*.py, *.pyi), shell (*.sh), Makefile and mk/*.mk,
#              meson.build and meson_options.txt, CMakeLists.txt and
#              cmake/*, TOML (*.toml), pkg-config templates (*.pc.in)
#
# on line 1, or on line 2 after a #! line. A file that already names an SPDX
# licence in its first 5 lines is left alone. Not touched: the generated
# corpus (tests/cases/), symbolic links, files of other kinds (Markdown,
# JSON, requirements.txt, .gitignore, the ABI baseline), and .ci/ (the CI
# entry point). The files are those git tracks (plus new ones not ignored).
#
#   sh scripts/spdx_headers.sh          add the line where it is missing
#   sh scripts/spdx_headers.sh --check  list the files without it; exit 1 if any
set -eu
cd "$(dirname "$0")/.."
mode=${1:-apply}
case $mode in apply|--check) ;; *) echo "usage: $0 [--check]" >&2; exit 2 ;; esac
id='SPDX-License-Identifier: Apache-2.0'

# comment_for FILE: the SPDX line in FILE's comment syntax, or nothing.
comment_for() {
    case $1 in
    tests/cases/*|.ci/*) ;;
    *.c|*.h|*.map) printf '/* %s */' "$id" ;;
    *.f90) printf '! %s' "$id" ;;
    *.py|*.pyi|*.sh|Makefile|*.mk|*/meson.build|meson.build|meson_options.txt|\
    CMakeLists.txt|*/CMakeLists.txt|cmake/*|*.toml|*.pc.in)
        printf '# %s' "$id" ;;
    esac
}

git ls-files --cached --others --exclude-standard | sort -u | while IFS= read -r f; do
    [ -f "$f" ] && [ ! -L "$f" ] || continue
    line=$(comment_for "$f")
    [ -n "$line" ] || continue
    if head -n 5 "$f" | grep -q 'SPDX-License-Identifier:'; then
        continue
    fi
    if [ "$mode" = --check ]; then
        echo "no SPDX line: $f"
        echo x
        continue
    fi
    tmp=$f.spdx.$$
    if head -n 1 "$f" | grep -q '^#!'; then
        { head -n 1 "$f"; printf '%s\n' "$line"; tail -n +2 "$f"; } >"$tmp"
    else
        { printf '%s\n' "$line"; cat "$f"; } >"$tmp"
    fi
    # Keep the file's mode (scripts stay executable).
    chmod "$(stat -c %a "$f")" "$tmp"
    mv "$tmp" "$f"
    echo "added: $f"
done | {
    # The loop runs in a subshell: count its "x" lines here.
    n=0
    while IFS= read -r out; do
        if [ "$out" = x ]; then n=$((n + 1)); else printf '%s\n' "$out"; fi
    done
    if [ "$mode" = --check ]; then
        if [ "$n" -eq 0 ]; then echo "SPDX headers: every source file has one"; exit 0; fi
        echo "SPDX headers: $n files without one (sh scripts/spdx_headers.sh adds them)"
        exit 1
    fi
}
