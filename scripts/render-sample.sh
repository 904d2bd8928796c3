#!/usr/bin/env bash
# The main job: install dependencies, build, and render the bundled head scene headless to
# head.png (1280x720; ignored by git), printing the output path and the frame time. Arguments
# are passed on to `preskin render` (for example --out other.png or --device llvmpipe); an
# --out of the caller's replaces head.png. PRESKIN_SKIP_SETUP=1 skips installing and building
# (the build in ${PRESKIN_BUILD_DIR:-build} must exist).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${PRESKIN_SKIP_SETUP:-}" ]; then
  ./scripts/install-deps.sh
  ./scripts/build.sh
fi
out=(--out head.png)
for arg in "$@"; do
  case "$arg" in --out | --out=* | -o) out=() ;; esac
done
"${PRESKIN_BUILD_DIR:-build}/bin/preskin" render "${out[@]}" "$@"
