#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the Debian packages the build, the tests and the demo need, when
# they are missing. Run by `make test` and `make demo` (and so by .ci/run),
# so the README's two commands work on a fresh machine. As non-root it only
# lists what is missing.
set -euo pipefail
packages=(build-essential clang meson ninja-build pkg-config cmake git libcjson-dev
          python3 python3-venv binutils gfortran abigail-tools
          libembree-dev
          libclang-rt-14-dev)  # the libFuzzer runtime of clang 14 (make fuzz)
need=()
for pkg in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' \
        || need+=("$pkg")
done
[ ${#need[@]} -eq 0 ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
    echo "missing Debian packages (install them as root): ${need[*]}" >&2
    exit 1
fi
echo "installing Debian packages: ${need[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${need[@]}"
