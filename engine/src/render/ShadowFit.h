// Fitting the directional shadow map: an orthographic light matrix whose image covers the shadow
// receivers in view (the skin: its bounds in the current pose, cut by the frusta of the view's
// eyes), so its texels are as small
// as the visible skin allows, while its depth range holds every caster (the scene's bounding
// sphere along the light). Skin's penumbra LUT then owns the softening of shadow edges instead
// of wide shadow-map texels (a 2048 map over a whole bust has 0.3 mm texels; over the face in
// view about half that).
// Limits: one map, no cascades: receivers far apart in view share the texels; the image is
// square (the larger of the two extents) and its centre snaps to whole texels (a moving camera
// does not make edges crawl, a moving fit still changes texel size); casters outside the
// scene's bounds do not exist.
#pragma once

#include <preskin/Scene.h>
#include <preskin/View.h>

#include "render/PoseBounds.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace preskin {

struct ShadowFit {
    glm::mat4 clipFromWorld{1.0f};  // orthographic, x and y in [-1, 1], depth 0 (near) .. 1 (far)
    float texelSizeM = 0.0f;        // one texel's width on the light's image plane
    float depthRangeM = 0.0f;       // the depth range's length along the light
};

// The posed world bounds of every skin primitive of the scene (empty without skin).
PoseBounds skinReceiverBounds(const Scene& scene);

// The light travels along `direction`. Receivers: where shadows matter (skinReceiverBounds);
// when they are empty or out of every eye's view, the image covers the casters' bounding sphere, as does the
// depth range always. A margin of 8 texels keeps the shadow filter's footprint inside the image.
ShadowFit fitDirectionalShadow(const Bounds& casters, const Bounds& receivers, const View& view,
                               const glm::vec3& direction, uint32_t mapSize);

}  // namespace preskin
