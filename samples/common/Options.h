// Command-line options shared by the sample programs, and the helpers that turn them into
// library objects (context, environment, renderer settings, lights). Public API only.
#pragma once

#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace preskin::cli {

// A diffusion profile as `--profile` names it: deon, burley (surface albedo and mean free path in
// mm, R,G,B each) or a profile JSON file (docs/gltf-extensions.md's forms).
struct ProfileChoice {
    std::string profile;  // "": none chosen
    std::string albedo;
    std::string meanFreePath;
};
// The viewer's and `preskin render`'s Burley parameters when none are given (skin's values of
// Christensen & Burley 2015's measured set).
inline constexpr const char* kDefaultBurleyAlbedo = "0.83,0.57,0.45";
inline constexpr const char* kDefaultBurleyMfp = "1.2,0.5,0.25";

struct CommonOptions {
    std::string env;
    float envIntensity = -1.0f;           // < 0: the scene's (or 1)
    std::optional<float> envRotationDeg;  // unset: the scene's (or 0)
    int envLights = -1;                   // < 0: environmentLightCount's default
    bool noSceneLights = false;
    bool envLightSize = false;  // --env-light-size: RenderSettings::environmentLightSizes
    std::string device;
    bool validation = false;
    std::string skin;  // material name, "all" or "none"
    bool standard = false;
    bool noLutDiffuse = false;
    bool noNormalPrefilter = false;
    bool noPenumbra = false;
    bool noShSkin = false;
    bool noTransmission = false;
    bool noDualSpecular = false;
    bool noOpposingLight = false;
    bool noNormalMapLevels = false;
    bool noLutShadowLight = false;
    bool noLightCurvature = false;
    bool lutOtherLights = false;
    bool noFullShadowFilter = false;
    bool noWidePenumbra = false;
    std::string skinQuality;  // --skin-quality: "" (each material's own), low, medium or high
    bool skinTermsPerFragment = false;
    bool noSpecular = false;
    bool noSpecularIbl = false;
    std::string debug = "none";
    std::vector<std::string> background;  // --background: empty (the default colour), env, transparent, color R,G,B
    uint32_t lights = 0;
    uint32_t seed = 1;
    float lightDensity = 0.0f;  // --light-density: lights per point for --lights (0: ranges of the scene's size)
    std::optional<float> sunRadiusDeg;  // --sun-radius: directional lights' angular radius, degrees
    std::string lightShape = "point";   // --light-shape: point (points and spots), sphere, tube, rectangle, disc
    std::string lightLoop = "clustered";
    std::string diffusion = "preintegrated";  // --diffusion: RenderSettings::diffusion
    uint32_t diffusionTaps = 17;              // --diffusion-taps: RenderSettings::screenDiffusionTaps
    uint32_t diffusionTextureSize = 1024;     // --diffusion-texture-size: RenderSettings::textureDiffusionSize
    float exposure = 1.0f;
    float shadowSoftness = 1.5f;
    uint32_t shadowMapSize = 2048;
    bool noShadows = false;
    uint32_t msaa = 1;
    bool noDepthPrepass = false;
    std::string luts;                // LUT set folder; default: the committed luts/ (d'Eon)
    ProfileChoice profile;           // render --profile: baked at start instead of a LUT folder
    bool allowOutsideLinks = false;  // SceneLoadOptions::allowLinksOutsideFolder
    bool noCache = false;            // bake the scene's profiles without the on-disk cache
    std::string cacheDir;            // profile cache folder; default: the XDG cache folder
    uint32_t profileLutSize = 256;   // table size the scene's analytic profiles are baked at
};

// Every option below: the scene options plus the renderer's (device, validation, skin
// techniques, specular, debug view, light loop, shadow map).
void addCommonOptions(CLI::App& cmd, CommonOptions& o);
// RenderSettings::diffusion of a --diffusion name (preintegrated, screen, texture); throws on another.
Diffusion diffusionMethod(const std::string& name);
// Scene::load with the options' SceneLoadOptions.
Scene loadScene(const std::filesystem::path& path, const CommonOptions& o);
// What defines the lit scene without a renderer (the reference uses only these): environment,
// --skin, --lights/--seed, --exposure, --no-shadows, --luts (the profile), --allow-outside-links.
void addSceneOptions(CLI::App& cmd, CommonOptions& o);
// --device, --validation.
void addDeviceOptions(CLI::App& cmd, CommonOptions& o);
// --shadow-softness, --shadow-map-size.
void addShadowMapOptions(CLI::App& cmd, CommonOptions& o);
// The skin technique switches (--no-lut-diffuse ... --skin-terms-per-fragment).
void addSkinTechniqueOptions(CLI::App& cmd, CommonOptions& o);
// The baselines' settings (--diffusion-taps, --diffusion-texture-size; RenderSettings).
void addDiffusionOptions(CLI::App& cmd, CommonOptions& o);
// The LUT set (--luts).
void addLutOptions(CLI::App& cmd, CommonOptions& o);
// How the scene's own profiles are baked (--no-cache, --cache-dir, --profile-lut-size).
void addProfileBakeOptions(CLI::App& cmd, CommonOptions& o);

// Image size and camera, shared by `render`, `reference` and `compare`.
struct ViewOptions {
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string camera;
    std::string orbit;
};
void addViewOptions(CLI::App& cmd, ViewOptions& o);
// Refuses malformed view options before anything is loaded.
void checkViewOptions(const ViewOptions& o);
// The index of the scene's camera named `name`; throws "--camera NAME: SCENE has no camera of
// that name (its cameras: a, b)" otherwise.
size_t findSceneCamera(const Scene& scene, const std::filesystem::path& scenePath, const std::string& name);
// --camera NAME (a glTF camera), --orbit YAW,PITCH,DIST, else the default framing of the bounds.
View makeView(const Scene& scene, const std::filesystem::path& scenePath, const ViewOptions& o);

// Where the tools find LUTs, shaders and the bundled sample scene: $PRESKIN_DATA_DIR when set,
// else <prefix>/share/preskin for an installed tool, else the source tree.
std::filesystem::path dataDir();
std::filesystem::path defaultScenePath();
std::filesystem::path defaultAnimatedScenePath();  // the bundled animated head
OutputEncoding encodingFor(const std::filesystem::path& out);
std::vector<float> parseFloats(const std::string& text, size_t count, const char* flag);

// Stereo camera options: --stereo, --ipd, --eye.
struct StereoOptions {
    bool stereo = false;
    float ipdM = 0.063f;
    std::string eye;  // "", "left" or "right"
};
void addStereoOptions(CLI::App& cmd, StereoOptions& o);
// The view to draw from a mono view: itself, its stereo pair, or one eye of the pair.
View applyStereoOptions(const View& mono, const StereoOptions& o);

ContextDesc contextDesc(const CommonOptions& o);
// --luts DIR, else the committed default set (luts/ of the data folder), else a fresh bake.
LutSet loadLuts(const CommonOptions& o);
// "R,G,B" as three finite numbers; Error naming `option` otherwise.
glm::dvec3 parseRgb(const std::string& text, const char* option);
// The profile `choice` names. burley without albedo or mean free path: `burleyDefaults` fills in
// kDefaultBurley*, else it is refused; --albedo or --mfp with another profile is refused.
DiffusionProfile selectProfile(const ProfileChoice& choice, bool burleyDefaults);
// render's --profile, --albedo and --mfp into o.profile.
void addProfileChoiceOptions(CLI::App& cmd, CommonOptions& o);
// The default set (loadLuts) and the scene's diffusion profiles, baked or read from the cache
// (--no-cache, --cache-dir, --profile-lut-size); prints the cache's warnings.
// `defaultLuts`: layer 0, or loadLuts(o) when null.
ProfileLibrary loadProfiles(const Scene& scene, const CommonOptions& o, std::shared_ptr<const LutSet> defaultLuts = {});
RenderSettings renderSettings(const CommonOptions& o);
// --background's words as RenderSettings::background; throws naming the option.
Background parseBackground(const std::vector<std::string>& words);
// --skin: makes the named material (or every one) skin, or with "none" removes skin from every
// material (removeSkin: returns whether any was skin).
void applySkinOption(Scene& scene, const CommonOptions& o);
bool removeSkin(Scene& scene);
// --env, else the scene's PRESKIN_environment, else a dim uniform grey.
Environment loadEnvironment(const Scene& scene, const CommonOptions& o);
// The key light of a scene that has none: directional from the upper right front, shadowed.
Light defaultKeyLight();
// The scene's lights plus --lights N scattered ones; a scene without any light gets a key light.
// The lights the environment gives (--env-lights): by default one when the scene has an
// environment image and no lights of its own.
int environmentLightCount(const Scene& scene, const CommonOptions& o);
// --light-shape: every point and spot light of `lights` made an area light of that shape
// ("point" leaves them), sized from its range (sphere radius 5 %, tube 2 % by 30 %, rectangle
// 20 % by 10 %, disc radius 8 %), rectangles and discs facing the bounds' centre.
void shapeLights(std::vector<Light>& lights, const std::string& shape, const Bounds& bounds);

// The scene's lights, the default key light when it has none and the environment gives none,
// and --lights' scattered ones.
std::vector<Light> sceneLights(const Scene& scene, const CommonOptions& o);
void applyLightOptions(Renderer& renderer, const Scene& scene, const CommonOptions& o);
// Refuses --msaa N unless the context's device offers N samples, naming the option and the
// counts it offers (before a renderer is made, whose own refusal names RenderSettings).
void checkMsaaOption(const Context& context, uint32_t msaa);
// Throws when validation is on and reported anything.
void reportValidation(const Context& context);
std::string formatStats(const FrameStats& stats);

}  // namespace preskin::cli
