// Distant lighting from an HDR environment, as 9 RGB spherical-harmonic coefficients (L2).
// Projection and evaluation follow Ramamoorthi & Hanrahan, "An Efficient Representation for
// Irradiance Environment Maps" (SIGGRAPH 2001): real SH basis with their constants; irradiance
// is radiance convolved with Lambert's zonal kernel A_l = (pi, 2pi/3, pi/4).
// Equirectangular convention: image column u in [0,1) is longitude phi = 2 pi (u - 0.5) measured
// from +X towards +Z; row v in [0,1] is the polar angle theta = pi v from +Y (up). Hence
// direction = (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)).
#pragma once

#include <preskin/Export.h>

#include <preskin/Glm.h>

#include <shared/constants.h>  // pi and the SH constants, shared with GLSL

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace preskin {

struct ShRgb {
    std::array<glm::vec3, 9> c{};  // index l*l + l + m: (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2)
};

// The 9 real SH basis functions at a unit direction.
PRESKIN_API std::array<float, 9> shBasis(const glm::vec3& direction);
// Sum of c_lm * Y_lm(direction), each band scaled by bandScale[l] (1,1,1: the function itself;
// Lambert's (pi, 2pi/3, pi/4): irradiance).
PRESKIN_API glm::vec3 evaluateSh(const ShRgb& sh, const glm::vec3& direction,
                                 const glm::vec3& bandScale = glm::vec3(1.0f));
inline constexpr float kPi = gpu::kPi;
inline const glm::vec3 kLambertBands{gpu::kShLambert0, gpu::kShLambert1, gpu::kShLambert2};

// Linear RGB equirectangular image.
struct EquirectImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgb;  // width * height * 3, top row first

    glm::vec3 texel(uint32_t x, uint32_t y) const {
        const size_t i = (size_t(y) * width + x) * 3;
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
    static glm::vec3 directionAt(float u, float v);
};

// The image box-filtered by powers of two until it is at most maxWidth texels wide (each texel
// the mean of the source texels it covers, so radiance is kept); the image itself when narrower.
PRESKIN_API EquirectImage boxFiltered(const EquirectImage& image, uint32_t maxWidth);

// Projects radiance onto SH by integrating over every texel with its exact solid angle. The
// image is turned by rotationY radians about +Y first (right-handed: +Z turns towards +X).
PRESKIN_API ShRgb projectEquirect(const EquirectImage& image, float rotationY = 0.0f);
// Direction d of the image turned by rotationY radians about +Y.
PRESKIN_API glm::vec3 rotateY(const glm::vec3& d, float rotationY);

// One of the environment's dominant lights (extractEnvironmentLights): a directional light that
// carries the radiance of the texels it was cut from.
struct EnvironmentLight {
    glm::vec3 directionWs{0.0f, -1.0f, 0.0f};  // the direction the light travels (world, rotation applied)
    glm::vec3 irradiance{0.0f};  // at normal incidence: the integral of its texels' radiance over their solid angle
    float solidAngleSr = 0.0f;   // of its texels
    // The angular radius of the disc with its texels' spread about its direction: sqrt(2 <theta^2>),
    // theta the angle from the direction, weighted by luminance and solid angle (a uniform disc of
    // radius sigma has <theta^2> = sigma^2 / 2 when small); at most pi/4. Light::angularRadius.
    float angularRadius = 0.0f;
};

// The environment's dominant lights and what is left for the L2 SH ambient.
struct EnvironmentLights {
    std::vector<EnvironmentLight> lights;  // strongest (luminance of irradiance) first
    ShRgb residualSh;                      // radianceSh() less the projection of every light's texels
    // The image the search ran on (at most 1024 texels wide, box-filtered) less every light's
    // texels: what specular reflection of the environment shows (empty for constant environments).
    EquirectImage residualImage;
};

class Environment;
// Up to `count` (at most kMaxEnvironmentLights) dominant lights of the environment, found by
// median cut (Debevec 2005, "A Median Cut Algorithm for Light Probe Sampling"): the image (at
// most 1024 texels wide) is split into 64 regions of equal luminous energy on a solid-angle
// weighted summed-area table; the densest region seeds a light if its mean radiance is at least
// 4 times the environment's; the light grows from that region's brightest texel over connected
// texels at least a tenth as bright, brightest first, up to 0.25 sr, and those texels leave the
// image before the next light is sought. Fewer lights come back when no concentration is left
// (a constant or smooth environment gives none). Every light's texels are removed from the SH,
// so a light and the ambient never count the same radiance twice.
PRESKIN_API EnvironmentLights extractEnvironmentLights(const Environment& environment, uint32_t count);
inline constexpr uint32_t kMaxEnvironmentLights = 16;

class PRESKIN_API Environment {
public:
    // Reads an equirectangular Radiance .hdr or OpenEXR file (recognised by its content) of at
    // most 8192x4096 (<preskin/Limits.h>): Radiance in the core library, OpenEXR through a
    // registered codec (the image component preskin::imageio, <preskin/ImageCodec.h>); throws preskin::Error naming the file on a missing,
    // unreadable, oversized or non-2:1 image, or a pixel or argument that the input-number rule
    // refuses (not finite, or beyond 1e6 in magnitude).
    static Environment load(const std::filesystem::path& path, float intensity = 1.0f, float rotationY = 0.0f);
    // The same from the file's content in memory (a scene's data URI: Scene::environmentData);
    // `label` names it in messages.
    static Environment load(std::span<const uint8_t> bytes, const std::string& label, float intensity = 1.0f,
                            float rotationY = 0.0f);
    // An image the host decoded itself (linear RGB radiance, width twice the height), turned by
    // rotationY; throws preskin::Error on a size or texel load() would refuse.
    static Environment fromImage(EquirectImage image, float rotationY = 0.0f);
    // Uniform radiance in every direction.
    static Environment constant(const glm::vec3& radiance);
    // The same environment (its SH, intensity and rotation unchanged) holding its image
    // box-filtered to at most maxWidth texels wide (boxFiltered): what a renderer keeps.
    Environment downsampled(uint32_t maxWidth) const;

    const ShRgb& radianceSh() const { return radianceSh_; }
    // The decoded image (empty for constant environments); kept for CPU references.
    const EquirectImage& image() const { return image_; }
    float intensity() const { return intensity_; }
    // The turn about +Y the image was loaded with (radians; 0 for constant environments).
    float rotationY() const { return rotationY_; }
    // What load() accepted but the host should hear of: texels of negative radiance (a lossy
    // encoding's small undershoot is not reported), taken as 0.
    const std::vector<std::string>& warnings() const { return warnings_; }
    // Radiance arriving from world direction `directionWs` (unit): the image's texel there
    // (nearest, intensity applied, turned by rotationY), or the constant.
    glm::vec3 radiance(const glm::vec3& directionWs) const;

private:
    ShRgb radianceSh_;
    EquirectImage image_;
    float intensity_ = 1.0f;
    float rotationY_ = 0.0f;
    glm::vec3 constant_{0.0f};
    std::vector<std::string> warnings_;
};

}  // namespace preskin
