#!/usr/bin/env bash
# Install dependencies, build, and run every test (GoogleTest through ctest) headless on
# lavapipe with the Vulkan validation layers on.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
