#!/usr/bin/env bash
# Benchmark (not a test): the cost of dense packings, side by side in one call. The channel of
# examples/channel/in.channel-small, 30 x 15 mm (Lx 30e-3), rods at phi_r 0.0414, beads from a
# fluid to the jammed corner of the phase diagram (total area fraction 0.70 to 0.862), each
# grown once (-var start grow, the state written with -var state), vibrated for WARM simulated
# seconds (resting yes) into a second state, and then run for TIME simulated seconds from that
# one (1 rank, LAMMPS's loop time), with pair gran/impulse:
#   impacts   resting no (every contact through the compliant impacts)
#   resting   resting yes (resting contacts solved together: docs/pair_gran_impulse.rst)
#   newton    resting newton (the same, keeping the restitution of collisions)
#   base      another build's plugin, e.g. an earlier commit (BASE: its checkout with build/),
#             on its own decks, from the same states (the fluid row only, for a build that
#             cannot read states)
# and the fluid reference: the same deck at its defaults (phi_b 0.75) from its own created start;
# then channel-small's condensate (its shipped state at 500 s, 60 x 15 mm) for TIME s, and the
# shipped states of a fluid (channel-small at 600 s) and of the jammed corner (grown, at rest) for
# TIME s each, the second over the first.
# The grow start leaves a packing at rest, without gravity or vibration: its first few vibration
# periods cost more (bench/README.md), so the packings are timed from vibrated states, as a long
# run spends its steps; the fluid settles into its steady cost from the start. Prints CPU us per
# atom-step (the loop time times its CPU use, so that a busy machine slows every row alike) and
# that over the fluid's (of the same side).
#   bench/dense.sh [--quick]         --quick: a few steps per run (checks the script)
#   BASE=../ag-base bench/dense.sh   with a baseline: git worktree add ../ag-base 8ca6466 &&
#                                    (cd ../ag-base && bash -c 'source tools/common.sh; prepare_build')
#   BASE_ARGS="-var resting yes"     the baseline's deck variables (default: none)
#   TIME (0.1), WARM (0.05) and PHI_B ("0.6586 0.7186 0.7586 0.7986 0.8203") override the
#   defaults; WARM=0 times the packings from their grown states.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0
for a in "$@"; do case $a in --quick) quick=1 ;; *) echo "unknown argument $a" >&2; exit 2 ;; esac; done
time=${TIME:-0.1}; [ $quick = 1 ] && time=${TIME:-0.002}
warm=${WARM:-0.05}; [ $quick = 1 ] && warm=${WARM:-0.002}
phis=(${PHI_B:-0.6586 0.7186 0.7586 0.7986 0.8203})
phi_r=0.0414
ours=$here/../build/lmp
base=${BASE:+$(cd "$BASE" && pwd)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

loop() {    # CPU seconds (the loop's wall time times its CPU use), steps and atoms of the last loop
  awk '/^Loop time of/ {t=$4; s=$9; n=$12} /% CPU use/ {c=$1+0} END {if (t=="") exit 1; print t*c/100, s, n}' "$1"
}
# side lmp deck_dir log end extra-args...: one timed run of in.channel-small, to simulated time end
run() {
  local side=$1 lmp=$2 dir=$3 log=$4 end=$5; shift 5
  (cd "$dir" && "$lmp" -in in.channel-small -var time "$end" -var dump 1.0 \
      -var out "$work/out-$side" -log "$log" -echo none "$@" >/dev/null 2>&1) \
    || { echo "run failed ($side): $log" >&2; tail -5 "$log" >&2; exit 1; }
}
# warm_deck phi_b extra-args...: ours at resting yes, untimed (the warm-up and its state)
warm_deck() {
  local phi_b=$1; shift
  (cd "$here/../examples/channel" && "$ours" -in in.channel-small -var Lx 30e-3 -var phi_b "$phi_b" \
      -var phi_r $phi_r -var resting yes -var dump 1.0 -var out "$work/out-warm" -echo none "$@" >/dev/null 2>&1)
}
cost() { read -r t s n < <(loop "$1"); awk -v t="$t" -v s="$s" -v n="$n" 'BEGIN{printf "%.4g", t/(s*n)*1e6}'; }
atoms_in() { gzip -dc "$1" | awk '/ atoms$/ && !n {n = $1} END {print n}'; }    # a state's atom count
# a build from before states (no in.read-state) times the fluid rows only: prints its empty cells
cannot_read_states() {
  [ "$1" = base ] && [ ! -f "$base/examples/rods-and-beads/in.read-state" ] && printf ' %-12s %-10s' - -
}
mkdir -p "$work"/out-{impacts,resting,newton,base,warm}

sides=(impacts resting newton); [ -n "$base" ] && sides+=(base)
lmp_of() { case $1 in base) echo "$base/build/lmp" ;; *) echo "$ours" ;; esac; }
dir_of() { case $1 in base) echo "$base/examples/channel" ;; *) echo "$here/../examples/channel" ;; esac; }
args_of() {
  case $1 in impacts) echo "-var resting no" ;; resting) echo "-var resting yes" ;; newton) echo "-var resting newton" ;;
    base) echo "${BASE_ARGS:-}" ;; esac
}

echo "# $(date -u +%F) TIME $time s after WARM $warm s; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
declare -A fluid densest
for side in "${sides[@]}"; do
  run "$side" "$(lmp_of $side)" "$(dir_of $side)" "$work/fluid-$side.log" "$time" -var Lx 30e-3 $(args_of $side)
  fluid[$side]=$(cost "$work/fluid-$side.log")
done
printf '%-8s %-8s %-7s %-6s' total phi_b phi_r atoms
for side in "${sides[@]}"; do printf ' %-12s %-10s' "$side:us" "x_fluid"; done; echo
printf '%-8s %-8s %-7s %-6s' fluid 0.75 0.04 "$(loop "$work/fluid-impacts.log" | cut -d' ' -f3)"
for side in "${sides[@]}"; do printf ' %-12s %-10s' "${fluid[$side]}" 1; done; echo
# channel-small's condensate (60 x 15 mm, the shipped state at 500 s), TIME s from it
condensed_state=states/channel-small-condensed-500s.data.gz
printf '%-8s %-8s %-7s %-6s' condensed 0.75 0.04 "$(atoms_in "$here/../examples/channel/$condensed_state")"
for side in "${sides[@]}"; do
  cannot_read_states "$side" && continue
  log="$work/condensed-$side.log"
  run "$side" "$(lmp_of $side)" "$(dir_of $side)" "$log" "$(awk -v b="$time" 'BEGIN{print 500 + b}')" \
      -var from "$condensed_state" $(args_of $side)
  c=$(cost "$log")
  printf ' %-12s %-10s' "$c" "$(awk -v a="$c" -v b="${fluid[$side]}" 'BEGIN{printf "%.2f", a/b}')"
done
echo
# From the shipped states, as a run starts from them, TIME s each: channel-small's fluid at 600 s
# (60 x 15 mm, phi_b 0.75, run at the decks' defaults) and the jammed corner's grown state (total
# 0.862, at rest when the run starts); the second over the first.
declare -A shipped
shipped_row() {    # label state start extra-args...
  local label=$1 state=$2 start=$3; shift 3
  printf '%-25s %-6s' "$label" "$(atoms_in "$here/../examples/channel/$state")"
  for side in "${sides[@]}"; do
    cannot_read_states "$side" && continue
    local log="$work/shipped-$label-$side.log"
    run "$side" "$(lmp_of $side)" "$(dir_of $side)" "$log" "$(awk -v a="$start" -v b="$time" 'BEGIN{print a + b}')" \
        -var from "$state" "$@" $(args_of $side)
    local c; c=$(cost "$log")
    [ "$label" = fluid-600s ] && shipped[$side]=$c
    printf ' %-12s %-10s' "$c" "$(awk -v a="$c" -v b="${shipped[$side]}" 'BEGIN{printf "%.2f", a/b}')"
  done
  echo
}
printf '%-25s %-6s' "shipped state" atoms
for side in "${sides[@]}"; do printf ' %-12s %-10s' "$side:us" "x_fluid600"; done; echo
shipped_row fluid-600s states/channel-small-mu0.003-seed2-600s.data.gz 600
shipped_row jammed-corner-0s states/channel-small-jammed-corner-0s.data.gz 0 \
    -var Lx 30e-3 -var phi_b 0.8203 -var phi_r 0.0414
for phi_b in "${phis[@]}"; do
  # the grown state, made once with ours (the grow start always reaches phi_b)
  (cd "$here/../examples/channel" && "$ours" -in in.channel-small -var Lx 30e-3 -var phi_b "$phi_b" \
      -var phi_r $phi_r -var start grow -var out "$work/out-impacts" -var state "$work/state-$phi_b" \
      -log "$work/grow-$phi_b.log" -echo none >/dev/null 2>&1) \
    || { echo "grow failed: phi_b $phi_b" >&2; tail -5 "$work/grow-$phi_b.log" >&2; exit 1; }
  state=$(ls "$work/state-$phi_b"-*s.data.gz)
  if awk -v w="$warm" 'BEGIN{exit !(w > 0)}'; then    # vibrated for WARM s into a state at that time
    warm_deck "$phi_b" -var from "$state" -var time "$warm" -log "$work/warm-$phi_b.log" \
      && warm_deck "$phi_b" -var continue "$work/out-warm/channel.restart.final" -var time "$warm" \
          -var state "$work/warm-$phi_b" -log "$work/warm-state-$phi_b.log" \
      || { echo "warm-up failed: phi_b $phi_b" >&2; tail -5 "$work/warm-$phi_b.log" >&2; exit 1; }
    state=$(ls "$work/warm-$phi_b"-*s.data.gz)
  fi
  atoms=$(atoms_in "$state")
  printf '%-8s %-8s %-7s %-6s' "$(awk -v a="$phi_b" -v b=$phi_r 'BEGIN{printf "%.3f", a+b}')" "$phi_b" $phi_r "$atoms"
  for side in "${sides[@]}"; do
    cannot_read_states "$side" && continue
    log="$work/$phi_b-$side.log"
    run "$side" "$(lmp_of $side)" "$(dir_of $side)" "$log" "$(awk -v a="$warm" -v b="$time" 'BEGIN{print a + b}')" \
        -var Lx 30e-3 -var phi_b "$phi_b" -var phi_r $phi_r \
        -var from "$state" $(args_of $side)
    c=$(cost "$log")
    densest[$side]=$c
    printf ' %-12s %-10s' "$c" "$(awk -v a="$c" -v b="${fluid[$side]}" 'BEGIN{printf "%.1f", a/b}')"
  done
  echo
done
# the cost of the densest packing with resting yes and newton over the deck's default fluid (resting no)
for side in resting newton; do
  echo "# densest ($(args_of $side | cut -d' ' -f2-)) over the default fluid (resting no): $(awk -v a="${densest[$side]}" -v b="${fluid[impacts]}" 'BEGIN{printf "%.2f", a/b}')"
done
