#!/usr/bin/env bash
# Pictures and profiles from an annulus run, with python/activegrain (lengths in bead diameters).
#   examples/annulus/analyse.sh OUTDIR [R_IN R_OUT]
# OUTDIR holds annulus.dump from in.annulus*; R_IN and R_OUT are the radii of the run in bead
# diameters (default 40 60, as in.annulus; 6 20 for in.annulus-small). A floral cell is analysed
# as the annulus of radius R_OUT (its lobes are drawn and binned as if cut off).
# Writes snapshot.png (last frame), profile_r.png/.txt (radial), profile_theta.png/.txt (angular),
# kymograph.png (bead area fraction against angle and time), polar.txt (rod order per frame, with
# the tangential order), phase.txt (phase per frame) and condensate.txt (the dense arc, its drift
# round the ring and the rods pressing on its ends, per frame: the trap of the paper's Fig. 3).
set -euo pipefail
out=${1:?usage: analyse.sh OUTDIR [R_IN R_OUT]}
r_in=${2:-40}
r_out=${3:-60}
source "$(dirname "$0")/../analyse-common.sh"
dump="$out/annulus.dump"
common=(--geometry annulus --centre 0 0 --r-in "${r_in}e-3" --r-out "${r_out}e-3" --length-unit 1e-3 --timestep "$timestep")
ag snapshot "$dump" "${common[@]}" --frame -1 -o "$out/snapshot.png"
for coord in r theta; do
  ag profile "$dump" "${common[@]}" --coord $coord --species all --plot "$out/profile_$coord.png" > "$out/profile_$coord.txt"
done
ag kymograph "$dump" "${common[@]}" --coord theta -o "$out/kymograph.png"
ag phase "$dump" "${common[@]}" --every 10 > "$out/phase.txt"
ag polar "$dump" "${common[@]}" --every 10 > "$out/polar.txt"
ag condensate "$dump" "${common[@]}" > "$out/condensate.txt"
