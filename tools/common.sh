# Shared by tools/run-example and tools/run-tests: system packages, LAMMPS source,
# a cached LAMMPS build keyed by version and options, and the plugin build.
# Sourced, not executed.
set -euo pipefail

AG_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
AG_CACHE=${ACTIVEGRAIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/activegrain}
AG_LAMMPS=${ACTIVEGRAIN_LAMMPS:-4Feb2025}     # 4Feb2025 (default) or 4Jul2026
AG_JOBS=${ACTIVEGRAIN_JOBS:-$(nproc)}

# LAMMPS packages our styles and examples need. Changing this list changes the cache key.
AG_LAMMPS_PACKAGES="PLUGIN GRANULAR RIGID MOLECULE EXTRA-FIX"

say() { printf '[activegrain] %s\n' "$*" >&2; }
die() { printf '[activegrain] ERROR: %s\n' "$*" >&2; exit 1; }

# Debian package name, tarball, checksum and top folder for each supported LAMMPS.
lammps_release() {
  case "$AG_LAMMPS" in
    4Feb2025) SUITE=trixie
              TARBALL=lammps_20250204+dfsg.1.orig.tar.xz
              SHA256=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7 ;;
    4Jul2026) SUITE=sid
              TARBALL=lammps_20260704+dfsg.orig.tar.gz
              SHA256=cddbc45a047416bd48a4a0b87f24a5b61b3446982b74d18cafe619c22b17eb62 ;;
    *) die "unknown ACTIVEGRAIN_LAMMPS='$AG_LAMMPS' (use 4Feb2025 or 4Jul2026, or pass your own tree with LAMMPS_SOURCE_DIR)" ;;
  esac
}

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else return 1; fi; }

# The Debian packages of tools/debian-packages whose probe fails on this machine, one a line.
# ACTIVEGRAIN_ASSUME_MISSING (package names) makes the probes of those fail: the tests use it to
# check what a machine without them is told.
missing_packages() {
  local pkg kind name pkgs=() modules=()
  while read -r pkg kind name _; do
    case "$pkg" in ''|'#'*) continue ;; esac
    case " ${ACTIVEGRAIN_ASSUME_MISSING:-} " in *" $pkg "*) echo "$pkg"; continue ;; esac
    case "$kind" in
      command) command -v "$name" >/dev/null || echo "$pkg" ;;
      header)  printf '#include <%s>\n' "$name" | c++ -x c++ -E - >/dev/null 2>&1 || echo "$pkg" ;;
      python)  pkgs+=("$pkg"); modules+=("$name") ;;
      file)    [ -e "$name" ] || echo "$pkg" ;;
      *)       die "tools/debian-packages: unknown probe '$kind' for $pkg" ;;
    esac
  done < "$AG_ROOT/tools/debian-packages"
  [ ${#modules[@]} -eq 0 ] && return 0
  # Only Debian's python3 sees Debian's python3-* packages; find_spec does not import them.
  /usr/bin/python3 - "${pkgs[@]}" "${modules[@]}" 2>/dev/null <<'PY' || printf '%s\n' "${pkgs[@]}"
import importlib.util, sys
args = sys.argv[1:]
half = len(args) // 2
for pkg, module in zip(args[:half], args[half:]):
    if importlib.util.find_spec(module) is None:
        print(pkg)
PY
}

# Install what tools/debian-packages lists and this machine lacks. When that cannot be done, one
# ERROR line names the Debian packages, before anything is configured.
ensure_system_packages() {
  local missing=() unknown=() p
  mapfile -t missing < <(missing_packages)
  [ ${#missing[@]} -eq 0 ] && return 0
  local list="${missing[*]}" log="$AG_CACHE/apt.log"
  command -v apt-get >/dev/null \
    || die "missing Debian packages: $list; there is no apt-get here to install them: install them (or the same software) yourself"
  # Not root: sudo, if it works without a password or can ask for one on a terminal.
  [ "$(id -u)" = 0 ] || { command -v sudo >/dev/null && { [ -t 0 ] || sudo -n true 2>/dev/null; }; } \
    || die "missing Debian packages: $list; run as root or with sudo, or install them yourself: apt-get install $list"
  mkdir -p "$AG_CACHE"
  say "installing Debian packages: $list"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get update -qq >"$log" 2>&1 \
    || die "missing Debian packages: $list; 'apt-get update' failed as root (log: $log): install them yourself: apt-get install $list"
  for p in "${missing[@]}"; do
    # (the output is read whole: grep -q would close the pipe early, which pipefail reports)
    [[ "$(apt-cache policy "$p" 2>/dev/null)" == *"Candidate: "[^\(]* ]] || unknown+=("$p")
  done
  [ ${#unknown[@]} -eq 0 ] \
    || die "Debian package not found by apt: ${unknown[*]} (needed: $list); these are in Debian 12's main archive: check the apt sources"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >>"$log" 2>&1 \
    || die "could not install Debian packages $list (log: $log)"
  mapfile -t missing < <(missing_packages)
  [ ${#missing[@]} -eq 0 ] || die "installed, but still not usable: Debian packages ${missing[*]} (see tools/debian-packages for what is probed)"
}

# Fetch Debian's orig tarball of LAMMPS with a private apt configuration: the deb-src entry is
# derived from the machine's own Debian sources, so no host is named and the system is untouched.
fetch_lammps_tarball() {
  local dl="$AG_CACHE/downloads"; mkdir -p "$dl"
  if [ -f "$dl/$TARBALL" ] && echo "$SHA256  $dl/$TARBALL" | sha256sum -c --status; then return 0; fi
  local sources=${ACTIVEGRAIN_APT_SOURCES:-/etc/apt/sources.list.d/debian.sources}
  [ -f "$sources" ] || die "no $sources to derive a Debian source entry from; download LAMMPS yourself and pass -DLAMMPS_SOURCE_DIR / LAMMPS_SOURCE_DIR"
  local apt="$AG_CACHE/apt-$SUITE"; mkdir -p "$apt/parts" "$apt/lists/partial"
  # Keep the first stanza's URIs and keyring; switch to source packages of $SUITE.
  awk -v suite="$SUITE" 'BEGIN{RS="";FS="\n"} NR==1{for(i=1;i<=NF;i++){
        if($i~/^Types:/)print "Types: deb-src"; else if($i~/^Suites:/)print "Suites: " suite; else print $i}}' \
      "$sources" > "$apt/parts/lammps-src.sources"
  local opts=(-o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$apt/parts"
              -o Dir::State::Lists="$apt/lists" -o Dir::Cache::srcpkgcache="" -o Dir::Cache::pkgcache="")
  say "fetching LAMMPS $AG_LAMMPS source ($TARBALL) from Debian's $SUITE sources"
  apt-get "${opts[@]}" update -qq >/dev/null 2>&1 || true
  # apt answers 404 for the .dsc/diff and exits non-zero although the tarball arrives:
  # success is judged by the tarball's checksum.
  (cd "$dl" && apt-get "${opts[@]}" source --download-only lammps >/dev/null 2>&1) || true
  [ -f "$dl/$TARBALL" ] && echo "$SHA256  $dl/$TARBALL" | sha256sum -c --status \
    || die "could not download $TARBALL from Debian's sources; fetch LAMMPS $AG_LAMMPS yourself and set LAMMPS_SOURCE_DIR=/path/to/lammps"
}

# Resolve LAMMPS_SRC (the LAMMPS tree: has cmake/ and src/): the user's own, or Debian's tarball
# unpacked into the cache.
resolve_lammps_source() {
  if [ -n "${LAMMPS_SOURCE_DIR:-}" ]; then
    LAMMPS_SRC=$(cd "$LAMMPS_SOURCE_DIR" 2>/dev/null && pwd) || die "LAMMPS_SOURCE_DIR=$LAMMPS_SOURCE_DIR does not exist"
    [ -f "$LAMMPS_SRC/src/version.h" ] && [ -f "$LAMMPS_SRC/cmake/CMakeLists.txt" ] \
      || die "LAMMPS_SOURCE_DIR=$LAMMPS_SRC is not a LAMMPS tree (needs src/version.h and cmake/CMakeLists.txt)"
    return 0
  fi
  lammps_release
  local dest="$AG_CACHE/source/$AG_LAMMPS"
  if [ ! -f "$dest/.unpacked" ]; then
    fetch_lammps_tarball
    say "unpacking $TARBALL"
    rm -rf "$dest"; mkdir -p "$dest"
    tar -xf "$AG_CACHE/downloads/$TARBALL" -C "$dest"
    touch "$dest/.unpacked"
  fi
  # 4Feb2025 unpacks into lammps-4Feb2025/, 20260704 has no top-level folder.
  LAMMPS_SRC=$(dirname "$(find "$dest" -maxdepth 3 -path '*/src/version.h' | head -n 1)")
  LAMMPS_SRC=$(dirname "$LAMMPS_SRC")
  [ -f "$LAMMPS_SRC/cmake/CMakeLists.txt" ] || die "unpacked $TARBALL but found no LAMMPS tree in $dest"
}

# The oldest LAMMPS we support is 2Aug2023: check before any long build.
check_lammps_version() {
  local v; v=$(sed -n 's/^#define LAMMPS_VERSION "\(.*\)"/\1/p' "$LAMMPS_SRC/src/version.h")
  [ -n "$v" ] || die "cannot read LAMMPS_VERSION from $LAMMPS_SRC/src/version.h"
  local date; date=$(date -d "$v" +%Y%m%d 2>/dev/null) || die "cannot parse LAMMPS version '$v'"
  [ "$date" -ge 20230802 ] || die "LAMMPS '$v' in $LAMMPS_SRC is too old: ActiveGrain needs 2Aug2023 or newer"
  LAMMPS_VERSION_STRING=$v
}

# Build LAMMPS once per (version, source, options, compiler, MPI) into $AG_CACHE/lammps/<key>.
# Sets LAMMPS_PREFIX (install: bin/lmp, lib/liblammps.so) and LAMMPS_BUILD (has lmpinstalledpkgs.h).
build_lammps() {
  local pk_flags=() p
  for p in $AG_LAMMPS_PACKAGES; do pk_flags+=("-DPKG_$p=yes"); done
  local opts=(-DBUILD_MPI=yes -DBUILD_OMP=no -DBUILD_SHARED_LIBS=yes -DFFT=FFTW3
              -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_STANDARD=17 -DBUILD_TOOLS=no
              -DLAMMPS_EXCEPTIONS=yes "${pk_flags[@]}")
  local key; key=$( { echo "$LAMMPS_VERSION_STRING $LAMMPS_SRC"; echo "${opts[*]}";
                      c++ --version | head -n 1; mpicxx --showme:version 2>/dev/null || true; } | sha256sum | cut -c1-12)
  local tag; tag=$(echo "$LAMMPS_VERSION_STRING" | tr -d ' ')
  local root="$AG_CACHE/lammps/$tag-$key"
  LAMMPS_PREFIX="$root/install"; LAMMPS_BUILD="$root/build"
  if [ -f "$root/.built" ]; then return 0; fi
  mkdir -p "$root"
  say "building LAMMPS $LAMMPS_VERSION_STRING with $AG_LAMMPS_PACKAGES (one-time, ~5 min on 2 cores) in $root"
  export CCACHE_DIR="$AG_CACHE/ccache"
  cmake -S "$LAMMPS_SRC/cmake" -B "$LAMMPS_BUILD" -DCMAKE_INSTALL_PREFIX="$LAMMPS_PREFIX" \
        -DCMAKE_CXX_COMPILER_LAUNCHER=ccache "${opts[@]}" > "$root/configure.log" 2>&1 \
    || { tail -n 30 "$root/configure.log" >&2; die "configuring LAMMPS failed (log: $root/configure.log)"; }
  cmake --build "$LAMMPS_BUILD" -j "$AG_JOBS" > "$root/build.log" 2>&1 \
    || { tail -n 30 "$root/build.log" >&2; die "building LAMMPS failed (log: $root/build.log)"; }
  cmake --install "$LAMMPS_BUILD" > /dev/null || die "installing LAMMPS into $LAMMPS_PREFIX failed"
  touch "$root/.built"
}

# Configure and build ActiveGrain in $AG_BUILD against the cached LAMMPS.
build_plugin() {
  local tag; tag=$(echo "$LAMMPS_VERSION_STRING" | tr -d ' ')
  AG_BUILD=${ACTIVEGRAIN_BUILD_DIR:-$AG_ROOT/build}
  [ "$tag" = 4Feb2025 ] && [ -z "${LAMMPS_SOURCE_DIR:-}" ] || AG_BUILD=${ACTIVEGRAIN_BUILD_DIR:-$AG_ROOT/build-$tag}
  # A build folder made against another LAMMPS is configured afresh.
  if [ -f "$AG_BUILD/CMakeCache.txt" ] && [ "$(cat "$AG_BUILD/.lammps-prefix" 2>/dev/null)" != "$LAMMPS_PREFIX" ]; then
    rm -rf "$AG_BUILD"
  fi
  mkdir -p "$AG_BUILD"
  export CCACHE_DIR="$AG_CACHE/ccache"
  if [ ! -f "$AG_BUILD/CMakeCache.txt" ]; then
    cmake -S "$AG_ROOT" -B "$AG_BUILD" -DLAMMPS_SOURCE_DIR="$LAMMPS_SRC" -DLAMMPS_INSTALL_DIR="$LAMMPS_PREFIX" \
          -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >"$AG_BUILD/configure.log" 2>&1 \
      || { tail -n 20 "$AG_BUILD/configure.log" >&2; die "configuring ActiveGrain failed (log: $AG_BUILD/configure.log)"; }
    echo "$LAMMPS_PREFIX" > "$AG_BUILD/.lammps-prefix"
  fi
  say "building ActiveGrain in $AG_BUILD"
  cmake --build "$AG_BUILD" -j "$AG_JOBS" >"$AG_BUILD/build.log" 2>&1 \
    || { grep -E -A5 'error|Error' "$AG_BUILD/build.log" | head -n 60 >&2; die "building ActiveGrain failed (log: $AG_BUILD/build.log)"; }
}

# Everything both README commands need before they run anything.
prepare_build() {
  ensure_system_packages
  resolve_lammps_source
  check_lammps_version
  build_lammps
  build_plugin
}
