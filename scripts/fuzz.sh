#!/usr/bin/env bash
# Runs the libFuzzer targets (glTF/GLB loader, profiles and LUT manifests, HDR/EXR environments)
# of the sanitizer build, each for SECONDS (default 600), from the seed corpora in tests/data.
# New inputs go to build-asan/fuzz/corpus/<target> (kept between runs); a crash, leak, timeout or
# sanitizer report stops the target, leaves the input in build-asan/fuzz/artifacts/ and fails the
# script. Each target's executions and coverage are printed at the end.
#   scripts/fuzz.sh [SECONDS]        (builds build-asan first when needed: scripts/build-sanitizers.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
[ -x build-asan/fuzz/fuzz_gltf ] || ./scripts/build-sanitizers.sh
PRESKIN_DETECT_LEAKS=1 source scripts/sanitizer-env.sh

declare -A seeds=(
  [fuzz_gltf]="tests/data/gltf tests/data/hostile"
  [fuzz_profile]="tests/data/profiles tests/data/hostile/deep_manifest luts/manifest.json tests/data/hostile/deep_profile.json"
  [fuzz_environment]="tests/data/environments tests/data/hostile/huge_header_no_pixels.hdr tests/data/hostile/oversized_header.hdr tests/data/hostile/radiance_near_flt_max.hdr"
)
summary=()
status=0
for target in fuzz_gltf fuzz_profile fuzz_environment; do
  corpus="build-asan/fuzz/corpus/$target"
  artifacts="build-asan/fuzz/artifacts/$target/"
  mkdir -p "$corpus" "$artifacts"
  seedDir="build-asan/fuzz/seeds/$target"
  rm -rf "$seedDir" && mkdir -p "$seedDir"
  for s in ${seeds[$target]}; do
    if [ -d "$s" ]; then find "$s" -maxdepth 1 -type f ! -name '*.py' -exec cp {} "$seedDir/" \;; else cp "$s" "$seedDir/"; fi
  done
  log="build-asan/fuzz/$target.log"
  echo "fuzz: $target for ${seconds}s"
  if ! "build-asan/fuzz/$target" -max_total_time="$seconds" -max_len=65536 -timeout=60 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="$artifacts" "$corpus" "$seedDir" >"$log" 2>&1; then
    echo "fuzz: $target FAILED, see $log and $artifacts" >&2
    tail -n 40 "$log" >&2
    status=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -n 1 || echo "cov: ?")
  summary+=("$target: $runs executions, $cov (edges and features reached), corpus $(ls "$corpus" | wc -l) inputs")
done
printf 'fuzz: %s\n' "${summary[@]}"
exit $status
