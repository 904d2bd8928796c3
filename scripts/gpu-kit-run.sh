#!/bin/sh
# The GPU kit's run.sh (scripts/gpu-kit.sh copies it into the kit): starts bin/preskin-gpu-kit
# with the kit's libraries.
#   ./run.sh [--device N|NAME] [--quick] [--out FOLDER] [--bundled-runtime]
#   (default FOLDER: the kit's folder)
# - Vulkan loader: the system's; the kit's (lib/vulkan) only when the system has none.
# - Vulkan driver: the loader's own search; when it would find no manifest, the driver of an
#   NVIDIA container (nvidia_icd.json under /usr/local/nvidia, or a manifest written here for the
#   libGLX_nvidia.so.0 found on the system), with its folder on the library path.
# - glvnd (libGLdispatch, libEGL, libOpenGL: NVIDIA's Vulkan driver loads them): the system's; the
#   kit's (lib/glvnd) when the system has none.
# - C and C++ runtime: the system's; the kit's (lib/runtime: glibc's loader, libc, libm,
#   libstdc++, libgcc_s) when the program cannot start with the system's (an older glibc or
#   libstdc++), or when --bundled-runtime says so.
here="$(cd "$(dirname "$0")" && pwd)"
libs="$here/lib"
say() { echo "run.sh: $*" >&2; }

# A library the system's dynamic linker finds by name.
hasSystemLibrary() {
    for d in /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu /lib64 /usr/lib64 /usr/lib /lib; do
        [ -e "$d/$1" ] && return 0
    done
    command -v ldconfig >/dev/null 2>&1 && ldconfig -p 2>/dev/null | grep -q "$1 "
}
if ! hasSystemLibrary libvulkan.so.1; then
    say "no Vulkan loader on this system; using the kit's"
    libs="$libs:$here/lib/vulkan"
fi
# glvnd's dispatch libraries (NVIDIA's Vulkan driver does not start without them).
if ! hasSystemLibrary libGLdispatch.so.0; then
    say "no glvnd (libGLdispatch.so.0) on this system; using the kit's"
    libs="$libs:$here/lib/glvnd"
fi

# The driver manifests the loader searches by default (and VK_DRIVER_FILES / VK_ICD_FILENAMES).
hasManifest() {
    [ -n "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}${VK_ADD_DRIVER_FILES:-}" ] && return 0
    dirs="${XDG_CONFIG_DIRS:-/etc/xdg}:/usr/local/etc:/etc:${XDG_DATA_DIRS:-/usr/local/share:/usr/share}:/usr/local/share:/usr/share"
    saved="$IFS"
    IFS=':'
    for d in $dirs; do
        for m in "$d"/vulkan/icd.d/*.json; do
            if [ -e "$m" ]; then IFS="$saved"; return 0; fi
        done
    done
    IFS="$saved"
    return 1
}
if ! hasManifest; then
    for m in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/local/nvidia/etc/vulkan/icd.d/nvidia_icd.json; do
        if [ -e "$m" ]; then VK_DRIVER_FILES="$m"; export VK_DRIVER_FILES; break; fi
    done
    if [ -z "${VK_DRIVER_FILES:-}" ]; then
        glx=""
        for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu /usr/lib64 /lib/x86_64-linux-gnu; do
            if [ -e "$d/libGLX_nvidia.so.0" ]; then glx="$d/libGLX_nvidia.so.0"; break; fi
        done
        if [ -n "$glx" ]; then
            manifest="${TMPDIR:-/tmp}/preskin-kit-icd-$(id -u).json"  # one per user, rewritten each run
            printf '{ "file_format_version": "1.0.1", "ICD": { "library_path": "%s", "api_version": "1.3.0" } }\n' "$glx" >"$manifest"
            VK_DRIVER_FILES="$manifest"
            export VK_DRIVER_FILES
        fi
    fi
    if [ -n "${VK_DRIVER_FILES:-}" ]; then
        say "no Vulkan driver manifest in the loader's folders; using $VK_DRIVER_FILES"
    fi
fi
# The NVIDIA driver's own libraries, where the dynamic linker's cache does not list them.
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
    [ -d "$d" ] && libs="$libs:$d"
done

out="$here"
bundled=""
for arg in "$@"; do
    case "$arg" in
        --out | --out=*) out="" ;;
        --bundled-runtime) bundled=1 ;;
    esac
done
# --bundled-runtime is run.sh's, not the program's.
if [ -n "$bundled" ]; then
    for arg in "$@"; do
        shift
        [ "$arg" = "--bundled-runtime" ] || set -- "$@" "$arg"
    done
fi
LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export LD_LIBRARY_PATH
PRESKIN_DATA_DIR="$here/share/preskin"
export PRESKIN_DATA_DIR

exe="$here/bin/preskin-gpu-kit"
runtime="$here/lib/runtime"
if [ -z "$bundled" ] && ! "$exe" --help >/dev/null 2>"/tmp/preskin-kit-start.$$"; then
    say "the program does not start with this system's C/C++ runtime ($(head -c 300 "/tmp/preskin-kit-start.$$")); using the kit's"
    bundled=1
fi
rm -f "/tmp/preskin-kit-start.$$"
if [ -n "$bundled" ]; then
    set -- "$runtime/ld-linux-x86-64.so.2" --library-path "$runtime:$LD_LIBRARY_PATH" "$exe" "$@"
else
    set -- "$exe" "$@"
fi
if [ -n "$out" ]; then
    exec "$@" --out "$out"
fi
exec "$@"
