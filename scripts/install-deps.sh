#!/usr/bin/env bash
# Installs every Debian 12 package preskin needs to build, run and test. Idempotent and
# non-interactive: packages already present are skipped; uses sudo when not root.
# --docs also installs what scripts/make-docs-images.sh needs (ImageMagick).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libvulkan-dev libvulkan-volk-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools glslang-dev spirv-tools
  libglm-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libjpeg-dev libpng-dev libopenimageio-dev
  libimgui-dev libcli11-dev libfmt-dev libtbb-dev libembree-dev
  libgtest-dev libbenchmark-dev xvfb xauth libx11-dev
  libglvnd0 libegl1 libglx0 libopengl0 libgl1
  python3-numpy python3-matplotlib clang libclang-rt-14-dev valgrind
)
for arg in "$@"; do
  case "$arg" in
    --docs) packages+=(imagemagick) ;;
    *) echo "install-deps: unknown option $arg (only --docs)" >&2; exit 1 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
