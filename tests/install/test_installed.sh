#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The C and Fortran examples built against an *installed* libisect:
#
#   1. make install PREFIX=/usr DESTDIR=$tmp/root   (the tree a package would ship)
#   2. cc / gfortran with `pkg-config --cflags --libs isect` (isect-fortran)
#      through PKG_CONFIG_PATH=$tmp/root/usr/lib/pkgconfig and
#      PKG_CONFIG_SYSROOT_DIR=$tmp/root
#   3. run with LD_LIBRARY_PATH=$tmp/root/usr/lib, check that the loader took
#      libisect.so.1 from there, and compare the output with the text below,
#      worked out by hand from the examples' geometry.
#
# Why the sysroot: the installed .pc files say prefix=/usr, libdir=/usr/lib,
# includedir=/usr/include (where the package will live), and libdir and
# includedir are absolute, not ${prefix}/..., so --define-variable=prefix=...
# would not move them. PKG_CONFIG_SYSROOT_DIR prefixes every -I and -L that
# pkg-config prints with the staging root, which is exactly the DESTDIR.
#
# Usage: sh tests/install/test_installed.sh   (MAKE, CC, FC may be set)
set -u
cd "$(dirname "$0")/../.."
MAKE=${MAKE:-make}
CC=${CC:-cc}
FC=${FC:-gfortran}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root
passed=0
failed=0

pass() { passed=$((passed + 1)); printf 'ok   %s\n' "$1"; }
fail() { failed=$((failed + 1)); printf 'FAIL %s\n' "$1"; }
finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

if ! $MAKE -s --no-print-directory install PREFIX=/usr DESTDIR="$root" >"$tmp/install.log" 2>&1
then
    cat "$tmp/install.log"
    fail "make install PREFIX=/usr DESTDIR=$root"
    finish
fi
pass "make install PREFIX=/usr DESTDIR=<tmp>"

abi=$(sh scripts/version.sh abi)
version=$(sh scripts/version.sh)
for f in include/isect.h include/isect.mod include/isect.f90 lib/libisect.so.$version lib/libisect.so.$abi \
         lib/libisect.so lib/libisect.a lib/libisect_fortran.a lib/pkgconfig/isect.pc \
         lib/pkgconfig/isect-fortran.pc share/doc/isect/LICENSE share/doc/isect/NOTICE; do
    if [ -e "$root/usr/$f" ]; then pass "installed /usr/$f"; else fail "installed /usr/$f"; fi
done
soname=$(readelf -d "$root/usr/lib/libisect.so.$abi" 2>/dev/null | sed -n 's/.*SONAME.*\[\(.*\)\].*/\1/p')
if [ "$soname" = "libisect.so.$abi" ]; then pass "soname $soname"
else fail "soname (expected libisect.so.$abi, got '$soname')"; fi

export PKG_CONFIG_PATH="$root/usr/lib/pkgconfig"
export PKG_CONFIG_SYSROOT_DIR="$root"
export PKG_CONFIG_LIBDIR="$root/usr/lib/pkgconfig"   # no system .pc of an older libisect
c_flags=$(pkg-config --cflags --libs isect) || { fail "pkg-config isect"; finish; }
f_flags=$(pkg-config --cflags --libs isect-fortran) || { fail "pkg-config isect-fortran"; finish; }
case "$c_flags" in
*"-I$root/usr/include"*"-L$root/usr/lib"*) pass "pkg-config --cflags --libs isect: $c_flags" ;;
*) fail "pkg-config --cflags --libs isect points outside the tree: $c_flags" ;;
esac

# The examples' output, worked out by hand:
#  sphere_and_polygon: the sphere |x - (0,0,5)| = 1 along +z from the origin
#    is entered at z = 4 and left at z = 6; the L-shaped polygon in z = 2,
#    counter-clockwise from above (normal +z), is met from z = 5 going down at
#    t = 3 on its front side (ENTER); (1.5, 1.5) is in its notch.
#  transformed_ellipsoid: radii (2, 1, 1) turned 90 degrees about z and moved
#    to (10, 0, 0) has its long axis along y: it spans y in [-2, 2] on the
#    line x = 10 and x in [9, 11] on the x axis. From (10, -5, 0) along +y:
#    t = 3 and 7; from the origin along +x: t = 9 and 11. The point
#    (10, 1.5, 0) is inside (1.5 < 2 along the long axis); (11.5, 0, 0) is not.
#  mesh_cube: the cube [-1, 1]^3 as 6 quads has V - E + F = 8 - 12 + 6 = 2,
#    is closed and outward-oriented, volume 2^3 = 8, area 6 * 2^2 = 24; from
#    (0.25, 0.5, -5) along +z it is entered at z = -1 (t = 4) and left at
#    z = 1 (t = 6); its centre is inside.
cat >"$tmp/sphere_and_polygon.expected" <<EOF
libisect $version (ABI $abi)
sphere: 2 hits
  hit 1: t = 4.000, enter, point (0.000, 0.000, 4.000), normal (0.000, 0.000, -1.000)
  hit 2: t = 6.000, exit, point (0.000, 0.000, 6.000), normal (0.000, 0.000, 1.000)
polygon at (0.5, 0.5): 1 hits
  hit 1: t = 3.000, enter, point (0.500, 0.500, 2.000), normal (0.000, 0.000, 1.000)
polygon at (1.5, 1.5): 0 hits
negative radius: status -1 (ISECT_E_ARG)
EOF
cat >"$tmp/transformed_ellipsoid.expected" <<EOF
along y: 2 hits
  hit 1: t = 3.000, enter, point (10.000, -2.000, 0.000), normal (0.000, -1.000, 0.000)
  hit 2: t = 7.000, exit, point (10.000, 2.000, 0.000), normal (0.000, 1.000, 0.000)
along x: 2 hits
  hit 1: t = 9.000, enter, point (9.000, 0.000, 0.000), normal (-1.000, 0.000, 0.000)
  hit 2: t = 11.000, exit, point (11.000, 0.000, 0.000), normal (1.000, 0.000, 0.000)
contains (10, 1.5, 0): 1
contains (11.5, 0, 0): 0
EOF
cat >"$tmp/mesh_cube.expected" <<EOF
mesh: 8 vertices, 12 edges, 6 faces, euler characteristic 2
closed 1, oriented 1, volume 8.000, area 24.000
along z: 2 hits
  hit 1: t = 4.000, enter, point (0.250, 0.500, -1.000), normal (0.000, 0.000, -1.000)
  hit 2: t = 6.000, exit, point (0.250, 0.500, 1.000), normal (0.000, 0.000, 1.000)
contains (0, 0, 0): 1
EOF

# build_and_run LANGUAGE SOURCE "COMPILER AND OPTIONS" "PKG-CONFIG FLAGS":
# compile (the libraries after the source, as --as-needed linkers want),
# run, compare.
build_and_run() {
    lang=$1; src=$2; compile=$3; flags=$4
    name=$(basename "$src" | sed 's/\.[^.]*$//')
    exe="$tmp/$lang-$name"
    # shellcheck disable=SC2086  # the option lists are meant to split
    if ! $compile "$src" -o "$exe" $flags >"$tmp/build.log" 2>&1; then
        cat "$tmp/build.log"
        fail "$lang $name: build"
        return
    fi
    pass "$lang $name: build"
    if LD_LIBRARY_PATH="$root/usr/lib" ldd "$exe" | grep -q "libisect.so.$abi => $root/usr/lib/"; then
        pass "$lang $name: loads libisect.so.$abi from the installed tree"
    else
        LD_LIBRARY_PATH="$root/usr/lib" ldd "$exe" | grep libisect
        fail "$lang $name: loads libisect.so.$abi from the installed tree"
    fi
    if ! LD_LIBRARY_PATH="$root/usr/lib" "$exe" >"$tmp/out" 2>&1; then
        cat "$tmp/out"
        fail "$lang $name: run"
        return
    fi
    if diff -u "$tmp/$name.expected" "$tmp/out"; then
        pass "$lang $name: output"
    else
        fail "$lang $name: output (diff above: - expected, + got)"
    fi
}

for src in examples/c/*.c; do
    build_and_run C "$src" "$CC -std=c99 -Wall -Wextra -Wpedantic -Werror" "$c_flags"
done
if command -v "$FC" >/dev/null 2>&1; then
    for src in examples/fortran/*.f90; do
        # -J: the example programs write no module, but keep gfortran from
        # writing anything into the source tree.
        build_and_run Fortran "$src" "$FC -std=f2008 -Wall -Wextra -Wpedantic -Werror -J$tmp" "$f_flags"
    done
else
    fail "$FC not found: the Fortran examples were not built"
fi
finish
