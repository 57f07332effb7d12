#!/bin/bash
# The eight impact-level benchmarks of Chung and Ooi (Granular Matter 13:643-656, 2011), run with
# in.impact for each contact law, printed one line per case (README.md, docs/impact_benchmarks.rst):
#
#   tests 1-3:  TEST LAW MATERIAL X VIN VOUT EKIN_RATIO DURATION
#               X the input restitution, VIN and VOUT the normal approach and separation speeds
#               (m/s), EKIN_RATIO the kinetic energy after over before, DURATION the contact's
#               duration (s; 0: the law has none). LAW hertz: Hertz's elastic contact time.
#   tests 4-8:  TEST LAW X VX VZ OMEGA
#               X the varied quantity (test 4: incidence from the normal, degrees; test 5: the
#               tangential velocity, m/s; tests 6-8: sphere 1's initial omegay, rad/s); VX, VZ,
#               OMEGA sphere 1's velocity and omegay after the impact (m/s, rad/s). LAW is the
#               law, or LAW:VARIANT for the test's second material or case.
#
#   ./run.sh                   all cases (a few minutes)
#   ./run.sh --short           three values of X per test, first material only (seconds)
#   ./run.sh --plot DIR        also write DIR/results.txt and draw DIR/test*.png (plot.py)
#   ./run.sh --laws "stick"    the laws to run (files law.NAME; default "stick compliant stock-mindlin")
#
# The package's law runs with ACTIVEGRAIN_LMP (default build/lmp of this checkout); stock LAMMPS is
# ACTIVEGRAIN_LMP_STOCK, by default the binary that the build/lmp wrapper runs, without the plugin.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
LMP=${ACTIVEGRAIN_LMP:-$ROOT/build/lmp}
SHORT=no
PLOT=""
LAWS="stick compliant stock-mindlin"
while [ $# -gt 0 ]; do
  case "$1" in
    --short) SHORT=yes ;;
    --plot) PLOT=$2; shift ;;
    --laws) LAWS=$2; shift ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

# Stock LAMMPS: the binary and library path that the wrapper names, when it is the wrapper that
# build/ writes; otherwise the given lmp itself (the plugin's styles are then loaded but unused).
if [ -z "${ACTIVEGRAIN_LMP_STOCK:-}" ]; then
  bin=$(sed -n 's/^LMP="\(.*\)"$/\1/p' "$LMP" 2>/dev/null || true)
  lib=$(sed -n 's/^LD_LIBRARY_PATH="\([^$"]*\)\${.*$/\1/p' "$LMP" 2>/dev/null || true)
  if [ -n "$bin" ] && [ -x "$bin" ]; then
    STOCK=(env "LD_LIBRARY_PATH=$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$bin")
  else
    STOCK=("$LMP")
  fi
else
  STOCK=("$ACTIVEGRAIN_LMP_STOCK")
fi

# lmp for a law; law files beside in.impact
binary() { if [ "${1%%-*}" = stock ]; then echo "${STOCK[@]}"; else echo "$LMP"; fi; }

# materials: E (Pa), nu, density (kg/m^3)
declare -A MAT=(
  [glass]="4.8e10 0.20 2800"            [limestone]="2.0e10 0.25 2500"
  [aluminium-alloy-2]="7.0e10 0.30 2699" [magnesium-alloy]="4.0e10 0.35 1800"
  [aluminium-oxide]="3.8e11 0.23 4000"  [cast-iron]="1.0e11 0.25 7000"
  [aluminium-alloy]="7.0e10 0.33 2700"  [steel]="2.08e11 0.30 7850"
  [polyethylene]="1.0e9 0.40 1400"      [nylon]="2.5e9 0.40 1000"
  [copper]="1.2e11 0.35 8900"
  [aluminium-alloy-x1000]="7.0e13 0.33 2.7e6"
)
matvars() {   # matvars INDEX MATERIAL: -var E1 .. -var nu1 .. -var rho1 ..
  read -r E nu rho <<<"${MAT[$2]}"
  echo "-var E$1 $E -var nu$1 $nu -var rho$1 $rho"
}

# X lists
angles=$(seq 5 5 85)
spins=$(awk 'BEGIN { for (k = 1; k <= 17; k++) printf "%.10g ", 2.0 * sin(k*5*atan2(1,1)/45) / cos(k*5*atan2(1,1)/45) }')
vts="0.5 1 1.5 2 3 4 5 6 7.5 9 10.5 12 15 20 30"
es="0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 1"
if [ $SHORT = yes ]; then
  angles="10 30 60"
  spins=$(awk 'BEGIN { for (k = 3; k <= 15; k += 6) printf "%.10g ", 2.0 * sin(k*5*atan2(1,1)/45) / cos(k*5*atan2(1,1)/45) }')
  vts="1.5 6 20"
  es="0 0.5 1"
fi

# run LAW X-LIST VARS...: the IMPACT lines of in.impact (fields after the tag)
run() {
  local law=$1 xs=$2; shift 2
  local out
  # shellcheck disable=SC2046
  out=$(cd "$HERE" && $(binary "$law") -in in.impact -log none -echo none -nocite -var law "$law" -var X $xs "$@" 2>&1) || {
    echo "run.sh: lmp failed (law $law):" >&2; echo "$out" | tail -20 >&2; exit 1; }
  if echo "$out" | grep -q "^ERROR"; then echo "$out" | grep "^ERROR" >&2; exit 1; fi
  echo "$out" | sed -n 's/^IMPACT //p'
}

# normal tests: TEST LAW MATERIAL X VIN VOUT EKIN_RATIO DURATION (+ hertz lines from the first law)
normal() {   # normal TEST LAWTAG MATERIAL TARGET X-LIST VARS...
  local test=$1 law=$2 mat=$3 target=$4 xs=$5; shift 5
  run "$law" "$xs" -var target "$target" "$@" | awk -v t="$test" -v l="$law" -v m="$mat" -v tg="$target" -v VIN="$VIN" '{
      x = $1; vz1 = $3; vz2 = $6; dur = $8; e0 = $9; e1 = $10; th = $11
      vout = (tg == "sphere") ? vz1 - vz2 : vz1
      printf "%s %s %s %s %s %.17g %.17g %.9g\n", t, l, m, x, VIN, vout, e1 / e0, dur
      if (l == "stick" && t != "test3") printf "%s hertz %s %s %s %s 1 %.9g\n", t, m, x, VIN, VIN, th
    }'
}

# oblique tests: TEST LAW X VX VZ OMEGA
oblique() {   # oblique TEST LAWTAG LAW X-LIST VARS...
  local test=$1 tag=$2 law=$3 xs=$4; shift 4
  run "$law" "$xs" "$@" | awk -v t="$test" -v l="$tag" '{ printf "%s %s %s %s %s %s\n", t, l, $1, $2, $3, $4 }'
}

# materials N MATERIAL: the material's variables for spheres 1 to N
materials() { matvars 1 "$2"; [ "$1" = 1 ] || matvars 2 "$2"; }

# both TEST X-LIST SPHERES MATERIAL SECOND VARS...: an oblique test for each law with MATERIAL and
# (not --short; not the stick law, whose answer does not depend on the material) with SECOND, as LAW:SECOND
both() {
  local test=$1 xs=$2 n=$3 mat=$4 second=$5; shift 5
  for law in $LAWS; do
    # shellcheck disable=SC2046
    oblique "$test" "$law" "$law" "$xs" "$@" $(materials "$n" "$mat")
    [ $SHORT = yes ] || [ "$law" = stick ] || \
      oblique "$test" "$law:$second" "$law" "$xs" "$@" $(materials "$n" "$second")
  done
}

{
for law in $LAWS; do
  [ -f "$HERE/law.$law" ] || { echo "run.sh: no law file law.$law" >&2; exit 2; }
done

echo "# Chung and Ooi (2011) impact benchmarks; lines: tests 1-3 TEST LAW MATERIAL X VIN VOUT EKIN_RATIO DURATION, tests 4-8 TEST LAW X VX VZ OMEGA"

# Test 1: elastic normal impact of two identical spheres, R 0.010 m, 10 m/s each
echo "# test1 two identical spheres R 0.010 m, 10 m/s each, e 1, mu 0.35: glass, limestone"
VIN=20
for mat in glass limestone; do
  [ $SHORT = yes ] && [ $mat != glass ] && continue
  for law in $LAWS; do
    normal test1 "$law" $mat sphere 1 -var vary none -var V 10 -var V2 10 -var R1 0.010 -var R2 0.010 \
      $(matvars 1 $mat) $(matvars 2 $mat) -var e 1 -var mu 0.35
  done
done

# Test 2: elastic normal impact of a sphere with a rigid plane, R 0.10 m, 0.2 m/s
echo "# test2 sphere on a rigid plane R 0.10 m, 0.2 m/s, e 1, mu 0: aluminium-alloy-2 (nu 0.30), magnesium-alloy"
VIN=0.2
for mat in aluminium-alloy-2 magnesium-alloy; do
  [ $SHORT = yes ] && [ $mat != aluminium-alloy-2 ] && continue
  for law in $LAWS; do
    normal test2 "$law" $mat plane 1 -var vary none -var V 0.2 -var R1 0.10 $(matvars 1 $mat) -var e 1 -var mu 0
  done
done

# Test 3: normal impact with different restitution coefficients, R 0.0025 m, 3.9 m/s
echo "# test3 sphere on a rigid plane R 0.0025 m, 3.9 m/s, e = X, mu 0: aluminium-oxide, cast-iron"
VIN=3.9
for mat in aluminium-oxide cast-iron; do
  [ $SHORT = yes ] && [ $mat != aluminium-oxide ] && continue
  for law in $LAWS; do
    xs=$es
    [ "${law%%-*}" = stock ] && xs=$(echo $es | tr ' ' '\n' | awk '$1 > 0' | tr '\n' ' ')   # damping from ln e
    normal test3 "$law" $mat plane "$xs" -var vary e -var V 3.9 -var R1 0.0025 $(matvars 1 $mat) -var mu 0
  done
done

# Test 4: oblique impact on a plane at 3.9 m/s and incidence X (degrees from the normal)
echo "# test4 sphere on a rigid plane R 0.0025 m, 3.9 m/s at incidence X, e 0.98, mu 0.092: aluminium-oxide, aluminium-alloy"
both test4 "$angles" 1 aluminium-oxide aluminium-alloy -var target plane -var vary angle -var V 3.9 -var R1 0.0025 \
  -var e 0.98 -var mu 0.092

# Test 5: oblique impact on a plane at normal velocity 5 m/s and tangential velocity X
echo "# test5 sphere on a rigid plane R 1e-5 m, normal 5 m/s, tangential X m/s, e 1, mu 0.3: steel, polyethylene"
both test5 "$vts" 1 steel polyethylene -var target plane -var vary vt -var V 5 -var R1 1e-5 -var e 1 -var mu 0.3

# Test 6: a spinning sphere on a plane, normal velocity 0.2 m/s, omegay X
echo "# test6 sphere on a rigid plane R 0.1 m, normal 0.2 m/s, omegay X rad/s, e 0.5, mu 0.4: aluminium-alloy, nylon"
both test6 "$spins" 1 aluminium-alloy nylon -var target plane -var vary spin -var V 0.2 -var R1 0.1 -var e 0.5 -var mu 0.4

# Test 7: two identical spheres, 0.2 m/s each, omegay X and -X
echo "# test7 two identical spheres R 0.1 m, 0.2 m/s each, omegay X (sphere 1) and -X (sphere 2), e 0.5, mu 0.4: aluminium-alloy, copper"
both test7 "$spins" 2 aluminium-alloy copper -var target sphere -var vary spin -var V 0.2 -var V2 0.2 -var spin2 -1 \
  -var R1 0.1 -var R2 0.1 -var e 0.5 -var mu 0.4

# Test 8: a spinning sphere (R 0.1 m, 0.2 m/s) on a sphere of R 0.5 m at rest, omegay X
echo "# test8 sphere R 0.1 m at 0.2 m/s, omegay X, on a sphere R 0.5 m at rest, e 0.5, mu 0.4: aluminium-alloy on aluminium-alloy-x1000 (E, density x 1000); variant equal-density: on aluminium-alloy"
for law in $LAWS; do
  oblique test8 "$law" "$law" "$spins" -var target sphere -var vary spin -var V 0.2 -var V2 0 -var spin2 0 \
    -var R1 0.1 -var R2 0.5 $(matvars 1 aluminium-alloy) $(matvars 2 aluminium-alloy-x1000) -var e 0.5 -var mu 0.4
  [ "$law" = stick ] || [ $SHORT = no ] || continue
  oblique test8 "$law:equal-density" "$law" "$spins" -var target sphere -var vary spin -var V 0.2 -var V2 0 \
    -var spin2 0 -var R1 0.1 -var R2 0.5 $(matvars 1 aluminium-alloy) $(matvars 2 aluminium-alloy) -var e 0.5 -var mu 0.4
done
} | if [ -n "$PLOT" ]; then
  mkdir -p "$PLOT"
  tee "$PLOT/results.txt"
else
  cat
fi

if [ -n "$PLOT" ]; then
  /usr/bin/python3 "$HERE/plot.py" "$PLOT/results.txt" "$PLOT"
fi
