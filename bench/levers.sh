#!/usr/bin/env bash
# Benchmark (not a test): the two speed levers on the paper's channel (examples/channel/in.channel,
# 249 x 31 d, 7650 atoms), side by side in one call, from its shipped state at 2000 s
# (examples/channel/states/channel-full-2000s.data.gz), TIME simulated seconds each on 1 rank:
#   decks      the decks' settings (resting no, dt 1e-4)
#   resting    -var resting yes
#   dt2e-4     -var dt 2e-4
#   both       -var resting yes -var dt 2e-4
# Prints CPU seconds of each loop (the loop time times its CPU use, so that a busy machine slows
# every row alike) and the speed-up over the decks' settings.
#   bench/levers.sh [--quick]      --quick: a few steps per run (checks the script)
#   TIME (0.1) overrides the simulated time.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quick=0
for a in "$@"; do case $a in --quick) quick=1 ;; *) echo "unknown argument $a" >&2; exit 2 ;; esac; done
time=${TIME:-0.1}; [ $quick = 1 ] && time=${TIME:-0.002}
state=states/channel-full-2000s.data.gz
lmp=$here/../build/lmp
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

loop() {    # CPU seconds (the loop's wall time times its CPU use) and steps of the last loop
  awk '/^Loop time of/ {t=$4; s=$9} /% CPU use/ {c=$1+0} END {if (t=="") exit 1; print t*c/100, s}' "$1"
}

cd "$here/../examples/channel"
end=$(awk -v t="$time" 'BEGIN {printf "%.6f", 2000 + t}')
printf '%-8s %-32s %10s %8s %10s\n' case variables "CPU s" steps speed-up
reference=
for name in decks resting dt2e-4 both; do
  case $name in
    decks) vars=() ;;
    resting) vars=(-var resting yes) ;;
    dt2e-4) vars=(-var dt 2e-4) ;;
    both) vars=(-var resting yes -var dt 2e-4) ;;
  esac
  "$lmp" -in in.channel -var out "$work/$name" -var from "$state" -var time "$end" \
    "${vars[@]}" -log "$work/$name.log" > "$work/$name.screen" 2>&1 \
    || { echo "$name failed: see its log" >&2; tail -n 5 "$work/$name.screen" >&2; exit 1; }
  read -r cpu steps < <(loop "$work/$name.log")
  reference=${reference:-$cpu}
  printf '%-8s %-32s %10.2f %8d %10.2f\n' "$name" "${vars[*]:-(none)}" "$cpu" "$steps" \
    "$(awk -v r="$reference" -v c="$cpu" 'BEGIN {print r / c}')"
done
