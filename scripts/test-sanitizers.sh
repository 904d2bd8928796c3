#!/usr/bin/env bash
# The sanitizer job of CI: builds build-asan (clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# every report fatal; scripts/build-sanitizers.sh), runs its tests there: the folders tests/unit,
# tests/gpu and tests/e2e (the code that reads input, the renderer on real scenes, the tools end to
# end; tests/CMakeLists.txt says why the other kinds stay with the regular build). Then every
# fuzz target runs for FUZZ_SECONDS (default 30) from the seed corpora (scripts/fuzz.sh). The
# tests run in one process per core (gtest shards): starting a sanitized process costs seconds.
# Prints the time each step took.
set -euo pipefail
cd "$(dirname "$0")/.."
fuzzSeconds="${FUZZ_SECONDS:-30}"
./scripts/install-deps.sh
t0=$(date +%s)
./scripts/build-sanitizers.sh
t1=$(date +%s)
source scripts/sanitizer-env.sh
shards="$(nproc)"
pids=()
for ((i = 0; i < shards; ++i)); do
  GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i PRESKIN_TEST_DEVICE=llvmpipe LP_NUM_THREADS=1 \
    build-asan/tests/preskin_tests --gtest_brief=1 >"build-asan/tests-shard$i.log" 2>&1 &
  pids+=($!)
done
status=0
for ((i = 0; i < shards; ++i)); do
  if ! wait "${pids[$i]}"; then
    status=1
    echo "test-sanitizers: shard $i FAILED:" >&2
    tail -n 60 "build-asan/tests-shard$i.log" >&2
  fi
done
grep -h "tests ran\|PASSED\|FAILED" build-asan/tests-shard*.log || true
[ $status -eq 0 ] || exit 1
t2=$(date +%s)
./scripts/fuzz.sh "$fuzzSeconds"
t3=$(date +%s)
echo "test-sanitizers: build $((t1 - t0)) s, tests $((t2 - t1)) s, fuzzing $((t3 - t2)) s"
