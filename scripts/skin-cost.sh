#!/usr/bin/env bash
# What each skin technique costs on this machine's Vulkan device, two ways, written as a Markdown
# table (docs/skin-cost-table.md by default; docs/skin-cost.md explains it):
#  - instructions per frame under valgrind's callgrind, whole process (every llvmpipe thread):
#    `preskin render --frames N` switches collection on after its warm-up frame and off after the
#    N measured frames (callgrind client requests, run with --instr-atstart=no), so start-up,
#    shader compiles and first-use costs are not counted; the count / N is one frame. Repeatable
#    on a busy machine, where wall time is not. At WIDTH x HEIGHT (default 1280x720, the goal's
#    size; valgrind runs the JIT code about 50 times slower, about a minute per configuration);
#  - time: `preskin bench`'s skin_techniques section (the all-on frame minus the frame with one
#    technique off, interleaved, medians; 1280x720) and the skin / standard-material ratio, in
#    wall time and in the process's CPU time per frame (on lavapipe the rendering threads' work,
#    steadier than wall time when other programs share the machine).
# A technique's cost is the all-on frame (the default, high) minus the frame with that technique
# off (its standard fallback on), an addition's (lut_other_lights, in no tier) its frame minus the
# all-on one; the standard frame is the same scene with the skin extension removed
# (`--skin none`). Both at LIGHTS scattered lights (default 256) on the bundled head.
#  - what each buys: with REFERENCES=DIR, `preskin compare` of the README's four head views (front
#    1024x1024; cheek_nose, lips, ear 768x768) with the same switch, skin's error over Lambert's
#    against the diffusion reference (pooled RMSE; all, concave, near cast-shadow edges, averaged
#    over the views). DIR keeps the references (<view>.exr; the first run computes each, 5 to 15
#    minutes at 768x768 on two cores, and later runs read them back). VIEWS (default "front
#    cheek_nose lips ear") chooses among the four.
# The quality tiers (--skin-quality low, medium) get the same rows.
#   scripts/skin-cost.sh [OUT.md]
#   env: FRAMES (default 1), WIDTH, HEIGHT, LIGHTS, REPS (bench, default 5), JOBS (parallel
#   valgrind runs, default: cores), SCENE (default: the bundled head), NO_BENCH=1 (instructions only),
#   REFERENCES=DIR (the fidelity columns), VIEWS, PRESKIN (the preskin program; default build/bin/preskin)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-docs/skin-cost-table.md}"
frames="${FRAMES:-1}"
width="${WIDTH:-1280}"
height="${HEIGHT:-720}"
lights="${LIGHTS:-256}"
reps="${REPS:-5}"
jobs="${JOBS:-$(nproc)}"
scene="${SCENE:-}"
preskin="${PRESKIN:-build/bin/preskin}"  # PRESKIN: another build or an installed tree's bin/preskin
[ -x "$preskin" ] || { echo "skin-cost: build the tools first (scripts/build.sh or cmake --build build)" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "skin-cost: needs valgrind (apt-get install valgrind)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# valgrind decodes only the instructions the processor's CPUID advertises. Some virtual machines
# hide RDTSCP but execute it, and libhwy (loaded with OpenImageIO's JPEG XL support) runs it when
# it loads, so valgrind stops preskin with SIGILL. There the measured runs load a copy of libhwy
# whose RDTSCP instructions (0f 01 f9) read RDTSC; NOP (0f 31 90): the same time stamp counter
# without the processor number, which libhwy does not use to time. Only the copy is changed, and
# only when every match of the bytes is an RDTSCP instruction.
(valgrind --tool=none "$preskin" --help >/dev/null 2>"$work/probe.log" || true) 2>/dev/null
if grep -q "Illegal opcode" "$work/probe.log"; then
  hwy="$(ldd "$preskin" | awk '/libhwy/ && !seen {print $3; seen = 1}')"
  [ -n "$hwy" ] || { echo "skin-cost: valgrind cannot run $preskin here:" >&2; tail -5 "$work/probe.log" >&2; exit 1; }
  mkdir -p "$work/lib"
  python3 - "$hwy" "$work/lib/$(basename "$(ldd "$preskin" | awk '/libhwy/ && !seen {print $1; seen = 1}')")" <<'PY'
import subprocess, sys
src, dst = sys.argv[1:3]
data = open(src, "rb").read()
pattern = b"\x0f\x01\xf9"
listed = subprocess.run(["objdump", "-d", src], capture_output=True, text=True).stdout.count("rdtscp")
if data.count(pattern) != listed:
    sys.exit(f"skin-cost: {src}: {data.count(pattern)} byte matches against {listed} rdtscp instructions; not patched")
open(dst, "wb").write(data.replace(pattern, b"\x0f\x31\x90"))
PY
  export LD_LIBRARY_PATH="$work/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  echo "skin-cost: this processor hides RDTSCP from valgrind; measuring with a copy of libhwy that reads RDTSC" >&2
fi

# name|flags (the rows of the table, in order)
configs=(
  "skin|"
  "standard|--skin none"
  "lut_diffuse|--no-lut-diffuse"
  "normal_prefilter|--no-normal-prefilter"
  "normal_map_levels|--no-normal-map-levels"
  "penumbra|--no-penumbra"
  "wide_penumbra|--no-wide-penumbra"
  "lut_shadow_light|--no-lut-shadow-light"
  "lut_other_lights|--lut-other-lights"
  "light_curvature|--no-light-curvature"
  "full_shadow_filter|--no-full-shadow-filter"
  "sh_ambient|--no-sh-skin"
  "transmission|--no-transmission"
  "dual_specular|--no-dual-specular"
  "opposing_light|--no-opposing-light"
  "specular_ibl|--no-specular-ibl"
  "quality_medium|--skin-quality medium"
  "quality_low|--skin-quality low"
  "all_off|--standard"
  "no_shadows|--no-shadows"
  "standard_no_shadows|--skin none --no-shadows"
  "stereo|--stereo"
  "stereo_standard|--stereo --skin none"
)
measure() {  # "name|flags" -> writes $work/<name>.count
  local name="${1%%|*}" flags="${1#*|}"
  # shellcheck disable=SC2086
  "$preskin" render $scene --lights "$lights" --width "$width" --height "$height" $flags \
    --out "$work/$name-warm.png" >/dev/null 2>&1  # fills Mesa's shader cache
  # shellcheck disable=SC2086
  valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$work/$name.cg" "$preskin" render $scene \
    --lights "$lights" --width "$width" --height "$height" --frames "$frames" $flags --out "$work/$name.png" \
    >"$work/$name.log" 2>&1 || { echo "skin-cost: $name failed:" >&2; tail -5 "$work/$name.log" >&2; return 1; }
  grep -o 'Collected : [0-9]*' "$work/$name.log" | head -1 | grep -o '[0-9]*$' >"$work/$name.count"
  echo "skin-cost: $name: $(( $(cat "$work/$name.count") / frames / 1000000 )) M instructions per frame" >&2
}
export -f measure
export preskin scene lights width height frames work
printf '%s\n' "${configs[@]}" | xargs -d '\n' -P "$jobs" -I{} bash -c 'measure "$1"' _ {}

# What each switch buys: compare on the four views, reading (or first computing) the references.
if [ -n "${REFERENCES:-}" ]; then
  mkdir -p "$REFERENCES"
  views=()
  for name in ${VIEWS:-front cheek_nose lips ear}; do
    case "$name" in
      front) views+=("front 1024") ;;
      cheek_nose | lips | ear) views+=("$name 768") ;;
      *) echo "skin-cost: VIEWS: '$name' is not one of front, cheek_nose, lips, ear" >&2; exit 1 ;;
    esac
  done
  for v in "${views[@]}"; do  # the references first, one at a time (each uses every core)
    set -- $v
    # shellcheck disable=SC2086
    "$preskin" compare $scene --camera "$1" --width "$2" --height "$2" --reference "$REFERENCES/$1.exr" \
      --json "$work/fidelity-skin-$1.json" >/dev/null 2>"$work/fidelity-skin-$1.log" ||
      { echo "skin-cost: compare $1 failed:" >&2; tail -3 "$work/fidelity-skin-$1.log" >&2; exit 1; }
  done
  for c in "lut_diffuse|--no-lut-diffuse" "normal_prefilter|--no-normal-prefilter" "penumbra|--no-penumbra" "wide_penumbra|--no-wide-penumbra" \
           "sh_ambient|--no-sh-skin" "transmission|--no-transmission" "opposing_light|--no-opposing-light" \
           "lut_shadow_light|--no-lut-shadow-light" "lut_other_lights|--lut-other-lights" \
           "light_curvature|--no-light-curvature" \
           "full_shadow_filter|--no-full-shadow-filter" \
           "quality_medium|--skin-quality medium" "quality_low|--skin-quality low"; do
    name="${c%%|*}" flags="${c#*|}"
    for v in "${views[@]}"; do
      set -- $v
      # shellcheck disable=SC2086
      "$preskin" compare $scene --camera "$1" --width "$2" --height "$2" --reference "$REFERENCES/$1.exr" $flags \
        --json "$work/fidelity-$name-$1.json" >/dev/null 2>"$work/fidelity-$name-$1.log" ||
        { echo "skin-cost: compare $name $1 failed:" >&2; tail -3 "$work/fidelity-$name-$1.log" >&2; exit 1; }
    done
    echo "skin-cost: fidelity of $name measured" >&2
  done
fi

bench_json=""
if [ -z "${NO_BENCH:-}" ]; then
  # shellcheck disable=SC2086
  "$preskin" bench $scene --counts 16 --skin-counts "$lights" --no-brute --no-build-compare \
    --no-lut-bake --no-vr --no-per-pixel --no-animation --no-profiles --reps "$reps" --out "$work/bench.json" >&2
  bench_json="$work/bench.json"
fi

device="$(grep -m1 '^preskin: frame time on ' "$work/skin.log" | sed 's/^preskin: frame time on //; s/: gpu .*//; s/ (median of [0-9]* frames)$//')"
python3 - "$work" "$out" "$width" "$height" "$lights" "$frames" "$bench_json" "$device" <<'PY'
import glob, json, os, sys
work, out, width, height, lights, frames, bench_path, device = sys.argv[1:9]
frames = int(frames)
count = {n[:-6]: int(open(os.path.join(work, n)).read()) / frames for n in os.listdir(work) if n.endswith(".count")}
bench = json.load(open(bench_path)) if bench_path else None
t = bench["skin_techniques"] if bench else None
# fidelity[name][view]: compare's regions (skin's pooled RMSE over Lambert's)
fidelity = {}
for path in glob.glob(os.path.join(work, "fidelity-*.json")):
    name, view = os.path.basename(path)[len("fidelity-"):-len(".json")].rsplit("-", 1)
    fidelity.setdefault(name, {})[view] = json.load(open(path))["regions"]
# The views measured, in the README's order.
views = [v for v in ["front", "cheek_nose", "lips", "ear"] if any(v in f for f in fidelity.values())]
sizes = {"front": "1024x1024", "cheek_nose": "768x768", "lips": "768x768", "ear": "768x768"}
def fid(name):
    """'all / concave / near edges' means over the views, and the per-view 'all'; blanks without references."""
    if name not in fidelity:
        return "| |"
    f = fidelity[name]
    def mean(region):  # over the views where the region has pixels
        r = [f[v][region]["ratioToLambertPooled"] for v in views if f[v][region]["pixels"] > 0]
        return f"{sum(r) / len(r):.3f}" if r else "no pixels"
    each = ", ".join(f"{f[v]['all']['ratioToLambertPooled']:.3f}" for v in views)
    return f"| {mean('all')} / {mean('concave')} / {mean('shadowEdge')} | {each} |"
skin, std = count["skin"], count["standard"]
M = lambda v: f"{v / 1e6:.1f}"
lines = [
    "# What the skin techniques cost, and what they buy",
    "",
    f"Measured by `scripts/skin-cost.sh` ({device or 'default Vulkan device'}), the bundled head with {lights} "
    "scattered lights. Instructions: valgrind's callgrind, whole process, the measured frames of `preskin render "
    f"--frames {frames}` only (start-up, shader compiles and the warm-up frame not counted), per frame, at "
    f"{width}x{height}."
    + (f" Time: `preskin bench` skin_techniques at {bench['width']}x{bench['height']}, interleaved frames, medians."
       if bench else ""),
    "A technique's cost is the all-on frame (the default, high) minus the frame with that technique off (its "
    "standard fallback on), the row marked added its frame minus the all-on one (its fidelity with it on); "
    "the costs overlap, so they do not add up to the total. Fidelity: `preskin compare` of the README's head "
    f"views ({', '.join(f'{v} {sizes[v]}' for v in views) or 'none measured'}) with the technique off, skin's pooled RMSE over "
    "Lambert's against the diffusion reference (below 1: closer than Lambert; higher than the all-on row: the "
    "technique buys accuracy there); specular is off in `compare`, so the specular rows buy nothing there, and "
    "it renders without normal maps (the reference shades the smooth surface), so the normal-map levels' row "
    "is not measured there (left blank).",
    "",
    "| | instructions per frame (M) | share of the skin frame | wall ms | process CPU ms | forward-pass ms "
    "| fidelity with it off: all / concave / near cast-shadow edges (mean of views) | all, per view |",
    "| --- | ---: | ---: | ---: | ---: | ---: | --- | --- |",
]
def timed(name):
    if not t or name not in t["cost_ms"]:
        return "| | | "
    c = t["cost_ms"][name]
    return f"| {c['wall']:.1f} | {c['cpu']:.1f} | {c['forward_gpu']:.1f} "
def frame(m):
    return f"| {m['wall_ms']:.1f} | {m['cpu_ms']:.1f} | {m['gpu_pass_ms']['forward']:.1f} "
lines.append(f"| skin frame, all techniques on | {M(skin)} | 100% "
             + (frame(t["skin"]) if t else "| | | ") + fid("skin"))
lines.append(f"| standard-material frame (`--skin none`) | {M(std)} | {100 * std / skin:.0f}% "
             + (frame(t["standard_material"]) if t else "| | | ") + "| | |")
labels = {"lut_diffuse": "diffuse LUT fetches (per light, per channel)",
          "normal_prefilter": "per-channel normals (geometric and normal-map)",
          "normal_map_levels": "normal-map levels per channel (of those)",
          "penumbra": "penumbra LUT", "wide_penumbra": "the wide shadow map (of the penumbra's)",
          "lut_shadow_light": "the diffuse LUT for the shadow light (of the LUT's; without it the row's fit)",
          "lut_other_lights": "added: the diffuse LUT for the other lights too (`--lut-other-lights`; in no tier)",
          "light_curvature": "the diffuse LUT's row along each light (of the LUT's; without it the mean curvature's)",
          "full_shadow_filter": "the shadow filter's 8 x 8 footprint (against 6 x 6)", "sh_ambient": "SH transfer", "transmission": "thickness and transmission",
          "opposing_light": "the opposing neighbours' light", "dual_specular": "dual specular",
          "specular_ibl": "specular IBL (prefiltered environment)"}
additions = {"lut_other_lights"}  # off by default: the row is its frame less the all-on one, its fidelity with it on
for name, label in labels.items():
    d = count[name] - skin if name in additions else skin - count[name]
    lines.append(f"| {label} (`{name}`) | {M(d)} | {100 * d / skin:.0f}% {timed(name)}{fid(name)}")
# Without a shadow map every light reads the diffuse LUT (no shadow light to tell the key by), so
# the shadow's cost is against the frame that reads it for every light with one.
d = count["lut_other_lights"] - count["no_shadows"]
ds = std - count["standard_no_shadows"]
lines.append(f"| shadow map and filter, skin (`--no-shadows`, against `--lut-other-lights`) | {M(d)} | {100 * d / skin:.0f}% | | | | | |")
lines.append(f"| shadow map and filter, standard material | {M(ds)} | {100 * ds / skin:.0f}% | | | | | |")
lines.append(f"| skin shader, every technique off (`--standard`) | {M(count['all_off'])} | "
             f"{100 * count['all_off'] / skin:.0f}% | | | | | |")
lines += [
    "",
    f"Skin / standard, instructions: {skin / std:.2f} (mono), "
    f"{count['stereo'] / count['stereo_standard']:.2f} (stereo, {M(count['stereo'])} M against "
    f"{M(count['stereo_standard'])} M)."
    + (f" Time: wall {t['skin']['wall_ms']:.1f} / {t['standard_material']['wall_ms']:.1f} ms = "
       f"{t['skin_over_standard']:.2f}; process CPU {t['skin']['cpu_ms']:.1f} / {t['standard_material']['cpu_ms']:.1f} ms "
       f"= {t['skin_over_standard_cpu']:.2f}."
       if t else ""),
    "",
    "## Quality tiers (`--skin-quality`, `SkinMaterial::quality`)",
    "",
    "| tier | instructions per frame (M) | / standard frame | fidelity: all / concave / near cast-shadow edges "
    "(mean of views) | all, per view |",
    "| --- | ---: | ---: | --- | --- |",
]
for name, label in (("skin", "high (every technique but the other lights' diffuse LUT)"), ("quality_medium", "medium"), ("quality_low", "low")):
    lines.append(f"| {label} | {M(count[name])} | {count[name] / std:.2f} {fid(name)}")
lines.append("")
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
open(out, "w").write("\n".join(lines))
print("\n".join(lines))
print(f"skin-cost: wrote {out}", file=sys.stderr)
PY
