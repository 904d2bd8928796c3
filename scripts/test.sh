#!/usr/bin/env bash
# Install dependencies, build, and run every test (GoogleTest through ctest) headless on
# lavapipe with the Vulkan validation layers on. The Khronos glTF-Validator (npm package
# gltf-validator) judges the test scenes when it can be installed into build/npm (best effort:
# without npm or the registry, GltfValidator.* says so and skips).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
if [ -z "${PRESKIN_GLTF_VALIDATOR:-}" ]; then
  if [ ! -d build/npm/node_modules/gltf-validator ] && command -v npm >/dev/null; then
    timeout 180 npm install --prefix build/npm --no-audit --no-fund --silent gltf-validator >/dev/null 2>&1 ||
      echo "test: gltf-validator could not be installed from npm; GltfValidator.* will skip"
  fi
  if [ -d build/npm/node_modules/gltf-validator ]; then
    PRESKIN_GLTF_VALIDATOR="$(pwd)/build/npm/node_modules/gltf-validator"
    export PRESKIN_GLTF_VALIDATOR
  fi
fi
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
