// preskin-viewer's Dear ImGui panels: scene and environment, camera, skin techniques, the
// selected material's skin parameters, diffusion profile (live LUT re-bake), lights, debug
// views, frame timing, shader hot reload and messages. Edits take effect as follows: render
// settings and lights at the next frame; profile changes after the background bake; material
// edits rebuild the Renderer when a control is released (the Renderer reads materials once).
// Limits: the panel layout is not saved between runs; one material is edited at a time.
#include "LightGizmos.h"
#include "Viewer.h"

#include <preskin/Error.h>
#include <preskin/LightRecord.h>

#include <imgui.h>
#include <imgui_stdlib.h>

#include <fmt/core.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace preskin::viewer {

namespace {

const ImVec4 kErrorColor{1.0f, 0.35f, 0.3f, 1.0f};
const ImVec4 kWarnColor{1.0f, 0.8f, 0.3f, 1.0f};

void tooltip(const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

size_t triangleCount(const Scene& scene) {
    size_t n = 0;
    for (const MeshInstance& inst : scene.instances)
        if (inst.mesh >= 0 && size_t(inst.mesh) < scene.meshes.size())
            for (const Primitive& p : scene.meshes[size_t(inst.mesh)].primitives) n += p.indices.size() / 3;
    return n;
}

}  // namespace

void Viewer::drawUi() {
    if (!showUi_) return;
    if (showLightGizmos_ && !stereo_ && swapchain_ && swapchain_->valid())
        drawAreaLightGizmos(sceneLights_, frameView().eye(), ImGui::GetIO().DisplaySize.x,
                            ImGui::GetIO().DisplaySize.y);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400.0f, std::max(display.y - 20.0f, 200.0f)), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("preskin")) {
        ImGui::PushItemWidth(-175.0f);  // room for the labels
        ImGui::TextDisabled("F1 hides the panels. Drop .gltf/.glb/.hdr/.exr");
        ImGui::TextDisabled("files on the window to load them.");
        panelScene();
        panelCamera();
        panelAnimation();
        panelTechniques();
        panelMaterial();
        panelProfile();
        panelLights();
        panelDebug();
        panelShaders();
        ImGui::PopItemWidth();
    }
    ImGui::End();

    ImGui::SetNextWindowPos(ImVec2(std::max(display.x - 350.0f, 10.0f), 10.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Frame", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) panelTiming();
    ImGui::End();

    ImGui::SetNextWindowPos(ImVec2(std::max(display.x - 350.0f, 10.0f), std::max(display.y - 210.0f, 10.0f)),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340.0f, 200.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Messages")) panelMessages();
    ImGui::End();
    statusBar();
}

void Viewer::panelScene() {
    if (!ImGui::CollapsingHeader("Scene and environment")) return;
    size_t skinMaterials = 0;
    for (const Material& m : scene_.materials) skinMaterials += m.skin ? 1 : 0;
    ImGui::Text("%s", scenePath_.filename().string().c_str());
    tooltip(scenePath_.string().c_str());
    ImGui::TextDisabled("%zu meshes, %zu triangles, %zu materials (%zu skin)", scene_.meshes.size(),
                        triangleCount(scene_), scene_.materials.size(), skinMaterials);
    ImGui::TextDisabled("%zu lights, %zu cameras", scene_.lights.size(), scene_.cameras.size());
    if (!scene_.warnings.empty())
        ImGui::TextColored(kWarnColor, "%zu loader warnings (see Messages)", scene_.warnings.size());
    ImGui::SetNextItemWidth(-90.0f);
    const bool enterScene = ImGui::InputText("##scenepath", &scenePathInput_, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if (ImGui::Button("Load scene") || enterScene) startSceneLoad(scenePathInput_);
    if (sceneJob_.valid()) ImGui::TextColored(kWarnColor, "loading scene...");

    ImGui::Separator();
    ImGui::Text("Environment: %s", std::filesystem::path(environmentName_).filename().string().c_str());
    tooltip(environmentName_.c_str());
    ImGui::SetNextItemWidth(-90.0f);
    const bool enterEnv = ImGui::InputText("##envpath", &environmentPathInput_, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if (ImGui::Button("Load env") || enterEnv)
        startEnvironmentLoad(std::filesystem::path(environmentPathInput_), environmentIntensity_);
    ImGui::SliderFloat("Intensity##env", &environmentIntensity_, 0.01f, 16.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    tooltip("Environment radiance scale (re-projects the environment when released)");
    if (ImGui::IsItemDeactivatedAfterEdit())
        startEnvironmentLoad(
            environmentFromScene_ ? std::nullopt : std::optional<std::filesystem::path>(environmentName_),
            environmentIntensity_, environmentRotationDeg_);
    const std::optional<std::filesystem::path> loadedPath =
        environmentFromScene_ ? std::nullopt : std::optional<std::filesystem::path>(environmentName_);
    ImGui::SliderFloat("Rotation##env", &environmentRotationDeg_, -180.0f, 180.0f, "%.0f deg");
    tooltip(
        "Turn the environment about +Y: its SH, specular map, background and extracted lights together "
        "(applied when released)");
    if (ImGui::IsItemDeactivatedAfterEdit())
        startEnvironmentLoad(loadedPath, environmentIntensity_, environmentRotationDeg_);
    if (environmentJob_.valid()) ImGui::TextColored(kWarnColor, "loading environment...");
    int background = static_cast<int>(settings_.background.mode);
    if (ImGui::Combo("Background", &background, "colour\0environment\0transparent\0"))
        settings_.background.mode = static_cast<BackgroundMode>(background);
    ImGui::Checkbox("Prefiltered specular", &settings_.specularIbl);
    tooltip("The environment's specular reflection from its GGX-prefiltered map; off: from its L2 SH");
    ImGui::SliderInt("Environment lights", &settings_.environmentLights, -1, int(kMaxEnvironmentLights),
                     settings_.environmentLights < 0 ? "auto" : "%d");
    tooltip(
        "Directional lights extracted from the environment by median cut, with the shadow when no scene light "
        "casts it; auto: one when the scene has no lights");
    ImGui::Checkbox("Environment light sizes", &settings_.environmentLightSizes);
    tooltip(
        "--env-light-size: each extracted light a sun of its texels' angular spread (soft terminator and "
        "shadow); off: parallel lights");
    if (renderer_)
        for (const Light& l : renderer_->environmentLights())
            ImGui::TextDisabled("%s: towards (%.2f, %.2f, %.2f), %.3g lux", l.name.c_str(), double(-l.directionWs.x),
                                double(-l.directionWs.y), double(-l.directionWs.z), double(l.intensity));
}

void Viewer::panelCamera() {
    if (!ImGui::CollapsingHeader("Camera")) return;
    int mode = static_cast<int>(camera_.mode());
    bool changed = ImGui::RadioButton("Orbit", &mode, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("Fly", &mode, 1);
    ImGui::SameLine();
    ImGui::BeginDisabled(scene_.cameras.empty());
    changed |= ImGui::RadioButton("Scene camera", &mode, 2);
    ImGui::EndDisabled();
    if (changed) camera_.setMode(static_cast<CameraMode>(mode), aspect());

    if (camera_.mode() == CameraMode::Scene) {
        int index = camera_.sceneCamera();
        std::vector<const char*> names;
        for (const Camera& c : scene_.cameras) names.push_back(c.name.empty() ? "(unnamed)" : c.name.c_str());
        if (ImGui::Combo("Camera", &index, names.data(), static_cast<int>(names.size()))) camera_.setSceneCamera(index);
    } else if (camera_.mode() == CameraMode::Orbit) {
        ImGui::SliderFloat("Yaw", &camera_.yawDeg(), -180.0f, 180.0f, "%.1f deg");
        ImGui::SliderFloat("Pitch", &camera_.pitchDeg(), -89.0f, 89.0f, "%.1f deg");
        float distanceM = camera_.orbitDistanceM(aspect());
        if (ImGui::DragFloat("Distance", &distanceM, 0.005f, 0.001f, 1000.0f,
                             camera_.distanceM() <= 0.0f ? "%.3f m (fit)" : "%.3f m"))
            camera_.distanceM() = std::max(distanceM, 0.001f);
        ImGui::SameLine();
        if (ImGui::SmallButton("Fit")) camera_.distanceM() = 0.0f;
    } else {
        ImGui::SliderFloat("Speed", &camera_.flySpeedMps(), 0.001f, 100.0f, "%.3f m/s", ImGuiSliderFlags_Logarithmic);
        ImGui::DragFloat3("Position", &camera_.flyPositionWs().x, 0.01f, 0.0f, 0.0f, "%.3f");
    }
    if (ImGui::Button("Reset view (Home)")) camera_.reset(scene_.worldBounds(), scene_.cameras);
    ImGui::Checkbox("Stereo preview (side by side)", &stereo_);
    tooltip("Both eyes of a stereo pair around the camera, drawn in one pass; left eye on the left.");
    if (stereo_) {
        float ipdMm = ipdM_ * 1000.0f;
        if (ImGui::SliderFloat("IPD", &ipdMm, 0.0f, 200.0f, "%.1f mm")) ipdM_ = ipdMm * 0.001f;
    }
    if (renderer_) {
        const std::vector<uint32_t> counts = renderer_->msaaSampleCounts();
        std::vector<std::string> labels;
        int current = 0;
        for (size_t i = 0; i < counts.size(); ++i) {
            labels.push_back(counts[i] == 1 ? std::string("off") : fmt::format("{}x", counts[i]));
            if (counts[i] == settings_.msaaSamples) current = int(i);
        }
        std::vector<const char*> names;
        for (const std::string& l : labels) names.push_back(l.c_str());
        if (ImGui::Combo("MSAA", &current, names.data(), int(names.size())))
            settings_.msaaSamples = counts[size_t(current)];
    }
    ImGui::TextDisabled("Orbit: drag to turn, wheel to zoom.");
    ImGui::TextDisabled("Fly: drag to look, W/A/S/D move, Q/E down/up,");
    ImGui::TextDisabled("Shift faster, wheel sets speed. Tab: orbit/fly.");
}

void Viewer::panelAnimation() {
    if (!ImGui::CollapsingHeader("Animation")) return;
    std::vector<std::string> names{"(rest pose)"};
    for (size_t i = 0; i < scene_.animations.size(); ++i)
        names.push_back(scene_.animations[i].name.empty() ? fmt::format("animation {}", i) : scene_.animations[i].name);
    std::vector<const char*> labels;
    for (const std::string& n : names) labels.push_back(n.c_str());
    int current = animation_ + 1;
    if (ImGui::Combo("Animation", &current, labels.data(), int(labels.size()))) {
        animation_ = current - 1;
        animationTimeS_ = animation_ >= 0 ? scene_.animations[size_t(animation_)].startS() : 0.0f;
    }
    if (animation_ >= 0) {
        const Animation& a = scene_.animations[size_t(animation_)];
        if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
        ImGui::SameLine();
        if (ImGui::Button("|<")) animationTimeS_ = a.startS();
        ImGui::SliderFloat("Time", &animationTimeS_, a.startS(), std::max(a.endS(), a.startS() + 1e-3f), "%.3f s");
        ImGui::SliderFloat("Speed", &playbackSpeed_, -2.0f, 4.0f, "%.2fx");
    }
    // Morph weights by hand, per instance with morph targets (they replace the animation's).
    morphOverrides_.resize(scene_.instances.size());
    const ScenePose& pose = renderer_ ? renderer_->pose() : ScenePose{};
    for (size_t i = 0; i < scene_.instances.size(); ++i) {
        const MeshInstance& inst = scene_.instances[i];
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene_.meshes.size() || i >= pose.instances.size()) continue;
        const Mesh& mesh = scene_.meshes[size_t(inst.mesh)];
        const size_t targets = pose.instances[i].morphWeights.size();
        if (targets == 0) continue;
        ImGui::PushID(int(i));
        bool byHand = !morphOverrides_[i].empty();
        if (ImGui::Checkbox(
                fmt::format("Morph weights of {} by hand", inst.nodeName.empty() ? mesh.name : inst.nodeName).c_str(),
                &byHand))
            morphOverrides_[i] = byHand ? pose.instances[i].morphWeights : std::vector<float>{};
        if (byHand) {
            morphOverrides_[i].resize(targets, 0.0f);
            for (size_t t = 0; t < targets; ++t) {
                const std::string name =
                    t < mesh.targetNames.size() ? mesh.targetNames[t] : fmt::format("target {}", t);
                ImGui::SliderFloat(name.c_str(), &morphOverrides_[i][t], 0.0f, 1.0f, "%.2f");
            }
        }
        ImGui::PopID();
    }
}

void Viewer::panelTechniques() {
    if (!ImGui::CollapsingHeader("Skin techniques", ImGuiTreeNodeFlags_DefaultOpen)) return;
    SkinFeatures& f = settings_.skin;
    ImGui::Checkbox("Pre-integrated diffuse (LUT)", &f.lutDiffuse);
    tooltip("Off: Lambert N.L");
    ImGui::Checkbox("Normal prefilter (per channel)", &f.normalPrefilter);
    tooltip("Off: one normal for all channels");
    ImGui::Checkbox("Normal-map levels (per channel)", &f.normalMapLevels);
    tooltip("Off: the normal map read once, on each channel's geometric normal");
    ImGui::Checkbox("Penumbra scattering", &f.penumbra);
    tooltip("Off: the plain filtered shadow");
    ImGui::Checkbox("Diffuse LUT for the shadow light", &f.lutShadowLight);
    tooltip("Off: the shadow light gets the LUT's row as a smoothed ramp");
    ImGui::Checkbox("Diffuse LUT for the other lights", &f.lutOtherLights);
    tooltip("On: every light reads the LUT (three fetches per light); off: the row's smoothed ramp");
    ImGui::Checkbox("Diffuse LUT row along each light", &f.lightCurvature);
    tooltip("Off: every light reads the mean curvature's row");
    ImGui::Checkbox("Shadow filter over 8 x 8 texels", &f.fullShadowFilter);
    tooltip("Off: 6 x 6 texels (9 gathers instead of 16)");
    ImGui::Checkbox("Wide penumbra (wide shadow map)", &f.widePenumbra);
    tooltip("Off: penumbra scattering within the shadow filter's reach only");
    ImGui::Checkbox("SH ambient skin transfer", &f.shAmbient);
    tooltip("Off: Lambert SH irradiance");
    ImGui::Checkbox("Transmission (thin parts)", &f.transmission);
    ImGui::Checkbox("Dual specular lobes", &f.dualSpecular);
    tooltip("Off: one GGX lobe");
    ImGui::Checkbox("Opposing neighbours' light", &f.opposingLight);
    tooltip("Off: no light from skin facing the point across a gap (lips, ear folds, nostrils)");
    if (ImGui::Button("All on")) f = SkinFeatures{};
    ImGui::SameLine();
    if (ImGui::Button("Standard (all off)")) f = SkinFeatures::none();
    // Quality tier: every skin material's own, or all at one tier.
    int tier = settings_.skinQuality ? 1 + static_cast<int>(*settings_.skinQuality) : 0;
    ImGui::Combo("Quality tier", &tier, "each material's own\0low\0medium\0high\0");
    settings_.skinQuality = tier == 0 ? std::nullopt : std::optional<SkinQuality>(static_cast<SkinQuality>(tier - 1));
    tooltip(
        "The techniques skin compiles in: high all, medium without transmission and the second lobe, low "
        "also without the wide shadow map, the normal map's per-channel levels and the diffuse LUT for lights "
        "other than the shadow light (the diffuse LUT, per-channel geometric normals, the penumbra within the "
        "shadow filter's reach, SH transfer and opposing light)");
    int method = static_cast<int>(settings_.diffusion);
    ImGui::RadioButton("Pre-integrated", &method, 0);
    ImGui::SameLine();
    ImGui::RadioButton("Screen-space", &method, 1);
    ImGui::SameLine();
    ImGui::RadioButton("Texture-space", &method, 2);
    tooltip(
        "--diffusion: preskin's own, or a baseline it replaces (Lambert skin blurred by the profile on the screen "
        "or in the mesh's UV layout, in more passes; of the techniques above only transmission and dual "
        "specular apply to them)");
    settings_.diffusion = static_cast<Diffusion>(method);
    ImGui::SliderFloat("Exposure", &settings_.exposure, 0.05f, 16.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
}

void Viewer::panelMaterial() {
    if (!ImGui::CollapsingHeader("Skin material", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (scene_.materials.empty()) {
        ImGui::TextDisabled("the scene has no materials");
        return;
    }
    selectedMaterial_ = std::clamp(selectedMaterial_, 0, static_cast<int>(scene_.materials.size()) - 1);
    std::vector<std::string> labels;
    for (size_t i = 0; i < scene_.materials.size(); ++i)
        labels.push_back(fmt::format(
            "{}{}", scene_.materials[i].name.empty() ? fmt::format("material {}", i) : scene_.materials[i].name,
            scene_.materials[i].skin ? " (skin)" : ""));
    std::vector<const char*> names;
    for (const std::string& l : labels) names.push_back(l.c_str());
    ImGui::Combo("Material", &selectedMaterial_, names.data(), static_cast<int>(names.size()));

    Material& material = scene_.materials[size_t(selectedMaterial_)];
    bool rebuild = false;
    if (!material.skin) {
        ImGui::TextDisabled("shaded as a standard material");
        if (ImGui::Button("Shade as skin")) {
            material.skin = SkinMaterial{};
            rebuild = true;
        }
        ImGui::SameLine();
        if (ImGui::Button("Every material as skin")) {
            scene_.makeSkin("all");
            rebuild = true;
        }
    } else {
        SkinMaterial& skin = *material.skin;
        const char* sources[] = {"Per vertex (from the mesh)", "Texture", "Screen-space derivatives"};
        int source = static_cast<int>(skin.curvatureSource);
        if (ImGui::Combo("Curvature source", &source, sources, 3)) {
            if (static_cast<CurvatureSource>(source) == CurvatureSource::Texture && !skin.curvatureTexture.valid()) {
                error(fmt::format("material '{}' has no curvature texture; curvature source unchanged", material.name));
            } else {
                skin.curvatureSource = static_cast<CurvatureSource>(source);
                rebuild = true;
            }
        }
        ImGui::SliderFloat("Scatter scale", &skin.scatterScale, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        tooltip(
            "Profile millimetres per world millimetre: scales curvature, penumbra width and thickness "
            "(1 for a life-size head in metres)");
        rebuild |= ImGui::IsItemDeactivatedAfterEdit();
        if (skin.curvatureSource == CurvatureSource::Texture) {
            ImGui::SliderFloat("Curvature texture scale", &skin.curvatureTextureScalePerM, 1.0f, 2000.0f, "%.0f 1/m",
                               ImGuiSliderFlags_Logarithmic);
            tooltip("Curvature (1/m) that a texture value of 1 above the bias stands for");
            rebuild |= ImGui::IsItemDeactivatedAfterEdit();
            ImGui::SliderFloat("Curvature texture bias", &skin.curvatureTextureBias, 0.0f, 1.0f, "%.2f");
            tooltip("The texture value of zero curvature (0.5 for signed maps, such as bake-curvature's)");
            rebuild |= ImGui::IsItemDeactivatedAfterEdit();
        }
        bool overrideBias = skin.normalLodBias.has_value();
        if (ImGui::Checkbox("Override normal-map LOD biases", &overrideBias)) {
            if (overrideBias)
                skin.normalLodBias = glm::vec3(2.0f, 1.0f, 0.5f);
            else
                skin.normalLodBias.reset();
            rebuild = true;
        }
        tooltip(
            "Per-channel mip bias of the prefiltered normal (red blurred most). Unset: derived from the "
            "profile's per-channel width and the normal map's texel density");
        if (skin.normalLodBias) {
            ImGui::SliderFloat3("LOD bias R G B", &skin.normalLodBias->x, 0.0f, 8.0f, "%.2f");
            rebuild |= ImGui::IsItemDeactivatedAfterEdit();
        } else {
            ImGui::TextDisabled("LOD biases derived from the profile");
        }
        ImGui::SliderFloat("Transmission##material", &skin.transmission, 0.0f, 1.0f, "%.2f");
        rebuild |= ImGui::IsItemDeactivatedAfterEdit();
        ImGui::SliderFloat("Thickness scale", &skin.thicknessScale, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        rebuild |= ImGui::IsItemDeactivatedAfterEdit();
        ImGui::SliderFloat("Specular intensity", &skin.specularIntensity, 0.0f, 3.0f, "%.2f");
        rebuild |= ImGui::IsItemDeactivatedAfterEdit();
    }
    if (ImGui::Button("Reset material edits")) {
        scene_.materials = loadedMaterials_;
        rebuild = true;
    }
    tooltip("Material edits rebuild the renderer when a control is released");
    if (rebuild) rebuildRenderer("material edited");
}

void Viewer::panelProfile() {
    if (!ImGui::CollapsingHeader("Diffusion profile", ImGuiTreeNodeFlags_DefaultOpen)) return;
    // The selected material's profile: the default set or one of the scene's (a LUT layer each).
    const bool skinSelected = selectedMaterial_ >= 0 && size_t(selectedMaterial_) < scene_.materials.size() &&
        scene_.materials[size_t(selectedMaterial_)].skin;
    if (skinSelected && profiles_) {
        SkinMaterial& skin = *scene_.materials[size_t(selectedMaterial_)].skin;
        std::vector<std::string> labels = {fmt::format("default: {}", lutsName_)};
        for (const SkinProfile& p : scene_.profiles) labels.push_back(p.name);
        std::vector<const char*> names;
        for (const std::string& l : labels) names.push_back(l.c_str());
        int choice = skin.profile + 1;
        if (ImGui::Combo("Profile of the material", &choice, names.data(), static_cast<int>(names.size()))) {
            skin.profile = choice - 1;
            rebuildRenderer("material profile chosen");
        }
        tooltip("Which of the scene's diffusion profiles this material uses; each is one layer of the LUT arrays");
        if (!skin.blendProfiles.empty())
            ImGui::TextDisabled("blends %zu more profiles by its weight texture", skin.blendProfiles.size());
    }
    const size_t layer = editedLayer();
    if (layer >= layerEdits_.size()) return;
    LayerEdit& edit = layerEdits_[layer];
    ImGui::Text("Editing LUT layer %zu (%s); only it is re-baked", layer,
                layer == 0 ? "the default set" : scene_.profiles[layer - 1].name.c_str());
    int choice = static_cast<int>(edit.choice);
    bool changed = ImGui::RadioButton(
        fmt::format("As loaded: {}", layer == 0 ? lutsName_ : scene_.profiles[layer - 1].name).c_str(), &choice, 0);
    changed |= ImGui::RadioButton("d'Eon & Luebke (sum of Gaussians)", &choice, 1);
    changed |= ImGui::RadioButton("Christensen & Burley (normalized diffusion)", &choice, 2);
    edit.choice = static_cast<ProfileChoice>(choice);
    if (edit.choice == ProfileChoice::Burley) {
        changed |= ImGui::SliderFloat3("Albedo", edit.albedo.data(), 0.01f, 1.0f, "%.2f");
        tooltip("Surface albedo per channel (R, G, B)");
        changed |= ImGui::SliderFloat3("Mean free path", edit.mfpMm.data(), 0.01f, 10.0f, "%.2f mm",
                                       ImGuiSliderFlags_Logarithmic);
        tooltip("Mean free path per channel in millimetres (R, G, B)");
    }
    if (edit.choice != ProfileChoice::Loaded) {
        const int sizes[] = {64, 128, 256, 512};
        int index = static_cast<int>(std::find(std::begin(sizes), std::end(sizes), lutSize_) - std::begin(sizes));
        const char* labels[] = {"64", "128", "256 (default)", "512"};
        if (ImGui::Combo("LUT size", &index, labels, 4)) {
            lutSize_ = sizes[std::clamp(index, 0, 3)];
            changed = true;
        }
    }
    if (changed) requestBake(layer);
    if (baker_.busy()) {
        ImGui::ProgressBar(static_cast<float>(baker_.progress()), ImVec2(-1.0f, 0.0f), "baking LUTs");
    } else if (!lutStatus_.empty()) {
        ImGui::TextDisabled("%s", lutStatus_.c_str());
    }
    if (profiles_) {
        const glm::dvec3 w = profiles_->layer(layer).profile().widthMm();
        ImGui::TextDisabled("Scattering width R %.2f G %.2f B %.2f mm", w.x, w.y, w.z);
    }
}

void Viewer::panelLights() {
    if (!ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
    bool changed = false;
    if (keyLight_ >= 0 && size_t(keyLight_) < sceneLights_.size()) {
        Light& key = sceneLights_[size_t(keyLight_)];
        ImGui::Text("Key light: %s", key.name.empty() ? "(unnamed)" : key.name.c_str());
        const glm::vec3 toLight =
            glm::length(key.directionWs) > 0.0f ? -glm::normalize(key.directionWs) : glm::vec3(0.0f, 0.0f, 1.0f);
        float azimuthDeg = glm::degrees(std::atan2(toLight.x, toLight.z));
        float elevationDeg = glm::degrees(std::asin(std::clamp(toLight.y, -1.0f, 1.0f)));
        bool direction = ImGui::SliderFloat("Azimuth", &azimuthDeg, -180.0f, 180.0f, "%.0f deg");
        tooltip("Where the light comes from, around +Y; 0 is the front (+Z)");
        direction |= ImGui::SliderFloat("Elevation", &elevationDeg, -89.0f, 89.0f, "%.0f deg");
        if (direction) {
            const float az = glm::radians(azimuthDeg);
            const float el = glm::radians(elevationDeg);
            key.directionWs = -glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
            changed = true;
        }
        changed |= ImGui::ColorEdit3("Colour", &key.color.x, ImGuiColorEditFlags_Float);
        changed |=
            ImGui::SliderFloat("Intensity", &key.intensity, 0.01f, 100.0f, "%.2f lux", ImGuiSliderFlags_Logarithmic);
        changed |= ImGui::Checkbox("Casts shadow", &key.castsShadow);
    } else {
        ImGui::TextDisabled("no directional light in the scene");
        if (ImGui::Button("Add a key light")) {
            sceneLights_.push_back(cli::defaultKeyLight());
            keyLight_ = static_cast<int>(sceneLights_.size()) - 1;
            changed = true;
        }
    }
    ImGui::Checkbox("Shadows", &settings_.shadows);
    ImGui::SliderFloat("Shadow softness", &settings_.shadowSoftnessTexels, 0.25f, 2.0f, "%.2f texels");
    tooltip("Gaussian sigma of the shadow filter in shadow-map texels; the penumbra LUT follows it");
    const uint32_t mapSizes[] = {512, 1024, 2048, 4096};
    const char* mapLabels[] = {"512", "1024", "2048", "4096"};
    int mapIndex = 2;
    for (int i = 0; i < 4; ++i)
        if (mapSizes[i] == settings_.shadowMapSize) mapIndex = i;
    if (ImGui::Combo("Shadow map", &mapIndex, mapLabels, 4)) settings_.shadowMapSize = mapSizes[mapIndex];

    changed |= panelAreaLights();

    ImGui::Separator();
    int scattered = static_cast<int>(scatteredLights_);
    if (ImGui::SliderInt("Clustered lights", &scattered, 0, 65536, "%d", ImGuiSliderFlags_Logarithmic)) {
        scatteredLights_ = static_cast<uint32_t>(std::max(scattered, 0));
        changed = true;
    }
    tooltip("Coloured point and spot lights scattered around the scene (preskin::scatterLights)");
    if (ImGui::SliderFloat("Lights per point", &scatterDensity_, 0.0f, 32.0f,
                           scatterDensity_ > 0.0f ? "%.1f" : "off")) {
        scatterDensity_ = std::clamp(scatterDensity_, 0.0f, 1000.0f);
        changed = true;
    }
    tooltip(
        "--light-density: the scattered lights' ranges shrink as their number grows, so that a point of the "
        "scene lies in about this many lights' volumes; off: ranges of the scene's size");
    int seed = static_cast<int>(scatterSeed_);
    if (ImGui::InputInt("Seed", &seed)) {
        scatterSeed_ = static_cast<uint32_t>(std::max(seed, 0));
        changed = true;
    }
    int loop = settings_.lightLoop == LightLoop::Clustered ? 0 : 1;
    ImGui::RadioButton("Clustered", &loop, 0);
    ImGui::SameLine();
    ImGui::RadioButton("Every light (brute force)", &loop, 1);
    settings_.lightLoop = loop == 0 ? LightLoop::Clustered : LightLoop::All;
    if (settings_.lightLoop == LightLoop::Clustered) {
        bool autoTile = settings_.clusters.tileSizePx == 0;
        if (ImGui::Checkbox("Tile size from the lights", &autoTile))
            settings_.clusters.tileSizePx = autoTile ? 0u : std::max(lastStats_.clusterTileSizePx, 4u);
        if (autoTile) {
            ImGui::TextDisabled("Tile size: %u px", lastStats_.clusterTileSizePx);
        } else {
            int tile = static_cast<int>(settings_.clusters.tileSizePx);
            if (ImGui::SliderInt("Tile size", &tile, 4, 256, "%d px")) settings_.clusters.tileSizePx = uint32_t(tile);
        }
        int slices = static_cast<int>(settings_.clusters.depthSlices);
        if (ImGui::SliderInt("Depth slices", &slices, 1, 64)) settings_.clusters.depthSlices = uint32_t(slices);
    }
    ImGui::TextDisabled("%u lights in the frame, %u clusters overflowed", lastStats_.lightCount,
                        lastStats_.clusterOverflows);
    if (lastStats_.clusterBuildCpuMs > 0.0)
        ImGui::TextDisabled("light grid build %.2f ms (cpu)", lastStats_.clusterBuildCpuMs);
    if (changed) applyLights();
}

// The scene's area lights (PRESKIN_lights_area): each one's size and intensity, a soft box to add,
// and whether their outlines show over the viewport. True when a light changed.
bool Viewer::panelAreaLights() {
    bool changed = false;
    ImGui::Separator();
    ImGui::Checkbox("Show area lights", &showLightGizmos_);
    tooltip("Outlines of the sphere, tube, rectangle and disc lights over the view (mono view)");
    ImGui::SameLine();
    if (ImGui::SmallButton("Add soft box")) {
        // A 1 m x 0.5 m rectangle at the upper right front, facing the scene's centre, about 3 lux there.
        const Bounds b = scene_.worldBounds();
        const float size = std::max(glm::length(b.max - b.min), 0.1f);
        const glm::vec3 towards = glm::normalize(glm::vec3(0.6f, 0.35f, 0.7f));
        Light box;
        box.name = "soft box";
        box.type = LightType::Rectangle;
        box.width = 1.0f;
        box.height = 0.5f;
        box.positionWs = b.center() + towards * (size + 0.5f);
        box.directionWs = -towards;
        box.axisWs = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), towards));
        box.intensity = 3.0f * (size + 0.5f) * (size + 0.5f);
        sceneLights_.push_back(box);
        changed = true;
    }
    static const char* const kShapes[] = {"sphere", "tube", "rectangle", "disc"};
    for (size_t i = 0; i < sceneLights_.size(); ++i) {
        Light& l = sceneLights_[i];
        if (l.type == LightType::Directional) {  // a sun: its angular radius
            float degrees = glm::degrees(l.angularRadius);
            ImGui::PushID(int(i));
            if (ImGui::SliderFloat("Sun radius", &degrees, 0.0f, 10.0f, "%.2f deg")) {
                l.angularRadius = glm::radians(std::clamp(degrees, 0.0f, 45.0f));
                changed = true;
            }
            tooltip(
                "--sun-radius: the directional light's angular radius (the sun's is 0.27 degrees): its shadow's "
                "penumbra widens with the occluder's distance");
            ImGui::PopID();
            continue;
        }
        if (!isAreaLight(l.type)) continue;
        const int shape = int(l.type) - int(LightType::Sphere);
        ImGui::PushID(int(i));
        if (ImGui::TreeNode("area", "%s (%s)", l.name.empty() ? "(unnamed)" : l.name.c_str(), kShapes[shape])) {
            const float lo = 0.001f, hi = 10.0f;
            const ImGuiSliderFlags log = ImGuiSliderFlags_Logarithmic;
            if (l.type == LightType::Rectangle) {
                changed |= ImGui::SliderFloat("Width", &l.width, lo, hi, "%.3f m", log);
                changed |= ImGui::SliderFloat("Height", &l.height, lo, hi, "%.3f m", log);
            } else {
                changed |= ImGui::SliderFloat("Radius", &l.radius, lo, hi, "%.3f m", log);
            }
            if (l.type == LightType::Tube) changed |= ImGui::SliderFloat("Length", &l.length, lo, hi, "%.3f m", log);
            changed |= ImGui::SliderFloat("Intensity##area", &l.intensity, 0.01f, 1000.0f, "%.2f cd", log);
            changed |= ImGui::ColorEdit3("Colour##area", &l.color.x, ImGuiColorEditFlags_Float);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    return changed;
}

void Viewer::panelDebug() {
    if (!ImGui::CollapsingHeader("Debug view", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const char* views[] = {"None (final image)",
                           "Curvature",
                           "Normals (per channel)",
                           "Shadow",
                           "Penumbra",
                           "Cluster heat map (lights per pixel)",
                           "SH ambient alone",
                           "Transmission"};
    int view = static_cast<int>(settings_.debugView);
    if (ImGui::Combo("Show", &view, views, static_cast<int>(std::size(views))))
        settings_.debugView = static_cast<DebugView>(view);
}

void Viewer::panelShaders() {
    if (!ImGui::CollapsingHeader("Shader hot reload")) return;
    if (!shaders_->enabled()) {
        ImGui::TextWrapped("Off: %s does not exist. Set PRESKIN_DATA_DIR to a preskin source tree.",
                           shaders_->directory().string().c_str());
        return;
    }
    ImGui::TextWrapped("Shaders from %s", shaders_->directory().string().c_str());
    bool watching = shaders_->watching();
    if (ImGui::Checkbox("Reload when files change", &watching)) shaders_->setWatching(watching);
    if (ImGui::Button("Reload now (F5)")) shaders_->requestBuild();
    ImGui::SameLine();
    ImGui::BeginDisabled(shaderOverrides_.empty());
    if (ImGui::Button("Use built-in shaders")) {
        try {
            if (renderer_) renderer_->setShaderOverrides({});
            shaderOverrides_.clear();
            shaderLog_.clear();
            shaderLogIsError_ = false;
            info("built-in shaders restored");
        } catch (const std::exception& e) {
            error(fmt::format("built-in shaders: {}", e.what()));
        }
    }
    ImGui::EndDisabled();
    if (shaders_->compiling()) ImGui::TextColored(kWarnColor, "compiling...");
    ImGui::TextDisabled("%s",
                        shaderOverrides_.empty()
                            ? "running the built-in shaders"
                            : fmt::format("running reloaded shaders ({} stages)", shaderOverrides_.size()).c_str());
    if (!shaderLog_.empty()) {
        ImGui::BeginChild("shaderlog", ImVec2(0.0f, 160.0f), true, ImGuiWindowFlags_HorizontalScrollbar);
        if (shaderLogIsError_) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextUnformatted(shaderLog_.c_str());
        if (shaderLogIsError_) ImGui::PopStyleColor();
        ImGui::EndChild();
    }
}

void Viewer::panelTiming() {
    ImGui::Text("%s", context_->deviceName().c_str());
    ImGui::TextDisabled("%ux%u, %s", swapchain_->extent().width, swapchain_->extent().height,
                        presentModeName(swapchain_->presentMode()));
    bool vsync = vsync_;
    ImGui::BeginDisabled(!swapchain_->canDisableVsync());
    if (ImGui::Checkbox("Vsync (V)", &vsync)) {
        vsync_ = vsync;
        swapchainDirty_ = true;
    }
    ImGui::EndDisabled();

    double interval = 0.0, cpu = 0.0, wait = 0.0, present = 0.0;
    size_t n = 0;
    for (auto it = timings_.rbegin(); it != timings_.rend() && n < 30; ++it) {
        if (it->intervalMs <= 0.0) continue;
        interval += it->intervalMs;
        cpu += it->cpuMs;
        wait += it->waitMs;
        present += it->presentMs;
        ++n;
    }
    if (n > 0) {
        const double scale = 1.0 / double(n);
        ImGui::Text("Frame %.2f ms (%.1f fps), mean of %zu", interval * scale,
                    interval > 0.0 ? 1000.0 / (interval * scale) : 0.0, n);
        ImGui::Text("CPU %.2f ms (panels %.2f ms)", cpu * scale, uiMs_);
        tooltip("Building the panels, recording the renderer and the overlay, submitting");
        ImGui::Text("Waiting: frame slot %.2f ms, present %.2f ms", wait * scale, present * scale);
        tooltip(
            "For the frame two back to finish and a swapchain image; in vkQueuePresentKHR "
            "(software drivers finish the frame there)");
    }
    if (lastStats_.passes.empty()) {
        ImGui::TextDisabled("GPU timestamps unavailable");
    } else {
        ImGui::Text("GPU %.2f ms (timestamps)", lastStats_.gpuMs);
        for (const PassTime& p : lastStats_.passes) ImGui::BulletText("%s %.2f ms", p.name.c_str(), p.gpuMs);
    }
    if (lastStats_.eyes > 0)
        ImGui::TextDisabled("%u eye(s), %s, MSAA %ux", lastStats_.eyes,
                            lastStats_.eyeDrawing == EyeDrawing::InstancedLayers ? "instanced layers" : "multiview",
                            settings_.msaaSamples);
    std::vector<float> history;
    float highest = 1.0f;
    for (const Timing& t : timings_) {
        history.push_back(static_cast<float>(t.intervalMs));
        highest = std::max(highest, static_cast<float>(t.intervalMs));
    }
    if (!history.empty())
        ImGui::PlotLines("##frames", history.data(), static_cast<int>(history.size()), 0, "frame ms", 0.0f,
                         highest * 1.2f, ImVec2(320.0f, 60.0f));
    if (ImGui::Button("Screenshot (F12)")) requestScreenshot(std::nullopt, screenshotWithUi_);
    ImGui::SameLine();
    ImGui::Checkbox("with panels", &screenshotWithUi_);
}

void Viewer::panelMessages() {
    if (ImGui::SmallButton("Clear")) messages_.clear();
    ImGui::BeginChild("messages", ImVec2(0.0f, 0.0f), false);
    for (const Message& m : messages_) {
        if (m.error) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextWrapped("[%.1f s] %s", m.timeS, m.text.c_str());
        if (m.error) ImGui::PopStyleColor();
    }
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
}

void Viewer::statusBar() {
    std::vector<std::pair<std::string, bool>> lines;  // text, is error
    if (sceneJob_.valid()) lines.emplace_back("loading scene...", false);
    if (environmentJob_.valid()) lines.emplace_back("loading environment...", false);
    if (baker_.busy()) lines.emplace_back(fmt::format("baking LUTs {:.0f}%", baker_.progress() * 100.0), false);
    if (shaders_->compiling()) lines.emplace_back("compiling shaders...", false);
    if (shaderLogIsError_)
        lines.emplace_back("shader error: the last good pipelines are running (see Shader hot reload)", true);
    const double nowS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!messages_.empty() && messages_.back().error && nowS - messages_.back().timeS < 8.0)
        lines.emplace_back(messages_.back().text, true);
    if (lines.empty()) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y - 10.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(display.x * 0.6f, display.y * 0.3f));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
        ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
        ImGuiWindowFlags_NoSavedSettings;
    if (ImGui::Begin("##status", nullptr, flags)) {
        ImGui::PushTextWrapPos(display.x * 0.55f);
        for (const auto& [text, isError] : lines) {
            if (isError)
                ImGui::TextColored(kErrorColor, "%s", text.c_str());
            else
                ImGui::TextUnformatted(text.c_str());
        }
        ImGui::PopTextWrapPos();
    }
    ImGui::End();
}

}  // namespace preskin::viewer
