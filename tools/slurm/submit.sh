#!/bin/bash
# Submits a kinray render to Slurm: the job array of kinray-array.sbatch, then the video
# (kinray-video.sbatch), a job that starts once every task of the array has succeeded
# (docs/render_farm.md).
#
#   tools/slurm/submit.sh SCENE OUT_DIR VIDEO [RENDER FLAGS...]
#
# Environment: KINRAY_CHUNKS, the number of tasks (default 20); KINRAY_SBATCH, more sbatch options
# for both jobs (e.g. "--partition=long"; the array's own go in kinray-array.sbatch's #SBATCH
# lines or on its command line); KINRAY_FPS and KINRAY, passed on to the jobs. Prints the two
# job ids, the array's and the video's.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
scene="$1" out="$2" video="$3"
shift 3
read -r -a options <<<"${KINRAY_SBATCH:-}"
array=$(sbatch --parsable "${options[@]}" --array="1-${KINRAY_CHUNKS:-20}" \
  "$here/kinray-array.sbatch" "$scene" "$out" "$@")
array="${array%%;*}"  # "id;cluster" on a federation
video_job=$(sbatch --parsable "${options[@]}" --dependency="afterok:$array" \
  "$here/kinray-video.sbatch" "$out" "$video")
echo "$array ${video_job%%;*}"
