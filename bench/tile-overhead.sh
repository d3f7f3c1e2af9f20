#!/bin/bash
# The cost of splitting an image into tiles: renders SCENE whole and as N
# tiles (one process each, one after another, --jobs 1 everywhere), merges
# the tiles, checks that the merged image is the whole one, and prints the
# medians of REPEATS runs: wall-clock seconds and CPU seconds (user + system,
# steadier than wall-clock on a busy machine).
#
#   bench/tile-overhead.sh [SCENE] [SIZE] [N] [REPEATS]
#   dune build --profile release && bench/tile-overhead.sh scenes/cgfs.scene 1920 16 5
#
# The tiles and the merge minus the whole render is the work that splitting
# adds (process start, scene parsing and preparation, writing and reading
# the parts), paid whatever engine runs the tiles. RAYTRACE names the
# command (default: the build in _build/default).
set -euo pipefail
scene=${1:-scenes/cgfs.scene} size=${2:-1920} n=${3:-16} repeats=${4:-5}
raytrace=${RAYTRACE:-_build/default/bin/main.exe}
work=$(mktemp -d "${TMPDIR:-/tmp}/tile-overhead.XXXXXX")
trap 'rm -rf "$work"' EXIT
TIMEFORMAT='%R %U %S'

median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
render() { "$raytrace" render "$scene" --width "$size" --height "$size" --jobs 1 "$@" 2>/dev/null; }
tiles() { for ((i = 1; i <= n; i++)); do render --tile "$i/$n" -o "$work/part-$i.ppm"; done; }
merge() { "$raytrace" merge "$work"/part-*.ppm -o "$work/merged.ppm" 2>/dev/null; }
# "wall cpu" of one run of a function.
measure() { { time "$@"; } 2>&1 | awk '{ print $1, $2 + $3 }'; }

for ((r = 1; r <= repeats; r++)); do
  measure render -o "$work/whole.ppm" >>"$work/whole"
  measure tiles >>"$work/tiles"
  measure merge >>"$work/merge"
  cmp -s "$work/whole.ppm" "$work/merged.ppm" || { echo "the merged image differs from the whole render" >&2; exit 1; }
done

col() { awk -v c="$1" '{ print $c }' "$work/$2" | median; }
awk -v s="$scene" -v z="$size" -v n="$n" -v r="$repeats" \
  -v ww="$(col 1 whole)" -v tw="$(col 1 tiles)" -v mw="$(col 1 merge)" \
  -v wc="$(col 2 whole)" -v tc="$(col 2 tiles)" -v mc="$(col 2 merge)" 'BEGIN {
  printf "%s at %dx%d, %d tiles, --jobs 1, median of %d runs; the merged image is the whole one\n", s, z, z, n, r
  printf "%-30s %10s %10s\n", "seconds", "wall", "cpu"
  printf "%-30s %10.3f %10.3f\n", "whole render", ww, wc
  printf "%-30s %10.3f %10.3f\n", n " tiles, one after another", tw, tc
  printf "%-30s %10.3f %10.3f\n", "merge", mw, mc
  printf "%-30s %10.3f %10.3f\n", "added by splitting", tw + mw - ww, tc + mc - wc
  printf "%-30s %9.1f%% %9.1f%%\n", "  of the whole render", 100 * (tw + mw - ww) / ww, 100 * (tc + mc - wc) / wc
  printf "%-30s %10.1f %10.1f\n", "  per tile, ms", 1000 * (tw + mw - ww) / n, 1000 * (tc + mc - wc) / n
}'
