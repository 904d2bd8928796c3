#!/usr/bin/env bash
# Writes the GPU kit: a self-contained folder that measures every performance goal of preskin on
# a machine with nothing installed but a GPU driver (x86-64 Linux):
#   DIR/run.sh [--device N|NAME] [--quick] [--out FOLDER]   -> gpu-report.json, gpu-report.md
#   DIR/bin/preskin-gpu-kit        the program (samples/gpukit), built against the core library
#   DIR/lib/                       libpreskin and every library it and the program load beyond
#                                  glibc, libstdc++ and libgcc (found through run.sh)
#   DIR/lib/vulkan/libvulkan.so.1  a Vulkan loader, used only when the system has none
#   DIR/lib/runtime/               glibc and libstdc++, used only when the system's are older
#   DIR/lib/glvnd/                 glvnd's dispatch libraries, used only when the system has none
#   DIR/share/preskin/             the head scenes, the studio environment, the default LUTs
#                                  (raw tables: the core reads them without the image component)
#   DIR/LICENSES/                  the bundled libraries' and the sample assets' licences
# Usage: scripts/gpu-kit.sh DIR [BUILD] (BUILD: a configured build folder, default build/; it is
# built first). DIR must not exist or be empty; the kit is made beside it and renamed into place,
# so a failed run leaves nothing. Fails when the kit would exceed 48 MiB.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: $0 DIR [BUILD]" >&2; exit 2; }
dir="$1"
build="${2:-build}"
if [ -e "$dir" ] && [ -n "$(ls -A "$dir" 2>/dev/null || echo file)" ]; then
    echo "gpu-kit: $dir exists and is not an empty folder" >&2
    exit 1
fi
[ -f "$build/CMakeCache.txt" ] || ./scripts/build.sh
# One build and one install at a time in this build folder (tests run this script beside others).
flock "$build/.install.lock" cmake --build "$build" --target preskin_gpu_kit preskin_cli >/dev/null

tmp="$(mktemp -d "$(dirname "$(realpath -m "$dir")")/.gpu-kit.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
chmod 755 "$tmp"
mkdir -p "$tmp/lib/vulkan" "$tmp/share/preskin/samples/assets" "$tmp/LICENSES"

# The program, its RUNPATH rewritten to $ORIGIN/../lib by the install.
flock "$build/.install.lock" cmake --install "$build" --component gpukit --prefix "$tmp" >/dev/null
exe="$tmp/bin/preskin-gpu-kit"
[ -x "$exe" ] || { echo "gpu-kit: the install wrote no bin/preskin-gpu-kit" >&2; exit 1; }

# Every library the program loads (with the build's libpreskin), except the C/C++ runtime.
runtime='^(linux-vdso\.so|ld-linux-x86-64\.so|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libstdc\+\+\.so|libgcc_s\.so)'
LD_LIBRARY_PATH="$build/engine" ldd "$build/bin/preskin-gpu-kit" | while read -r name arrow path rest; do
    [ "$arrow" = "=>" ] || continue
    if [[ "$name" =~ $runtime ]]; then continue; fi
    [ -f "$path" ] || { echo "gpu-kit: $name not found" >&2; exit 1; }
    cp -L "$path" "$tmp/lib/$name"
    echo "$path" >>"$tmp/.sources"
done
# The C and C++ runtime, for a system whose own is older than the one the kit was built on
# (run.sh uses it only then): glibc's loader and libraries, libstdc++, libgcc_s.
mkdir -p "$tmp/lib/runtime"
for name in ld-linux-x86-64.so.2 libc.so.6 libm.so.6 libdl.so.2 libpthread.so.0 librt.so.1 libstdc++.so.6 libgcc_s.so.1; do
    path="$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ && !found {print $NF; found = 1}')"
    [ -n "$path" ] && [ -f "$path" ] || { echo "gpu-kit: $name not found" >&2; exit 1; }
    cp -L "$path" "$tmp/lib/runtime/$name"
    echo "$path" >>"$tmp/.sources"
done
# glvnd's dispatch libraries (libGLdispatch, and libEGL and libOpenGL over it: none needs X11),
# which NVIDIA's Vulkan driver (libGLX_nvidia) loads and an NVIDIA container may lack (run.sh
# uses them only then).
mkdir -p "$tmp/lib/glvnd"
for name in libGLdispatch.so.0 libEGL.so.1 libOpenGL.so.0; do
    path="$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ && !found {print $NF; found = 1}')"
    [ -n "$path" ] && [ -f "$path" ] || { echo "gpu-kit: $name not found (scripts/install-deps.sh installs it)" >&2; exit 1; }
    cp -L "$path" "$tmp/lib/glvnd/$name"
    echo "$path" >>"$tmp/.sources"
done
loader="$(ldconfig -p | awk '/libvulkan\.so\.1 .*x86-64/ && !found {print $NF; found = 1}')"
[ -n "$loader" ] || { echo "gpu-kit: no Vulkan loader (libvulkan.so.1) on this machine to pack" >&2; exit 1; }
cp -L "$loader" "$tmp/lib/vulkan/libvulkan.so.1"
echo "$loader" >>"$tmp/.sources"
strip --strip-unneeded "$tmp/lib/"*.so* "$tmp/lib/vulkan/"*.so* "$tmp/lib/glvnd/"*.so* "$exe" 2>/dev/null || true

# Data: the scenes the bench renders, their textures and environment, raw default LUTs.
mkdir -p "$tmp/share/preskin/samples/assets/head"
for f in head.gltf head.bin head_animated.gltf head_animated.bin Map-COL.jpg Map-SPEC.jpg \
         Infinite-Level_02_Tangent_SmoothUV.jpg studio_small_05_1k.hdr studio_small_05_1k.LICENSE.txt \
         CREDITS.md LICENSE.txt LeePerrySmith_License.txt; do
    cp "samples/assets/head/$f" "$tmp/share/preskin/samples/assets/head/"
done
"$build/bin/preskin" bake --profile deon --raw --out "$tmp/share/preskin/luts" >/dev/null
# The commit the kit is made from (the reports name it).
echo "$(git describe --always --dirty 2>/dev/null || echo unknown) ($(date -u +%Y-%m-%d))" >"$tmp/share/preskin/kit-source.txt"

# Licences of what the kit carries.
cp samples/assets/head/CREDITS.md "$tmp/LICENSES/head-CREDITS.md"
while read -r source; do
    case "$source" in "$(realpath "$build")"/*|"$build"/*) continue ;; esac  # preskin's own
    pkg="$( (dpkg -S "$source" 2>/dev/null || dpkg -S "$(realpath "$source")" 2>/dev/null || true) | head -1 | cut -d: -f1)"
    if [ -n "$pkg" ] && [ -f "/usr/share/doc/$pkg/copyright" ]; then
        cp "/usr/share/doc/$pkg/copyright" "$tmp/LICENSES/$pkg.copyright"
    fi
done <"$tmp/.sources"
rm "$tmp/.sources"
cp "$(dirname "$0")/gpu-kit-run.sh" "$tmp/run.sh"
chmod +x "$tmp/run.sh"
cat > "$tmp/README.txt" <<EOF
preskin GPU kit ($(git describe --always --dirty 2>/dev/null || echo unknown), made $(date -u +%Y-%m-%d))

  ./run.sh [--device N|NAME] [--quick] [--out FOLDER]

measures preskin's performance goals on this machine's GPU (GPU timestamps per pass, the median
of 30 frames after warm-up) and writes gpu-report.json and gpu-report.md (into this folder unless
--out says otherwise). --quick: small sizes and 3 frames per figure, a check that the kit runs.
--device: an index or part of the device's name (default: the best GPU). A full run takes at most
8 minutes on an H100/H200-class GPU. Nothing is installed; the kit needs an x86-64 Linux and a
Vulkan driver (an NVIDIA container's driver is found under /usr/local/nvidia); it brings a Vulkan
loader and glvnd's dispatch libraries for a system without them and, for a system with an older
glibc or libstdc++, its own (--bundled-runtime forces it).
LICENSES/ holds the licences of what it carries.
EOF

size=$(du -sb "$tmp" | cut -f1)
if [ "$size" -gt $((48 * 1024 * 1024)) ]; then
    echo "gpu-kit: the kit takes $size bytes, over 48 MiB" >&2
    exit 1
fi
rmdir "$dir" 2>/dev/null || true
mv "$tmp" "$dir"
trap - EXIT
echo "gpu-kit: wrote $dir ($(du -sh "$dir" | cut -f1), $(ls "$dir/lib" | wc -l) files in lib/)"
