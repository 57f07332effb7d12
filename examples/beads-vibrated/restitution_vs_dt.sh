#!/usr/bin/env bash
# Effective restitution of a bead bouncing on a still plate under gravity versus the time step:
# e_eff = sqrt(h2/h1) from the first two apex heights, for drops of 0.08 to 0.12 mm (impact
# speeds ~4.4 cm/s, like the beads' play between the plates; several heights sample the phase
# of the impact within a step). Prints dt, steps per 200 Hz period, the e_eff range and the
# largest relative error.
#   examples/beads-vibrated/restitution_vs_dt.sh [path/to/lmp]   (default: build/lmp; DTS="..." other steps)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${1:-$here/../../build/lmp}
e=0.3
printf '%-8s %-14s %-10s %-10s %s\n' dt steps/period e_eff_min e_eff_max max_rel_error
for dt in ${DTS:-1e-6 2e-6 5e-6 1e-5 2e-5 5e-5 1e-4}; do
  for h in 0.80e-4 0.87e-4 0.93e-4 1.00e-4 1.07e-4 1.13e-4 1.20e-4; do
    "$lmp" -in "$here/in.bounce" -var dt $dt -var e $e -var h $h -log none -echo none 2>/dev/null |
      awk '/^ +Step/ {on=1; next} /^Loop time/ {on=0}
           on && NF==2 {z[n++]=$2}
           END { a0=z[0]; for (i=1;i<n-1;i++) if (z[i]>=z[i-1] && z[i]>z[i+1] && z[i]>1e-9) { print sqrt(z[i]/a0); exit } }'
  done | awk -v dt=$dt -v e=$e 'NR==1 {lo=$1; hi=$1} {if ($1<lo) lo=$1; if ($1>hi) hi=$1}
      END { err=(hi-e>e-lo)?(hi-e)/e:(e-lo)/e; printf "%-8s %-14.0f %-10.5f %-10.5f %.4f\n", dt, 1/(200*dt), lo, hi, err }'
done
