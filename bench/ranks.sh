#!/usr/bin/env bash
# Benchmark (not a test): what solving islands whole across ranks costs, side by side in one
# call. Each system runs TIME simulated seconds from a shipped state on 1 and on 2 ranks, with
# this checkout's build and, with BASE, another build's (e.g. 57e4d5b, whose islands were split
# between ranks), at the decks' defaults; prints the loop times and the 2-rank efficiency (the
# 1-rank time over twice the 2-rank time):
#   channel   the paper's channel (examples/channel/in.channel, 7650 atoms) at 2000 s: a fluid
#             with moving groups of rods, few islands on a cut
#   jammed    channel-small's jammed corner (515 atoms, total area fraction 0.862): one island
#             across every cut, gathered whole to one rank
#   bench/ranks.sh [--quick]          --quick: a few steps per run (checks the script)
#   BASE=../ag-base bench/ranks.sh    git worktree add ../ag-base 57e4d5b &&
#                                     (cd ../ag-base && bash -c 'source tools/common.sh; prepare_build')
#   TIME (0.1 s; 0.01 s for the jammed corner) overrides the run length; OURS_ARGS adds deck
#   variables to this checkout's runs (e.g. "-var resting newton").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0
for a in "$@"; do case $a in --quick) quick=1 ;; *) echo "unknown argument $a" >&2; exit 2 ;; esac; done
time=${TIME:-0.1}; [ $quick = 1 ] && time=0.002
jammed_time=$(awk -v t="$time" 'BEGIN{print t/10}')
ours=$here/../build/lmp
base=${BASE:+$(cd "$BASE" && pwd)}
mpirun=(mpirun); [ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

loop() { awk '/^Loop time of/ && $9 >= s {t=$4; s=$9} END {if (t=="") exit 1; print t}' "$1"; }    # the longest loop
# one_run lmp examples ranks log deck args...
one_run() {
  local lmp=$1 examples=$2 ranks=$3 log=$4 deck=$5; shift 5
  local launch=(); [ "$ranks" -gt 1 ] && launch=("${mpirun[@]}" -np "$ranks")
  (cd "$examples/channel" && "${launch[@]}" "$lmp" -in "$deck" -var out "$work/out" -var dump 1.0 -var profile 0.1 \
      -log "$log" -echo none "$@" >/dev/null 2>&1) || { echo "run failed: $log" >&2; tail -5 "$log" >&2; exit 1; }
  loop "$log"
}
declare -A args=(
  [channel]="in.channel -var from states/channel-full-2000s.data.gz -var time $(awk -v t="$time" 'BEGIN{printf "%.6f", 2000+t}')"
  [jammed]="in.channel-small -var Lx 30e-3 -var phi_b 0.8203 -var phi_r 0.0414 -var from states/channel-small-jammed-corner-0s.data.gz -var time $jammed_time"
)
sides=(ours); [ -n "$base" ] && sides+=(base)
echo "# $(date -u +%F) TIME $time s (jammed corner $jammed_time s); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %-6s %-10s %-10s %-10s\n' system build 1rank:s 2ranks:s efficiency
for system in channel jammed; do
  for side in "${sides[@]}"; do
    lmp=$ours; examples=$here/../examples
    [ "$side" = base ] && { lmp=$base/build/lmp; examples=$base/examples; }
    mkdir -p "$work/out"
    extra=(); [ "$side" = ours ] && extra=(${OURS_ARGS:-})
    t1=$(one_run "$lmp" "$examples" 1 "$work/$system-$side-1.log" ${args[$system]} "${extra[@]}")
    t2=$(one_run "$lmp" "$examples" 2 "$work/$system-$side-2.log" ${args[$system]} "${extra[@]}")
    printf '%-8s %-6s %-10s %-10s %-10s\n' "$system" "$side" "$t1" "$t2" "$(awk -v a="$t1" -v b="$t2" 'BEGIN{printf "%.0f %%", 100*a/(2*b)}')"
  done
done
