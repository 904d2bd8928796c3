#!/usr/bin/env bash
# Regenerates the golden images under tests/golden/<driver>/ (head_256.png: the bundled head scene
# as `preskin render` draws it at 256x256) by running the golden test in update mode
# (PRESKIN_UPDATE_GOLDENS=1), which renders with the CLI and writes the golden and device.txt.
#
# Usage: scripts/update-goldens.sh [DEVICE...]
#   DEVICE: a Vulkan device name or part of it, as `preskin render --device` takes it.
#   Default: llvmpipe, plus the device of every existing golden folder (its device.txt) that
#   this machine has; folders whose device is missing here are left as they are.
# Builds the tests first (and configures when needed) in $PRESKIN_BUILD_DIR, default build/.
# Review the new images (git diff --stat tests/golden; open them) before committing.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${PRESKIN_BUILD_DIR:-build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target preskin_tests
tests="$build/tests/preskin_tests"

requested=1
devices=("$@")
if [ ${#devices[@]} -eq 0 ]; then
  requested=0
  devices=(llvmpipe)
  for file in tests/golden/*/device.txt; do
    [ -f "$file" ] && devices+=("$(head -n 1 "$file")")
  done
fi

status=0
declare -A seen=()
for device in "${devices[@]}"; do
  [ -n "${seen[$device]:-}" ] && continue
  seen[$device]=1
  echo "update-goldens: rendering on '$device'"
  if ! PRESKIN_TEST_DEVICE="$device" PRESKIN_UPDATE_GOLDENS=1 LP_NUM_THREADS="${LP_NUM_THREADS:-$(nproc)}" \
      "$tests" --gtest_filter='SkinGolden.*' --gtest_brief=1; then
    if [ "$requested" = 1 ]; then
      echo "update-goldens: failed on '$device'" >&2
      status=1
    else
      echo "update-goldens: could not render on '$device' (not on this machine?); its goldens are kept" >&2
    fi
  fi
done
git status --short -- tests/golden || true
exit "$status"
