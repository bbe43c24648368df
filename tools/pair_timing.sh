#!/usr/bin/env bash
# Wall time per event of the kinetic grid for two kinray binaries, measured at the same moments:
# each round runs both at once, one per core (swapped every round), at real-time priority so the
# machine's other work waits, and reads time_s.events / events.total from their --stats. On a
# shared machine run-to-run noise is +-30%, sequential alternation does not resolve a 10% change,
# and callgrind cannot see what this is for (memory latency, prefetches); pairs run at once share
# whatever load there is. Needs root (chrt) and two cores.
#
#   tools/pair_timing.sh ROUNDS BINARY_A BINARY_B [SCENE [SIZE [TIME]]]
#
# Defaults: wavy-sphere, 512x512, --time 0.5:0.5833 (the instruction protocol's interval), one
# thread each. Prints both medians (with min-max), B/A and in how many rounds B was faster.
set -euo pipefail
rounds=$1 a=$2 b=$3
scene=${4:-wavy-sphere} size=${5:-512x512} interval=${6:-0.5:0.5833}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

ns_per_event() {  # CORE BINARY OUT
  local dir="$work/$1"
  mkdir -p "$dir"
  chrt -f 50 taskset -c "$1" "$2" render "$scene" --size "$size" --time "$interval" \
    --inbetweens 1 --threads 1 --quiet --out "$dir/frames" --stats "$dir/s.json" > /dev/null
  python3 -c "import json; d = json.load(open('$dir/s.json')); \
print(round(1e9 * d['time_s']['events'] / d['events']['total']))" > "$3"
}

times_a=() times_b=()
for ((i = 0; i < rounds; ++i)); do
  core_a=$((i % 2)) core_b=$((1 - i % 2))
  ns_per_event "$core_a" "$a" "$work/a" &
  ns_per_event "$core_b" "$b" "$work/b" &
  wait
  times_a+=("$(cat "$work/a")") times_b+=("$(cat "$work/b")")
done
python3 - "${times_a[*]}" "${times_b[*]}" <<'PY'
import statistics, sys
a = [int(x) for x in sys.argv[1].split()]
b = [int(x) for x in sys.argv[2].split()]
ma, mb = statistics.median(a), statistics.median(b)
print(f"A {ma:.0f} ns/event ({min(a)}-{max(a)})  B {mb:.0f} ns/event ({min(b)}-{max(b)})  "
      f"B/A {mb / ma:.3f}  B faster in {sum(y < x for x, y in zip(a, b))}/{len(a)} rounds")
PY
