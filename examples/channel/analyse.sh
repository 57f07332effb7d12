#!/usr/bin/env bash
# Pictures and profiles from a channel run, with python/activegrain (lengths in bead diameters,
# times in seconds); the profile and the kymograph are both of the beads' area fraction.
#   examples/channel/analyse.sh OUTDIR      (OUTDIR holds channel.dump from in.channel*)
set -euo pipefail
out=${1:?usage: analyse.sh OUTDIR}
source "$(dirname "$0")/../analyse-common.sh"
dump="$out/channel.dump"
common=(--geometry channel --length-unit 1e-3 --timestep "$timestep")
ag snapshot "$dump" "${common[@]}" --frame -1 -o "$out/snapshot.png"
ag profile "$dump" "${common[@]}" --coord x --species beads --plot "$out/profile.png" > "$out/profile.txt"
ag kymograph "$dump" "${common[@]}" --coord x --species beads -o "$out/kymograph.png"
ag phase "$dump" "${common[@]}" --every 10 > "$out/phase.txt"
ag polar "$dump" "${common[@]}" --every 10 > "$out/polar.txt"
