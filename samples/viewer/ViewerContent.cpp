// preskin-viewer's content (see Viewer.h): scenes and environments loaded on worker threads and
// swapped in between frames, the LUT layers the profile panel edits, the renderer rebuilt when
// materials change, pose and lights applied, shader builds, bakes and screenshots requested.
#include "Viewer.h"

#include <preskin/Error.h>
#include <preskin/LightScatter.h>
#include <preskin/View.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>

namespace preskin::viewer {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string lowerExtension(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// The shadow-casting directional light (as the renderer picks it), else the first directional.
int findKeyLight(const std::vector<Light>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional && lights[i].castsShadow) return static_cast<int>(i);
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional) return static_cast<int>(i);
    return -1;
}

}  // namespace

void Viewer::adoptScene(Scene scene, const std::filesystem::path& path, const char* why) {
    scene_ = std::move(scene);
    loadedMaterials_ = scene_.materials;
    scenePath_ = path;
    cli::CommonOptions withoutScatter = options_.common;
    withoutScatter.lights = 0;
    sceneLights_ = cli::sceneLights(scene_, withoutScatter);
    settings_.environmentLights = cli::environmentLightCount(scene_, options_.common);
    keyLight_ = findKeyLight(sceneLights_);
    selectedMaterial_ = -1;
    for (size_t i = 0; i < scene_.materials.size() && selectedMaterial_ < 0; ++i)
        if (scene_.materials[i].skin) selectedMaterial_ = static_cast<int>(i);
    if (selectedMaterial_ < 0 && !scene_.materials.empty()) selectedMaterial_ = 0;
    camera_.reset(scene_.worldBounds(), scene_.cameras);
    morphOverrides_.clear();
    animation_ = scene_.animations.empty() ? -1 : 0;
    animationTimeS_ = animation_ >= 0 ? scene_.animations[0].startS() : 0.0f;
    playing_ = false;
    prepareProfiles();
    rebuildRenderer(why);
}

void Viewer::prepareProfiles() {
    const auto begin = Clock::now();
    auto defaultLuts = std::make_shared<const LutSet>(luts_ ? *luts_ : LutSet::loadDefault());
    try {
        profiles_ = cli::loadProfiles(scene_, options_.common, defaultLuts);
        for (const std::string& w : profiles_->warnings()) info("warning: " + w);
        if (!scene_.profiles.empty()) {
            const ProfileLoadStats& st = profiles_->stats();
            info(fmt::format("{} profiles ready in {:.0f} ms ({} from the cache, {} baked, {} LUT folders)",
                             scene_.profiles.size(), msSince(begin), st.cacheHits, st.baked, st.lutFolders));
        }
    } catch (const std::exception& e) {
        error(fmt::format("profiles: {} (only the default set is loaded)", e.what()));
        profiles_.emplace(defaultLuts);
    }
    preparedLayers_.clear();
    for (size_t i = 0; i < profiles_->layerCount(); ++i) preparedLayers_.push_back(profiles_->layerPointer(i));
    LayerEdit fresh = startEdit_;
    fresh.choice = ProfileChoice::Loaded;
    layerEdits_.assign(profiles_->layerCount(), fresh);
}

size_t Viewer::editedLayer() const {
    if (selectedMaterial_ < 0 || size_t(selectedMaterial_) >= scene_.materials.size()) return 0;
    const Material& m = scene_.materials[size_t(selectedMaterial_)];
    const size_t layer = m.skin ? size_t(m.skin->profile + 1) : 0;
    return profiles_ && layer < profiles_->layerCount() ? layer : 0;
}

void Viewer::applyBakedLayer(size_t layer, std::shared_ptr<const LutSet> luts) {
    if (!profiles_ || layer >= profiles_->layerCount()) return;
    profiles_->setLayer(layer, luts);
    if (layer == 0) luts_ = *luts;
    if (!renderer_) return;
    try {
        renderer_->setProfileLayer(layer, *luts);  // only this layer is uploaded
    } catch (const std::exception&) {
        renderer_->setProfiles(*profiles_);  // larger tables than the arrays': rebuild them
    }
}

void Viewer::rebuildRenderer(const char* why) {
    const auto begin = Clock::now();
    renderer_.reset();  // waits for the device; frees the old scene's memory before the upload
    try {
        renderer_ = profiles_
            ? std::make_unique<Renderer>(*context_, scene_, environment_, *profiles_, settings_)
            : std::make_unique<Renderer>(*context_, scene_, environment_, luts_ ? &*luts_ : nullptr, settings_);
    } catch (const std::exception& e) {
        error(fmt::format("renderer: {}", e.what()));
        return;
    }
    applyLights();
    if (!shaderOverrides_.empty()) {
        try {
            renderer_->setShaderOverrides(shaderOverrides_);
        } catch (const std::exception& e) {
            error(fmt::format("reloaded shaders dropped, built-in ones used: {}", e.what()));
            shaderOverrides_.clear();
        }
    }
    info(fmt::format("renderer built ({}) in {:.0f} ms", why, msSince(begin)));
}

void Viewer::applyPose(float dtS) {
    if (!renderer_) return;
    const Animation* animation = animation_ >= 0 && size_t(animation_) < scene_.animations.size()
        ? &scene_.animations[size_t(animation_)]
        : nullptr;
    if (animation && playing_) {
        const float start = animation->startS();
        const float length = animation->endS() - start;
        animationTimeS_ += dtS * playbackSpeed_;
        if (length > 0.0f)
            animationTimeS_ = start + std::fmod(std::fmod(animationTimeS_ - start, length) + length, length);
        else
            animationTimeS_ = start;
    }
    ScenePose pose =
        posedScene(scene_, animation ? animationNodePose(scene_, *animation, animationTimeS_) : restNodePose(scene_));
    for (size_t i = 0; i < pose.instances.size() && i < morphOverrides_.size(); ++i)
        if (!morphOverrides_[i].empty()) pose.instances[i].morphWeights = morphOverrides_[i];
    try {
        renderer_->setPose(pose);
    } catch (const std::exception& e) {
        error(fmt::format("pose: {}", e.what()));
        morphOverrides_.clear();
    }
}

void Viewer::applyLights() {
    if (!renderer_) return;
    std::vector<Light> lights = sceneLights_;
    if (scatteredLights_ > 0) {
        const auto scattered = scatterLights(scene_.worldBounds(), scatteredLights_, scatterSeed_, scatterDensity_);
        lights.insert(lights.end(), scattered.begin(), scattered.end());
    }
    renderer_->setLights(lights);
}

void Viewer::loadFile(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".gltf" || ext == ".glb")
        startSceneLoad(path);
    else if (ext == ".hdr" || ext == ".exr")
        startEnvironmentLoad(path, environmentIntensity_);
    else
        error(fmt::format("{}: not a scene (.gltf, .glb) or an environment (.hdr, .exr)", path.string()));
}

void Viewer::startSceneLoad(const std::filesystem::path& path) {
    if (sceneJob_.valid()) {
        error(fmt::format("{}: a scene is still loading; try again when it is done", path.string()));
        return;
    }
    info(fmt::format("loading {}", path.string()));
    const cli::CommonOptions common = options_.common;
    sceneJob_ = std::async(std::launch::async, [path, common] {
        SceneLoad result;
        result.path = path;
        const auto begin = Clock::now();
        try {
            Scene scene = cli::loadScene(path, common);
            cli::applySkinOption(scene, common);
            result.scene = std::move(scene);
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        result.loadMs = msSince(begin);
        return result;
    });
}

void Viewer::startEnvironmentLoad(std::optional<std::filesystem::path> path, float intensity,
                                  std::optional<float> rotationDeg) {
    if (environmentJob_.valid()) {
        error("an environment is still loading; try again when it is done");
        return;
    }
    // Loads like `preskin render` does (cli::loadEnvironment): a file, else the scene's own.
    cli::CommonOptions common = options_.common;
    common.env = path ? path->string() : std::string();
    common.envIntensity = intensity;
    if (rotationDeg) common.envRotationDeg = rotationDeg;
    Scene sceneEnvironment;  // only the scene's environment fields
    sceneEnvironment.sourcePath = scene_.sourcePath;
    sceneEnvironment.environmentPath = scene_.environmentPath;
    sceneEnvironment.environmentData = scene_.environmentData;
    sceneEnvironment.environmentIntensity = scene_.environmentIntensity;
    sceneEnvironment.environmentRotation = scene_.environmentRotation;
    const std::string name = path      ? path->string()
        : scene_.environmentPath       ? scene_.environmentPath->string()
        : scene_.hasEnvironmentImage() ? std::string("the scene's embedded environment")
                                       : std::string("uniform grey");
    environmentJob_ = std::async(std::launch::async, [common, sceneEnvironment, name, intensity, fromScene = !path] {
        EnvironmentLoad result;
        result.name = name;
        result.intensity = intensity;
        result.fromScene = fromScene;
        try {
            result.environment = cli::loadEnvironment(sceneEnvironment, common);
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        return result;
    });
}

void Viewer::applyShaderBuild(ShaderBuild build) {
    const std::string changed = build.changedFiles.empty() ? std::string("requested") : [&] {
        std::string list;
        for (const std::string& f : build.changedFiles) list += (list.empty() ? "" : ", ") + f;
        return list;
    }();
    if (!build.ok) {
        shaderLog_ = build.log;
        shaderLogIsError_ = true;
        error(fmt::format("shaders ({}) did not compile; the last good pipelines keep running", changed));
        return;
    }
    try {
        if (renderer_) renderer_->setShaderOverrides(build.spirvByFile);
        shaderOverrides_ = std::move(build.spirvByFile);
        shaderLog_ = build.log.empty()
            ? fmt::format("compiled {} stages in {:.0f} ms", shaderOverrides_.size(), build.compileMs)
            : build.log;
        shaderLogIsError_ = false;
        info(fmt::format("shaders reloaded ({}) in {:.0f} ms", changed, build.compileMs));
    } catch (const std::exception& e) {
        shaderLog_ = std::string(e.what()) + "\n" + build.log;
        shaderLogIsError_ = true;
        error(fmt::format("reloaded shaders rejected, the last good pipelines keep running: {}", e.what()));
    }
}

void Viewer::requestBake(size_t layer) {
    if (!profiles_ || layer >= layerEdits_.size()) return;
    const LayerEdit& edit = layerEdits_[layer];
    if (edit.choice == ProfileChoice::Loaded) {
        applyBakedLayer(layer, preparedLayers_.at(layer));
        lutStatus_ = "using " + (layer == 0 ? lutsName_ : scene_.profiles[layer - 1].name + " as loaded");
        return;
    }
    try {
        const DiffusionProfile profile = edit.choice == ProfileChoice::Burley
            ? DiffusionProfile::burley(glm::dvec3(edit.albedo[0], edit.albedo[1], edit.albedo[2]),
                                       glm::dvec3(edit.mfpMm[0], edit.mfpMm[1], edit.mfpMm[2]))
            : DiffusionProfile::deonLuebke();
        baker_.request(layer, profile, LutBakeSettings::withSize(lutSize_));
    } catch (const std::exception& e) {
        error(fmt::format("profile: {}", e.what()));
    }
}

void Viewer::requestScreenshot(std::optional<std::filesystem::path> path, bool withUi) {
    if (!path) {
        char stamp[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
        path = fmt::format("preskin-viewer-{}-{}.png", stamp, ++screenshotCounter_);
    }
    try {
        checkOutputPath(*path, OutputEncoding::DisplaySrgb8);
    } catch (const std::exception& e) {
        error(fmt::format("screenshot: {}", e.what()));
        return;
    }
    captureNext_ = *path;
    captureNextUi_ = withUi;
}

void Viewer::pollJobs() {
    shaders_->poll();
    if (auto build = shaders_->takeResult()) applyShaderBuild(std::move(*build));

    if (auto baked = baker_.poll()) {
        if (baked->luts) {
            const auto begin = Clock::now();
            auto luts = std::make_shared<const LutSet>(std::move(*baked->luts));
            applyBakedLayer(baked->layer, luts);
            lutStatus_ = fmt::format("{} (layer {}): baked in {:.0f} ms, uploaded in {:.0f} ms", luts->profile().name(),
                                     baked->layer, baked->bakeMs, msSince(begin));
            info("LUTs " + lutStatus_);
        } else {
            error(fmt::format("LUT bake failed: {}", baked->error));
        }
    }

    if (sceneJob_.valid() && sceneJob_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        SceneLoad loaded = sceneJob_.get();
        if (!loaded.scene) {
            error(fmt::format("scene not loaded, keeping the current one: {}", loaded.error));
        } else {
            for (const std::string& w : loaded.scene->warnings) info("warning: " + w);
            info(fmt::format("{} loaded in {:.0f} ms", loaded.path.string(), loaded.loadMs));
            const bool newEnvironment =
                environmentFromScene_ && (loaded.scene->hasEnvironmentImage() || scene_.hasEnvironmentImage());
            scenePathInput_ = loaded.path.string();
            adoptScene(std::move(*loaded.scene), loaded.path, "scene loaded");
            if (newEnvironment) startEnvironmentLoad(std::nullopt, scene_.environmentIntensity);
        }
    }

    if (environmentJob_.valid() && environmentJob_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        EnvironmentLoad loaded = environmentJob_.get();
        if (!loaded.environment) {
            error(fmt::format("environment not loaded, keeping the current one: {}", loaded.error));
        } else {
            environment_ = std::move(*loaded.environment);
            environmentName_ = loaded.name;
            environmentPathInput_ = loaded.name;
            environmentIntensity_ = loaded.intensity;
            environmentFromScene_ = loaded.fromScene;
            environmentRotationDeg_ = glm::degrees(environment_.rotationY());
            if (renderer_) renderer_->setEnvironment(environment_);
            info(fmt::format("environment {} (intensity {:.2f})", loaded.name, loaded.intensity));
        }
    }
}

}  // namespace preskin::viewer
