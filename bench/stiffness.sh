#!/usr/bin/env bash
# Which spring the stock decks use (not a test): one rod of in.create on flat plates in stock
# LAMMPS (in.stock), its walking speed along its axis for a scan of kn, the time step a fixed
# fraction of the contact time (dt = 5e-7 s at kn 2e4 N/m, ~1/37 of the bead-bead contact time,
# so dt ~ kn^-1/2). The softest kn whose speed is within 2 % of the stiffest one's is the one.
#   bench/stiffness.sh [path/to/lmp] [kn ...]     (default: build/lmp, 5e3 1e4 2e4 4e4 8e4 3.2e5 1.28e6)
# WARM and TIME (s) set the settling and the measured time (0.3 and 1.0); XGT the tangential
# damping as a fraction of the normal one (in.stock's x_gammat, 0).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${1:-$here/../build/lmp}
shift || true
kns=("$@")
[ ${#kns[@]} -gt 0 ] || kns=(5e3 1e4 2e4 4e4 8e4 3.2e5 1.28e6)
lmp=$(cd "$(dirname "$lmp")" && pwd)/$(basename "$lmp")   # absolute: the runs start in bench/
warm=${WARM:-0.3}
time=${TIME:-1.0}
xgt=${XGT:-0}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$here"
"$lmp" -in in.ours -var out "$work" -var geometry box -var Lx 20e-3 -var Ly 20e-3 -var phi_b 0 \
    -var phi_r 0.0093 -var rough 0 -var steps 0 -log none -echo none >"$work/create.log" ||
  { cat "$work/create.log"; exit 1; }
echo "# x_gammat $xgt, settle $warm s, measure $time s"
printf '%-9s %-10s %-9s %-12s %s\n' kn dt steps speed_mm/s wall_s
for kn in "${kns[@]}"; do
  dt=$(awk -v k="$kn" 'BEGIN{printf "%.4g", 5e-7*sqrt(2e4/k)}')
  warm_steps=$(awk -v t="$warm" -v dt="$dt" 'BEGIN{printf "%d", t/dt}')
  steps=$(awk -v t="$time" -v dt="$dt" 'BEGIN{printf "%d", t/dt}')
  start=$(date +%s.%N)
  speed=$("$lmp" -in in.stock -var data "$work/system.data" -var by p -var kn "$kn" -var xgt "$xgt" -var dt "$dt" \
      -var warm "$warm_steps" -var steps "$steps" -log none -echo none | awk '/^stock single rod/ {print $(NF-1)*1e3}')
  printf '%-9s %-10s %-9s %-12.4f %.1f\n' "$kn" "$dt" "$steps" "$speed" "$(echo "$(date +%s.%N) - $start" | bc)"
done
