#include "Options.h"
#include "CommandLine.h"

#include <preskin/Error.h>
#include <preskin/LightScatter.h>
#include <preskin/Limits.h>

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <system_error>

namespace preskin::cli {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

void addSceneOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--env", o.env, "HDR environment (equirectangular .hdr or .exr); default: the scene's");
    cmd.add_option("--env-intensity", o.envIntensity, "Environment radiance scale")->check(numberIn(0.0, 1e6));
    cmd.add_option("--env-rotation", o.envRotationDeg, "Turn the environment about +Y, degrees")
        ->check(numberIn(-3600.0, 3600.0));
    cmd.add_option("--env-lights", o.envLights,
                   "Directional lights extracted from the environment (median cut), with shadows; default: 1 when "
                   "the scene has an environment image and no lights, else 0")
        ->check(wholeNumberIn(0, kMaxEnvironmentLights));
    cmd.add_flag("--env-light-size", o.envLightSize,
                 "Give the environment's extracted lights the angular radius of their texels' spread: softer "
                 "terminators and shadows whose penumbra widens with the occluder's distance (slower on a CPU "
                 "driver)");
    cmd.add_flag("--no-scene-lights", o.noSceneLights,
                 "Leave out the scene's own lights (KHR_lights_punctual): the environment's extracted light (or the "
                 "default key light) takes their place");
    cmd.add_option("--skin", o.skin,
                   "Shade this material (or 'all') as skin with default parameters; 'none': no material is skin "
                   "(the standard glTF material everywhere)");
    cmd.add_option("--lights", o.lights, "Scatter this many coloured point and spot lights (clustered)")
        ->check(wholeNumberIn(0, 1 << 20));
    cmd.add_option("--light-density", o.lightDensity,
                   "Ranges of --lights' lights scaled so that a point of the scene lies in about this many lights' "
                   "volumes, whatever --lights is (0: ranges of the scene's size)")
        ->check(numberIn(0.0, 1000.0))
        ->capture_default_str();
    cmd.add_option("--light-shape", o.lightShape,
                   "Shape of --lights' lights: point (points and spots), or sphere, tube, rectangle or disc area "
                   "lights sized from their ranges (rectangles and discs facing the scene's centre)")
        ->check(CLI::IsMember({"point", "sphere", "tube", "rectangle", "disc"}))
        ->capture_default_str();
    cmd.add_option("--sun-radius", o.sunRadiusDeg,
                   "Angular radius in degrees given to the scene's directional lights (the sun's is 0.27): a softer "
                   "terminator, and shadow penumbrae that widen with the occluder's distance (0: parallel light; "
                   "default: as the scene says)")
        ->check(numberIn(0.0, 45.0));
    cmd.add_option("--seed", o.seed, "Seed for --lights")->check(wholeNumberIn(0, UINT32_MAX))->capture_default_str();
    cmd.add_option("--exposure", o.exposure, "Exposure multiplier")->check(numberIn(0.0, 1e6))->capture_default_str();
    cmd.add_flag("--no-shadows", o.noShadows, "Disable the shadow map");
}

void addDeviceOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--device", o.device, "Vulkan device: index or part of its name (default: best GPU, else lavapipe)");
    cmd.add_flag("--validation", o.validation, "Enable Vulkan validation layers; any message makes the run fail");
}

void addShadowMapOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--shadow-softness", o.shadowSoftness, "Shadow filter sigma in shadow-map texels")
        ->check(numberIn(0.25, 2.0))
        ->capture_default_str();
    cmd.add_option("--shadow-map-size", o.shadowMapSize, "Shadow map resolution")
        ->check(wholeNumberIn(16, 8192))
        ->capture_default_str();
}

void addCommonOptions(CLI::App& cmd, CommonOptions& o) {
    addSceneOptions(cmd, o);
    addDeviceOptions(cmd, o);
    cmd.add_flag("--standard", o.standard, "Turn every skin technique off (standard shading, for comparison)");
    addSkinTechniqueOptions(cmd, o);
    cmd.add_flag("--no-specular-ibl", o.noSpecularIbl,
                 "The environment's specular reflection from its L2 SH instead of the prefiltered environment");
    cmd.add_flag("--no-specular", o.noSpecular,
                 "No specular at all, every material: diffuse without Fresnel (what `preskin reference` models)");
    cmd.add_option("--background", o.background,
                   "What is shown where no surface is: env (the environment, exposed and tone-mapped), "
                   "transparent (alpha 0), or color R,G,B (linear, 0..1e6); default: color 0.045,0.045,0.05")
        ->expected(1, 2);
    cmd.add_option("--debug", o.debug,
                   "Debug view: none, curvature, normals, shadow, penumbra, lightcount, shambient, transmission")
        ->check(
            oneOf({"none", "curvature", "normals", "shadow", "penumbra", "lightcount", "shambient", "transmission"}))
        ->capture_default_str();
    cmd.add_option("--diffusion", o.diffusion,
                   "How skin's diffuse light scatters: preintegrated (preskin, in the one forward pass) or screen "
                   "(the screen-space separable baseline: Lambert skin blurred by the profile in two more passes) "
                   "or texture (the texture-space baseline: irradiance in the mesh's UV layout blurred by the "
                   "profile's Gaussians)")
        ->check(oneOf({"preintegrated", "screen", "texture"}))
        ->capture_default_str();
    addDiffusionOptions(cmd, o);
    cmd.add_option("--light-loop", o.lightLoop, "clustered (light grid) or all (every light, brute force)")
        ->check(oneOf({"clustered", "all"}))
        ->capture_default_str();
    addShadowMapOptions(cmd, o);
    cmd.add_option("--msaa", o.msaa, "Samples per pixel (1, 2, 4 or 8, as the device offers; lavapipe: 1 or 4)")
        ->check(oneOf({"1", "2", "4", "8"}))
        ->capture_default_str();
    cmd.add_flag("--no-depth-prepass", o.noDepthPrepass,
                 "Shade opaque meshes without drawing their depth first (the same image, more fragments shaded)");
    addLutOptions(cmd, o);
    addProfileBakeOptions(cmd, o);
    cmd.add_flag("--allow-outside-links", o.allowOutsideLinks,
                 "Follow symbolic links in the scene's folder that lead out of it (refused by default)");
}

void addSkinTechniqueOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_flag("--no-lut-diffuse", o.noLutDiffuse, "Skin: Lambert instead of the pre-integrated diffuse LUT");
    cmd.add_flag("--no-lut-shadow-light", o.noLutShadowLight,
                 "Skin: the shadow light gets the diffuse LUT's row as a smoothed ramp, as the other lights do");
    cmd.add_flag("--lut-other-lights", o.lutOtherLights,
                 "Skin: the lights besides the shadow light read the diffuse LUT too (high and medium tiers)");
    cmd.add_flag("--no-light-curvature", o.noLightCurvature,
                 "Skin: every light's diffuse LUT row at the mean curvature (not the curvature along the light)");
    cmd.add_flag("--no-normal-prefilter", o.noNormalPrefilter,
                 "Skin: one normal for all channels (no per-channel geometric normals or normal-map levels)");
    cmd.add_flag("--no-full-shadow-filter", o.noFullShadowFilter,
                 "Skin: a parallel light's shadow map filtered over 6 x 6 texels (9 gathers) instead of 8 x 8 (16)");
    cmd.add_flag("--no-wide-penumbra", o.noWidePenumbra,
                 "Skin: penumbra scattering within the shadow filter's reach only (no wide shadow map)");
    cmd.add_flag("--no-normal-map-levels", o.noNormalMapLevels,
                 "Skin: the normal map read once for all channels (each keeps its own geometric normal)");
    cmd.add_flag("--no-penumbra", o.noPenumbra, "Skin: plain PCF shadow instead of penumbra scattering");
    cmd.add_flag("--no-sh-skin", o.noShSkin, "Skin: Lambert SH ambient instead of the skin transfer");
    cmd.add_flag("--no-transmission", o.noTransmission, "Skin: no transmission through thin parts");
    cmd.add_flag("--no-dual-specular", o.noDualSpecular, "Skin: one GGX lobe instead of two");
    cmd.add_flag("--no-opposing-light", o.noOpposingLight,
                 "Skin: no light from neighbours facing the point across a gap or a thin part");
    cmd.add_option("--skin-quality", o.skinQuality,
                   "Skin: every skin material at this quality tier (low, medium, high; default: each material's "
                   "own, high unless its PRESKIN_materials_skin quality says otherwise)")
        ->check(oneOf({"low", "medium", "high"}));
    cmd.add_flag("--skin-terms-per-fragment", o.skinTermsPerFragment,
                 "Skin: find the curvature-only terms (SH transfer, shadow lift, sphere transmittance) per fragment "
                 "instead of per vertex");
}

void addDiffusionOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--diffusion-taps", o.diffusionTaps, "--diffusion screen: taps per blur direction (odd)")
        ->check(wholeNumberIn(3, 63))
        ->capture_default_str();
    cmd.add_option("--diffusion-texture-size", o.diffusionTextureSize,
                   "--diffusion texture: texels per side of each skin draw's irradiance texture")
        ->check(wholeNumberIn(16, 8192))
        ->capture_default_str();
}

void addLutOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--luts", o.luts, "Skin LUT set folder (from `preskin bake`); default: the bundled d'Eon set");
}

void addProfileBakeOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_flag("--no-cache", o.noCache,
                 "Bake the scene's diffusion profiles without reading or writing the LUT cache");
    cmd.add_option("--cache-dir", o.cacheDir,
                   "LUT cache folder (default: $XDG_CACHE_HOME/preskin/luts or ~/.cache/preskin/luts)");
    cmd.add_option("--profile-lut-size", o.profileLutSize, "Table size of the scene's baked profiles")
        ->check(wholeNumberIn(LutBakeSettings::kMinSize, LutBakeSettings::kMaxSize))
        ->capture_default_str();
}

Diffusion diffusionMethod(const std::string& name) {
    if (name == "preintegrated") return Diffusion::PreIntegrated;
    if (name == "screen") return Diffusion::ScreenSpace;
    if (name == "texture") return Diffusion::TextureSpace;
    throw Error(fmt::format("--diffusion {}: unknown method (preintegrated, screen or texture)", name));
}

Scene loadScene(const std::filesystem::path& path, const CommonOptions& o) {
    SceneLoadOptions options;
    options.allowLinksOutsideFolder = o.allowOutsideLinks;
    return Scene::load(path, options);
}

void addViewOptions(CLI::App& cmd, ViewOptions& o) {
    cmd.add_option("--width", o.width, "Image width in pixels")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd.add_option("--height", o.height, "Image height in pixels")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    auto* camera = cmd.add_option("--camera", o.camera, "Use the scene's camera of this name");
    auto* orbit = cmd.add_option("--orbit", o.orbit,
                                 "Orbit the scene's centre: YAW,PITCH,DIST in degrees, degrees, metres (DIST 0: fit)");
    camera->excludes(orbit);
}

void checkViewOptions(const ViewOptions& o) {
    if (!o.orbit.empty()) parseFloats(o.orbit, 3, "--orbit");
}

size_t findSceneCamera(const Scene& scene, const std::filesystem::path& scenePath, const std::string& name) {
    std::vector<std::string> names;
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        if (scene.cameras[i].name == name) return i;
        names.push_back(scene.cameras[i].name.empty() ? fmt::format("cameras[{}] (no name)", i)
                                                      : scene.cameras[i].name);
    }
    throw Error(fmt::format("--camera {}: {} has no camera of that name ({})", name, scenePath.string(),
                            names.empty() ? std::string("it has no cameras")
                                          : "its cameras: " + fmt::format("{}", fmt::join(names, ", "))));
}

View makeView(const Scene& scene, const std::filesystem::path& scenePath, const ViewOptions& o) {
    const float aspect = float(o.width) / float(o.height);
    if (!o.camera.empty())
        return cameraView(scene.cameras[findSceneCamera(scene, scenePath, o.camera)], aspect, scene.worldBounds());
    if (!o.orbit.empty()) {
        const auto v = parseFloats(o.orbit, 3, "--orbit");
        return orbitView(scene.worldBounds(), v[0], v[1], v[2], aspect);
    }
    return frameBoundsView(scene.worldBounds(), aspect);
}

void addStereoOptions(CLI::App& cmd, StereoOptions& o) {
    auto* stereo = cmd.add_flag("--stereo", o.stereo,
                                "Render a stereo pair (one multiview pass), eyes side by side, left eye left; "
                                "--width and --height are each eye's (the image is twice as wide)");
    cmd.add_option("--ipd", o.ipdM, "Interpupillary distance of --stereo and --eye, metres")
        ->check(numberIn(0.0, 1.0))
        ->capture_default_str();
    cmd.add_option("--eye", o.eye, "Render only this eye of the stereo pair (mono): left or right")
        ->check(oneOf({"left", "right"}))
        ->excludes(stereo);
}

View applyStereoOptions(const View& mono, const StereoOptions& o) {
    if (!o.stereo && o.eye.empty()) return mono;
    if (!std::isfinite(o.ipdM) || o.ipdM < 0.0f || o.ipdM > 1.0f)
        throw Error(fmt::format("--ipd {}: the interpupillary distance must be a finite 0..1 metres", o.ipdM));
    View stereo = stereoFromMono(mono, o.ipdM);
    if (o.eye.empty()) return stereo;
    return View(stereo.eyes[o.eye == "left" ? 0 : 1]);
}

std::filesystem::path dataDir() {
    if (const char* env = std::getenv("PRESKIN_DATA_DIR"); env && *env) return env;
    // An installed tool: <prefix>/bin/preskin finds <prefix>/share/preskin.
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path installed = (exe.parent_path() / PRESKIN_BIN_TO_DATA).lexically_normal();
        if (std::filesystem::is_regular_file(installed / "luts" / "manifest.json", ec)) return installed;
    }
    return PRESKIN_SOURCE_DIR;
}

std::filesystem::path defaultScenePath() { return dataDir() / "samples" / "assets" / "head" / "head.gltf"; }

std::filesystem::path defaultAnimatedScenePath() {
    return dataDir() / "samples" / "assets" / "head" / "head_animated.gltf";
}

OutputEncoding encodingFor(const std::filesystem::path& out) {
    const std::string ext = lower(out.extension().string());
    if (ext == ".png") return OutputEncoding::DisplaySrgb8;
    if (ext == ".exr") return OutputEncoding::LinearFloat;
    std::error_code ec;
    if (std::filesystem::is_directory(out, ec) || !out.has_filename())
        throw Error(fmt::format("--out {}: is a folder; name the image file in it (.png or .exr)", out.string()));
    if (ext.empty()) throw Error(fmt::format("--out {}: no file extension; name a .png or .exr file", out.string()));
    throw Error(fmt::format("--out {}: unsupported image type '{}' (use .png or .exr)", out.string(), ext));
}

std::vector<float> parseFloats(const std::string& text, size_t count, const char* flag) {
    std::vector<float> values;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v) ||
            std::abs(v) > limits::kMaxInputMagnitude)
            throw Error(fmt::format("{}: value: '{}' is not a finite number of magnitude at most {}", flag, item,
                                    limits::kMaxInputMagnitude));
        values.push_back(static_cast<float>(v));
    }
    if (values.size() != count)
        throw Error(fmt::format("{}: value: expected {} comma-separated numbers, got {} in '{}'", flag, count,
                                values.size(), text));
    return values;
}

ContextDesc contextDesc(const CommonOptions& o) {
    ContextDesc desc;
    desc.validation = o.validation;
#ifndef NDEBUG
    desc.validation = true;  // debug builds always validate
#endif
    if (const char* env = std::getenv("PRESKIN_VALIDATION"); env && std::string(env) == "1") desc.validation = true;
    desc.device = o.device;
    return desc;
}

glm::dvec3 parseRgb(const std::string& text, const char* option) {
    glm::dvec3 rgb(0.0);
    size_t start = 0;
    for (int c = 0; c < 3; ++c) {
        const size_t comma = text.find(',', start);
        const bool last = c == 2;
        if (last != (comma == std::string::npos))
            throw Error(fmt::format("{}: expected three comma-separated numbers R,G,B, got '{}'", option, text));
        const std::string part = text.substr(start, last ? std::string::npos : comma - start);
        double value = 0.0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (error != std::errc() || end != part.data() + part.size() || !std::isfinite(value))
            throw Error(fmt::format("{}: expected three comma-separated numbers R,G,B, got '{}'", option, text));
        rgb[c] = value;
        start = comma + 1;
    }
    return rgb;
}

DiffusionProfile selectProfile(const ProfileChoice& c, bool burleyDefaults) {
    const bool burley = c.profile == "burley";
    if (!burley && (!c.albedo.empty() || !c.meanFreePath.empty()))
        throw Error(fmt::format("--albedo and --mfp apply only to --profile burley (got --profile {})", c.profile));
    if (burley) {
        if (!burleyDefaults && (c.albedo.empty() || c.meanFreePath.empty()))
            throw Error(
                "--profile burley: needs --albedo R,G,B (surface albedo, 0..1) and --mfp R,G,B (mean free path, mm)");
        const glm::dvec3 albedo = parseRgb(c.albedo.empty() ? kDefaultBurleyAlbedo : c.albedo, "--albedo");
        const glm::dvec3 meanFreePathMm =
            parseRgb(c.meanFreePath.empty() ? kDefaultBurleyMfp : c.meanFreePath, "--mfp");
        return DiffusionProfile::burley(albedo, meanFreePathMm);
    }
    if (c.profile == "deon") return DiffusionProfile::deonLuebke();
    std::error_code ec;
    if (!std::filesystem::exists(c.profile, ec)) {
        std::string lowered = c.profile;
        for (char& ch : lowered) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        const bool keyword = lowered == "deon" || lowered == "burley";
        throw Error(
            fmt::format("--profile {}: value: neither a keyword (deon or burley{}) nor a profile JSON file "
                        "(looked for {})",
                        c.profile, keyword ? "; did you mean " + lowered + "?" : "",
                        std::filesystem::absolute(c.profile, ec).lexically_normal().string()));
    }
    return DiffusionProfile::fromJsonFile(c.profile);
}

void addProfileChoiceOptions(CLI::App& cmd, CommonOptions& o) {
    auto* profile = cmd.add_option("--profile", o.profile.profile,
                                   "Diffusion profile baked at start (at --profile-lut-size) as the default LUT set: "
                                   "deon, burley (with --albedo and --mfp, or the viewer's defaults) or a profile "
                                   "JSON file");
    cmd.add_option("--albedo", o.profile.albedo, "--profile burley: surface albedo per channel, R,G,B in (0, 1]");
    cmd.add_option("--mfp", o.profile.meanFreePath, "--profile burley: mean free path per channel in mm, R,G,B");
    profile->excludes(cmd.get_option("--luts"));
}

LutSet loadLuts(const CommonOptions& o) {
    if (!o.profile.profile.empty())
        return LutSet::bake(selectProfile(o.profile, true), LutBakeSettings::withSize(int(o.profileLutSize)));
    if (!o.luts.empty()) return LutSet::load(o.luts);
    const std::filesystem::path bundled = dataDir() / "luts";
    std::error_code ec;
    if (std::filesystem::exists(bundled / "manifest.json", ec)) return LutSet::load(bundled);
    return LutSet::loadDefault();
}

ProfileLibrary loadProfiles(const Scene& scene, const CommonOptions& o, std::shared_ptr<const LutSet> defaultLuts) {
    ProfileCacheOptions cache;
    cache.enabled = !o.noCache;
    cache.folder = o.cacheDir;
    if (!defaultLuts) defaultLuts = std::make_shared<const LutSet>(loadLuts(o));
    ProfileLibrary library = ProfileLibrary::forScene(scene, std::move(defaultLuts),
                                                      LutBakeSettings::withSize(int(o.profileLutSize)), cache);
    for (const std::string& warning : library.warnings()) fmt::print(stderr, "preskin: warning: {}\n", warning);
    return library;
}

RenderSettings renderSettings(const CommonOptions& o) {
    RenderSettings s;
    s.skin.lutDiffuse = !o.noLutDiffuse;
    s.skin.normalPrefilter = !o.noNormalPrefilter;
    s.skin.penumbra = !o.noPenumbra;
    s.skin.shAmbient = !o.noShSkin;
    s.skin.transmission = !o.noTransmission;
    s.skin.dualSpecular = !o.noDualSpecular;
    s.skin.opposingLight = !o.noOpposingLight;
    s.skin.normalMapLevels = !o.noNormalMapLevels;
    s.skin.widePenumbra = !o.noWidePenumbra;
    s.skin.lutShadowLight = !o.noLutShadowLight;
    s.skin.lutOtherLights = o.lutOtherLights;
    s.skin.lightCurvature = !o.noLightCurvature;
    s.skin.fullShadowFilter = !o.noFullShadowFilter;
    if (!o.skinQuality.empty())
        s.skinQuality = o.skinQuality == "low" ? SkinQuality::Low
            : o.skinQuality == "medium"        ? SkinQuality::Medium
                                               : SkinQuality::High;
    s.skinTermsPerVertex = !o.skinTermsPerFragment;
    if (o.standard) s.skin = SkinFeatures::none();
    s.specular = !o.noSpecular;
    s.specularIbl = !o.noSpecularIbl;
    const std::string d = lower(o.debug);
    if (d == "none")
        s.debugView = DebugView::None;
    else if (d == "curvature")
        s.debugView = DebugView::Curvature;
    else if (d == "normals")
        s.debugView = DebugView::Normals;
    else if (d == "shadow")
        s.debugView = DebugView::Shadow;
    else if (d == "penumbra")
        s.debugView = DebugView::Penumbra;
    else if (d == "lightcount")
        s.debugView = DebugView::LightCount;
    else if (d == "shambient")
        s.debugView = DebugView::ShAmbient;
    else if (d == "transmission")
        s.debugView = DebugView::Transmission;
    else
        throw Error(
            fmt::format("--debug {}: unknown debug view (none, curvature, normals, shadow, penumbra, lightcount, "
                        "shambient or transmission)",
                        o.debug));
    s.lightLoop = o.lightLoop == "all" ? LightLoop::All : LightLoop::Clustered;
    s.diffusion = diffusionMethod(o.diffusion);
    if (o.diffusionTaps % 2 == 0)
        throw Error(fmt::format("--diffusion-taps: {} is even (the kernel has a middle tap: use an odd count)",
                                o.diffusionTaps));
    s.screenDiffusionTaps = o.diffusionTaps;
    s.textureDiffusionSize = o.diffusionTextureSize;
    s.exposure = o.exposure;
    s.shadowSoftnessTexels = o.shadowSoftness;
    s.shadowMapSize = o.shadowMapSize;
    s.shadows = !o.noShadows;
    s.msaaSamples = o.msaa;
    s.depthPrepass = !o.noDepthPrepass;
    s.environmentLightSizes = o.envLightSize;
    s.background = parseBackground(o.background);
    return s;
}

Background parseBackground(const std::vector<std::string>& words) {
    Background b;
    if (words.empty()) return b;
    const std::string mode = lower(words[0]);
    if (words.size() == 1 && (mode == "env" || mode == "environment"))
        b.mode = BackgroundMode::Environment;
    else if (words.size() == 1 && mode == "transparent")
        b.mode = BackgroundMode::Transparent;
    else if (words.size() == 2 && mode == "color") {
        const std::vector<float> c = parseFloats(words[1], 3, "--background color");
        for (float v : c)
            if (!(v >= 0.0f && v <= 1e6f))
                throw Error(fmt::format("--background color {}: each value must be within 0..1e6", words[1]));
        b.color = glm::vec3(c[0], c[1], c[2]);
    } else
        throw Error(fmt::format("--background {}: expected env, transparent or color R,G,B", fmt::join(words, " ")));
    return b;
}

bool removeSkin(Scene& scene) {
    bool hadSkin = false;
    for (Material& material : scene.materials) {
        hadSkin = hadSkin || material.skin.has_value();
        material.skin.reset();
    }
    return hadSkin;
}

void applySkinOption(Scene& scene, const CommonOptions& o) {
    if (o.skin == "none")
        removeSkin(scene);
    else if (!o.skin.empty())
        scene.makeSkin(o.skin);
}

Environment loadEnvironment(const Scene& scene, const CommonOptions& o) {
    const float sceneIntensity = o.envIntensity >= 0.0f ? o.envIntensity : scene.environmentIntensity;
    const float sceneRotation = o.envRotationDeg ? glm::radians(*o.envRotationDeg) : scene.environmentRotation;
    Environment environment = !o.env.empty() ? Environment::load(o.env, o.envIntensity >= 0.0f ? o.envIntensity : 1.0f,
                                                                 glm::radians(o.envRotationDeg.value_or(0.0f)))
        : scene.environmentPath              ? Environment::load(*scene.environmentPath, sceneIntensity, sceneRotation)
        : !scene.environmentData.empty()
        ? Environment::load(scene.environmentData,
                            scene.sourcePath.string() + ": extensions.PRESKIN_environment.uri (data URI)",
                            sceneIntensity, sceneRotation)
        : Environment::constant(glm::vec3(0.25f) * (o.envIntensity >= 0.0f ? o.envIntensity : 1.0f));
    for (const std::string& warning : environment.warnings()) fmt::print(stderr, "preskin: warning: {}\n", warning);
    return environment;
}

Light defaultKeyLight() {
    Light key;
    key.name = "default key";
    key.type = LightType::Directional;
    key.directionWs = glm::normalize(glm::vec3(0.5f, -0.6f, -0.65f));
    key.intensity = 3.0f;
    key.castsShadow = true;
    return key;
}

int environmentLightCount(const Scene& scene, const CommonOptions& o) {
    if (o.envLights >= 0) return o.envLights;
    const bool environmentImage = !o.env.empty() || scene.hasEnvironmentImage();
    return (scene.lights.empty() || o.noSceneLights) && environmentImage ? 1 : 0;
}

void shapeLights(std::vector<Light>& lights, const std::string& shape, const Bounds& bounds) {
    if (shape == "point") return;
    for (Light& l : lights) {
        if (l.type == LightType::Directional) continue;
        const glm::vec3 toCenter = bounds.center() - l.positionWs;
        l.directionWs = glm::length(toCenter) > 1e-6f ? glm::normalize(toCenter) : glm::vec3(0.0f, -1.0f, 0.0f);
        l.axisWs = glm::abs(l.directionWs.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
        const float r = l.range > 0.0f ? l.range : glm::length(bounds.max - bounds.min);
        if (shape == "sphere") {
            l.type = LightType::Sphere;
            l.radius = 0.05f * r;
        } else if (shape == "tube") {
            l.type = LightType::Tube;
            l.radius = 0.02f * r;
            l.length = 0.3f * r;
        } else if (shape == "rectangle") {
            l.type = LightType::Rectangle;
            l.width = 0.2f * r;
            l.height = 0.1f * r;
        } else {
            l.type = LightType::Disc;
            l.radius = 0.08f * r;
        }
    }
}

std::vector<Light> sceneLights(const Scene& scene, const CommonOptions& o) {
    std::vector<Light> lights = o.noSceneLights ? std::vector<Light>{} : scene.lights;
    if (lights.empty() && environmentLightCount(scene, o) == 0) lights.push_back(defaultKeyLight());
    if (o.sunRadiusDeg)
        for (Light& l : lights)
            if (l.type == LightType::Directional)
                l.angularRadius = *o.sunRadiusDeg * std::numbers::pi_v<float> / 180.0f;
    if (o.lights > 0) {
        auto scattered = scatterLights(scene.worldBounds(), o.lights, o.seed, o.lightDensity);
        shapeLights(scattered, o.lightShape, scene.worldBounds());
        lights.insert(lights.end(), scattered.begin(), scattered.end());
    }
    return lights;
}

void applyLightOptions(Renderer& renderer, const Scene& scene, const CommonOptions& o) {
    RenderSettings settings = renderer.settings();
    settings.environmentLights = environmentLightCount(scene, o);
    renderer.setSettings(settings);
    renderer.setLights(sceneLights(scene, o));
}

void checkMsaaOption(const Context& context, uint32_t msaa) {
    const std::vector<uint32_t> offered = context.msaaSampleCounts();
    if (std::find(offered.begin(), offered.end(), msaa) == offered.end())
        throw Error(fmt::format("--msaa: value: {} samples are not offered by {} (offered: {})", msaa,
                                context.deviceName(), fmt::join(offered, ", ")));
}

void reportValidation(const Context& context) {
    const uint32_t n = context.validationMessageCount();
    if (n > 0) throw Error(fmt::format("Vulkan validation reported {} message(s) (printed above)", n));
}

std::string formatStats(const FrameStats& stats) {
    std::string passes;
    for (const PassTime& p : stats.passes)
        passes += fmt::format("{}{} {:.2f}", passes.empty() ? "" : ", ", p.name, p.gpuMs);
    std::string text =
        stats.passes.empty() ? "gpu timestamps unavailable" : fmt::format("gpu {:.2f} ms ({})", stats.gpuMs, passes);
    text += fmt::format(", wall {:.2f} ms", stats.wallMs);
    if (stats.clusterBuildCpuMs > 0.0)
        text += fmt::format(" (light grid build {:.2f} ms cpu)", stats.clusterBuildCpuMs);
    return text;
}

}  // namespace preskin::cli
