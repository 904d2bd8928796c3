// preskin/shadow.glsl: directional shadow map filtered by hand with a Gaussian PCF kernel.
// Lavapipe cannot filter depth formats (no LINEAR compare sampler), so 4x4 gathers fetch the
// 8x8 texels around the sample point (textureGather, no filtering), each is compared with the
// receiver's depth, and the results are summed with Gaussian weights of the texel centres'
// distances to the exact sample point. The weights are separable; the kernel's variance is
// sigma^2 + 1/6 texels^2 (the requested sigma widened like a bilinear tap's tent, so the
// smallest sigma still blends neighbouring texels) and it is windowed to zero at 4 texels,
// where texels enter and leave the footprint: the result varies continuously and smoothly with
// the position (no texel blocks, no plateaus between taps). Receiver-plane depth bias (Isidoro,
// "Shadow Mapping: GPU-based Tips and Techniques", GDC 2006) tilts the compared depth per texel
// along the surface so wide kernels do not self-shadow sloped receivers. Also gives what skin
// needs: the filter's width in world units (penumbra LUT), the standard deviation of the weights
// actually used, and the occluder's distance and slope (transmission, preskinShadowOccluder).
// Lights with a size get penumbrae that widen with the occluder's distance (below).
// Limits: one orthographic map (no cascades); a wide penumbra's kernel samples one texel in s x s
// (occluders thinner than s texels can flicker through it); the window narrows wide
// kernels (the reported width is that of the weights used: sigma 1 gives 1.07 texels, 1.5 gives
// 1.41, 2 gives 1.58), and the shadow map quantises an edge's position to its texels.
#ifndef PRESKIN_SHADOW_GLSL
#define PRESKIN_SHADOW_GLSL

#include "preskin/common.glsl"

struct PreskinShadowSample {
    float visibility;     // filtered, 0 (shadowed) .. 1 (lit)
    float kernelWidthM;   // standard deviation of the filter on the light's image plane, metres
    float penumbraWidthM; // of that, the light's own penumbra (a light with a size; 0 for a parallel light)
    float blockerDistanceM; // along the light from the filter's occluding texels (weighted mean) to the receiver; 0: none
    vec3 gradientWs;      // the visibility's gradient in the light's image plane (per metre, world space): across
                          // the shadow's edge towards its lit side, 0 where the filter sees no edge
};

// Where the light enters the body that shadows positionWs: the nearest occluder in the map.
struct PreskinShadowOccluder {
    float distanceM;  // along the light from that surface to the receiver, metres (0 outside the map)
    float cosine;     // its normal's cosine to the light (1 outside the map)
    vec2 slope;       // its depth's slope along the map's axes, metres of depth per metre
    vec2 uv;          // where the receiver falls on the map
    float depth;      // the receiver's depth on the map
};

// How far the shadow pass's slope bias moved a surface of depth slope `slope` (metres per metre)
// away from the light, metres.
float preskinShadowSlopeBiasM(vec2 slope, vec4 params) {
    return kShadowDepthBiasSlope * max(abs(slope.x), abs(slope.y)) * params.x;
}

// The occluder of positionWs: its distance from the map's depth (the shadow pass's slope bias,
// kShadowDepthBiasSlope times the depth's slope per texel, added back), its cosine from the
// depth's differences to the neighbouring texels.
PreskinShadowOccluder preskinShadowOccluder(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                            vec3 positionWs) {
    vec4 clip = shadowClipFromWorld * vec4(positionWs, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return PreskinShadowOccluder(0.0, 1.0, vec2(0.0), uv, clip.z);
    // Two gathers: the texel with the ones right and up of it, and with the ones left and down
    // (gather order: (0, 1), (1, 1), (1, 0), (0, 0) of the 2 x 2 quad; clamped at the map's edge).
    vec2 texelF = floor(uv * params.w);
    vec4 upRight = textureGather(shadowMap, (texelF + 1.0) / params.w, 0);
    vec4 downLeft = textureGather(shadowMap, texelF / params.w, 0);
    float z = upRight.w;
    float right = upRight.z, up = upRight.x, left = downLeft.x, down = downLeft.z;
    // Per axis the flatter one-sided difference: across the occluder's outline one side is another surface.
    vec2 dz = vec2(abs(right - z) < abs(z - left) ? right - z : z - left, abs(up - z) < abs(z - down) ? up - z : z - down);
    vec2 slope = dz * params.z / params.x;  // metres of depth per metre
    return PreskinShadowOccluder(max(clip.z - z, 0.0) * params.z + preskinShadowSlopeBiasM(slope, params),
                                 inversesqrt(1.0 + dot(slope, slope)), slope, uv, clip.z);
}

// Where a receiver falls on the map: its point moved along its normal, and its plane's depth per
// texel. Normal offset: a quarter texel along the normal, growing to 1.75 texels only where the
// light grazes (cos < 0.25). An offset along the normal moves the lookup across the map by its
// component perpendicular to the light, which at grazing light puts cast-shadow edges off their
// place: against the ray-traced reference on the head, growing it over the whole hemisphere
// shrank the nose's shadow on the cheek by about a millimetre (green RMSE 0.0038 against 0.0031
// at 1024x1024). The receiver plane's depth step per texel (Isidoro's receiver-plane bias) is
// clamped to 0.02 times texelScale (the map's texels per shadow-map texel side).
struct PreskinShadowReceiver {
    vec2 uv;          // on the map
    float z;          // the receiver's depth on the map
    vec2 dzPerTexel;  // its plane's depth step per texel along the map's axes
    bool inside;      // within the map (outside: lit)
};

// One texel of a map of mapSize texels a side: the first of the gather at its upper-right corner,
// the same value as texelFetch, which a CPU driver (lavapipe) fetches lane by lane at about three
// times a gather's cost (the four texels of the occluder's coverage were 2.4 % of the head's skin
// frame as texelFetch, 1.6 % as gathers).
float preskinShadowTexel(sampler2D shadowMap, ivec2 texel, float mapSize) {
    return textureGather(shadowMap, (vec2(texel) + 1.0) / mapSize, 0).w;
}

// Whether a point at uv and depth z on the map lies within it.
bool preskinShadowInside(vec2 uv, float z) {
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && z <= 1.0;
}

PreskinShadowReceiver preskinShadowReceiver(mat4 shadowClipFromWorld, vec4 params, vec3 positionWs, vec3 normalWs,
                                            float texelScale) {
    vec3 r0 = vec3(shadowClipFromWorld[0][0], shadowClipFromWorld[1][0], shadowClipFromWorld[2][0]);
    vec3 r1 = vec3(shadowClipFromWorld[0][1], shadowClipFromWorld[1][1], shadowClipFromWorld[2][1]);
    vec3 r2 = vec3(shadowClipFromWorld[0][2], shadowClipFromWorld[1][2], shadowClipFromWorld[2][2]);
    float cosTheta = abs(dot(normalWs, normalize(r2)));
    vec3 offsetWs = normalWs * params.x * (0.25 + 1.5 * smoothstep(0.25, 0.0, cosTheta));
    vec4 clip = shadowClipFromWorld * vec4(positionWs + offsetWs, 1.0);
    PreskinShadowReceiver r;
    r.uv = clip.xy * 0.5 + 0.5;
    r.z = clip.z;
    float n0 = dot(normalWs, r0) / dot(r0, r0);
    float n1 = dot(normalWs, r1) / dot(r1, r1);
    float n2 = dot(normalWs, r2) / dot(r2, r2);
    n2 = sign(n2) * max(abs(n2), 1e-4 * (abs(n0) + abs(n1)) + 1e-12);
    r.dzPerTexel = clamp(-vec2(n0, n1) / n2 * (2.0 / params.w), vec2(-0.02 * texelScale), vec2(0.02 * texelScale));
    r.inside = preskinShadowInside(r.uv, r.z);
    return r;
}

// Visibility alone from the 2 x 2 texels around the receiver r (one gather), bilinear. For a
// lookup that needs no edge, width or occluder (one texel's blur is all it is meant to have).
float preskinShadowVisibility2x2(sampler2D shadowMap, vec4 params, PreskinShadowReceiver r) {
    if (!r.inside) return 1.0;
    vec2 t = r.uv * params.w - 0.5;
    vec2 first = floor(t);
    vec2 f = t - first;
    vec4 occluder = textureGather(shadowMap, (first + 1.0) / params.w, 0);  // (0,1), (1,1), (1,0), (0,0)
    float z = r.z - 2e-4;
    vec4 receiver = z + r.dzPerTexel.x * (vec4(0.0, 1.0, 1.0, 0.0) - f.x) + r.dzPerTexel.y * (vec4(1.0, 1.0, 0.0, 0.0) - f.y);
    vec4 lit = vec4(greaterThanEqual(occluder, receiver));
    return mix(mix(lit.w, lit.z, f.x), mix(lit.x, lit.y, f.x), f.y);
}

// The receiver plane's depth slope along the map's axes (metres per metre) for its normal and the
// direction L towards the light.
vec2 preskinShadowReceiverSlope(mat4 shadowClipFromWorld, vec3 normal, vec3 L) {
    vec3 mapU = normalize(vec3(shadowClipFromWorld[0][0], shadowClipFromWorld[1][0], shadowClipFromWorld[2][0]));
    vec3 mapV = normalize(vec3(shadowClipFromWorld[0][1], shadowClipFromWorld[1][1], shadowClipFromWorld[2][1]));
    float NoL = dot(normal, L);
    return vec2(dot(normal, mapU), dot(normal, mapV)) / (NoL < 0.0 ? min(NoL, -0.05) : max(NoL, 0.05));
}

// How much of the occluder's tangent plane (o, its distanceM from the receiver) is there around
// the plane's point nearest the receiver, within radiusM: of four taps on the map there (along
// its axes), the share whose depth lies nearer the occluder's plane than the receiver's
// (receiverSlope, preskinShadowReceiverSlope). Near an occluder's outline the plane goes on where
// the occluder does not; a curved occluder stays counted while it is nearer its own plane.
float preskinOccluderCoverage(sampler2D shadowMap, vec4 params, PreskinShadowOccluder o, vec2 receiverSlope,
                              float radiusM) {
    float norm2 = 1.0 + dot(o.slope, o.slope);
    vec2 footM = o.distanceM * o.slope / norm2;  // the nearest point, metres along the map's axes
    float receiverM = o.depth * params.z;
    float occluderM = receiverM - o.distanceM;
    float metresPerUv = params.w * params.x;
    ivec2 last = ivec2(params.w) - 1;
    float on = 0.0;
    const vec2 taps[4] = vec2[4](vec2(1.0, 0.0), vec2(-1.0, 0.0), vec2(0.0, 1.0), vec2(0.0, -1.0));
    for (int k = 0; k < 4; ++k) {
        vec2 tapM = footM + radiusM * taps[k];
        vec2 uv = o.uv + tapM / metresPerUv;
        ivec2 texel = clamp(ivec2(uv * params.w), ivec2(0), last);
        float mapM = preskinShadowTexel(shadowMap, texel, params.w) * params.z;
        float midM = 0.5 * (occluderM + dot(o.slope, tapM) + receiverM + dot(receiverSlope, tapM));
        on += mapM < midM ? 1.0 : 0.0;
    }
    return 0.25 * on;
}

// How a map is filtered: the Gaussian PCF below on a shadow map, or on a coarser map whose texels
// hold whole blocks of one (shaders/shadow_reduce.comp).
struct PreskinShadowFilter {
    int gathersPerAxis;     // the footprint, 2 x gathersPerAxis texels on a side, the window at
                            // gathersPerAxis texels (4: 8 x 8 texels by 16 gathers, for sigma up to 2;
                            // 3: 6 x 6 by 9, up to 1.2; 2: 4 x 4 by 4, up to 0.8)
    float slopeBiasTexels;  // extra depth bias, in texels of the receiver plane's slope (a map of each
                            // block's nearest depth holds a sloped receiver that much nearer than its plane)
    float riseM;            // how far (m) the receiver rises towards the light above its plane within the
                            // kernel (a concave receiver's own walls)
    float texelScale;       // the map's texels per shadow-map texel side: the receiver plane's depth step
                            // per texel is clamped to 0.02 times it (the same steepest slope on any map)
};

// The filter of a shadow map: 8 x 8 texels, no extra bias.
const PreskinShadowFilter kPreskinShadowMapFilter = PreskinShadowFilter(4, 0.0, 0.0, 1.0);

// The windowed Gaussian percentage-closer sum of the header over 2G x 2G texels around texel
// coordinate t (texel i's centre at t = i), comparing z - bias tilted by dzPerTexel, and the
// occluding texels' weighted mean depth. At stride 1 the texels are floor(t) - G + 1 ..
// floor(t) + G, G x G gathers, windowed at G texels. At stride s > 1 they are the texels nearest
// the points of a square lattice of spacing s turned by atan(2/5), anchored to the map, weighted
// by the points' own offsets along the lattice's axes, windowed at s (G - 1/2) (a point enters
// and leaves the footprint at weight 0): a wide kernel costs no more lookups, and since the
// lattice's rows lie along no axis or diagonal, an edge's position is resolved to a fifth of s or
// better, not s.
struct PreskinShadowPcf {
    float visibility;
    float varianceTexels;  // the weights' variance (mean of the two axes), texels^2
    float blockerDepth;    // the occluding texels' weighted mean depth (map units); z where none
    float blockerWeight;   // their share of the weights
    vec2 gradient;         // sum of weight x (lit - visibility) x offset over the weights: the visibility's
                           // gradient direction in texels (towards the lit side), 0 without an edge
};

PreskinShadowPcf preskinShadowPcf(sampler2D shadowMap, vec2 t, float mapSize, float z, float bias, vec2 dzPerTexel,
                                  int G, float stride, float sigma) {
    float twoVariance = 2.0 * (sigma * sigma + 1.0 / 6.0);
    float sum = 0.0;
    float weightSum = 0.0;  // summed like `sum`, so fully lit gives exactly 1 and fully shadowed 0
    float blockerSum = 0.0;
    float blockerWeight = 0.0;
    vec2 litMoment = vec2(0.0);     // sum of weight x lit x offset
    vec2 sparseMoment = vec2(0.0);  // sum of weight x offset at stride s > 1 (separable at stride 1)
    // Column and row k lie at offset origin + step k from t: the lattice's points along its axes
    // (stride > 1), or the texels (stride 1).
    bool sparse = stride > 1.0;
    const vec2 ax = vec2(5.0, 2.0) / sqrt(29.0);
    const vec2 ay = vec2(-2.0, 5.0) / sqrt(29.0);
    vec2 u = vec2(dot(t, ax), dot(t, ay)) / stride;  // lattice units
    vec2 firstU = ceil(u - (float(G) - 0.5));
    vec2 first = floor(t) - float(G - 1);  // stride 1: the first column's and row's texel
    float W = sparse ? stride * (float(G) - 0.5) : float(G);
    vec2 origin = sparse ? stride * (firstU - u) : first - t;
    float step = sparse ? stride : 1.0;
    float window = exp(-W * W / twoVariance);
    float wx[8];
    float wy[8];
    float sumX = 0.0;
    float sumY = 0.0;
    float varianceX = 0.0;
    float varianceY = 0.0;
    vec2 weightMoment = vec2(0.0);  // the weights' first moments along each axis
    // The Gaussian at d_k = origin + step k by its ratios: exp(-d_k^2 / 2v) is the one at k - 1
    // times exp(-step (2 origin + step (2k - 1)) / 2v), a ratio that itself changes by the factor
    // exp(-2 step^2 / 2v) per tap: three exponentials per axis instead of one per tap.
    vec2 gaussian = exp(-origin * origin / twoVariance);
    vec2 ratio = exp(-step * (2.0 * origin + step) / twoVariance);
    float ratioStep = exp(-2.0 * step * step / twoVariance);
    PRESKIN_UNROLL for (int k = 0; k < 2 * G; ++k) {
        vec2 d = origin + step * float(k);
        wx[k] = max(gaussian.x - window, 0.0);
        wy[k] = max(gaussian.y - window, 0.0);
        gaussian *= ratio;
        ratio *= ratioStep;
        sumX += wx[k];
        sumY += wy[k];
        weightMoment += vec2(wx[k] * d.x, wy[k] * d.y);
        varianceX += wx[k] * d.x * d.x;
        varianceY += wy[k] * d.y * d.y;
    }
    if (sparse) {  // each lattice point compared at its nearest texel
        ivec2 last = ivec2(mapSize) - 1;
        PRESKIN_UNROLL for (int j = 0; j < 2 * G; ++j) {
            PRESKIN_UNROLL for (int i = 0; i < 2 * G; ++i) {
                vec2 lu = firstU + vec2(i, j);
                vec2 texel = floor(stride * (lu.x * ax + lu.y * ay) + 0.5);
                float w = wx[i] * wy[j];
                float occluder = preskinShadowTexel(shadowMap, clamp(ivec2(texel), ivec2(0), last), mapSize);
                float lit = occluder >= z - bias + dot(dzPerTexel, texel - t) ? 1.0 : 0.0;
                sum += w * lit;
                weightSum += w;
                litMoment += w * lit * (texel - t);
                sparseMoment += w * (texel - t);
                blockerSum += w * (1.0 - lit) * occluder;
                blockerWeight += w * (1.0 - lit);
            }
        }
    } else {
        PRESKIN_UNROLL for (int j = 0; j < G; ++j) {
            float y0 = first.y + float(2 * j) - t.y;  // offsets of the gathered rows: y0 and y0 + 1
            PRESKIN_UNROLL for (int i = 0; i < G; ++i) {
                float x0 = first.x + float(2 * i) - t.x;
                // The 2x2 texels from (x0, y0); gather order: (0,1), (1,1), (1,0), (0,0).
                vec4 occluder = textureGather(shadowMap, (first + vec2(2 * i, 2 * j) + 1.0) / mapSize, 0);
                vec4 receiver = z - bias + dzPerTexel.x * vec4(x0, x0 + 1.0, x0 + 1.0, x0) +
                                dzPerTexel.y * vec4(y0 + 1.0, y0 + 1.0, y0, y0);
                vec4 lit = vec4(greaterThanEqual(occluder, receiver));
                vec4 w = vec4(wx[2 * i] * wy[2 * j + 1], wx[2 * i + 1] * wy[2 * j + 1], wx[2 * i + 1] * wy[2 * j],
                              wx[2 * i] * wy[2 * j]);
                vec4 wLit = w * lit;
                float litSum = wLit.x + wLit.y + wLit.z + wLit.w;
                sum += litSum;
                weightSum += dot(w, vec4(1.0));
                // The lit weights' first moment: the texels' offsets are x0 + (0, 1, 1, 0), y0 + (1, 1, 0, 0).
                litMoment += vec2(x0, y0) * litSum + vec2(wLit.y + wLit.z, wLit.x + wLit.y);
                blockerSum += dot(w - wLit, occluder);
            }
        }
    }
    float variance = 0.5 * (varianceX / sumX + varianceY / sumY);
    PreskinShadowPcf r;
    r.visibility = sum / weightSum;
    r.varianceTexels = variance;
    // The occluding texels' weights, sum of w (1 - lit): at stride 1 the weights less the lit ones
    // (a fully lit footprint leaves rounding's few ulps, which the test below takes for none).
    if (!sparse) blockerWeight = max(weightSum - sum, 0.0);
    r.blockerDepth = blockerWeight > 1e-6 * weightSum ? blockerSum / blockerWeight : z;
    r.blockerWeight = blockerWeight / weightSum;
    vec2 moment = sparse ? sparseMoment : weightMoment * vec2(sumY, sumX);  // sum of weight x offset
    r.gradient = (litMoment - r.visibility * moment) / weightSum;
    return r;
}

// shadowClipFromWorld: orthographic light matrix (depth 0 near .. 1 far).
// params: x texel size (m), y Gaussian sigma (texels), z depth range (m), w map size (texels).
// A light with a size (penumbraPerM > 0: the penumbra's standard deviation per metre between
// occluder and receiver; for a disc of angular radius sigma, 0.545 tan(sigma)) widens the kernel
// by its penumbra at the occluders' distance, found by a blocker search first (percentage-closer soft shadows: Fernando,
// "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch): the occluding texels' weighted mean
// depth over the widest penumbra the receiver can have (occluders at the map's near plane).
PreskinShadowSample preskinSampleShadow(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                        vec3 positionWs, vec3 geometricNormalWs, PreskinShadowFilter shadowFilter,
                                        float penumbraPerM) {
    PreskinShadowSample result;
    float mapSize = params.w;
    float sigma = max(params.y, 0.25);
    PreskinShadowReceiver receiver =
        preskinShadowReceiver(shadowClipFromWorld, params, positionWs, geometricNormalWs, shadowFilter.texelScale);
    vec2 uv = receiver.uv;
    float z = receiver.z;
    vec2 dzPerTexel = receiver.dzPerTexel;
    float bias = 2e-4 + shadowFilter.slopeBiasTexels * (abs(dzPerTexel.x) + abs(dzPerTexel.y)) + shadowFilter.riseM / params.z;

    vec2 t = uv * mapSize - 0.5;
    const int G = shadowFilter.gathersPerAxis;
    float stride = 1.0;
    result.penumbraWidthM = 0.0;
    if (penumbraPerM > 0.0) {
        // The widest penumbra's radius (about 2 penumbraPerM per metre), covered by 4 x 4 texels at
        // a stride: their window is 1.5 strides.
        float reachTexels = 2.0 * penumbraPerM * max(z, 0.0) * params.z / params.x;
        float searchStride = clamp(ceil(reachTexels / 1.5), 1.0, 32.0);
        float searchWindow = searchStride <= 1.0 ? 2.0 : 1.5 * searchStride;
        PreskinShadowPcf search =
            preskinShadowPcf(shadowMap, t, mapSize, z, bias, dzPerTexel, 2, searchStride, 0.4 * searchWindow);
        float penumbraTexels = max(z - search.blockerDepth, 0.0) * params.z * penumbraPerM / params.x;
        // The map's own filter only hides its texels, which a wider penumbra's filter does too.
        sigma = max(sigma, penumbraTexels);
        result.penumbraWidthM = penumbraTexels * params.x;
        // Stride 1 holds sigma up to 0.4 G texels (the window at 2.5 sigma); wider, a stride keeps
        // the window at 2.5 sigma or more.
        if (sigma > 0.4 * float(G)) stride = min(ceil(2.5 * sigma / (float(G) - 0.5)), 16.0);
    }
    PreskinShadowPcf pcf = preskinShadowPcf(shadowMap, t, mapSize, z, bias, dzPerTexel, G, stride, sigma);
    bool inside = receiver.inside;
    result.visibility = inside ? pcf.visibility : 1.0;
    // The weights' standard deviation (mean of the two axes), the filter's width across an edge.
    result.kernelWidthM = sqrt(pcf.varianceTexels) * params.x;
    result.blockerDistanceM = inside ? max(z - pcf.blockerDepth, 0.0) * params.z : 0.0;
    // The Gaussian's gradient is its first moment over its variance (texels); texel coordinates
    // change by mapSize / 2 times rows r0, r1 of the transform per metre.
    vec3 r0 = vec3(shadowClipFromWorld[0][0], shadowClipFromWorld[1][0], shadowClipFromWorld[2][0]);
    vec3 r1 = vec3(shadowClipFromWorld[0][1], shadowClipFromWorld[1][1], shadowClipFromWorld[2][1]);
    vec3 gradient = (pcf.gradient.x * r0 + pcf.gradient.y * r1) * (0.5 * mapSize / max(pcf.varianceTexels, 1e-6));
    result.gradientWs = inside ? gradient : vec3(0.0);
    return result;
}

// A parallel light's.
PreskinShadowSample preskinSampleShadow(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                        vec3 positionWs, vec3 geometricNormalWs, PreskinShadowFilter shadowFilter) {
    return preskinSampleShadow(shadowMap, shadowClipFromWorld, params, positionWs, geometricNormalWs, shadowFilter, 0.0);
}

PreskinShadowSample preskinSampleShadow(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                        vec3 positionWs, vec3 geometricNormalWs) {
    return preskinSampleShadow(shadowMap, shadowClipFromWorld, params, positionWs, geometricNormalWs,
                               kPreskinShadowMapFilter);
}

// The transform of a map covering the shadow map's region scaled by uvScale from its corner
// (uv' = uv * uvScale): a coarser map whose texels hold whole blocks of the shadow map.
mat4 preskinScaledShadowClip(mat4 shadowClipFromWorld, float uvScale) {
    mat4 m = shadowClipFromWorld;
    for (int c = 0; c < 4; ++c) {
        m[c][0] = uvScale * m[c][0] + (uvScale - 1.0) * m[c][3];
        m[c][1] = uvScale * m[c][1] + (uvScale - 1.0) * m[c][3];
    }
    return m;
}

#endif
