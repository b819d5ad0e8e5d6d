#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# libisect used the ways other projects take in a library: a tiny C program
# (and, where the route carries the Fortran module, a tiny Fortran program)
# is built against libisect through each route of README.md, "Using libisect
# from your project", run, and checked: the library's version string equals
# isect.h's, and a ray along +z from the origin enters the unit sphere at
# (0, 0, 5) at t = 4 and leaves it at t = 6.
#
#   1. pkg-config   make install PREFIX=<tmp>, cc $(pkg-config --cflags --libs isect)
#                   (shared, and static with libisect.a); the installed
#                   isect.f90 compiled with a Fortran program
#   2. CMake        cmake --install of CMakeLists.txt (shared), then a
#                   consumer's find_package(isect CONFIG) (SameMajorVersion:
#                   the next major version is refused); isect.pc of that
#                   install through pkg-config
#   3. FetchContent SOURCE_DIR = this checkout (static), and GIT_REPOSITORY
#                   file://<this checkout> at HEAD (shared) when it is a git
#                   checkout; no compile option of libisect reaches the consumer
#   4. meson        subprojects/libisect -> this checkout: only the library is
#                   built, without -Werror; with fortran=enabled and
#                   default_library=static, dependency('isect-fortran') too
#   5. fpm          a Fortran consumer with isect = { path = ... } and
#                   { git = "file://..." }, built with the documented
#                   --c-flag; without it GCC must stop at fpm_flags.c.
#                   fpm: $FPM, else fpm on PATH, else .venv/bin/fpm (pip
#                   package fpm, pinned in requirements.txt); none: skipped
#
# Prints ok/FAIL/skip per check and "N passed, N failed, N skipped".
# Usage: sh tests/install/consumers.sh   (MAKE, CC, FC, CMAKE, MESON, FPM may be set)
set -u
cd "$(dirname "$0")/../.."
root=$(pwd)
MAKE=${MAKE:-make}
CC=${CC:-cc}
FC=${FC:-gfortran}
CMAKE=${CMAKE:-cmake}
MESON=${MESON:-meson}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
skipped=0
version=$(sh scripts/version.sh)
abi=$(sh scripts/version.sh abi)
major=${version%%.*}
head=$(git -C "$root" rev-parse HEAD 2>/dev/null)   # for the git routes

pass() { passed=$((passed + 1)); printf 'ok   %s\n' "$1"; }
fail() { failed=$((failed + 1)); printf 'FAIL %s\n' "$1"; }
skip() { skipped=$((skipped + 1)); printf 'skip %s\n' "$1"; }
have() { command -v "$1" >/dev/null 2>&1; }

# run_logged LOG COMMAND...: run quietly; on failure show the log's end.
run_logged() {
    log=$1; shift
    if "$@" >"$log" 2>&1; then return 0; fi
    tail -n 40 "$log"
    return 1
}

# ------------------------------------------------------------ the consumers
cat >"$tmp/consumer.c" <<'EOF'
/* A program that uses libisect: its version, and one sphere. */
#include <isect.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void)
{
    const isect_ray ray = { { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 1.0 }, 0.0, INFINITY };
    const double centre[3] = { 0.0, 0.0, 5.0 };
    isect_hit hits[2];
    int n = isect_ray_sphere(&ray, centre, 1.0, NULL, hits, 2);
    printf("libisect %s: %d hits", isect_version_string(), n);
    if (n == 2)
        printf(" at t = %g (%d) and %g (%d)", hits[0].t, hits[0].kind, hits[1].t, hits[1].kind);
    printf("\n");
    if (strcmp(isect_version_string(), ISECT_VERSION_STRING) != 0) {
        printf("the library is %s but isect.h says %s\n", isect_version_string(),
               ISECT_VERSION_STRING);
        return 1;
    }
    return !(n == 2 && hits[0].t == 4.0 && hits[0].kind == ISECT_ENTER && hits[1].t == 6.0 &&
             hits[1].kind == ISECT_EXIT);
}
EOF
cat >"$tmp/consumer.f90" <<'EOF'
! A Fortran program that uses the module isect: its version, and one sphere.
program consumer
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use isect
    implicit none
    type(isect_ray) :: ray
    type(isect_hit) :: hits(2)
    integer(c_int) :: n
    logical :: ok
    ray = isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], &
                         [0.0_c_double, 0.0_c_double, 1.0_c_double])
    n = isect_ray_sphere(ray, [0.0_c_double, 0.0_c_double, 5.0_c_double], 1.0_c_double, hits)
    print '(a, a, a, i0, a, 2(1x, f0.3))', 'libisect ', isect_version_text(), ': ', n, &
        ' hits at t =', hits(1:n)%t
    ok = n == 2
    if (ok) ok = abs(hits(1)%t - 4.0_c_double) <= 0.0_c_double .and. &
                 abs(hits(2)%t - 6.0_c_double) <= 0.0_c_double .and. &
                 hits(1)%kind == ISECT_ENTER .and. hits(2)%kind == ISECT_EXIT
    if (.not. ok) error stop 'wrong hits'
end program consumer
EOF
expected_c="libisect $version: 2 hits at t = 4 (1) and 6 (2)"
expected_f="libisect $version: 2 hits at t = 4.000 6.000"

# check_run NAME EXPECTED COMMAND...: the consumer runs, succeeds, and prints
# EXPECTED.
check_run() {
    name=$1; want=$2; shift 2
    if out=$("$@" 2>&1) && [ "$out" = "$want" ]; then
        pass "$name: $out"
    else
        printf '%s\n' "$out"
        fail "$name: run (expected \"$want\")"
    fi
}

# check_loads NAME EXE LIBDIR: the dynamic loader takes libisect.so.ABI from
# LIBDIR (through the rpath the route put into EXE).
check_loads() {
    if ldd "$2" | grep -q "libisect.so.$abi => $3/"; then
        pass "$1: loads libisect.so.$abi from $3"
    else
        ldd "$2" | grep isect
        fail "$1: loads libisect.so.$abi from $3"
    fi
}

# ------------------------------------------------------------ 1. pkg-config
echo "== pkg-config, after make install PREFIX=<tmp>"
prefix=$tmp/make-prefix
if run_logged "$tmp/make-install.log" $MAKE -s --no-print-directory install PREFIX="$prefix"; then
    pass "make install PREFIX=<tmp>"
    pc() { PKG_CONFIG_PATH="$prefix/lib/pkgconfig" PKG_CONFIG_LIBDIR="$prefix/lib/pkgconfig" \
           pkg-config "$@"; }
    if [ "$(pc --modversion isect)" = "$version" ]; then pass "pkg-config --modversion isect: $version"
    else fail "pkg-config --modversion isect: '$(pc --modversion isect)', expected $version"; fi
    # shellcheck disable=SC2046  # the flags are meant to split
    if run_logged "$tmp/pc-build.log" $CC -std=c99 -Wall -Wextra -Wpedantic -Werror \
           "$tmp/consumer.c" -o "$tmp/pc-consumer" $(pc --cflags --libs isect) \
           -Wl,-rpath,"$prefix/lib"; then
        pass "pkg-config: cc consumer.c \$(pkg-config --cflags --libs isect)"
        check_loads "pkg-config" "$tmp/pc-consumer" "$prefix/lib"
        check_run "pkg-config consumer" "$expected_c" "$tmp/pc-consumer"
    else
        fail "pkg-config: build"
    fi
    # shellcheck disable=SC2046
    if run_logged "$tmp/pc-static.log" $CC -std=c99 "$tmp/consumer.c" -o "$tmp/pc-static" \
           $(pc --cflags isect) "$prefix/lib/libisect.a" -lm; then
        check_run "pkg-config consumer, static libisect.a" "$expected_c" "$tmp/pc-static"
    else
        fail "pkg-config: static build"
    fi
    # The module's source installed beside isect.mod, for compilers that
    # cannot read gfortran's .mod: compiled with the program.
    if ! have "$FC"; then
        skip "installed isect.f90: $FC not found"
    elif [ ! -f "$prefix/include/isect.f90" ]; then
        fail "isect.f90 installed in $prefix/include"
    else
        mkdir -p "$tmp/f90-mod"
        # shellcheck disable=SC2046
        if run_logged "$tmp/pc-f90.log" $FC -std=f2008 -J"$tmp/f90-mod" "$prefix/include/isect.f90" \
               "$tmp/consumer.f90" -o "$tmp/pc-f90" $(pc --libs isect) -Wl,-rpath,"$prefix/lib"; then
            check_run "installed isect.f90 + consumer.f90, \$(pkg-config --libs isect)" \
                "$expected_f" "$tmp/pc-f90"
        else
            fail "installed isect.f90: build"
        fi
    fi
else
    fail "make install PREFIX=<tmp>"
fi

# ------------------------------------------------------------ 2. CMake
# configure_build_consumer NAME SRCDIR BUILDDIR [CMAKE ARGS...]
cmake_consumer() {
    name=$1; src=$2; bld=$3; shift 3
    if run_logged "$bld.configure.log" $CMAKE -S "$src" -B "$bld" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@" \
       && run_logged "$bld.build.log" $CMAKE --build "$bld" -j 2; then
        pass "$name: configure and build"
        return 0
    fi
    fail "$name: configure and build"
    return 1
}

if have "$CMAKE"; then
    echo "== CMake: install, then find_package(isect CONFIG)"
    cprefix=$tmp/cmake-prefix
    if run_logged "$tmp/cmake-lib.log" $CMAKE -S "$root" -B "$tmp/cmake-lib" -DBUILD_SHARED_LIBS=ON \
           -DISECT_WERROR=ON -DCMAKE_INSTALL_PREFIX="$cprefix" -DCMAKE_INSTALL_LIBDIR=lib \
       && run_logged "$tmp/cmake-lib-build.log" $CMAKE --build "$tmp/cmake-lib" -j 2 \
       && run_logged "$tmp/cmake-lib-install.log" $CMAKE --install "$tmp/cmake-lib"; then
        pass "cmake build (shared, ISECT_WERROR) and cmake --install"
        for f in include/isect.h lib/libisect.so.$version lib/libisect.so.$abi lib/libisect.so \
                 lib/cmake/isect/isectConfig.cmake lib/cmake/isect/isectConfigVersion.cmake \
                 lib/cmake/isect/isectTargets.cmake lib/pkgconfig/isect.pc \
                 share/doc/isect/LICENSE share/doc/isect/NOTICE; do
            if [ -e "$cprefix/$f" ]; then pass "cmake installed $f"; else fail "cmake installed $f"; fi
        done
        soname=$(readelf -d "$cprefix/lib/libisect.so.$abi" 2>/dev/null \
                 | sed -n 's/.*SONAME.*\[\(.*\)\].*/\1/p')
        if [ "$soname" = "libisect.so.$abi" ]; then pass "cmake: soname $soname"
        else fail "cmake: soname (expected libisect.so.$abi, got '$soname')"; fi
        if run_logged "$tmp/cmake-exports.log" sh scripts/check_exports.sh "$cprefix/lib/libisect.so.$abi"
        then pass "cmake: $(cat "$tmp/cmake-exports.log")"
        else fail "cmake: exported symbols (version script)"; fi

        mkdir -p "$tmp/fp"
        cp "$tmp/consumer.c" "$tmp/fp/"
        cat >"$tmp/fp/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.16)
project(consumer C)
find_package(isect $major.0 CONFIG REQUIRED)
if(NOT isect_VERSION STREQUAL "$version")
  message(FATAL_ERROR "isect_VERSION is \${isect_VERSION}, expected $version")
endif()
add_executable(consumer consumer.c)
set_target_properties(consumer PROPERTIES C_STANDARD 99 C_EXTENSIONS OFF)
target_compile_options(consumer PRIVATE -Wall -Wextra -Wpedantic -Werror)
target_link_libraries(consumer PRIVATE isect::isect)
EOF
        if cmake_consumer "find_package(isect $major.0 CONFIG)" "$tmp/fp" "$tmp/fp-build" \
               -DCMAKE_PREFIX_PATH="$cprefix"; then
            check_loads "find_package" "$tmp/fp-build/consumer" "$cprefix/lib"
            check_run "find_package consumer" "$expected_c" "$tmp/fp-build/consumer"
        fi
        # SameMajorVersion: a request for the next major version is refused.
        mkdir -p "$tmp/fp-next"
        sed "s/find_package(isect $major.0 /find_package(isect $((major + 1)).0 /" \
            "$tmp/fp/CMakeLists.txt" >"$tmp/fp-next/CMakeLists.txt"
        cp "$tmp/consumer.c" "$tmp/fp-next/"
        if $CMAKE -S "$tmp/fp-next" -B "$tmp/fp-next-build" -DCMAKE_PREFIX_PATH="$cprefix" \
               >"$tmp/fp-next.log" 2>&1; then
            fail "find_package(isect $((major + 1)).0) accepted version $version"
        elif grep -q "isectConfig.cmake, version: $version" "$tmp/fp-next.log"; then
            pass "find_package(isect $((major + 1)).0) refuses $version (SameMajorVersion)"
        else
            tail -n 20 "$tmp/fp-next.log"
            fail "find_package(isect $((major + 1)).0): refused, but not for its version"
        fi
        # The isect.pc that cmake --install wrote.
        # shellcheck disable=SC2046
        if run_logged "$tmp/cmake-pc.log" $CC -std=c99 "$tmp/consumer.c" -o "$tmp/cmake-pc" \
               $(PKG_CONFIG_PATH="$cprefix/lib/pkgconfig" PKG_CONFIG_LIBDIR="$cprefix/lib/pkgconfig" \
                 pkg-config --cflags --libs isect) -Wl,-rpath,"$cprefix/lib"; then
            check_run "pkg-config on the cmake install" "$expected_c" "$tmp/cmake-pc"
        else
            fail "pkg-config on the cmake install: build"
        fi
    else
        fail "cmake build (shared, ISECT_WERROR) and cmake --install"
    fi

    # -------------------------------------------------------- 3. FetchContent
    echo "== CMake FetchContent"
    # fetch_consumer DIR DECLARATION: a consumer project around
    # FetchContent_Declare(isect DECLARATION).
    fetch_consumer() {
        mkdir -p "$1"
        cp "$tmp/consumer.c" "$1/"
        cat >"$1/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.16)
project(consumer C)
include(FetchContent)
FetchContent_Declare(isect $2)
FetchContent_MakeAvailable(isect)
# Nothing of libisect's own compile options reaches its users.
get_target_property(isect_opts isect INTERFACE_COMPILE_OPTIONS)
if(isect_opts)
  message(FATAL_ERROR "isect passes compile options on: \${isect_opts}")
endif()
add_executable(consumer consumer.c)
set_target_properties(consumer PROPERTIES C_STANDARD 99 C_EXTENSIONS OFF)
target_link_libraries(consumer PRIVATE isect::isect)
EOF
    }
    # check_flags NAME BUILDDIR: libisect's sources are compiled with
    # -ffp-contract=off and without -Werror; the consumer without either.
    check_flags() {
        cc_json=$2/compile_commands.json
        lib_lines=$(grep '"command"' "$cc_json" | grep 'libisect/src/')
        user_line=$(grep '"command"' "$cc_json" | grep 'consumer\.c')
        if [ -n "$lib_lines" ] && ! printf '%s\n' "$lib_lines" | grep -vq -- '-ffp-contract=off' \
           && ! printf '%s\n' "$lib_lines" | grep -q -- '-Werror' \
           && ! printf '%s\n' "$user_line" | grep -q -- '-ffp-contract\|-Werror'; then
            pass "$1: libisect compiled with -ffp-contract=off, no -Werror; none of it on the consumer"
        else
            printf '%s\n' "$lib_lines" | head -n 2
            printf '%s\n' "$user_line"
            fail "$1: compile flags"
        fi
    }
    fetch_consumer "$tmp/fc-src" "SOURCE_DIR \"$root\""
    if cmake_consumer "FetchContent SOURCE_DIR (static)" "$tmp/fc-src" "$tmp/fc-src-build"; then
        check_flags "FetchContent SOURCE_DIR" "$tmp/fc-src-build"
        if ldd "$tmp/fc-src-build/consumer" | grep -q libisect; then
            fail "FetchContent SOURCE_DIR: consumer should link libisect statically"
        else
            pass "FetchContent SOURCE_DIR: libisect linked statically"
        fi
        check_run "FetchContent SOURCE_DIR consumer" "$expected_c" "$tmp/fc-src-build/consumer"
    fi
    if [ -n "$head" ] && have git; then
        fetch_consumer "$tmp/fc-git" "GIT_REPOSITORY \"file://$root\" GIT_TAG $head"
        if cmake_consumer "FetchContent GIT_REPOSITORY file:// at HEAD (shared)" "$tmp/fc-git" \
               "$tmp/fc-git-build" -DBUILD_SHARED_LIBS=ON; then
            check_flags "FetchContent GIT_REPOSITORY" "$tmp/fc-git-build"
            check_loads "FetchContent GIT_REPOSITORY" "$tmp/fc-git-build/consumer" \
                "$tmp/fc-git-build/_deps/isect-build"
            check_run "FetchContent GIT_REPOSITORY consumer" "$expected_c" "$tmp/fc-git-build/consumer"
        fi
    else
        skip "FetchContent GIT_REPOSITORY: $root is not a git checkout"
    fi
else
    skip "CMake routes: $CMAKE not found"
fi

# ------------------------------------------------------------ 4. meson
if have "$MESON" && have ninja; then
    echo "== meson subproject"
    # meson_consumer DIR: a consumer project with subprojects/libisect -> root.
    meson_consumer() {
        mkdir -p "$1/subprojects"
        ln -s "$root" "$1/subprojects/libisect"
        cp "$tmp/consumer.c" "$tmp/consumer.f90" "$1/"
    }
    meson_consumer "$tmp/ms"
    cat >"$tmp/ms/meson.build" <<'EOF'
project('consumer', 'c', default_options : ['c_std=c99'])
subproject('libisect')
executable('consumer', 'consumer.c', dependencies : dependency('isect'))
EOF
    if run_logged "$tmp/ms-setup.log" $MESON setup "$tmp/ms/build" "$tmp/ms" \
       && run_logged "$tmp/ms-build.log" ninja -C "$tmp/ms/build"; then
        pass "meson subproject: setup and build"
        targets=$($MESON introspect --targets "$tmp/ms/build" | python3 -c \
            'import json, sys; print(" ".join(sorted(t["name"] for t in json.load(sys.stdin))))')
        if [ "$targets" = "consumer isect isect" ]; then
            pass "meson subproject: builds only the library (targets: $targets)"
        else
            fail "meson subproject: builds more than the library (targets: $targets)"
        fi
        if grep '"command"' "$tmp/ms/build/compile_commands.json" | grep -q -- '-Werror'; then
            fail "meson subproject: -Werror in a compile command"
        else
            pass "meson subproject: no -Werror imposed"
        fi
        check_loads "meson subproject" "$tmp/ms/build/consumer" "$tmp/ms/build/subprojects/libisect"
        check_run "meson subproject consumer" "$expected_c" "$tmp/ms/build/consumer"
    else
        fail "meson subproject: setup and build"
    fi

    if have "$FC"; then
        meson_consumer "$tmp/msf"
        cat >"$tmp/msf/meson.build" <<'EOF'
project('consumer', 'c', 'fortran', default_options : ['c_std=c99', 'default_library=static'])
subproject('libisect', default_options : ['fortran=enabled'])
executable('consumer', 'consumer.c', dependencies : dependency('isect'))
executable('fconsumer', 'consumer.f90', dependencies : dependency('isect-fortran'))
EOF
        if run_logged "$tmp/msf-setup.log" env FC="$FC" $MESON setup "$tmp/msf/build" "$tmp/msf" \
           && run_logged "$tmp/msf-build.log" ninja -C "$tmp/msf/build"; then
            pass "meson subproject, fortran=enabled, default_library=static: setup and build"
            check_run "meson subproject consumer (static)" "$expected_c" "$tmp/msf/build/consumer"
            check_run "meson subproject Fortran consumer" "$expected_f" "$tmp/msf/build/fconsumer"
        else
            fail "meson subproject, fortran=enabled, default_library=static: setup and build"
        fi
    else
        skip "meson subproject with the Fortran module: $FC not found"
    fi
else
    skip "meson subproject: meson or ninja not found"
fi

# ------------------------------------------------------------ 5. fpm
fpm=${FPM:-}
if [ -z "$fpm" ]; then
    if have fpm; then fpm=fpm
    elif [ -x .venv/bin/fpm ]; then fpm=$root/.venv/bin/fpm
    fi
fi
if [ -z "$fpm" ]; then
    skip "fpm: not found (FPM, PATH, .venv/bin/fpm; make venv installs the pip package fpm)"
elif ! have "$FC"; then
    skip "fpm: $FC not found"
else
    echo "== fpm ($($fpm --version 2>/dev/null | sed -n 's/^ *Version: *//p'))"
    fpm_version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' fpm.toml)
    if [ "$fpm_version" = "$version" ]; then pass "fpm.toml version $fpm_version equals isect.h's"
    else fail "fpm.toml version '$fpm_version', isect.h says $version"; fi
    # fpm_consumer DIR DEPENDENCY: an fpm project whose app uses module isect.
    fpm_consumer() {
        mkdir -p "$1/app"
        cp "$tmp/consumer.f90" "$1/app/main.f90"
        printf 'name = "consumer"\nversion = "0.1.0"\n\n[dependencies]\nisect = %s\n' "$2" \
            >"$1/fpm.toml"
    }
    # fpm_exe DIR: the program fpm built (build/<compiler>_<hash>/app/consumer).
    fpm_exe() { find "$1/build" -path '*/app/consumer' -type f | head -n 1; }
    fpm_flags="-std=c99 -ffp-contract=off"
    # fpm takes a relative path (it prefixes the project directory).
    fpm_consumer "$tmp/fpm-path" "{ path = \"$(realpath --relative-to="$tmp/fpm-path" "$root")\" }"
    if (cd "$tmp/fpm-path" && run_logged "$tmp/fpm-path.log" "$fpm" build --c-flag "$fpm_flags"); then
        pass "fpm, isect = { path = ... }: fpm build --c-flag \"$fpm_flags\""
        check_run "fpm path consumer" "$expected_f" "$(fpm_exe "$tmp/fpm-path")"
    else
        fail "fpm, isect = { path = ... }: build"
    fi
    # GCC without an ISO mode (fpm's default: no C flags at all) must stop.
    if "${FPM_CC:-gcc}" --version 2>/dev/null | grep -qi 'free software foundation'; then
        if (cd "$tmp/fpm-path" && rm -rf build && "$fpm" build >"$tmp/fpm-noflags.log" 2>&1); then
            fail "fpm without --c-flag: the build should stop at bindings/fortran/fpm_flags.c"
        elif grep -q 'libisect under fpm needs' "$tmp/fpm-noflags.log"; then
            pass "fpm without --c-flag: stopped by fpm_flags.c with the flags to use"
        else
            tail -n 20 "$tmp/fpm-noflags.log"
            fail "fpm without --c-flag: failed, but not at fpm_flags.c"
        fi
    fi
    if [ -n "$head" ] && have git; then
        fpm_consumer "$tmp/fpm-git" "{ git = \"file://$root\", rev = \"$head\" }"
        if (cd "$tmp/fpm-git" && run_logged "$tmp/fpm-git.log" "$fpm" build --c-flag "$fpm_flags"); then
            pass "fpm, isect = { git = \"file://...\", rev = HEAD }: build"
            check_run "fpm git consumer" "$expected_f" "$(fpm_exe "$tmp/fpm-git")"
        else
            fail "fpm, isect = { git = ... }: build"
        fi
    else
        skip "fpm git dependency: $root is not a git checkout"
    fi
fi

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
