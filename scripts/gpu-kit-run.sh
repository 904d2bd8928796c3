#!/bin/sh
# The GPU kit's run.sh (scripts/gpu-kit.sh copies it into the kit): starts bin/preskin-gpu-kit
# with the kit's libraries, and the kit's Vulkan loader only when the system has none.
#   ./run.sh [--device N|NAME] [--quick] [--out FOLDER]   (default FOLDER: the kit's folder)
here="$(cd "$(dirname "$0")" && pwd)"
libs="$here/lib"
systemLoader=""
for d in /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu /lib64 /usr/lib64 /usr/lib /lib; do
    if [ -e "$d/libvulkan.so.1" ]; then systemLoader="$d/libvulkan.so.1"; break; fi
done
if [ -z "$systemLoader" ] && command -v ldconfig >/dev/null 2>&1 && ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1 '; then
    systemLoader="ldconfig"
fi
if [ -z "$systemLoader" ]; then
    echo "run.sh: no Vulkan loader on this system; using the kit's" >&2
    libs="$libs:$here/lib/vulkan"
fi
out="$here"
for arg in "$@"; do
    case "$arg" in --out|--out=*) out="" ;; esac
done
LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export LD_LIBRARY_PATH
if [ -n "$out" ]; then
    exec "$here/bin/preskin-gpu-kit" --out "$out" "$@"
fi
exec "$here/bin/preskin-gpu-kit" "$@"
