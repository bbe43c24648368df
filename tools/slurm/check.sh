#!/usr/bin/env bash
# A real one-node Slurm cluster on this machine renders a short shot with the shipped job array
# (kinray-array.sbatch, submit.sh), and the result must be that of one process: every frame bit
# for bit, a video with every frame; then one task is cancelled while it renders and requeued,
# and the folder must again be whole and clean. Run through `bash tools/checks.sh slurm`
# (docs/render_farm.md "The check"). Everything (munged, slurmctld, slurmd, their state and logs,
# the frames) lives in one temporary folder, and the daemons are stopped on exit.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"

# Debian's Slurm and MUNGE; ffprobe (ffmpeg) counts the video's frames by decoding them.
packages=(slurm-wlm munge ffmpeg)
missing=()
for package in "${packages[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
  [[ "$status" == "install ok installed" ]] || missing+=("$package")
done
if ((${#missing[@]} > 0)); then
  echo "slurm: installing ${missing[*]}"
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi
[[ -x build/bin/kinray ]] || bash tools/setup.sh build
kinray="$root/build/bin/kinray"
scene="${KINRAY_SLURM_SCENE:-$root/../shared/data/bart/robots/Robot.aff}"

tmp="$(mktemp -d /tmp/kinray-slurm.XXXXXX)"
daemons=()
stop() {
  # Jobs first (their processes are the daemons' children), then the daemons, then the folder.
  if [[ -n "${SLURM_CONF:-}" ]] && ((${#daemons[@]} > 0)); then
    scancel --quiet --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 50); do
      [[ -z "$(squeue -h -o %i 2>/dev/null)" ]] && break
      sleep 0.2
    done
  fi
  local i
  for ((i = ${#daemons[@]} - 1; i >= 0; i--)); do
    kill "${daemons[i]}" 2>/dev/null || true
    wait "${daemons[i]}" 2>/dev/null || true
  done
  rm -rf "$tmp"
}
trap stop EXIT

# MUNGE with its own key, socket and files.
mkdir -p "$tmp"/{munge,state,spool,log,jobs}
chmod 700 "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
munge_socket="$tmp/munge/munge.socket"
munged --foreground --force --socket="$munge_socket" --key-file="$tmp/munge/munge.key" \
  --log-file="$tmp/log/munged.log" --pid-file="$tmp/munge/munged.pid" \
  --seed-file="$tmp/munge/munged.seed" 2>>"$tmp/log/munged.log" &
daemons+=($!)

# One node: this machine, its CPUs and (a little less than) its memory.
node="$(hostname -s)"
cpus="$(nproc)"
memory=$(($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 * 9 / 10))
port="${KINRAY_SLURM_PORT:-16817}"
export SLURM_CONF="$tmp/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=kinray-check
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge_socket,cred_expire=10
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
PlugStackConfig=$tmp/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=check Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
: >"$tmp/plugstack.conf"
slurmctld -D -i >>"$tmp/log/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D -N "$node" >>"$tmp/log/slurmd.out" 2>&1 &
daemons+=($!)

passed=0 failed=0
check() {  # check WHAT COMMAND...: runs COMMAND, counts it
  if "${@:2}"; then
    echo "slurm: ok: $1"
    passed=$((passed + 1))
  else
    echo "slurm: FAILED: $1" >&2
    failed=$((failed + 1))
  fi
}
finish() {
  echo "slurm: $passed passed, $failed failed"
  exit $((failed > 0 ? 1 : 0))
}
give_up() {  # the cluster or a job went wrong: show its logs, stop
  echo "slurm: $1" >&2
  tail -n 15 "$tmp"/log/* "$tmp"/jobs/* >&2 2>/dev/null || true
  failed=$((failed + 1))
  finish
}
# Waits (at most $2 seconds) until the jobs $1 (comma-separated) have all left the queue.
wait_jobs() {
  local deadline=$((SECONDS + $2))
  while [[ -n "$(squeue -h -j "$1" -o %i)" ]]; do
    ((SECONDS < deadline)) ||
      give_up "jobs $1 still queued after $2 s: $(squeue -h -j "$1" -o '%i %T %r' | tr '\n' ' ')"
    sleep 1
  done
}
# Runs COMMAND... until it succeeds, for at most $1 seconds.
eventually() {
  local deadline=$((SECONDS + $1))
  until "${@:2}"; do
    ((SECONDS < deadline)) || return 1
    sleep 0.5
  done
}
# The state of every task of the jobs $1, one "ID STATE" a line, sorted.
job_states() { squeue -h -t all -j "$1" -o '%i %T' | sort; }
completed() {  # completed JOBS COUNT: COUNT jobs (or tasks), all COMPLETED
  local states
  states="$(job_states "$1")"
  [[ "$(grep -c ' COMPLETED$' <<<"$states")" == "$2" && "$(wc -l <<<"$states")" == "$2" ]] ||
    { echo "$states" >&2; return 1; }
}
# The folder $2 holds exactly the files of $1 (hidden ones included), each bit for bit.
same_frames() {
  diff <(ls -A "$1") <(ls -A "$2") >&2 || return 1
  local file
  for file in "$1"/*; do cmp "$file" "$2/${file##*/}" || return 1; done
}
# The video $1 decodes to $2 frames (ffprobe reads every frame).
video_frames() {
  local count
  count="$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
    -of default=noprint_wrappers=1:nokey=1 "$1")"
  [[ "$count" == "$2" ]] || { echo "$1 decodes to ${count:-no} frames, not $2" >&2; return 1; }
}

for _ in $(seq 60); do
  [[ "$(sinfo -h -n "$node" -o %T 2>/dev/null)" == idle ]] && break
  sleep 1
done
[[ "$(sinfo -h -n "$node" -o %T 2>/dev/null)" == idle ]] || give_up "node $node is not idle after 60 s"
echo "slurm: cluster up: $node, $cpus CPUs; $(sinfo --version)"

# The jobs: 1 CPU a task (two at once on two CPUs), their output in jobs/.
export KINRAY="$kinray" KINRAY_CHUNKS=4 KINRAY_FPS=4
export KINRAY_SBATCH="--cpus-per-task=1 --mem=1G --chdir=$tmp --output=$tmp/jobs/%x-%A_%a.out"
read -r -a sbatch_options <<<"$KINRAY_SBATCH"

# 1. The short shot: 4 tasks of 2 frames each, then the video, against one process.
shot=(--backend kinetic --time 0:2 --frames 8 --size 64x48 --keyrate 4)
"$kinray" render "$scene" "${shot[@]}" --out "$tmp/whole" --quiet 2>>"$tmp/log/whole.err" ||
  give_up "the single-process render failed"
read -r array video < <(bash tools/slurm/submit.sh "$scene" "$tmp/farm" "$tmp/farm.mp4" "${shot[@]}")
[[ -n "${video:-}" ]] || give_up "submit.sh failed"
echo "slurm: submitted array $array (4 tasks) and video $video"
wait_jobs "$array,$video" 240
check "the array's 4 tasks completed" completed "$array" 4
check "the video job completed" completed "$video" 1
check "the 8 frames equal a single process's, bit for bit" same_frames "$tmp/whole" "$tmp/farm"
check "the video decodes to 8 frames" video_frames "$tmp/farm.mp4" 8

# 2. A task cancelled while it renders, then requeued: the same index, the same array, so the
# same slice; --skip-existing renders only the frames it had not written. Larger frames and 6 a
# task (0.2 to 1.5 s each here) leave time to cancel task 2 between its first frame and its last.
slow=(--backend kinetic --time 0:2 --frames 24 --size 160x120 --keyrate 4)
chunk2=(frame_0000{6..9}.png frame_0001{0,1}.png)  # task 2 of 4: frames 6 to 11 of 24
"$kinray" render "$scene" "${slow[@]}" --out "$tmp/whole-slow" --quiet 2>>"$tmp/log/whole.err" ||
  give_up "the single-process render failed"
array='' video=''
read -r array video < <(bash tools/slurm/submit.sh "$scene" "$tmp/fault" "$tmp/fault.mp4" "${slow[@]}")
[[ -n "$video" ]] || give_up "submit.sh failed"
echo "slurm: submitted array $array (4 tasks) and video $video; task 2 renders frames 6-11"
deadline=$((SECONDS + 120))
until [[ -e "$tmp/fault/${chunk2[0]}" ]]; do
  ((SECONDS < deadline)) || give_up "task ${array}_2 wrote no frame in 120 s"
  sleep 0.1
done
scancel "${array}_2" || give_up "scancel failed"
wait_jobs "$array" 240
kept=()
for frame in "${chunk2[@]}"; do [[ -e "$tmp/fault/$frame" ]] && kept+=("$tmp/fault/$frame"); done
kept_inodes="$(stat -c '%n %i' "${kept[@]}")"
echo "slurm: cancelled task ${array}_2 after ${#kept[@]} of its 6 frames"
check "task 2 was cancelled before its last frame" test "${#kept[@]}" -lt 6
check "the cancelled task left no hidden file" test -z "$(find "$tmp/fault" -name '.*')"
never_satisfied() { [[ "$(squeue -h -j "$video" -o %r)" == DependencyNeverSatisfied ]]; }
check "the video job waits for good (its dependency failed)" eventually 30 never_satisfied
# The recipe of docs/render_farm.md: requeue the task, and the video after it.
scontrol requeue "${array}_2" || give_up "scontrol requeue failed"
scancel "$video"
video=$(sbatch --parsable "${sbatch_options[@]}" --dependency="afterok:${array}_2" \
  tools/slurm/kinray-video.sbatch "$tmp/fault" "$tmp/fault.mp4") || give_up "sbatch failed"
echo "slurm: requeued task ${array}_2 and submitted video $video after it"
wait_jobs "$array,$video" 240
check "the array's 4 tasks completed after the requeue" completed "$array" 4
check "the requeued task kept the frames it had written" \
  test "$(stat -c '%n %i' "${kept[@]}")" == "$kept_inodes"
check "the 24 frames equal a single process's, bit for bit, nothing else in the folder" \
  same_frames "$tmp/whole-slow" "$tmp/fault"
check "the new video job completed" completed "$video" 1
check "the video decodes to 24 frames" video_frames "$tmp/fault.mp4" 24
finish
