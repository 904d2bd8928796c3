// Options of the diffusion reference shared by `preskin reference` and `preskin compare`, and the
// helpers that build a DiffusionReference from the command line's scene.
#pragma once

#include "Options.h"  // samples/common

#include <preskin/DiffusionReference.h>

#include <CLI/CLI.hpp>

#include <memory>

namespace preskin::cli {

struct ReferenceOptions {
    ReferenceSettings settings;
    uint32_t threads = 0;  // 0: every core
};

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& o);

// The reference of the scene as `preskin render` would light it: the same lights (sceneLights),
// environment (its SH, or traced with --trace-environment; it must outlive the reference), the
// LUT set's profile, and --no-shadows.
std::unique_ptr<DiffusionReference> makeReference(const Scene& scene, const Environment& environment,
                                                  const LutSet& luts, const CommonOptions& common,
                                                  const ReferenceOptions& o);

// What the reference of this command line depends on, for reference files reused by
// `preskin compare --reference`: the model's version, the scene file (path and a hash of its
// bytes), the view and size, the lighting options, the LUT set's profile (name and a hash of its
// definition: a LUT set baked again from it, at any size, keeps the reference) and the quadrature.
// `scene`: the loaded scene (whether its environment gives lights depends on its lights).
ReferenceKey referenceKey(const std::filesystem::path& scenePath, const Scene& scene, const ViewOptions& view,
                          const CommonOptions& common, const ReferenceOptions& o, const LutSet& luts);

// Renders it with a progress bar on stderr, on --threads threads.
ReferenceImage renderReference(const DiffusionReference& reference, const View& view, const ViewOptions& size,
                               float exposure, const ReferenceOptions& o);

}  // namespace preskin::cli
