#!/usr/bin/env bash
# Does the bead bed stay agitated? The rms horizontal bead speed of in.beads-vibrated, as a
# fraction of the plate speed amplitude A omega, every 0.1 s for 1 s (after the random start),
# for plate roughness (fix wall/impulse rough: rms slope, 1 mm correlation length) 0 to 0.05.
# Flat plates (0) lock the beads into the plates' rhythm and their horizontal motion decays to
# nothing; rough plates keep a steady agitation.
#   examples/beads-vibrated/agitation_vs_roughness.sh [path/to/lmp] [phi]   (default: build/lmp, 0.75)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${1:-$here/../../build/lmp}
phi=${2:-0.75}
deck=$(mktemp)
trap 'rm -f "$deck"' EXIT
cat > "$deck" <<DECK
variable steps index 0
include $here/in.beads-vibrated
variable kh atom 0.5*mass*(vx*vx+vy*vy)
compute kh all reduce sum v_kh
variable vh equal sqrt(2*c_kh/mass(all))/(2*PI*\${f}*\${A})
thermo_style custom step time v_vh
thermo 10000
run 100000
DECK
printf 'phi %s; rms horizontal bead speed / (A omega) at t = 0, 0.1, ..., 1 s\n' "$phi"
for rough in 0 0.01 0.02 0.05; do
  printf 'rough %-5s' "$rough"
  "$lmp" -in "$deck" -var rough "$rough" -var rough_length 1e-3 -var phi "$phi" -log none -echo none 2>/dev/null |
    awk '/^ +Step/ {on=1; next} /^Loop time/ {on=0} on && NF==3 {printf " %.3g", $3} END {print ""}'
done
