#!/usr/bin/env bash
# Compares two kinray binaries on the kinetic backend: a refactoring that must not change
# behaviour passes when every run agrees bit for bit.
#
#   tools/compare_kinetic_runs.sh BASE_BINARY NEW_BINARY [WORK_DIR]
#
# For the five built-in scenes (wavy-sphere, static-moving, orbit, flythrough, cloth) and three
# animated models, at --threads 1 and 2, both binaries run
#   kinray render SCENE --size 96x72 --frames 6 --threads T --aov id,depth --stats S.json --quiet
# and the script compares
#   - the events by kind, certificates computed, coverage changes and every other counter of the
#     stats' "events", "kinetic" and "quality" sections (timings and per-frame seconds left out),
#   - every file written (frame_N.png, id_N.png, depth_N.tiff) byte for byte.
# It prints one line per run (events total, certificates computed, coverage changes, files
# compared, OK or DIFF with what differs) and exits non-zero if any run differs.
# Environment: SIZE (default 96x72), FRAMES (6), SORTS (default "list"; e.g. "list tournament
# heap" runs every pixel order), MODELS (space-separated model paths, default three animated ones),
# IGNORE_COUNTERS (space-separated counter names left out of the comparison, default none: e.g.
# "kinetic.certificates_computed quality.responsiveness" for a change that only computes fewer
# certificates; the line then still shows how those counters moved).
set -euo pipefail
base=${1:?usage: compare_kinetic_runs.sh BASE_BINARY NEW_BINARY [WORK_DIR]}
new=${2:?usage: compare_kinetic_runs.sh BASE_BINARY NEW_BINARY [WORK_DIR]}
work=${3:-$(mktemp -d /tmp/kinray-compare.XXXXXX)}
size=${SIZE:-96x72}
frames=${FRAMES:-6}
sorts=${SORTS:-list}
models=${MODELS:-"/usr/share/assimp/models/X/Testwuson.X /work/shared/data/models/glTF2/AnimatedMorphSphere/glTF/AnimatedMorphSphere.gltf /usr/share/assimp/models/BVH/01_01.bvh"}
scenes="wavy-sphere static-moving orbit flythrough cloth $models"

# The counters of one stats file, one "key value" line each, timings left out.
counters() {
  python3 - "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
out = {}
def walk(prefix, v):
    if isinstance(v, dict):
        for k, x in v.items():
            if k in ("events_s", "readout_s", "time_s"): continue
            walk(prefix + "." + k if prefix else k, x)
    else:
        out[prefix] = v
for section in ("events", "kinetic", "quality", "certificates_live_max"):
    if section in s: walk(section, s[section])
for k in sorted(out): print(k, json.dumps(out[k]))
PY
}

ignore=${IGNORE_COUNTERS:-}

# The counters of one run, without the ignored ones.
compared() {
  awk -v ignore="$ignore" 'BEGIN { n = split(ignore, names, " "); for (i = 1; i <= n; i++) skip[names[i]] = 1 }
                           !($1 in skip)' "$1"
}

status=0
for sort in $sorts; do
  for scene in $scenes; do
    for threads in 1 2; do
      name=$(basename "$scene" | tr -c 'A-Za-z0-9_.\n-' '_')-$sort-t$threads
      for side in base new; do
        bin=$base; [[ $side == new ]] && bin=$new
        rm -rf "$work/$side/$name"
        mkdir -p "$work/$side/$name"
        "$bin" render "$scene" --size "$size" --frames "$frames" --threads "$threads" --sort "$sort" \
          --aov id,depth --stats "$work/$side/$name.json" --out "$work/$side/$name" --quiet \
          >"$work/$side/$name.log" 2>&1 || { echo "$name: $side run failed, see $work/$side/$name.log"; status=1; continue 2; }
        counters "$work/$side/$name.json" >"$work/$side/$name.counters"
      done
      what=""
      diff -q <(compared "$work/base/$name.counters") <(compared "$work/new/$name.counters") >/dev/null || what="counters"
      files=0
      for f in "$work/base/$name"/*; do
        files=$((files + 1))
        cmp -s "$f" "$work/new/$name/$(basename "$f")" || what="$what $(basename "$f")"
      done
      [[ $(ls "$work/base/$name" | wc -l) == $(ls "$work/new/$name" | wc -l) ]] || what="$what file-count"
      get() { awk -v k="$1" '$1 == k { print $2 }' "$work/new/$name.counters"; }
      summary="events $(get events.total) (boundary $(get events.boundary) vertex_row $(get events.vertex_row) orientation $(get events.orientation) swap $(get events.swap) flightplan $(get events.flightplan) insert $(get events.insert) delete $(get events.delete)), certificates $(get kinetic.certificates_computed), coverage changes $(get kinetic.coverage_changes), $files files"
      for counter in $ignore; do
        before=$(awk -v k="$counter" '$1 == k { print $2 }' "$work/base/$name.counters")
        after=$(get "$counter")
        [[ $before == "$after" ]] || summary="$summary, ignored $counter $before -> $after"
      done
      if [[ -z $what ]]; then
        echo "$name: OK   $summary"
      else
        echo "$name: DIFF ($what) $summary"
        diff <(compared "$work/base/$name.counters") <(compared "$work/new/$name.counters") | head -20 || true
        status=1
      fi
    done
  done
done
echo "work dir: $work"
exit $status
