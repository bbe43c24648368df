#!/usr/bin/env bash
# tools/diff_all.sh: `kinray diff S --against embree` and `--against osmesa` for every built-in
# scene S and every animated model of Debian's assimp-testmodels and of the shared folder, at a
# small size, with the kinetic backend's audit on; prints a Markdown table and writes it, with
# every run's JSON summary, heat maps and stderr, into OUT_DIR.
#
#   tools/diff_all.sh [OUT_DIR]            (default out/diff_all)
#
# Environment: KINRAY (default build/bin/kinray), SIZE (160x120), FRAMES (8), AUDIT (1; 0 = off),
# TIMEOUT per run in seconds (900), MODELS (/usr/share/assimp/models), SHARED (../shared),
# REFERENCES ("embree osmesa").
#
# A model is "animated" when `kinray info` loads it and reports a moving object or a camera with
# more than one key. Result column: ok (within the budget: 0 real mismatches against Embree, 0.1%
# of the pixels per frame against OSMesa), REAL (over budget), ERROR (the diff failed, e.g. an
# audit violation, in which case the real/tie counts are those of a second run without --audit;
# its stderr is in OUT_DIR/log), CRASH (killed by a signal), TIMEOUT.
set -u

out=${1:-out/diff_all}
kinray=${KINRAY:-build/bin/kinray}
size=${SIZE:-160x120}
frames=${FRAMES:-8}
audit=${AUDIT:-1}
timeout_s=${TIMEOUT:-900}
models=${MODELS:-/usr/share/assimp/models}
shared=${SHARED:-../shared}
references=${REFERENCES:-embree osmesa}

if [ ! -x "$kinray" ]; then
  echo "diff_all.sh: no kinray program at '$kinray' (build it, or set KINRAY)" >&2
  exit 2
fi
mkdir -p "$out/json" "$out/report" "$out/log" "$out/info"

# name<TAB>spec<TAB>triangles, one line per scene to diff.
scenes="$out/scenes.tsv"
: > "$scenes"
for builtin in wavy-sphere cloth orbit flythrough static-moving; do
  "$kinray" info "$builtin" --json > "$out/info/$builtin.json" 2>/dev/null
  triangles=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["triangles"])' "$out/info/$builtin.json")
  printf '%s\t%s\t%s\n' "$builtin" "$builtin" "$triangles" >> "$scenes"
done

echo "discovering animated models under $models and $shared/data/models ..." >&2
find "$models" "$shared/data/models" -type f 2>/dev/null | sort | while read -r file; do
  case "$file" in
    *.png|*.jpg|*.jpeg|*.bmp|*.tga|*.dds|*.txt|*.md|*.bin|*.mtl|*.pdf|*.html|*.ini|*.cfg|*.LICENSE|*LICENSE*|*README*) continue ;;
  esac
  key=$(printf '%s' "$file" | md5sum | cut -c1-12)
  if ! timeout 120 "$kinray" info "$file" --json > "$out/info/$key.json" 2>/dev/null; then
    rm -f "$out/info/$key.json"
    continue
  fi
  python3 - "$out/info/$key.json" "$file" "$models" "$shared/data/models" >> "$scenes" <<'EOF'
import json, os, sys
info = json.load(open(sys.argv[1]))
path = sys.argv[2]
if info.get("moving_objects", 0) > 0 or len(info.get("camera_keys", [])) > 1:
    root = sys.argv[3] if path.startswith(sys.argv[3]) else sys.argv[4]
    name = ("shared:" if root == sys.argv[4] else "") + os.path.relpath(path, root)
    print(f"{name}\t{path}\t{info['triangles']}")
EOF
done
echo "$(wc -l < "$scenes") scenes to diff" >&2

table="$out/table.md"
{
  echo "size $size, $frames frames per scene, kinetic backend$([ "$audit" = 1 ] && echo ', audit on'), $(date -u +%Y-%m-%dT%H:%MZ)"
  echo
  echo "| scene | triangles | against | real | ties | cracks | worst frame (real) | result | seconds |"
  echo "|---|---:|---|---:|---:|---:|---:|---|---:|"
} > "$table"
cat "$table"

failures=0
while IFS=$'\t' read -r name spec triangles; do
  for reference in $references; do
    tag=$(printf '%s' "$name" | tr '/: ' '___').$reference
    json="$out/json/$tag.json"
    rm -f "$json"
    start=$(date +%s.%N)
    args=(diff "$spec" --against "$reference" --size "$size" --frames "$frames" -q --json "$json" --report "$out/report/$tag")
    audit_flag=()
    [ "$audit" = 1 ] && audit_flag=(--audit)
    timeout "$timeout_s" "$kinray" "${args[@]}" "${audit_flag[@]}" > "$out/log/$tag.out" 2> "$out/log/$tag.err"
    status=$?
    seconds=$(python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$start" "$(date +%s.%N)")
    if [ -f "$json" ]; then
      read -r real ties cracks worst < <(python3 - "$json" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
worst = max(s["per_frame"], key=lambda f: f["mismatch_real"]) if s["per_frame"] else None
label = f'{worst["mismatch_real"]} at t={worst["time"]:.4g}' if worst and worst["mismatch_real"] else "0"
print(s["mismatch_real"], s["mismatch_tie"], s["cracks"], label.replace(" ", "_"))
EOF
)
    else
      real=-; ties=-; cracks=-; worst=-
    fi
    case $status in
      0) result=ok ;;
      1) if [ -f "$json" ]; then
           result=REAL
         else
           result="ERROR: $(tail -n 1 "$out/log/$tag.err" | sed 's/kinray: error: //' | cut -c1-110)"
           if [ "$audit" = 1 ]; then
             # The audit stops at the first violation; without it, count what the frames show.
             timeout "$timeout_s" "$kinray" "${args[@]}" > /dev/null 2>&1
             [ -f "$json" ] && read -r real ties cracks worst < <(python3 - "$json" <<'EOF2'
import json, sys
s = json.load(open(sys.argv[1]))
worst = max(s["per_frame"], key=lambda f: f["mismatch_real"]) if s["per_frame"] else None
label = f'{worst["mismatch_real"]} at t={worst["time"]:.4g}' if worst and worst["mismatch_real"] else "0"
print(s["mismatch_real"], s["mismatch_tie"], s["cracks"], label.replace(" ", "_"))
EOF2
) && result="$result (counts without --audit)"
           fi
         fi ;;
      2) result="bad input: $(tail -n 1 "$out/log/$tag.err" | cut -c1-160)" ;;
      124) result="TIMEOUT (${timeout_s} s)" ;;
      *) if [ "$status" -gt 128 ]; then result="CRASH (signal $((status - 128))): $(grep -m1 -E 'CHECK|audit' "$out/log/$tag.err" | cut -c1-160)"; else result="exit $status"; fi ;;
    esac
    [ "$status" = 0 ] || failures=$((failures + 1))
    line="| $name | $triangles | $reference | $real | $ties | $cracks | ${worst//_/ } | ${result//|/\\|} | $seconds |"
    echo "$line" | tee -a "$table"
  done
done < "$scenes"

echo >> "$table"
echo "$failures run(s) not ok" | tee -a "$table"
echo "table: $table" >&2
[ "$failures" = 0 ]
