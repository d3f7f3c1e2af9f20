#!/bin/sh
# Render a scene as N tiles with GNU parallel, on this machine or across
# hosts, and merge them: byte for byte the image `raytrace render` gives.
#
#   contrib/parallel-tiles.sh SCENE N OUT [PARALLEL OPTIONS...]
#
#   contrib/parallel-tiles.sh scenes/cgfs.scene 16 cgfs.png
#       16 tiles on this machine, one process per core at a time.
#   contrib/parallel-tiles.sh scenes/cgfs.scene 64 cgfs.png --sshlogin 8/host1,8/host2,:
#       64 tiles over host1 and host2 (8 at a time each) and this machine
#       (':'). Each host needs raytrace and rsync, and ssh without a
#       password; parallel copies the scene there and the parts back.
#
# Environment: RAYTRACE, the raytrace command (default: raytrace, on every
# host); RAYTRACE_OPTS, more render options, e.g. "--width 3840 --height 2160".
set -eu
if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE N OUT [parallel options...]" >&2
  exit 2
fi
scene=$1 n=$2 out=$3
shift 3
raytrace=${RAYTRACE:-raytrace}

# Scene and parts in a fresh directory, named relative to its parent: on a
# remote host, parallel puts them at the same path under the login directory.
work=$(mktemp -d "${TMPDIR:-/tmp}/raytrace-tiles.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM
dir=$(basename "$work")
cp "$scene" "$work/scene.scene"

# With other hosts, parallel sends the scene and fetches the parts (rsync).
set -- --will-cite -q --halt now,fail=1 "$@"
for arg in "$@"; do
  case $arg in
  -S | -S?* | --sshlogin | --sshlogin=* | --slf | --slf=* | --sshloginfile | --sshloginfile=*)
    set -- "$@" --basefile "$dir/scene.scene" --return "$dir/part-{}.ppm" --cleanup
    break
    ;;
  esac
done

# shellcheck disable=SC2086 # RAYTRACE_OPTS is a list of options
(cd "$work/.." && seq "$n" | parallel "$@" \
  "$raytrace" render "$dir/scene.scene" --jobs 1 ${RAYTRACE_OPTS:-} --tile "{}/$n" -o "$dir/part-{}.ppm")

"$raytrace" merge "$work"/part-*.ppm -o "$out"
