#!/usr/bin/env bash
# The continuous checks beyond the test suite (README "Continuous checks"); tools/setup.sh
# installs what they need and then runs this.
#
#   bash tools/checks.sh sanitize   # build-sanitize/: everything with ASan + UBSan, the whole suite
#   bash tools/checks.sh fuzz       # build-fuzz/: the libFuzzer harnesses (clang-14), each run for
#                                   # KINRAY_FUZZ_SECONDS (default 30) from its seed corpus, with
#                                   # libFuzzer's seed KINRAY_FUZZ_SEED (default 0: a random one)
#   bash tools/checks.sh fuzz NAME  # one harness only
#   bash tools/checks.sh slurm      # a one-node Slurm cluster renders a shot with the shipped job
#                                   # array (tools/slurm/), a task cancelled and requeued included
#
# Extra CMake arguments (a compiler launcher such as ccache, say) go in KINRAY_CMAKE_ARGS.
set -euo pipefail

mode="${1:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
read -r -a extra <<<"${KINRAY_CMAKE_ARGS:-}"
jobs="$(nproc)"

# Sanitizer settings for everything these checks run, the kinray processes the suite starts
# included. Every UBSan finding stops the program with a stack (the build also makes them
# fatal); leaks are reported at exit. Nothing of kinray's own is suppressed.
# allocator_may_return_null keeps C++'s std::bad_alloc for an allocation that cannot be had (ASan
# would abort instead): kinray turns that into an error, and the reading child of model_guard.h
# relies on it under its address-space limit.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:check_initialization_order=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# Leaks inside third-party libraries only, each with its reason (tools/lsan_suppressions.txt).
# The count of suppressed leaks that LeakSanitizer prints at exit is not printed: it would follow
# kinray's own one-line errors on stderr, which the suite compares whole (OSMesa's leak, say).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/tools/lsan_suppressions.txt:print_suppressions=0}"

case "$mode" in
  sanitize)
    echo "checks: building into build-sanitize/ (AddressSanitizer + UndefinedBehaviorSanitizer)"
    cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Release -DKINRAY_SANITIZE=ON \
      -DKINRAY_BUILD_BENCHMARKS=OFF "${extra[@]}"
    cmake --build build-sanitize -j "$jobs" --target kinray kinray_test
    ctest --test-dir build-sanitize --output-on-failure -j2
    ;;
  fuzz)
    echo "checks: building the fuzz harnesses into build-fuzz/ (clang-14, libFuzzer, ASan + UBSan)"
    cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 \
      -DKINRAY_FUZZ=ON -DKINRAY_BUILD_TESTS=OFF -DKINRAY_BUILD_BENCHMARKS=OFF "${extra[@]}"
    cmake --build build-fuzz -j "$jobs" --target fuzz_all
    seconds="${KINRAY_FUZZ_SECONDS:-30}"
    mapfile -t names < build-fuzz/fuzz_targets.txt
    if [[ -n "${2:-}" ]]; then names=("$2"); fi
    failed=()
    for name in "${names[@]}"; do
      [[ -n "$name" ]] || continue
      # New inputs go to the first folder (build-fuzz/corpus/NAME, kept between local runs); the
      # committed seeds and regressions are read only.
      work="build-fuzz/corpus/$name" artifacts="build-fuzz/artifacts/$name"
      mkdir -p "$work" "$artifacts"
      inputs=("$work" "tests/fuzz/corpus/$name")
      [[ -d "tests/fuzz/regressions/$name" ]] && inputs+=("tests/fuzz/regressions/$name")
      dictionary=()
      [[ -f "tests/fuzz/dictionaries/$name.dict" ]] && dictionary=("-dict=tests/fuzz/dictionaries/$name.dict")
      echo "checks: fuzz_$name for ${seconds} s"
      start=$SECONDS
      if ! "build-fuzz/bin/fuzz_$name" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 \
        -seed="${KINRAY_FUZZ_SEED:-0}" \
        -print_final_stats=1 -artifact_prefix="$artifacts/" "${dictionary[@]}" "${inputs[@]}" \
        >"build-fuzz/fuzz_$name.log" 2>&1; then
        failed+=("$name")
        tail -n 60 "build-fuzz/fuzz_$name.log"
        echo "checks: fuzz_$name found a problem; its input is in $artifacts/. Fix it, then keep" \
          "the input as tests/fuzz/regressions/$name/<what-it-was> (the suite replays it)."
      fi
      runs="$(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "build-fuzz/fuzz_$name.log" | grep -o '[0-9]*$' || true)"
      echo "checks: fuzz_$name: ${runs:-?} inputs in $((SECONDS - start)) s"
    done
    passed=0
    for name in "${names[@]}"; do [[ -n "$name" ]] && passed=$((passed + 1)); done
    passed=$((passed - ${#failed[@]}))
    # The closing line in the plain form CI reads: harnesses that ran clean and that found something.
    echo "fuzz: $passed passed, ${#failed[@]} failed"
    if ((${#failed[@]} > 0)); then
      echo "checks: fuzzing found problems in: ${failed[*]}" >&2
      exit 1
    fi
    ;;
  slurm)
    # Installs Slurm and MUNGE, starts its own daemons in a temporary folder and stops them.
    exec bash tools/slurm/check.sh
    ;;
  *)
    echo "usage: bash tools/checks.sh sanitize|fuzz [NAME]|slurm" >&2
    exit 2
    ;;
esac
