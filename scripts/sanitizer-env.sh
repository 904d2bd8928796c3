# Environment for running the sanitizer build (sourced by scripts/test-sanitizers.sh and
# scripts/fuzz.sh): every report is fatal. Leak detection is on for the fuzz targets (CPU code
# only); the test suite runs without it, since the Vulkan driver (lavapipe) is unloaded before
# LeakSanitizer runs at exit and its allocations can then be told apart from no one's. The
# leaks that remain in third-party libraries preskin cannot free (OpenImageIO's caches, TBB's
# workers) are suppressed by tests/sanitizers/lsan.supp.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=${PRESKIN_DETECT_LEAKS:-0}:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
