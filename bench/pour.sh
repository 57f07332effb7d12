#!/usr/bin/env bash
# Benchmark (not a test): LAMMPS's own pour example side by side in one call, 1 rank.
#   stock  bench/in.pour-stock: examples/pour/in.pour with the stiffness and time step its comment
#          recommends for realistic work (hooke/history, k 2e5 for pair and wall, dt 1e-4)
#   ours   examples/lammps-granular/in.pour: pair gran/impulse and fix wall/impulse (e 0.5,
#          mu 0.5) in place of the Hookean styles, at time step DT (default 0.02) with neighbor
#          skin SKIN (default 0.5: at least 4 dt times the fastest grain), resting RESTING
#          (default yes), resolution 50, slop SLOP (default 0.01), the resting solve's TOLERANCE
#          (0.3) and MAX_SWEEPS (100), the tangential law TANGENTIAL (default stick; "compliant
#          0.2857" is stock's tangential over normal stiffness, hooke/history's 2/7)
# Both runs of the example (pour 3000 grains for 25 time units, then 25 of chute flow). Prints,
# per run and side: the loop's CPU seconds (its wall time times its CPU use), simulated time per
# CPU second and ours over stock's, the heap's atoms, kinetic and rotational energy at the
# run's end with ours over stock's, and ours' largest overlap over the run (grain diameters).
#   bench/pour.sh [--quick]    --quick: a hundredth of each run (checks the script)
#   DT, SKIN, RESTING, RESOLUTION (50), SLOP, TOLERANCE, MAX_SWEEPS, OURS_ARGS (more -var
#   settings for ours) override the defaults; SLOP=0 TOLERANCE=0.01 MAX_SWEEPS=1000 are the
#   style's defaults.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0
for a in "$@"; do case $a in --quick) quick=1 ;; *) echo "unknown argument $a" >&2; exit 2 ;; esac; done
lmp=$here/../build/lmp
dt=${DT:-0.02}
span=25    # simulated time of each run (the shipped 25000 steps of 0.001)
[ $quick = 1 ] && span=0.25
stock_steps=$(awk -v s=$span 'BEGIN{printf "%d", s / 1e-4 + 0.5}')
ours_steps=$(awk -v s=$span -v dt="$dt" 'BEGIN{printf "%d", s / dt + 0.5}')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {
  local side=$1; shift
  (cd "$work" && "$lmp" -log "$work/$side.log" -echo none "$@" >/dev/null 2>&1) \
    || { echo "run failed ($side): $work/$side.log" >&2; tail -5 "$work/$side.log" >&2; exit 1; }
}
# Per run of a log: CPU seconds, then the last thermo line's atoms, ke, c_1 and (ours) its
# largest overlap (c_health[4], in grain diameters; 0 for stock).
runs() {
  awk '/^ *Step/ {thermo=1; next} thermo && $1 ~ /^[0-9]+$/ {last=$0}
       /^Loop time of/ {t=$4; thermo=0} /% CPU use/ {split(last, f); print t*($1+0)/100, f[2], f[3], f[4], f[8]+0}' "$1"
}

echo "# $(date -u +%F) each run $span time units; stock dt 1e-4 ($stock_steps steps), ours dt $dt ($ours_steps steps), tangential ${TANGENTIAL:-stick}; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
run stock -in "$here/in.pour-stock" -var steps "$stock_steps"
run ours -in "$here/../examples/lammps-granular/in.pour" -var steps "$ours_steps" -var dt "$dt" \
    -var resting "${RESTING:-yes}" -var resolution "${RESOLUTION:-50}" -var skin "${SKIN:-0.5}" -var slop "${SLOP:-0.01}" \
    -var tolerance "${TOLERANCE:-0.3}" -var max_sweeps "${MAX_SWEEPS:-100}" -var tangential "${TANGENTIAL:-stick}" \
    ${OURS_ARGS:-}
paste <(runs "$work/stock.log") <(runs "$work/ours.log") | awk -v span=$span '
  BEGIN {split("pour chute", name)
         printf "%-6s %-9s %-9s %-7s %-7s %-7s %-10s %-10s %-6s %-9s %-9s %-6s %-8s\n", "run", "stock:s", "ours:s",
                "x_stock", "atoms", "ours", "ke_stock", "ke_ours", "ratio", "rot_stock", "rot_ours", "ratio", "overlap"}
  function ratio(a, b) {return b > 0 ? sprintf("%.2f", a / b) : "-"}
  {printf "%-6s %-9.4g %-9.4g %-7.3g %-7d %-7d %-10.4g %-10.4g %-6s %-9.4g %-9.4g %-6s %-8.3g\n", name[NR], $1, $6,
          $1 / $6, $2, $7, $3, $8, ratio($8, $3), $4, $9, ratio($9, $4), $10}'
