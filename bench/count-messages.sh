#!/usr/bin/env bash
# Measurement (not a test): the MPI traffic of a time step, per rank, counted by mpi_counts.c
# (a PMPI library preloaded under mpirun): point-to-point messages and bytes sent, the ranks sent
# to, and the collectives (MPI_Allreduce and the rest) per step. Each case runs twice from the
# same start, for N and for 2N steps; the difference over N is one step's traffic, without the
# setup's, the deck's reading and the output at the end. Cases:
#   bench  run.sh's channel case: bench/in.ours, 80 x 12 mm, periodic in x, phi_b 0.75, 8 rods
#          (989 atoms), WARM steps from the created state, then N = STEPS steps
#   box    run.sh's box case: 40 x 40 mm, periodic in x and y, phi_b 0.80, 13 rods (1747 atoms),
#          the same way: a grid in both directions from 4 ranks on (2 x 2, 4 x 2)
#   paper  the paper's channel, examples/channel/in.channel (249 x 31 mm, 7650 atoms), continued
#          from its state after RELAX simulated seconds (one run on 2 ranks, first), for
#          N = TIME / dt steps; RELAX=0 counts from the created state
# on each rank count of NPS, with the processor grid LAMMPS picks for the decks (they set none:
# strips along x for the channels). Prints per case and rank count: the grid, atoms and ghosts
# per rank (LAMMPS's Nlocal and Nghost, the longer run's averages over ranks), and per rank and
# step the messages sent (mean and max over ranks), the kilobytes sent (mean, max), the ranks
# sent to in the N steps (max), MPI_Allreduce calls and all other collectives (the same on every
# rank), and the neighbour-list builds per step (each moves atoms between ranks and rebuilds the
# ghosts: a few more messages).
#   bench/count-messages.sh [--quick] [path/to/lmp]     (default ../build/lmp)
#     --quick  a few steps per run, 2 ranks, RELAX 0 (seconds in all): checks the script
#   NPS ("2 4 8"), CASES ("bench box paper"), WARM (100), STEPS (500), RELAX (0.2), TIME (0.02)
#   override the defaults. About 3 min on 2 busy cores.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0; lmp=$here/../build/lmp
for a in "$@"; do
  case $a in --quick) quick=1 ;; -*) echo "unknown argument $a" >&2; exit 2 ;; *) lmp=$a ;; esac
done
lmp=$(cd "$(dirname "$lmp")" && pwd)/$(basename "$lmp")   # absolute: the runs start elsewhere
nps=(${NPS:-2 4 8}); cases=(${CASES:-bench box paper})
warm=${WARM:-100}; steps=${STEPS:-500}; relax=${RELAX:-0.2}; time=${TIME:-0.02}
[ $quick = 1 ] && { nps=(${NPS:-2}); warm=${WARM:-10}; steps=${STEPS:-20}; relax=${RELAX:-0}; time=${TIME:-0.002}; }
dt=1.0e-4    # the decks' time step
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mpicc -shared -fPIC -O2 -o "$work/libmpi_counts.so" "$here/mpi_counts.c"
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1} OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}

# np tag dir log lmp-args...: one counted run, from dir; its counts go to $work/tag/counts.<rank>
counted() {
  local np=$1 tag=$2 dir=$3 log=$4; shift 4
  mkdir -p "$work/$tag"
  (cd "$dir" && MPI_COUNTS_DIR=$work/$tag mpirun --allow-run-as-root --oversubscribe -np "$np" \
      -x LD_PRELOAD="$work/libmpi_counts.so" -x MPI_COUNTS_DIR "$lmp" -log "$log" -echo none "$@" \
      >/dev/null 2>&1) || { echo "run failed: $log" >&2; tail -5 "$log" >&2; exit 1; }
}
# case np short long n: the table's row from the counts of the two runs (n steps apart)
row() {
  local grid ghosts nlocal
  grid=$(awk '/MPI processor grid/ {print $1 "x" $3 "x" $5; exit}' "$work/$3.log")
  nlocal=$(awk '/^Nlocal:/ {v=$2} END {print v}' "$work/$4.log")
  ghosts=$(awk '/^Nghost:/ {v=$2} END {print v}' "$work/$4.log")
  builds="$(awk '/^Neighbor list builds/ {v=$5} END {print v}' "$work/$3.log") $(awk '/^Neighbor list builds/ {v=$5} END {print v}' "$work/$4.log")"
  for f in "$work/$3"/counts.*; do
    r=${f##*.}; paste -d' ' "$f" "$work/$4/counts.$r"
  done | awk -v c="$1" -v np="$2" -v n="$5" -v grid="$grid" -v nl="$nlocal" -v ng="$ghosts" -v nb="$builds" '
    { h = NF/2                  # fields 1..h: the short run, h+1..NF: the long one
      delete d; p = 0; o = 0
      for (i = 3; i < h; i += 2) d[$i] = ($(h+i+1) - $(i+1)) / n
      m += d["send"]; b += d["send_bytes"]; k++
      if (d["send"] > mm) mm = d["send"]; if (d["send_bytes"] > bm) bm = d["send_bytes"]
      for (x in d) if (x ~ /^to/) p += d[x] > 0     # ranks sent to in these n steps
      if (p > pm) pm = p
      ar = d["allreduce"]
      for (x in d) if (x !~ /_bytes$/ && x !~ /^to/ && x != "send" && x != "allreduce") o += d[x] }
    END { split(nb, B, " ")
          printf "%-6s %-5s %-7s %-7.0f %-7.0f %-7.1f %-7.1f %-8.1f %-8.1f %-5d %-9.2f %-10.2f %.3f\n",
                 c, np, grid, nl, ng, m/k, mm, b/k/1e3, bm/1e3, pm, ar, o, (B[2]-B[1])/n }'
}

echo "# $(date -u +%F) WARM $warm STEPS $steps (bench), RELAX $relax TIME $time (paper); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-6s %-5s %-7s %-7s %-7s %-7s %-7s %-8s %-8s %-5s %-9s %-10s %s\n' case ranks grid atoms/r ghost/r \
  msg/step max kB/step max peers allreduce other_coll builds/step
for c in "${cases[@]}"; do
  case $c in
    bench|box)
      args=(-in in.ours -var geometry channel -var Lx 80e-3 -var Ly 12e-3 -var phi_b 0.75 -var phi_r 0.031)
      [ $c = box ] && args=(-in in.ours -var geometry box -var Lx 40e-3 -var Ly 40e-3 -var phi_b 0.80 -var phi_r 0.03)
      for np in "${nps[@]}"; do
        counted "$np" $c$np-1 "$here" "$work/$c$np-1.log" "${args[@]}" -var dt $dt -var warm "$warm" \
            -var out "$work/o$c$np-1" -var steps "$steps"
        counted "$np" $c$np-2 "$here" "$work/$c$np-2.log" "${args[@]}" -var dt $dt -var warm "$warm" \
            -var out "$work/o$c$np-2" -var steps $((2*steps))
        row $c "$np" $c$np-1 $c$np-2 "$steps"
      done ;;
    paper)
      dir=$here/../examples/channel; from=()
      if [ "$(awk -v r="$relax" 'BEGIN{print (r > 0)}')" = 1 ]; then
        (cd "$dir" && mpirun --allow-run-as-root -np 2 "$lmp" -in in.channel -var out "$work/relax" \
            -var time "$relax" -var dump 1.0 -log "$work/relax.log" -echo none >/dev/null 2>&1) \
          || { echo "relaxation failed" >&2; tail -5 "$work/relax.log" >&2; exit 1; }
        from=(-var continue "$work/relax/channel.restart.final")
      fi
      n=$(awk -v t="$time" -v dt=$dt 'BEGIN{print int(t/dt+0.5)}')
      t1=$(awk -v r="$relax" -v t="$time" 'BEGIN{print r+t}'); t2=$(awk -v r="$relax" -v t="$time" 'BEGIN{print r+2*t}')
      for np in "${nps[@]}"; do
        counted "$np" p$np-1 "$dir" "$work/p$np-1.log" -in in.channel "${from[@]}" -var out "$work/op$np-1" -var time "$t1" -var dump 1.0
        counted "$np" p$np-2 "$dir" "$work/p$np-2.log" -in in.channel "${from[@]}" -var out "$work/op$np-2" -var time "$t2" -var dump 1.0
        row paper "$np" p$np-1 p$np-2 "$n"
      done ;;
    *) echo "unknown case $c" >&2; exit 2 ;;
  esac
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
