// `preskin bake`: bakes the pre-integrated skin LUTs (diffuse ring integral after Penner &
// Borshukov 2011, penumbra, SH transfer, transmittance) of a diffusion profile on all cores and
// writes them as half-float EXR (or raw half floats with --raw) plus manifest.json (and PNG
// previews with --preview):
//   preskin bake --profile deon|burley|FILE.json [--albedo R,G,B] [--mfp R,G,B] [--size N]
//                [--preview] [--raw] --out DIR
// Bad input (a profile file, a size, a colour) is refused before anything is written.
// Limits: --size sets every table axis at once (16..4096); finer control is in the library
// (preskin::LutBakeSettings).
#include "Commands.h"
#include "Options.h"  // samples/common
#include "ProgressBar.h"

#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

namespace preskin::cli {
namespace {

struct BakeOptions {
    std::string profile = "deon";
    std::string albedo;
    std::string meanFreePath;
    std::string size;
    bool preview = false;
    bool raw = false;
    std::string out;
};

int parseSize(const std::string& text) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < LutBakeSettings::kMinSize ||
        value > LutBakeSettings::kMaxSize)
        throw Error(fmt::format("--size: must be an integer in [{}, {}], got '{}'", LutBakeSettings::kMinSize,
                                LutBakeSettings::kMaxSize, text));
    return value;
}

void runBake(const BakeOptions& o) {
    // Everything is validated before the (possibly long) bake, and the bake before any file.
    const LutBakeSettings settings = o.size.empty() ? LutBakeSettings{} : LutBakeSettings::withSize(parseSize(o.size));
    const DiffusionProfile profile = selectProfile({o.profile, o.albedo, o.meanFreePath}, false);

    const auto start = std::chrono::steady_clock::now();
    const LutSet luts = [&] {
        ProgressBar bar("baking");
        return LutSet::bake(profile, settings, [&bar](double fraction) { bar(fraction); });
    }();
    const auto baked = std::chrono::steady_clock::now();
    luts.save(o.out, {.previewPngs = o.preview, .rawTables = o.raw});
    const auto saved = std::chrono::steady_clock::now();

    auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
    const glm::dvec3 width = profile.widthMm();
    fmt::print("profile: {} (RMS width R {:.3f} G {:.3f} B {:.3f} mm)\n", profile.name(), width.r, width.g, width.b);
    fmt::print(
        "baked in {:.1f} ms on {} hardware threads: diffuse {}x{}, penumbra {}x{}, SH transfer {}x{}, "
        "transmittance {}x{}\n",
        ms(baked - start), std::thread::hardware_concurrency(), luts.diffuse().width(), luts.diffuse().height(),
        luts.penumbra().width(), luts.penumbra().height(), luts.shTransfer().width(), luts.shTransfer().height(),
        luts.transmittance().width(), luts.transmittance().height());
    fmt::print("wrote {} in {:.1f} ms{}\n", o.out, ms(saved - baked), o.preview ? " (with preview_*.png)" : "");
}

}  // namespace

void addBakeCommand(CLI::App& app) {
    auto options = std::make_shared<BakeOptions>();
    CLI::App* command = app.add_subcommand("bake", "Bake the pre-integrated skin LUTs of a diffusion profile");
    command
        ->add_option("--profile", options->profile,
                     "deon (d'Eon & Luebke 2007 six-Gaussian skin), burley (Christensen & Burley 2015, needs --albedo "
                     "and --mfp) or a profile JSON file")
        ->capture_default_str();
    command->add_option("--albedo", options->albedo, "burley: surface albedo per channel, R,G,B in (0, 1]");
    command->add_option("--mfp", options->meanFreePath, "burley: mean free path per channel in mm, R,G,B");
    command->add_option("--size", options->size, "samples along every table axis, 16..4096 (default 256)");
    command->add_flag("--preview", options->preview, "also write preview_*.png visualisations of each table");
    command->add_flag("--raw", options->raw,
                      "write the tables as raw little-endian half floats (<table>.f16) instead of EXR: what the core "
                      "library reads without the image component");
    command->add_option("--out", options->out, "output folder (created if missing)")->required();
    command->callback([options] { runBake(*options); });
}

}  // namespace preskin::cli
