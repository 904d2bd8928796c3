// Keyframe interpolation of one glTF animation sampler (glTF 2.0, "Animations" and Appendix C,
// "Interpolation"): STEP holds a key's value up to the next key; LINEAR interpolates linearly,
// or by spherical linear interpolation over the short arc for rotations; CUBICSPLINE evaluates the
// cubic Hermite spline whose in- and out-tangents are scaled by the key interval. Times before the
// first key and after the last take the first and last value. Computed in double precision;
// rotations are normalised.
#include <preskin/Animation.h>
#include <preskin/Error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace preskin {

namespace {

void normalizeQuaternion(std::vector<double>& q) {
    const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (length > 0.0) {
        for (double& c : q) c /= length;
    } else {
        q = {0.0, 0.0, 0.0, 1.0};
    }
}

// Spherical linear interpolation from a to b by s in [0, 1] over the short arc (b is negated when
// the quaternions lie more than 90 degrees apart on the 4D sphere, which is the same rotation).
std::vector<double> slerp(std::vector<double> a, std::vector<double> b, double s) {
    normalizeQuaternion(a);
    normalizeQuaternion(b);
    double cosAngle = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (cosAngle < 0.0) {
        for (double& c : b) c = -c;
        cosAngle = -cosAngle;
    }
    std::vector<double> out(4);
    if (cosAngle > 1.0 - 1e-12) {  // (almost) the same rotation: the linear form is exact enough
        for (size_t k = 0; k < 4; ++k) out[k] = a[k] + s * (b[k] - a[k]);
    } else {
        const double angle = std::acos(cosAngle);
        const double wa = std::sin((1.0 - s) * angle) / std::sin(angle);
        const double wb = std::sin(s * angle) / std::sin(angle);
        for (size_t k = 0; k < 4; ++k) out[k] = wa * a[k] + wb * b[k];
    }
    normalizeQuaternion(out);
    return out;
}

}  // namespace

std::vector<float> AnimationSampler::sample(float timeS) const {
    const size_t keys = times.size();
    const size_t n = components;
    const bool cubic = interpolation == Interpolation::CubicSpline;
    const size_t stride = cubic ? 3 * n : n;  // CUBICSPLINE keys: in-tangent, value, out-tangent
    const size_t valueOffset = cubic ? n : 0;
    if (keys == 0 || n == 0) throw Error("animation sampler: no keys to sample");
    if (values.size() != keys * stride) {
        throw Error("animation sampler: " + std::to_string(values.size()) + " values for " + std::to_string(keys) +
                    " keys of " + std::to_string(n) + " components" + (cubic ? " (CUBICSPLINE: 3 per key)" : ""));
    }
    if (rotation && n != 4) throw Error("animation sampler: a rotation needs 4 components, not " + std::to_string(n));
    if (!std::isfinite(timeS)) throw Error("animation sampler: the time is not a finite number");

    auto at = [&](size_t key, size_t offset, size_t k) {
        return static_cast<double>(values[key * stride + offset + k]);
    };
    std::vector<double> result(n);
    auto keyValue = [&](size_t key) {
        for (size_t k = 0; k < n; ++k) result[k] = at(key, valueOffset, k);
    };

    if (timeS <= times.front()) {
        keyValue(0);
    } else if (timeS >= times.back()) {
        keyValue(keys - 1);
    } else {
        // times[k] <= t < times[k + 1]
        const size_t k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), timeS) - times.begin()) - 1;
        const double t0 = times[k], t1 = times[k + 1];
        const double intervalS = t1 - t0;
        const double s = (static_cast<double>(timeS) - t0) / intervalS;
        switch (interpolation) {
        case Interpolation::Step: keyValue(k); break;
        case Interpolation::Linear:
            if (rotation) {
                std::vector<double> a(4), b(4);
                for (size_t c = 0; c < 4; ++c) {
                    a[c] = at(k, 0, c);
                    b[c] = at(k + 1, 0, c);
                }
                result = slerp(a, b, s);
            } else {
                for (size_t c = 0; c < n; ++c) result[c] = at(k, 0, c) + s * (at(k + 1, 0, c) - at(k, 0, c));
            }
            break;
        case Interpolation::CubicSpline: {
            // p(s) = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) d b_k + (-2s^3 + 3s^2) v_k+1 + (s^3 - s^2) d a_k+1,
            // with d = t_k+1 - t_k, b_k the out-tangent of key k and a_k+1 the in-tangent of key k+1.
            const double s2 = s * s, s3 = s2 * s;
            const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
            const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
            for (size_t c = 0; c < n; ++c) {
                result[c] = h00 * at(k, n, c) + h10 * intervalS * at(k, 2 * n, c) + h01 * at(k + 1, n, c) +
                    h11 * intervalS * at(k + 1, 0, c);
            }
            break;
        }
        }
    }
    if (rotation) normalizeQuaternion(result);
    return std::vector<float>(result.begin(), result.end());
}

}  // namespace preskin
