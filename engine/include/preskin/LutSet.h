// LutSet: the four pre-integrated skin tables baked from one DiffusionProfile, their files
// (half-float EXR + manifest.json) and CPU lookups that match the GLSL in shaders/preskin/lut.glsl
// (both use the mapping functions of shaders/shared/lut_mapping.h).
//
// Tables (every one RGB, values rounded to half; see LutTable.h for the texel layout):
//  - diffuse D(NoL, curvature): Penner & Borshukov's pre-integration (GPU Pro 2, 2011) over the
//    sphere of the signed mean curvature, see engine/src/skin/SphereScatter.h: convex rows are
//    the outside of a sphere, concave rows the inside of one limited to the local patch
//    (localPatchMm), which shadows itself. x: NoL in [-1, 1], SplitLinear (a texel centre sits
//    exactly at NoL = 0, so the flat limit saturate(NoL) is reproduced without interpolation
//    error). y: signed curvature 1/r in [-curvatureMaxPerMm, curvatureMaxPerMm] (default 1/mm:
//    radii from 1 mm to flat, either side), SplitSqrt mapping: row N/2 is exactly flat
//    (D = saturate(NoL)) and each half puts half its rows below a quarter of its range, where
//    faces are (radii ~2..100 mm, |curvature| 0.01..0.5 1/mm).
//  - penumbra P(shadow, filter width): the skin response at a cast-shadow edge of a point-like
//    light, found through the project's Gaussian shadow filter (shaders/preskin/shadow.glsl).
//    x: the filtered shadow value s in [0, 1] (Linear). y: w = sigma_f / referenceWidthMm,
//    sigma_f the filter's standard deviation on the receiver across the edge (mm),
//    referenceWidthMm the profile's widest channel (DiffusionProfile::maxWidthMm); Rational
//    mapping t = w / (w + 1), last row w = infinity.
//    Model: the filter's softness is the shadow map's anti-aliasing, not light: it only tells
//    where the edge is, x = sigma_f Phi^-1(s), and the skin there sees the hard edge through its
//    profile, edgeResponse(x) (sums of Gaussians: sum_i w_i Phi(x / sqrt(v_i)) / albedo): green
//    and blue as sharp as their profiles, red reaching into the dark side. The filter only
//    resolves |x| <= 3 sigma_f, so the response is renormalised to that window:
//    P = (E(x) - E(-3 sigma_f)) / (E(3 sigma_f) - E(-3 sigma_f)); P = 0 for s <= Phi(-3) and 1
//    for s >= Phi(3). Limit rows: w = 0 gives (Phi^-1(s) / 3 + 1) / 2, w = infinity the edge
//    itself (0 below s = 1/2, 1 above). Measured against the ray-traced reference on the head
//    (docs/fidelity.md): green RMSE near cast-shadow edges 0.0105 -> 0.0073 (1024x1024), 0.0122
//    -> 0.0066 close up, against the filter's own soft edge convolved with the profile.
//  - SH transfer A_l(curvature), l = 0, 1, 2: x: curvature (same range and mapping as diffuse);
//    y: band l (row l). Stored relative to Lambert: A_l / (pi, 2 pi / 3, pi / 4)_l, so flat
//    skin stores exactly 1 and the absolute coefficients are the table times Lambert's.
//  - transmittance T(thickness): x: thickness in mm, Log1p mapping with scale = the profile's
//    narrowest scale, range [0, transmittanceMaxMm] where the largest channel falls to 1e-4.
//    One row. T = DiffusionProfile::transmittance: for Gaussians sum_i w_i exp(-d^2 / 2 v_i)
//    (the plane integral of the profile, i.e. Jimenez et al. 2010's exp(-d^2 / v_i) with the
//    published variances doubled; no 1.414 factor), normalised to T(0) = 1.
//
// Every table carries the profile's shape only (normalised per channel); the albedo / colour
// comes from the material.
//
// Files (save/load): diffuse.exr, penumbra.exr, sh_transfer.exr, transmittance.exr (RGB half,
// zip; written and read through a registered codec: the image component preskin::imageio) or
// raw half-float tables (LutSaveOptions::rawTables; the core reads and writes them itself) and
// manifest.json (profile, settings, every axis with range, unit, mapping and formula,
// sizes, sample counts, conventions and an FNV-1a content hash per table). Every file is first
// written under a temporary name and then renamed into place, the manifest last; targets are
// checked before the renames, and on failure the temporary files (and folders save created) are
// removed, so nothing new is left behind.
//
// Limits: see SphereScatter.h (sphere model), the penumbra model above (straight edges, a
// point-like light, red's scattering cut at the filter's reach), and LutTable.h (GPU sub-texel
// precision).
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/Export.h>
#include <preskin/LutTable.h>

#include <preskin/Glm.h>

// The LutMapping struct, shared with GLSL: the GLSL include root (shaders/, installed as
// share/preskin/shaders) is on preskin::preskin's include path.
#include <shared/lut_mapping.h>

#include <array>
#include <filesystem>
#include <functional>
#include <utility>

namespace preskin {

struct PRESKIN_API LutBakeSettings {
    static constexpr int kMinSize = 16;
    static constexpr int kMaxSize = 4096;

    int diffuseNoLSize = 256;
    int diffuseCurvatureSize = 256;
    int penumbraShadowSize = 256;
    int penumbraWidthSize = 256;
    int shCurvatureSize = 256;
    int transmittanceSize = 256;
    double curvatureMaxPerMm = 1.0;  // in (0, 100]

    // Every table axis (other than the SH band and the transmittance row) at `size` samples.
    static LutBakeSettings withSize(int size);
    // Throws preskin::Error "LutBakeSettings.<field>: must be ..., got ..." on a bad value.
    void validate() const;
    bool operator==(const LutBakeSettings&) const = default;
};

// Bake progress in [0, 1]; calls are serialised (never concurrent) and non-decreasing, the last
// one is 1. They may come from worker threads.
using LutBakeProgress = std::function<void(double fraction)>;

struct LutSaveOptions {
    bool previewPngs = false;  // also write preview_<table>.png (8-bit sRGB visualisations)
    // The tables as raw half floats (<table>.f16: RGB, row-major, little-endian) instead of
    // OpenEXR: read back without decoding, checked by the same content hashes (the profile cache
    // writes these). LutSet::load reads either.
    bool rawTables = false;
};

class PRESKIN_API LutSet {
public:
    // Bakes every table on all cores (TBB). Validates the settings first.
    static LutSet bake(const DiffusionProfile& profile, const LutBakeSettings& settings = {},
                       const LutBakeProgress& progress = {});
    // Writes the set into `dir` (created if missing). Throws preskin::Error naming the file.
    void save(const std::filesystem::path& dir, const LutSaveOptions& options = {}) const;
    // Reads and validates a set (manifest fields, sizes, axes, content hashes). Throws
    // preskin::Error naming the file and field, e.g. "luts/manifest.json: tables.diffuse.hash: ...".
    static LutSet load(const std::filesystem::path& dir);
    // The default set: d'Eon & Luebke's profile at default settings, baked on first use and
    // cached. It equals the committed luts/ directory (a test keeps them in sync).
    static const LutSet& loadDefault();

    const DiffusionProfile& profile() const { return profile_; }
    const LutBakeSettings& settings() const { return settings_; }
    const LutTable& diffuse() const { return diffuse_; }
    const LutTable& penumbra() const { return penumbra_; }
    const LutTable& shTransfer() const { return shTransfer_; }
    const LutTable& transmittance() const { return transmittance_; }
    double penumbraReferenceWidthMm() const { return penumbraReferenceWidthMm_; }
    // Radius of the local patch (profile mm): the surface around a shaded point whose own
    // shadowing the diffuse LUT models; skin looks the shadow map up above it.
    double localPatchMm() const;
    double transmittanceMaxMm() const { return transmittance_.x.max; }

    // Texture coordinates and bilinear CPU lookups, identical to lut.glsl.
    glm::vec2 diffuseUv(float NoL, float curvaturePerMm) const;
    glm::vec3 lookupDiffuse(float NoL, float curvaturePerMm) const;
    glm::vec2 penumbraUv(float shadow, float filterSigmaMm) const;
    glm::vec3 lookupPenumbra(float shadow, float filterSigmaMm) const;
    glm::vec2 shTransferUv(float curvaturePerMm, int band) const;
    // Absolute per-channel A_0, A_1, A_2 (the table times Lambert's coefficients).
    std::array<glm::vec3, 3> lookupShTransfer(float curvaturePerMm) const;
    glm::vec2 transmittanceUv(float thicknessMm) const;
    glm::vec3 lookupTransmittance(float thicknessMm) const;

private:
    explicit LutSet(DiffusionProfile profile) : profile_(std::move(profile)) {}
    friend struct LutSetAccess;

    DiffusionProfile profile_;
    LutBakeSettings settings_;
    double penumbraReferenceWidthMm_ = 1.0;
    LutTable diffuse_;
    LutTable penumbra_;
    LutTable shTransfer_;
    LutTable transmittance_;
};

// The LUT coordinate mapping of a set, for the `LutMapping` member of a shader's uniform block
// (preskin/lut.glsl): the same numbers the set's CPU lookups use.
PRESKIN_API gpu::LutMapping lutMapping(const LutSet& luts);

// Texture extents (texels) that hold a set's tables, per table; 0: the table's own size. A
// table smaller than its texture sits at texel (0, 0), padded with copies of its edge texels
// (layers of LUT array textures, <preskin/ProfileLibrary.h>).
struct LutExtents {
    glm::ivec2 diffuse{0};
    glm::ivec2 penumbra{0};
    glm::ivec2 shTransfer{0};
    glm::ivec2 transmittance{0};
};
// The mapping of the set's tables held in such larger (padded) textures.
PRESKIN_API gpu::LutMapping lutMapping(const LutSet& luts, const LutExtents& extents);

}  // namespace preskin
