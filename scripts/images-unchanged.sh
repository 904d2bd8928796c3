#!/usr/bin/env bash
# Renders one set of scenes and `compare` reports with two builds of the tool and says whether
# every image and every figure is the same: the check that a change meant to leave pictures alone
# did. Usage: scripts/images-unchanged.sh OLD_PRESKIN NEW_PRESKIN (e.g. a build of the parent
# commit in a git worktree, and build/bin/preskin). Covers the head (front, close-ups, stereo
# with MSAA 4x, 300 scattered lights clustered and 64 in one loop, the sunny sky with its
# background), the animated head and tube at a time, the four-profile heads, both skin spheres,
# and `compare` on the 10 mm sphere and the head. PNGs are compared by their pixels
# (scripts/png-pixels.py), reports by their figures. Exit status 1 when anything differs.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: $0 OLD_PRESKIN NEW_PRESKIN" >&2; exit 2; }
assets="$(pwd)/samples/assets"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

renderAll() {
    local bin="$1" out="$2"
    mkdir -p "$out"
    r() { local name="$1"; shift; "$bin" render "$@" --out "$out/$name.png" >"$out/$name.log" 2>&1 || echo "$bin: $name failed" >&2; }
    c() { local name="$1"; shift; "$bin" compare "$@" --json "$out/$name.json" --image "$out/$name.png" >"$out/$name.log" 2>&1 || echo "$bin: $name failed" >&2; }
    r head "$assets/head/head.gltf" --width 512 --height 512
    r head_cheek "$assets/head/head.gltf" --width 384 --height 384 --camera cheek_nose
    r head_lips "$assets/head/head.gltf" --width 384 --height 384 --camera lips
    r head_ear "$assets/head/head.gltf" --width 384 --height 384 --camera ear
    r head_stereo_msaa "$assets/head/head.gltf" --width 256 --height 256 --stereo --msaa 4
    r head_lights "$assets/head/head.gltf" --width 320 --height 240 --lights 300 --seed 3
    r head_lights_all "$assets/head/head.gltf" --width 320 --height 240 --lights 64 --light-loop all
    r head_sky "$assets/head/head.gltf" --width 320 --height 320 --env "$assets/sky/sunny_sky_1k.hdr" --background env
    r head_animated "$assets/head/head_animated.gltf" --width 320 --height 320 --time 0.7
    r head_profiles "$assets/head/head_profiles.gltf" --width 480 --height 200
    r sphere10 "$assets/spheres/sphere_10mm.gltf" --width 256 --height 256
    r sphere40 "$assets/spheres/sphere_40mm.gltf" --width 256 --height 256 --no-specular
    r tube "$assets/tube/tube.gltf" --width 256 --height 256 --time 0.5
    c compare_sphere10 "$assets/spheres/sphere_10mm.gltf" --width 160 --height 160
    c compare_head "$assets/head/head.gltf" --width 160 --height 160
}

renderAll "$1" "$work/old"
renderAll "$2" "$work/new"
status=0
for f in "$work"/old/*.png "$work"/old/*.json; do
    name="$(basename "$f")"
    if [[ "$name" == *.json ]]; then
        # Figures only: timings differ run to run.
        same=$(python3 -c 'import json, sys
def figures(d):
    if isinstance(d, dict): return {k: figures(v) for k, v in d.items() if not k.endswith("_ms") and "seconds" not in k}
    if isinstance(d, list): return [figures(x) for x in d]
    return d
print(int(figures(json.load(open(sys.argv[1]))) == figures(json.load(open(sys.argv[2])))))' "$f" "$work/new/$name")
    else
        # Pixels, not bytes: two PNG writers may compress the same pixels differently.
        same=$(python3 scripts/png-pixels.py "$f" "$work/new/$name" >/dev/null && echo 1 || echo 0)
    fi
    if [ "$same" = 1 ]; then echo "same      $name"; else echo "DIFFERENT $name"; status=1; fi
done
exit $status
