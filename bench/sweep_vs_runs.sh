#!/bin/sh
# A sweep of N points of sphere_roll (friction coefficient from 0.05 to 0.5) in one
# `stiction sweep` process against the same N points as N separate `stiction run --no-video
# --no-plots` calls (what a shell loop over --set does). Prints both wall times.
#   bench/sweep_vs_runs.sh [N] [BINARY]     (defaults: 1000, build/src/app/stiction)
set -eu
n=${1:-1000}
bin=${2:-build/src/app/stiction}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$bin" "$work/stiction"  # a rebuild during the benchmark must not change the binary
bin=$work/stiction
now() { date +%s.%N; }

start=$(now)
"$bin" sweep sphere_roll --vary "impedances.ground.mu=0.05:0.5:$n" --keep none --quiet \
    --out "$work/sweep"
sweep=$(awk "BEGIN { print $(now) - $start }")

# The same values, as the sweep formats them (the mu column of its table).
cut -d, -f2 "$work/sweep/sweep.csv" | tail -n +2 > "$work/values"
start=$(now)
i=0
while read -r mu; do
  "$bin" run sphere_roll --no-video --no-plots --quiet --set "impedances.ground.mu=$mu" \
      --out "$work/run"
  i=$((i + 1))
done < "$work/values"
runs=$(awk "BEGIN { print $(now) - $start }")

echo "sphere_roll, $n points ($(nproc) cores):"
printf '  one stiction sweep (-j %s):      %8.1f s\n' "$(nproc)" "$sweep"
printf '  %d separate stiction run calls: %8.1f s  (%.1fx the sweep)\n' "$i" "$runs" \
    "$(awk "BEGIN { print $runs / $sweep }")"
