#!/usr/bin/env bash
# The main job: install dependencies, build, and render the bundled head scene headless to
# head.png (1280x720), printing the output path and the frame time. Arguments are passed on to
# `preskin render` (for example --out other.png or --device llvmpipe).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
./build/bin/preskin render --out head.png "$@"
