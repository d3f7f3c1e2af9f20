#!/bin/bash
# A thousand instances of the 1M-triangle torus knot against one knot
# (issue 26, item 4): writes the knot (bench/gen.exe), a scene of one knot
# (one), the same picture made by one instance of it (use: the cost of the
# indirection alone), and two of 1,000 instances of it ((define knot ...), then 1,000
# (use knot ...), each turned its own way): in a 10x10x10 block (block: a
# ray crosses the boxes of ten knots or more) and in one layer of 40x25
# facing the camera (wall: a ray meets one knot's box, or two); and
# field, 1,000 instances as a user places them: standing on a floor (a
# plane) in 25 columns and 40 rows receding toward the horizon, each
# shifted and turned its own way, under another camera. Renders each at
# WIDTHxHEIGHT with --jobs JOBS, in alternation REPEATS times, and prints
# per scene the median wall-clock seconds, the median CPU seconds (user +
# system: steadier than wall-clock on a busy machine), the largest peak
# resident memory (GNU time's maximum resident set size) and the fraction
# of the picture's pixels that show a knot (red above blue: the knots'
# colour, not the floor's nor the black background).
#
#   bench/instances.sh [REPEATS] [WIDTH] [HEIGHT] [JOBS]
#   dune build --profile release && bench/instances.sh 3 1920 1080 1
#
# RAYTRACE and GEN name the commands (default: the builds in _build/default).
set -euo pipefail
repeats=${1:-3} width=${2:-1920} height=${3:-1080} jobs=${4:-1}
raytrace=${RAYTRACE:-_build/default/bin/main.exe}
gen=${GEN:-_build/default/bench/gen.exe}
work=$(mktemp -d "${TMPDIR:-/tmp}/instances.XXXXXX")
trap 'rm -rf "$work"' EXIT

"$gen" knot --segments 31250 --sides 16 -o "$work/knot.obj"
# The canvas, the camera ($1, or the knots' front view) and the lights.
head() {
  cat <<SCENE
(canvas (width $width) (height $height))
(viewport (width 1.7777777777777777) (height 1) (distance 1))
${1:-(camera (position 0 0 -9) (look-at 0 0 0))}
(light ambient (intensity 0.2))
(light point (intensity 0.6) (position -6 8 -10))
(light directional (intensity 0.2) (direction 1 3 -2))
SCENE
}
{
  head
  echo '(mesh (file "knot.obj") (color 200 120 60) (specular 100) (smooth true) (scale 1.2))'
} >"$work/one.scene"
{
  head
  echo '(define knot (mesh (file "knot.obj") (color 200 120 60) (specular 100) (smooth true)))'
  echo '(use knot (transform ((scale 1.2))))'
} >"$work/use.scene"
{
  head
  echo '(define knot (mesh (file "knot.obj") (color 200 120 60) (specular 100) (smooth true)))'
  for ((i = 0; i < 10; i++)); do
    for ((j = 0; j < 10; j++)); do
      for ((k = 0; k < 10; k++)); do
        x=$(awk "BEGIN { print ($i - 4.5) * 0.75 }") y=$(awk "BEGIN { print ($j - 4.5) * 0.45 }") z=$(awk "BEGIN { print ($k - 4.5) * 0.75 }")
        echo "(use knot (transform ((scale 0.11) (rotate-x $((i * 37 + k * 11))) (rotate-y $((j * 23 + k * 7))) (translate $x $y $z))))"
      done
    done
  done
} >"$work/block.scene"
{
  head
  echo '(define knot (mesh (file "knot.obj") (color 200 120 60) (specular 100) (smooth true)))'
  for ((i = 0; i < 40; i++)); do
    for ((j = 0; j < 25; j++)); do
      x=$(awk "BEGIN { print ($i - 19.5) * 0.4 }") y=$(awk "BEGIN { print ($j - 12) * 0.36 }")
      echo "(use knot (transform ((scale 0.075) (rotate-x $((i * 37 + j * 11))) (rotate-y $((j * 23 + i * 7))) (translate $x $y 0))))"
    done
  done
} >"$work/wall.scene"
{
  head '(camera (position 0 2.2 -4) (look-at 0 0.3 12))'
  echo '(plane (point 0 0 0) (normal 0 1 0) (color 70 100 200) (specular 10))'
  echo '(define knot (mesh (file "knot.obj") (color 200 120 60) (specular 100) (smooth true)))'
  # Each knot's shift (up to 0.2) and turn from its place: integers, the
  # same scene from every awk.
  awk 'BEGIN {
    for (i = 0; i < 25; i++) for (k = 0; k < 40; k++) {
      x = (i - 12) * 1.2 + ((i * 7919 + k * 104729) % 41 - 20) / 100
      z = k * 1.2 + ((i * 104729 + k * 7919) % 41 - 20) / 100
      printf "(use knot (transform ((scale 0.35) (rotate-x %d) (rotate-y %d) (translate %g 0.5 %g))))\n", (i * 11 + k * 17) % 31 - 15, (i * 37 + k * 73) % 360, x, z
    } }'
} >"$work/field.scene"
scenes="one use block wall field"

median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
for ((r = 1; r <= repeats; r++)); do
  for s in $scenes; do
    /usr/bin/time -f "%e %M %U %S" -o "$work/$s.t" "$raytrace" render "$work/$s.scene" --jobs "$jobs" -o "$work/$s.ppm" 2>/dev/null
    cat "$work/$s.t" >>"$work/$s.times"
  done
done
# The percentage of the pixels of image $1 whose red exceeds their blue.
covered() {
  tail -c $((3 * width * height)) "$1" | od -An -v -tu1 -w3 | awk '$1 > $3 { c++ } END { printf "%.1f%%", 100 * c / NR }'
}
printf '%-10s %10s %10s %12s %10s\n' scene "wall (s)" "cpu (s)" "peak (MB)" "knots"
for s in $scenes; do
  wall=$(awk '{ print $1 }' "$work/$s.times" | median)
  cpu=$(awk '{ print $3 + $4 }' "$work/$s.times" | median)
  peak=$(awk '{ if ($2 > m) m = $2 } END { printf "%.1f", m / 1024 }' "$work/$s.times")
  printf '%-10s %10s %10s %12s %10s\n' "$s" "$wall" "$cpu" "$peak" "$(covered "$work/$s.ppm")"
done
if [ -n "${KEEP:-}" ]; then cp "$work"/*.ppm "$work"/*.scene "$KEEP"/; fi
