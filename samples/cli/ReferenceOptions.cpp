#include "ReferenceOptions.h"
#include "CommandLine.h"  // samples/common
#include "ProgressBar.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <optional>

namespace preskin::cli {

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& o) {
    ReferenceSettings& s = o.settings;
    cmd.add_option("--tail-fraction", s.tailFraction, "Reference: profile energy left out beyond the integration radius")
        ->check(numberIn(1e-9, 0.1))
        ->capture_default_str();
    cmd.add_option("--leaf-ratio", s.leafRatio, "Reference: irradiance piece size over its distance from the point")
        ->check(numberIn(1e-3, 2.0))
        ->capture_default_str();
    cmd.add_option("--finest-leaf-ratio", s.finestLeafRatio,
                   "Reference: smallest irradiance piece over the profile's narrowest scale")
        ->check(numberIn(1e-3, 100.0))
        ->capture_default_str();
    cmd.add_option("--moment-tolerance", s.momentTolerance, "Reference: adaptive profile quadrature tolerance per piece")
        ->check(numberIn(1e-12, 1e-2))
        ->capture_default_str();
    cmd.add_option("--threads", o.threads, "Reference: CPU threads (0: all cores); the result does not depend on it")
        ->check(wholeNumberIn(0, 1024))
        ->capture_default_str();
}

std::unique_ptr<DiffusionReference> makeReference(const Scene& scene, const Environment& environment,
                                                  const LutSet& luts, const CommonOptions& common,
                                                  const ReferenceOptions& o) {
    ReferenceSettings settings = o.settings;
    settings.shadows = !common.noShadows;
    return std::make_unique<DiffusionReference>(scene, sceneLights(scene, common), environment.radianceSh(),
                                                luts.profile(), settings);
}

ReferenceImage renderReference(const DiffusionReference& reference, const View& view, const ViewOptions& size,
                               float exposure, const ReferenceOptions& o) {
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    ProgressBar bar("reference");
    return reference.render(view.eye(), size.width, size.height, exposure, [&](double f) { bar(f); });
}

}  // namespace preskin::cli
