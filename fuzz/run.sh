#!/usr/bin/env bash
# Builds the libFuzzer targets into build/fuzz (clang, ASan + UBSan) and runs each for
# SECONDS (default 600). Corpus: the committed seeds fuzz/corpus/<target> (read only) plus
# the working corpus build/fuzz/corpus/<target>, where libFuzzer adds the inputs it finds.
# Usage: fuzz/run.sh [SECONDS] [TARGET...]   targets: scene_parser checkpoint_reader
# Crashes are written to build/fuzz/artifacts/<target>/ and make the script exit non-zero.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene_parser checkpoint_reader)
build="$root/build/fuzz"
cxx="${CXX_FUZZ:-clang++-14}"
cc="${CC_FUZZ:-clang-14}"

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" -DDUSTLIFT_FUZZ=ON \
  -DDUSTLIFT_WITH_VTK=OFF -DDUSTLIFT_BUILD_TESTS=OFF -DDUSTLIFT_BUILD_BENCH=OFF -DDUSTLIFT_NATIVE=OFF >/dev/null
cmake --build "$build" -j2 --target $(printf 'fuzz_%s ' "${targets[@]}")

status=0
for t in "${targets[@]}"; do
  seeds="$root/fuzz/corpus/$t"
  corpus="$build/corpus/$t"
  artifacts="$build/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  echo "== fuzz_$t for ${seconds}s, $(ls "$seeds" | wc -l) seeds, working corpus $(ls "$corpus" | wc -l) files"
  # -rss_limit_mb: HDF5 payloads may ask for large allocations; 2 GB is a real failure.
  # The checkpoint reader's sealed mode hands corrupt HDF5 to libhdf5, which asks malloc for
  # absurd sizes (and copes with NULL) and may have bugs of its own: let malloc return NULL,
  # and keep fuzzing after a crash (fork mode) so that every finding is collected.
  extra=()
  asan="allocator_may_return_null=0"
  if [ "$t" = checkpoint_reader ]; then
    extra=(-fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1)
    asan="allocator_may_return_null=1"
  fi
  rc=0
  ASAN_OPTIONS="$asan" LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0" \
    "$build/fuzz/fuzz_$t" "$corpus" "$seeds" -max_total_time="$seconds" -artifact_prefix="$artifacts/" \
    -rss_limit_mb=2048 -max_len=65536 -timeout=30 -print_final_stats=1 "${extra[@]}" >"$build/fuzz_$t.log" 2>&1 || rc=$?
  grep -E "^#[0-9]+ +(DONE|INITED)|stat::number_of_executed_units|stat::peak_rss|ERROR|SUMMARY" "$build/fuzz_$t.log" || true
  [ "$rc" -eq 0 ] || { echo "   fuzz_$t FAILED (exit $rc), see artifacts in $artifacts"; status=1; }
  found=$(ls "$artifacts" | wc -l)
  [ "$found" -eq 0 ] || { echo "   $found crash/leak/oom inputs in $artifacts"; status=1; }
  echo "   corpus now $(ls "$corpus" | wc -l) files; log $build/fuzz_$t.log"
done
exit $status
