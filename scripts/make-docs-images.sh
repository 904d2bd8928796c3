#!/usr/bin/env bash
# Renders docs/skin-vs-standard.png: the bundled head with the standard material (left) and with
# pre-integrated skin (right), same view and lights: the scene's front camera, then a close-up of
# the nose's shadow on the cheek and the ear. Also docs/stereo-head.png: the head as a stereo
# pair (README, VR); docs/profiles-side-by-side.png: four diffusion profiles in one scene
# (README, Profiles); docs/fidelity-closeup.png: `preskin compare` of the cheek and nose close up
# at 768x768, shown at a third of its size (README, Fidelity; its reference takes minutes);
# docs/environment-lighting.png: the head under two environments, background on (README);
# docs/area-light-softbox.png: the head under a soft box and under a point light (README);
# docs/sun-penumbra.png: the head's close-up under its key light as a parallel light and as suns
# of 0.27 and 3 degrees (README, Area lights); docs/diffusion-methods.png: the close-up with Lambert
# skin, pre-integrated skin and the two baselines (README, docs/baselines.md);
# docs/khronos-suzanne-skin.png: a public model made for other viewers, as authored and as skin
# (README, Profiles); docs/viewer.png: the viewer with its panels (README).
# Needs ImageMagick (convert, montage): scripts/install-deps.sh --docs installs it.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v montage >/dev/null; then
  echo "make-docs-images: ImageMagick's montage is missing; run scripts/install-deps.sh --docs" >&2
  exit 1
fi
bin=${PRESKIN_BUILD_DIR:-build}/bin/preskin
[ -x "$bin" ] || ./scripts/build.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

render() { "$bin" render --camera front "$@" >/dev/null; }
render --width 520 --height 520 --out "$tmp/front_std.png" --standard
render --width 520 --height 520 --out "$tmp/front_skin.png"
render --width 1200 --height 1200 --out "$tmp/big_std.png" --standard
render --width 1200 --height 1200 --out "$tmp/big_skin.png"
for v in std skin; do convert "$tmp/big_$v.png" -crop 520x520+500+440 +repage "$tmp/close_$v.png"; done
montage -label "standard material" "$tmp/front_std.png" -label "pre-integrated skin" "$tmp/front_skin.png" \
  -label "standard, close-up" "$tmp/close_std.png" -label "skin, close-up" "$tmp/close_skin.png" \
  -tile 2x2 -geometry +4+4 -background '#202022' -fill '#dddddd' -pointsize 16 -depth 8 docs/skin-vs-standard.png
echo "wrote docs/skin-vs-standard.png"
# The stereo pair: both eyes in one multiview pass with 4x MSAA, left eye on the left.
"$bin" render --stereo --ipd 0.063 --msaa 4 --width 480 --height 540 --out docs/stereo-head.png >/dev/null
echo "wrote docs/stereo-head.png"
# Four diffusion profiles in one scene (docs/profiles.md): the head four times, one profile each.
"$bin" render samples/assets/head/head_profiles.gltf --camera front --width 1200 --height 400 \
  --out docs/profiles-side-by-side.png >/dev/null
echo "wrote docs/profiles-side-by-side.png"
# The fidelity close-up: reference, skin and Lambert with their error maps.
"$bin" compare --camera cheek_nose --width 768 --height 768 --json "$tmp/closeup.json" --image "$tmp/closeup.png" >/dev/null
convert "$tmp/closeup.png" -resize 33.333% -depth 8 docs/fidelity-closeup.png
echo "wrote docs/fidelity-closeup.png"
# Environment lighting (README): the head lit by an environment alone (its extracted light casts
# the shadow), the environment as background: the synthetic sunny sky and the studio.
render --width 480 --height 480 --env samples/assets/sky/sunny_sky_1k.hdr --no-scene-lights --background env \
  --exposure 0.5 --out "$tmp/env_sky.png"
render --width 480 --height 480 --env samples/assets/head/studio_small_05_1k.hdr --no-scene-lights --background env \
  --out "$tmp/env_studio.png"
montage "$tmp/env_sky.png" "$tmp/env_studio.png" -tile 2x1 -geometry +4+4 -background '#202022' -depth 8 \
  docs/environment-lighting.png
echo "wrote docs/environment-lighting.png"
# Area lights (README, docs/area-lights.md): the head under a 1 m x 0.5 m soft box and under the
# point light it stands for in a viewer without PRESKIN_lights_area, from the front and close up.
python3 scripts/make-area-light-scenes.py "$tmp/area" >/dev/null
for s in softbox softbox_point; do
  "$bin" render "$tmp/area/head_$s.gltf" --camera front --width 480 --height 480 --out "$tmp/$s.png" >/dev/null
  "$bin" render "$tmp/area/head_$s.gltf" --camera cheek_nose --width 480 --height 480 --out "$tmp/${s}_close.png" >/dev/null
done
montage -label "point light" "$tmp/softbox_point.png" -label "1 m x 0.5 m soft box" "$tmp/softbox.png" \
  -label "point light, close-up" "$tmp/softbox_point_close.png" -label "soft box, close-up" "$tmp/softbox_close.png" \
  -tile 4x1 -geometry +4+4 -background '#202022' -fill '#dddddd' -pointsize 16 -depth 8 docs/area-light-softbox.png
echo "wrote docs/area-light-softbox.png"
# Suns (README, docs/area-lights.md): the key light's shadow as its angular radius grows.
for r in 0 0.27 3; do
  "$bin" render samples/assets/head/head.gltf --camera cheek_nose --width 480 --height 480 --sun-radius "$r" \
    --out "$tmp/sun_$r.png" >/dev/null
done
montage -label "parallel light" "$tmp/sun_0.png" -label "sun, 0.27 degrees" "$tmp/sun_0.27.png" \
  -label "3 degrees" "$tmp/sun_3.png" \
  -tile 3x1 -geometry +4+4 -background '#202022' -fill '#dddddd' -pointsize 16 -depth 8 docs/sun-penumbra.png
echo "wrote docs/sun-penumbra.png"
# The methods preskin replaces (README, docs/baselines.md): the cheek and nose close-up with
# Lambert skin, preskin's pre-integrated skin, the screen-space and the texture-space baselines.
for m in preintegrated screen texture; do
  "$bin" render --camera cheek_nose --width 480 --height 480 --diffusion "$m" --out "$tmp/method_$m.png" >/dev/null
done
"$bin" render --camera cheek_nose --width 480 --height 480 --standard --out "$tmp/method_lambert.png" >/dev/null
montage -label "Lambert skin" "$tmp/method_lambert.png" -label "pre-integrated (preskin, 1 pass)" \
  "$tmp/method_preintegrated.png" -label "screen-space separable (+2 passes)" "$tmp/method_screen.png" \
  -label "texture-space (+13 passes)" "$tmp/method_texture.png" \
  -tile 4x1 -geometry +4+4 -background '#202022' -fill '#dddddd' -pointsize 16 -depth 8 docs/diffusion-methods.png
echo "wrote docs/diffusion-methods.png"
# A model made for other viewers (docs/gltf-extensions.md): Khronos's Iridescence Suzanne
# (samples/assets/suzanne, CC0; its materials carry KHR_materials_volume) as its authors' materials
# shade in preskin's standard path, and rendered as skin (--skin all).
for m in none all; do
  "$bin" render samples/assets/suzanne/IridescenceSuzanne.gltf --skin "$m" --width 900 --height 420 \
    --out "$tmp/suzanne_$m.png" >/dev/null 2>&1
  convert "$tmp/suzanne_$m.png" -crop 900x250+0+75 +repage "$tmp/suzanne_${m}_band.png"
done
montage -label "as authored (standard material)" "$tmp/suzanne_none_band.png" \
  -label "rendered as skin (--skin all)" "$tmp/suzanne_all_band.png" \
  -tile 1x2 -geometry +4+4 -background '#202022' -fill '#dddddd' -pointsize 16 -depth 8 docs/khronos-suzanne-skin.png
echo "wrote docs/khronos-suzanne-skin.png"
# The viewer with its panels (README, The viewer): the bundled head at 1600x900 under a virtual
# display (xvfb-run; scripts/install-deps.sh installs it), the screenshot taken with the panels.
viewer=${PRESKIN_BUILD_DIR:-build}/bin/preskin-viewer
if [ -x "$viewer" ]; then
  xvfb-run -a -s "-screen 0 1600x900x24" "$viewer" --width 1600 --height 900 --frames 12 --no-shader-reload \
    --screenshot "$tmp/viewer.png" --screenshot-ui >/dev/null
  cp "$tmp/viewer.png" docs/viewer.png
  echo "wrote docs/viewer.png"
else
  echo "make-docs-images: $viewer is not built (PRESKIN_BUILD_VIEWER=OFF); docs/viewer.png kept" >&2
fi
