// An animated scene rendered at a time equals the render of a static glTF holding the deformed
// mesh, written here from the CPU deformation (deformPrimitive): same materials (made skin, so
// curvature matters), lights, environment and view; golden tolerance (at most 0.1 % of pixels
// more than 5/255 apart). The animated render deforms on the GPU and recomputes curvature there;
// the static file's curvature comes from the loader's CPU estimator.
// Scenes: the skinned tube at several times of its bend, and the animated head (morph targets
// and a neck joint) when the sample is present.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"

#include <preskin/Deformation.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <unistd.h>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

// Appends `bytes` to the model's only buffer (4-byte aligned) and returns a view of them.
int addView(tinygltf::Model& model, const void* bytes, size_t size, int target) {
    std::vector<unsigned char>& data = model.buffers[0].data;
    while (data.size() % 4) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    data.insert(data.end(), static_cast<const unsigned char*>(bytes), static_cast<const unsigned char*>(bytes) + size);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& model, int view, int componentType, int type, size_t count) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

// A static glTF of every instance of `scene` deformed in `pose` on the CPU: skinned instances in
// world space, others in object space under their pose transform. Materials are plain (their
// parameters are copied onto the loaded scene by the test).
void writeStaticGltf(const fs::path& path, const Scene& scene, const ScenePose& pose) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.buffers.resize(1);
    model.scenes.resize(1);
    model.defaultScene = 0;
    for (size_t m = 0; m < scene.materials.size(); ++m) model.materials.emplace_back().name = scene.materials[m].name;
    std::vector<Vertex> deformed;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& inst = scene.instances[i];
        if (inst.mesh < 0) continue;
        tinygltf::Mesh mesh;
        for (const Primitive& p : scene.meshes[size_t(inst.mesh)].primitives) {
            deformPrimitive(p, pose.instances[i], deformed);
            std::vector<glm::vec3> positions, normals;
            std::vector<glm::vec4> tangents;
            std::vector<glm::vec2> uvs;
            glm::vec3 lo(1e30f), hi(-1e30f);
            for (const Vertex& v : deformed) {
                positions.push_back(v.positionOs);
                normals.push_back(v.normalOs);
                tangents.push_back(v.tangentOs);
                uvs.push_back(v.uv0);
                lo = glm::min(lo, v.positionOs);
                hi = glm::max(hi, v.positionOs);
            }
            tinygltf::Primitive prim;
            const size_t n = positions.size();
            const int pos = addAccessor(model, addView(model, positions.data(), n * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
                                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
            model.accessors[size_t(pos)].minValues = {lo.x, lo.y, lo.z};
            model.accessors[size_t(pos)].maxValues = {hi.x, hi.y, hi.z};
            prim.attributes["POSITION"] = pos;
            prim.attributes["NORMAL"] =
                addAccessor(model, addView(model, normals.data(), n * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
            prim.attributes["TANGENT"] =
                addAccessor(model, addView(model, tangents.data(), n * 16, TINYGLTF_TARGET_ARRAY_BUFFER),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n);
            prim.attributes["TEXCOORD_0"] =
                addAccessor(model, addView(model, uvs.data(), n * 8, TINYGLTF_TARGET_ARRAY_BUFFER),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
            prim.indices = addAccessor(
                model, addView(model, p.indices.data(), p.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, p.indices.size());
            prim.material = p.material;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            mesh.primitives.push_back(prim);
        }
        model.meshes.push_back(mesh);
        tinygltf::Node node;
        node.mesh = int(model.meshes.size()) - 1;
        const bool skinned = inst.skin >= 0;
        const glm::dmat4 m(skinned ? glm::mat4(1.0f) : pose.instances[i].worldFromObject);
        node.matrix.assign(glm::value_ptr(m), glm::value_ptr(m) + 16);
        model.nodes.push_back(node);
        model.scenes[0].nodes.push_back(int(model.nodes.size()) - 1);
    }
    model.buffers[0].uri = path.stem().string() + ".bin";
    tinygltf::TinyGLTF writer;
    ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), false, false, true, false));
}

// Textures off (the static file carries none), every material skin.
void prepare(Scene& scene) {
    for (Material& m : scene.materials) {
        m.baseColor = m.metallicRoughness = m.normal = m.occlusion = m.emissive = TextureRef{};
        if (m.skin) m.skin->specularTexture = m.skin->detailNormalTexture = m.skin->curvatureTexture = SkinTextureRef{};
    }
    scene.images.clear();
    scene.makeSkin("all");
}

class AnimationRender : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        dir_ = fs::temp_directory_path() / ("preskin_anim_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
        GpuTest::TearDown();
    }

    void expectStaticEqualsAnimated(const fs::path& file, const std::string& animationName,
                                    const std::vector<float>& times) {
        Scene animated = Scene::load(file);
        prepare(animated);
        const Animation& animation = findAnimation(animated, animationName);
        const std::vector<Light> lights = {[] {
            Light key;
            key.directionWs = glm::normalize(glm::vec3(0.4f, -0.5f, -0.7f));
            key.intensity = 3.0f;
            key.castsShadow = true;
            return key;
        }()};
        const Environment env = Environment::constant(glm::vec3(0.2f));
        const View view = frameBoundsView(animated.worldBounds(), 1.0f);
        Renderer renderer(context(), animated, env, nullptr);
        renderer.setLights(lights);
        for (float t : times) {
            const ScenePose pose = posedScene(animated, animationNodePose(animated, animation, t));
            renderer.setPose(pose);
            const RenderedImage moving = renderer.render(view, 128, 128, OutputEncoding::DisplaySrgb8);

            const fs::path staticFile = dir_ / ("static_" + std::to_string(int(t * 1000)) + ".gltf");
            writeStaticGltf(staticFile, animated, pose);
            Scene still = Scene::load(staticFile);
            for (size_t m = 0; m < still.materials.size(); ++m) still.materials[m] = animated.materials[m];
            prepare(still);
            Renderer stillRenderer(context(), still, env, nullptr);
            stillRenderer.setLights(lights);
            const RenderedImage reference = stillRenderer.render(view, 128, 128, OutputEncoding::DisplaySrgb8);
            dumpImage("animated_" + file.stem().string() + "_" + std::to_string(int(t * 1000)), moving);

            size_t differing = 0, covered = 0;
            for (size_t i = 0; i < moving.rgba8.size(); i += 4) {
                int d = 0;
                for (int c = 0; c < 3; ++c)
                    d = std::max(d, std::abs(int(moving.rgba8[i + size_t(c)]) - int(reference.rgba8[i + size_t(c)])));
                differing += d > 5;
                covered += moving.rgba8[i] != moving.rgba8[0];
            }
            EXPECT_GT(covered, 400u) << file << " at t = " << t << ": the mesh should be in the picture";
            EXPECT_LE(differing, moving.rgba8.size() / 4 / 1000) << file << " at t = " << t;
        }
    }

    fs::path dir_;
};

TEST_F(AnimationRender, TubeAtTimeEqualsStaticDeformedTube) {
    expectStaticEqualsAnimated(fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/tube/tube.gltf", "bend",
                               {0.0f, 0.6f, 1.0f});
}

TEST_F(AnimationRender, AnimatedHeadAtTimeEqualsStaticDeformedHead) {
    const fs::path head = fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head_animated.gltf";
    if (!fs::exists(head)) GTEST_SKIP() << head << " is not in this tree";
    const Scene scene = Scene::load(head);
    ASSERT_FALSE(scene.animations.empty());
    const Animation& animation = scene.animations[0];
    expectStaticEqualsAnimated(head, "0",
                               {animation.startS(), 0.5f * (animation.startS() + animation.endS()), animation.endS()});
}

}  // namespace
}  // namespace preskin::test
