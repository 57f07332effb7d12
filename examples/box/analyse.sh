#!/usr/bin/env bash
# Pictures and profiles from a square-box run, with python/activegrain (lengths in bead diameters).
#   examples/box/analyse.sh OUTDIR      (OUTDIR holds box.dump from in.box*)
# Writes snapshot.png (last frame), map.png (bead area fraction, mean over the run), profile_x.png/.txt
# and profile_y.png/.txt (bead and rod area fraction along x and y), kymograph.png (beads along x
# against time), polar.txt (rod order per frame) and phase.txt (phase per frame).
set -euo pipefail
out=${1:?usage: analyse.sh OUTDIR}
source "$(dirname "$0")/../analyse-common.sh"
dump="$out/box.dump"
common=(--geometry box --length-unit 1e-3 --timestep "$timestep")
ag snapshot "$dump" "${common[@]}" --frame -1 -o "$out/snapshot.png"
ag map "$dump" "${common[@]}" --every 10 --bins 50 50 --species beads -o "$out/map.png"
for coord in x y; do
  ag profile "$dump" "${common[@]}" --coord $coord --species all --plot "$out/profile_$coord.png" > "$out/profile_$coord.txt"
done
ag kymograph "$dump" "${common[@]}" --coord x -o "$out/kymograph.png"
ag phase "$dump" "${common[@]}" --every 10 > "$out/phase.txt"
ag polar "$dump" "${common[@]}" --every 10 > "$out/polar.txt"
