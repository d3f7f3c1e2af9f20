#!/bin/sh
# make bench-embree (issue 28): raytrace and Embree 3 side by side on the same
# camera rays and shadow rays, one thread, CPU time, for a torus knot and a
# terrain of each size (triangles) in SIZES. Per mesh it writes the OBJ
# (bench/gen.exe, exact digits) and a scene of the mesh alone (an ambient
# light, recursion depth 0, so that a pixel's time is its camera ray's),
# then runs raytrace_rays (which writes the camera rays, the shadow rays from
# its hits toward the mesh's light point, and both hit masks) and
# embree_rays in its default and robust modes on those rays, each in its own
# process (its own peak RSS), the three in alternation REPEATS times. It
# prints the median of each time and of the peak bytes per triangle; the raw
# rows stay in DIR/rows.
#
# compare.sh GEN RAYTRACE_RAYS EMBREE_RAYS DIR WIDTH HEIGHT REPEATS SIZES...
set -e
gen=$1 rt=$2 em=$3 dir=$4 w=$5 h=$6 repeats=$7
shift 7
mkdir -p "$dir"
rows=$dir/rows
: >"$rows"
for kind in knot terrain; do
  for n in "$@"; do
    obj=$dir/$kind-$n.obj scene=$dir/$kind-$n.scene
    case $kind in
      knot)
        # speed.ml's knot and camera, the mesh's (scale 0.9) (translate 0 1.45 3)
        # moved onto the camera so that both tracers read the same vertices.
        "$gen" knot --tube 0.35 --segments $((n / 32)) --sides 16 -o "$obj"
        camera='(camera (position 0 0.8333333333333334 -8.333333333333334) (look-at 0 -0.6111111111111112 0))'
        # Above, left of and behind the camera: the knot shadows itself.
        light='-3 5 -5' ;;
      terrain)
        side=$(awk "BEGIN { printf \"%d\", sqrt($n / 2) + 0.5 }")
        "$gen" terrain --nx "$side" --nz "$side" -o "$obj"
        camera='(camera (position 0 3 -7) (look-at 0 0 0))'
        # Low, from the side: the hills' long shadows.
        light='8 1.5 2' ;;
    esac
    tris=$(grep -c '^f ' "$obj")
    cat >"$scene" <<SCENE
(canvas (width $w) (height $h)) (viewport (width $(awk "BEGIN { printf \"%.17g\", $w / $h }")) (height 1) (distance 1))
$camera
(recursion-depth 0)
(mesh (file "$(basename "$obj")") (color 230 150 40))
(light ambient (intensity 1))
SCENE
    rays=$dir/$kind-$n.rays mask=$dir/$kind-$n.raytrace.mask
    shadows=$dir/$kind-$n.shadows smask=$dir/$kind-$n.raytrace.smask
    i=0
    while [ $i -lt "$repeats" ]; do
      # shellcheck disable=SC2086 # $light is three numbers
      { printf '%s %s ' $kind "$tris"; "$rt" "$scene" "$rays" "$mask" "$shadows" "$smask" $light; } >>"$rows"
      for mode in "" --robust; do
        { printf '%s %s ' $kind "$tris"
          "$em" $mode --compare "$mask" --shadows "$shadows" "$dir/$kind-$n.embree$mode.smask" --compare-shadows "$smask" \
            "$obj" "$rays" "$dir/$kind-$n.embree$mode.mask"; } >>"$rows"
      done
      i=$((i + 1))
    done
    rm -f "$obj" "$rays" "$shadows"
  done
done
# Per mesh and tracer, in the order of the rows: the medians of read,
# build, the hierarchy's build alone, ns per camera ray with the pixel's
# shading (Embree: none) and alone, bytes per triangle, ns per shadow ray;
# the largest counts of differing pixels and shadow rays; for Embree's rows,
# raytrace's ns per camera ray alone and per shadow ray over this row's.
awk '
  function median(key, col,   n, a, i, j, t) {
    n = split(vals[key, col], a, " ")
    for (i = 2; i <= n; i++) { t = a[i] + 0; for (j = i - 1; j >= 1 && a[j] + 0 > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  {
    key = $1 " " $2 " " $3
    if (!(key in seen)) { seen[key] = 1; order[++keys] = key; hits[key] = $9; differ[key] = $11; blocked[key] = $13; sdiffer[key] = $14 }
    for (c = 4; c <= 12; c++) vals[key, c] = vals[key, c] " " $c
    if ($11 != "-" && $11 + 0 > differ[key] + 0) differ[key] = $11
    if ($14 != "-" && $14 + 0 > sdiffer[key] + 0) sdiffer[key] = $14
  }
  END {
    printf "%-8s %9s  %-14s %7s %7s %7s %7s %7s %7s %6s %6s %6s %7s %6s %6s %6s\n", "mesh", "triangles", "tracer", "read s", "build s", "bvh s", "pix ns", "cam ns", "hits", "B/tri", "differ", "shd ns", "blocked", "sdiff", "cam x", "shd x"
    for (k = 1; k <= keys; k++) {
      split(order[k], f, " ")
      cam = median(order[k], 8); shd = median(order[k], 12)
      if (f[3] == "raytrace") { rcam = cam; rshd = shd; rc = "-"; rs = "-" }
      else { rc = sprintf("%.2fx", rcam / cam); rs = shd > 0 ? sprintf("%.2fx", rshd / shd) : "-" }
      printf "%-8s %9d  %-14s %7.3f %7.3f %7.3f %7.0f %7.0f %7s %6.0f %6s %6.0f %7s %6s %6s %6s\n", f[1], f[2], f[3], median(order[k], 4), median(order[k], 5), median(order[k], 6), median(order[k], 7), cam, hits[order[k]], median(order[k], 10), differ[order[k]], shd, blocked[order[k]], sdiffer[order[k]], rc, rs
    }
  }' "$rows"
