#!/usr/bin/env bash
# Runs every command of docs/performance.md in one sitting, in the file's order, and keeps each
# command's output (text and JSON) in one folder, so that the tables can be replaced together from
# figures measured on one machine under one load.
#
#   bash tools/measure_performance.sh OUT_DIR [--long]
#
# KINRAY (default build/bin/kinray) names the binary: copy it aside first if the build folder may
# be rebuilt while this runs. Each step's wall time and the load average before it go to
# OUT_DIR/steps.txt. --long adds BART's whole animations (over an hour on two cores).
set -uo pipefail

if [[ $# -lt 1 ]]; then
  echo "usage: bash tools/measure_performance.sh OUT_DIR [--long]" >&2
  exit 2
fi
out=$1
long=${2:-}
kinray=${KINRAY:-build/bin/kinray}
shared=${KINRAY_SHARED:-../shared}
testwuson=/usr/share/assimp/models/X/Testwuson.X
mkdir -p "$out" || exit 1
[[ -x $kinray ]] || { echo "measure_performance: $kinray is not an executable" >&2; exit 1; }

# step NAME COMMAND...: runs COMMAND, its output in OUT_DIR/NAME.txt, a line in steps.txt.
step() {
  local name=$1
  shift
  local load start end status
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  start=$(date +%s)
  "$@" >"$out/$name.txt" 2>&1
  status=$?
  end=$(date +%s)
  printf '%-28s %5d s  exit %d  load before %s\n' "$name" $((end - start)) "$status" "$load" |
    tee -a "$out/steps.txt"
}

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "commit: $(git rev-parse --short HEAD 2>/dev/null)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)"
  echo "cores: $(nproc)"
  echo "l2: $(lscpu | grep -m1 'L2 cache' | tr -s ' ')"
} >"$out/machine.txt"

# The kinetic grid against Embree.
step grid_inbetweens "$kinray" bench wavy-sphere:triangles=40000 --size 512x512 --time 0:0.125 \
  --inbetweens 1,4,16,128 --repetitions 3 --json "$out/grid_inbetweens.json"
for scene in cloth flythrough orbit static-moving "$testwuson"; do
  step "grid_$(basename "$scene" .X)" "$kinray" bench "$scene" --size 320x240 \
    --inbetweens 1,16,128 --repetitions 1 --json "$out/grid_$(basename "$scene" .X).json"
done
rm -rf "$out/slow_motion"
step slow_motion_render "$kinray" render wavy-sphere:triangles=40000 --size 512x512 \
  --time 0:0.125 --inbetweens 128 --out "$out/slow_motion" --stats "$out/slow_motion.json"
rm -rf "$out/slow_motion"
for mode in refit rebuild; do
  for packet in 1 4 8 16; do  # a width the machine lacks is refused (exit 2)
    step "embree_${mode}_$packet" "$kinray" render wavy-sphere --frames 24 --size 512x512 \
      --backend embree --embree-mode "$mode" --packet "$packet" \
      --stats "$out/embree_${mode}_$packet.json" --quiet --out "$out/embree_frames"
  done
done
rm -rf "$out/embree_frames"

# Motion blur: time at 512 x 512, error at 128 x 128, then with lights.
blur_scenes=cloth,orbit,$testwuson
step blur_time "$kinray" bench wavy-sphere --size 512x512 --shutter 0.5 --blur-samples 64 \
  --reference-samples 16 --blur-frames 5 --blur-scenes "$blur_scenes" --json "$out/blur_time.json"
step blur_error "$kinray" bench wavy-sphere --size 128x128 --shutter 0.5 --blur-samples 64,256 \
  --reference-samples 4096 --blur-frames 3 --blur-scenes "$blur_scenes" \
  --json "$out/blur_error.json"
step blur_lights_wavy "$kinray" bench wavy-sphere --shutter 0.5 --light point:2,3,4 \
  --light dir:-1,1,1 --size 128x128 --blur-samples 16,64 --reference-samples 1024 \
  --json "$out/blur_lights_wavy.json"
step blur_lights_kitchen "$kinray" bench "$shared/data/bart/kitchen/kitchen.aff" --shutter 0.5 \
  --size 320x240 --blur-samples 16,32,64 --reference-samples 1024 --blur-frames 3 --time 5:20 \
  --json "$out/blur_lights_kitchen.json"

# Exact antialiasing.
for scene in wavy-sphere orbit cloth flythrough; do
  step "aa_$scene" "$kinray" bench "$scene" --aa exact --size 128x128 --json "$out/aa_$scene.json"
done
step aa_lights "$kinray" bench wavy-sphere --aa exact --size 128x128 --light point:2,3,4 \
  --light dir:-1,1,1 --json "$out/aa_lights.json"
for scene in wavy-sphere orbit; do
  step "aa_shutter_$scene" "$kinray" bench "$scene" --aa exact --shutter 0.5 --size 128x128 \
    --json "$out/aa_shutter_$scene.json"
done

# Kinetic trees.
step trees "$kinray" bench wavy-sphere:triangles=100000 --structure aabb \
  --inbetweens 16,128 --time 0:0.25 --size 128x128 --repetitions 3 --json "$out/trees.json"

# Separation list and primitive CCD.
for scene in glide:gap=-0.05 cloth-slide:gap=0.005 crossing cloth-fold; do
  name=$(echo "$scene" | cut -d: -f1)
  step "collide_$name" timeout 600 "$kinray" bench "$scene" --structure ksl,swept \
    --inbetweens 1,10,100,1000 --repetitions 1 --json "$out/collide_$name.json"
done
for scene in glide:gap=-0.05 cloth-slide:gap=0.005; do
  name=$(echo "$scene" | cut -d: -f1)
  step "collide_${name}_triangles" timeout 600 "$kinray" bench "$scene" --structure ksl,swept \
    --inbetweens 100 --triangles 1000,10000,100000 --repetitions 1 \
    --json "$out/collide_${name}_triangles.json"
done
step collide_glide_1m timeout 600 "$kinray" bench glide:gap=-0.05,keyrate=6 \
  --structure ksl,swept --inbetweens 100 --triangles 1000000 --repetitions 1 \
  --json "$out/collide_glide_1m.json"
for run in 1 2 3; do
  step "ccd_queries_$run" "$kinray" ccd-queries "$shared/data/ccd" --threads 1 --repetitions 3
done

# Choosing the backend.
for scene in wavy-sphere cloth orbit flythrough static-moving "$testwuson"; do
  step "auto_$(basename "$scene" .X)" "$kinray" bench "$scene" --size 320x240 \
    --inbetweens 1,4,16,128 --repetitions 1 --reference-frames 4 \
    --json "$out/auto_$(basename "$scene" .X).json"
done
step auto_robots "$kinray" bench "$shared/data/bart/robots/Robot.aff" --keyrate 4 --time 1:2 \
  --size 320x240 --inbetweens 1,4,16,128 --repetitions 1 --reference-frames 4 \
  --json "$out/auto_robots.json"

# BART and the suite.
step suite "$kinray" bench --suite --reference-frames 6 --json "$out/suite.json"
step load_kitchen /usr/bin/time -v "$kinray" info "$shared/data/bart/kitchen/kitchen.aff"
step load_robots /usr/bin/time -v "$kinray" info "$shared/data/bart/robots/Robot.aff"
if [[ $long == --long ]]; then
  step suite_whole_animation "$kinray" bench --suite --scenes kitchen,robots --whole-animation \
    --reference-frames 6 --json "$out/suite_whole_animation.json"
fi
echo "measure_performance: done, outputs in $out" | tee -a "$out/steps.txt"
