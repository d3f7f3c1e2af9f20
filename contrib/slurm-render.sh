#!/bin/bash
# Render a scene as N tiles on a Slurm cluster: a job array of N tile
# tasks (contrib/slurm-tiles.sbatch), then a merge job
# (contrib/slurm-merge.sbatch) that runs once they have all ended and
# refuses in one line if a tile is missing. Run it from a directory that
# every node shares:
#
#   contrib/slurm-render.sh SCENE N OUT [RENDER OPTIONS...]
#   contrib/slurm-render.sh scenes/cgfs.scene 64 big.png --width 7680 --height 4320
#
# It prints the two job IDs. Extra sbatch options (partition, account, time)
# go in SBATCH_OPTS; RAYTRACE names the raytrace command (default: raytrace).
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE N OUT [render options...]" >&2
  exit 2
fi
scene=$1 n=$2 out=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
parts=$out.parts
# shellcheck disable=SC2086 # SBATCH_OPTS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTS:-} --array="1-$n" "$here/slurm-tiles.sbatch" "$scene" "$parts" "$@")
array=${array%%;*}
# afterany, not afterok: with afterok a failed tile would leave the merge
# pending for ever (DependencyNeverSatisfied) on most clusters.
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTS:-} --dependency="afterany:$array" "$here/slurm-merge.sbatch" "$parts" "$out")
echo "tiles: job $array; merge: job ${merge%%;*}"
