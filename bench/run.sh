#!/usr/bin/env bash
# Benchmark (not a test): rods and beads in this package against stock LAMMPS, side by side, one
# run after the other. Each system is created once by in.create (in.ours writes it out) and
# stock LAMMPS (in.stock: GRANULAR + RIGID styles only) starts from the same atoms.
#   beads    80 x 12 mm channel (periodic in x, side walls in y), phi_b 0.75, no rods (917 beads)
#   channel  the same channel with 8 rods (phi_r 0.031; 917 beads + 8 x 9 rod spheres)
#   box      in.box-small's 40 x 40 mm periodic box, phi_b 0.80, phi_r 0.03 (1630 beads, 13 rods)
# Sides and plates:
#   ours       the paper decks' defaults: rough plates (rms slope 0.06, 5 um), dt 1e-4 s
#   ours-flat  the same with -var rough 0: flat plates, like for like with stock
#   stock      flat plates (fix wall/gran has no roughness), hooke kn 3.2e5 N/m, dt 1.25e-7 s, no
#              tangential damping: the softest kn of stiffness.sh's scan whose single-rod speed
#              is within 2 % of the stiffest's (README.md); KN, DT_STOCK, XGT override them
#              (KN=2e4 DT_STOCK=5e-7 XGT=1 is the issue's setting)
# Each run settles for WARM simulated seconds, then TIME seconds are timed (LAMMPS's loop time).
# Prints per run: atom-steps/s, simulated seconds per wall-clock hour, and that over stock's.
#   bench/run.sh [--quick] [--np4] [path/to/lmp]
#     --quick  a few hundred steps per run (seconds in all): checks the script, not the machine
#     --np4    also mpirun --oversubscribe -np 4
#   WARM (0.05) and TIME (0.1) override the simulated seconds; CASES="channel box" picks cases;
#   DT_OURS (1e-4) and OURS_ARGS (more -var settings, e.g. "-var resting yes") change ours.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0; nps=(1 2); lmp=$here/../build/lmp
for a in "$@"; do
  case $a in
    --quick) quick=1 ;;
    --np4) nps=(1 2 4) ;;
    *) lmp=$a ;;
  esac
done
lmp=$(cd "$(dirname "$lmp")" && pwd)/$(basename "$lmp")   # absolute: the runs start in bench/
warm=${WARM:-0.05}; time=${TIME:-0.1}
[ $quick = 1 ] && { warm=${WARM:-0}; time=${TIME:-0.002}; }
cases=(${CASES:-beads channel box})
dt_ours=${DT_OURS:-1.0e-4}; dt_stock=${DT_STOCK:-1.25e-7}; kn=${KN:-3.2e5}; xgt=${XGT:-0}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$here"

args_of() {   # the in.create variables of a case
  case $1 in
    beads)   echo "-var geometry channel -var Lx 80e-3 -var Ly 12e-3 -var phi_b 0.75 -var phi_r 0" ;;
    channel) echo "-var geometry channel -var Lx 80e-3 -var Ly 12e-3 -var phi_b 0.75 -var phi_r 0.031" ;;
    box)     echo "-var geometry box -var Lx 40e-3 -var Ly 40e-3 -var phi_b 0.80 -var phi_r 0.03" ;;
  esac
}
launch() {    # np: the launcher words
  if [ "$1" = 1 ]; then echo ""
  elif [ "$1" -gt 2 ]; then echo "mpirun --oversubscribe -np $1"
  else echo "mpirun -np $1"; fi
}
steps_of() { awk -v t="$1" -v dt="$2" 'BEGIN{n=int(t/dt+0.5); if (n<1 && t>0) n=1; print n}'; }
loop() {      # the last "Loop time" line of a log: seconds steps atoms
  awk '/^Loop time of/ {t=$4; s=$9; n=$12} END {if (t=="") exit 1; print t, s, n}' "$1"
}
row() {       # case np side plates dt log stock_simrate
  read -r t s n < <(loop "$6") || { echo "run failed: $6" >&2; tail -5 "$6" >&2; exit 1; }
  awk -v c="$1" -v np="$2" -v side="$3" -v pl="$4" -v dt="$5" -v t="$t" -v s="$s" -v n="$n" -v ref="${7:-}" '
    BEGIN { sim = s*dt/t*3600; ratio = (ref == "") ? "1" : sprintf("%.2f", sim/ref)
            printf "%-8s %-3s %-10s %-6s %-7s %-6d %-8d %-9.3f %-9.1f %-12.4g %-11.4g %s\n",
                   c, np, side, pl, dt, n, s, t, t/s*1e6, n*s/t, sim, ratio }'
}
simrate() { read -r t s n < <(loop "$1"); awk -v t="$t" -v s="$s" -v dt="$2" 'BEGIN{print s*dt/t*3600}'; }

export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1} OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
echo "# lmp: $("$lmp" -h 2>/dev/null | awk '/^Large-scale/ {print $(NF-2), $(NF-1), $NF; exit}'); stock kn $kn x_gammat $xgt dt $dt_stock; WARM $warm s, TIME $time s; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %-3s %-10s %-6s %-7s %-6s %-8s %-9s %-9s %-12s %-11s %s\n' \
  case np side plates dt atoms steps loop_s us/step atom-steps/s sim-s/hour x_stock
for c in "${cases[@]}"; do
  # the system, created once (ours on 1 rank, no dynamics) for the stock side
  "$lmp" -in in.ours $(args_of "$c") -var out "$work/$c" -var steps 0 -log none -echo none \
      >"$work/$c.create.log" 2>&1 || { tail -5 "$work/$c.create.log"; exit 1; }
  by=f; [ "$c" = box ] && by=p
  for np in "${nps[@]}"; do
    L=$(launch "$np")
    $L "$lmp" -in in.stock -var data "$work/$c/system.data" -var by $by -var dt $dt_stock -var kn $kn -var xgt $xgt \
        -var warm "$(steps_of "$warm" $dt_stock)" -var steps "$(steps_of "$time" $dt_stock)" \
        -log "$work/stock.log" -echo none >/dev/null 2>&1 || { tail -5 "$work/stock.log"; exit 1; }
    ref=$(simrate "$work/stock.log" $dt_stock)
    row "$c" "$np" stock flat $dt_stock "$work/stock.log"
    for rough in 0.06 0; do
      side=ours; pl=rough; [ "$rough" = 0 ] && { side=ours-flat; pl=flat; }
      $L "$lmp" -in in.ours $(args_of "$c") -var rough $rough -var out "$work/run" -var dt $dt_ours ${OURS_ARGS:-} \
          -var warm "$(steps_of "$warm" $dt_ours)" -var steps "$(steps_of "$time" $dt_ours)" \
          -log "$work/ours.log" -echo none >/dev/null 2>&1 || { tail -5 "$work/ours.log"; exit 1; }
      row "$c" "$np" $side $pl $dt_ours "$work/ours.log" "$ref"
    done
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
