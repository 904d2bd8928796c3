#!/usr/bin/env bash
# Configures and builds the sanitizer tree build-asan with clang: AddressSanitizer and
# UndefinedBehaviorSanitizer (every report fatal) plus libFuzzer coverage on all code, -O1; the
# tool, the test binary and the fuzz targets (no viewer). Extra arguments go to CMake's configure.
set -euo pipefail
cd "$(dirname "$0")/.."
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS_RELEASE="-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DPRESKIN_SANITIZE=ON -DPRESKIN_BUILD_FUZZERS=ON -DPRESKIN_BUILD_VIEWER=OFF -DPRESKIN_WARNINGS_AS_ERRORS=OFF "$@" >/dev/null
cmake --build build-asan -j"$(nproc)" --target preskin_cli preskin_tests fuzz_gltf fuzz_profile fuzz_environment
