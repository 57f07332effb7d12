#!/usr/bin/env bash
# Benchmark (not a test): the bead monolayer of in.beads-vibrated with this package's impulse
# contacts (dt 1e-5 s, restitution within 2 %: see restitution_vs_dt.sh) against stock LAMMPS
# GRANULAR (pair_style granular Hertz/Mindlin + fix wall/gran ... wiggle, aluminium's modulus,
# dt 2e-7 s, ~25 steps per Hertz contact). Prints atom-steps/s and simulated seconds per
# wall-clock hour of each. Both on flat plates (stock fix wall/gran has no roughness).
#   examples/beads-vibrated/bench.sh [path/to/lmp] [nx ny]   (default: build/lmp, 36 20 = 1440 beads)
#   NP=2 examples/beads-vibrated/bench.sh                    (under mpirun -np 2)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${1:-$here/../../build/lmp}
nx=${2:-36}
ny=${3:-20}
np=${NP:-1}
launcher=()
[ "$np" -gt 1 ] && launcher=(mpirun -np "$np")

run() {    # model dt steps
  "${launcher[@]}" "$lmp" -in "$here/in.beads-vibrated" -var model "$1" -var dt "$2" -var steps "$3" -var rough 0 \
      -var nx "$nx" -var ny "$ny" -log none -echo none |
    awk -v model="$1" -v dt="$2" -v steps="$3" '
      /^Loop time of/ {t=$4; n=$(NF-1)}
      END { printf "%-8s %-8s %-8d %-7d %-10.3f %-14.4g %.4g\n", model, dt, steps, n, t, n*steps/t, steps*dt/t*3600 }'
}
printf '%-8s %-8s %-8s %-7s %-10s %-14s %s\n' model dt steps atoms loop_s atom-steps/s sim-s/hour
run impulse 1.0e-5 10000
run stock   2.0e-7 10000
