#!/bin/sh
# End-to-end sphere_roll video (BM_SphereRollVideo: 121 frames at 1280x720, render + H.264)
# of this build against the build before the video work of issue 13 (commit 71058f3),
# run alternately so that the machine's load hits both alike. Prints each pair of fps and
# the median of the ratios (goal of issue 13: >= 1.3).
#   bench/video_speedup.sh [ROUNDS] [BUILD]     (defaults: 5, build)
# The old build goes to ../stiction-base (a git worktree, built once, Release).
set -eu
rounds=${1:-5}
build=${2:-build}
base=../stiction-base
if [ ! -x "$base/build/bench/render/bench_render" ]; then
  [ -d "$base" ] || git worktree add --detach "$base" 71058f3
  cmake -S "$base" -B "$base/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$base/build" --target bench_render >/dev/null
fi
cmake --build "$build" --target bench_render >/dev/null
fps() {
  "$1" --benchmark_filter=BM_SphereRollVideo 2>/dev/null |
    sed -n 's/.*fps=\([0-9.]*\).*/\1/p'
}
ratios=""
i=1
while [ "$i" -le "$rounds" ]; do
  old=$(fps "$base/build/bench/render/bench_render")
  new=$(fps "$build/bench/render/bench_render")
  ratio=$(awk "BEGIN { printf \"%.3f\", $new / $old }")
  echo "round $i: before $old fps, now $new fps, ratio $ratio"
  ratios="$ratios $ratio"
  i=$((i + 1))
done
echo "$ratios" | tr ' ' '\n' | sed '/^$/d' | sort -g |
  awk '{ r[NR] = $1 } END { printf "median ratio %.3f over %d rounds\n", (NR % 2 ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2), NR }'
