#!/usr/bin/env bash
# Build an lmp with ActiveGrain compiled in, as a user of tools/install-in-tree would: a copy of a
# LAMMPS tree's cmake/ and src/, the install script run on it, LAMMPS's own CMake build with
# -D PKG_ACTIVEGRAIN=on (pkg_depends adds RIGID and GRANULAR). Prints the path of that lmp.
#   tests/integration/build_in_tree.sh /path/to/lammps
# Cached in $AG_CACHE/in-tree/<version>-<key>, keyed by the LAMMPS version and tree, the options,
# compiler and MPI, and the package's sources with the install script; the three newest builds of
# a LAMMPS version are kept. ccache with the build's own folder as its base dir sees the same
# relative paths in every such build, so a new key (a changed source) recompiles only what changed.
source "$(dirname "${BASH_SOURCE[0]}")/../../tools/common.sh"

[ $# -eq 1 ] || die "usage: $0 /path/to/lammps"
LAMMPS_SRC=$(cd "$1" && pwd)
check_lammps_version

opts=(-DCMAKE_BUILD_TYPE=Release -DBUILD_MPI=yes -DBUILD_OMP=no -DBUILD_TOOLS=no -DPKG_ACTIVEGRAIN=on)
key=$( { echo "$LAMMPS_VERSION_STRING $LAMMPS_SRC"; echo "${opts[*]}"; c++ --version | head -n 1
         mpicxx --showme:version 2>/dev/null || true
         cd "$AG_ROOT" && sha256sum tools/install-in-tree src/USER-ACTIVEGRAIN/*; } | sha256sum | cut -c1-12)
tag=$(echo "$LAMMPS_VERSION_STRING" | tr -d ' ')
root="$AG_CACHE/in-tree/$tag-$key"
if [ ! -f "$root/.built" ]; then
  rm -rf "$root"; mkdir -p "$root"
  cp -a "$LAMMPS_SRC/cmake" "$LAMMPS_SRC/src" "$root/"
  "$AG_ROOT/tools/install-in-tree" "$root" > "$root/install.log" || die "install-in-tree failed (log: $root/install.log)"
  export CCACHE_DIR="$AG_CACHE/ccache" CCACHE_BASEDIR="$root"
  say "building an in-tree lmp of LAMMPS $LAMMPS_VERSION_STRING with ACTIVEGRAIN in $root"
  cmake -S "$root/cmake" -B "$root/build" -DCMAKE_CXX_COMPILER_LAUNCHER=ccache "${opts[@]}" \
        > "$root/configure.log" 2>&1 || die "configuring the in-tree LAMMPS failed (log: $root/configure.log)"
  cmake --build "$root/build" -j "$AG_JOBS" > "$root/build.log" 2>&1 \
    || { grep -E -A5 'error' "$root/build.log" | head -n 40 >&2; die "building the in-tree LAMMPS failed (log: $root/build.log)"; }
  touch "$root/.built"
  # The older builds of this LAMMPS version, beyond the three newest, go.
  ls -dt "$AG_CACHE/in-tree/$tag"-*/.built | tail -n +4 | xargs -r -n 1 dirname | xargs -r rm -rf
fi
echo "$root/build/lmp"
