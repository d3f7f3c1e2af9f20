#!/bin/sh
# make bench-embree (issue 28): raytrace and Embree 3 side by side on the same
# camera rays, one thread, CPU time, for a torus knot and a terrain of each
# size (triangles) in SIZES. Per mesh it writes the OBJ (bench/gen.exe, exact
# digits) and a scene of the mesh alone (an ambient light, recursion depth 0,
# so that a pixel's time is its camera ray's), then runs raytrace_rays (which
# writes the rays and its hit mask) and embree_rays in its default and robust
# modes on those rays, each in its own process (its own peak RSS).
#
# compare.sh GEN RAYTRACE_RAYS EMBREE_RAYS DIR WIDTH HEIGHT SIZES...
set -e
gen=$1 rt=$2 em=$3 dir=$4 w=$5 h=$6
shift 6
mkdir -p "$dir"
printf '%-8s %9s  %-16s %8s %8s %8s %8s %7s %8s\n' mesh triangles tracer "read s" "build s" "ns/ray" hits "B/tri" differ
for kind in knot terrain; do
  for n in "$@"; do
    obj=$dir/$kind-$n.obj scene=$dir/$kind-$n.scene
    case $kind in
      knot)
        # speed.ml's knot and camera, the mesh's (scale 0.9) (translate 0 1.45 3)
        # moved onto the camera so that both tracers read the same vertices.
        "$gen" knot --tube 0.35 --segments $((n / 32)) --sides 16 -o "$obj"
        camera='(camera (position 0 0.8333333333333334 -8.333333333333334) (look-at 0 -0.6111111111111112 0))' ;;
      terrain)
        side=$(awk "BEGIN { printf \"%d\", sqrt($n / 2) + 0.5 }")
        "$gen" terrain --nx "$side" --nz "$side" -o "$obj"
        camera='(camera (position 0 3 -7) (look-at 0 0 0))' ;;
    esac
    tris=$(grep -c '^f ' "$obj")
    cat >"$scene" <<SCENE
(canvas (width $w) (height $h)) (viewport (width $(awk "BEGIN { printf \"%.17g\", $w / $h }")) (height 1) (distance 1))
$camera
(recursion-depth 0)
(mesh (file "$(basename "$obj")") (color 230 150 40))
(light ambient (intensity 1))
SCENE
    rays=$dir/$kind-$n.rays
    printf '%-8s %9d  ' $kind "$tris"; "$rt" "$scene" "$rays" "$dir/$kind-$n.raytrace.mask"
    for mode in "" --robust; do
      printf '%-8s %9d  ' $kind "$tris"
      "$em" $mode --compare "$dir/$kind-$n.raytrace.mask" "$obj" "$rays" "$dir/$kind-$n.embree$mode.mask"
    done
    rm -f "$obj" "$rays"
  done
done
