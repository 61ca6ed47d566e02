// shading/test_extreme_values.h — test support: random input that reaches the shading code's edge
// cases (zero, tiny and huge magnitudes), for the tests that its results stay free of NaN.
#pragma once

#include <cmath>
#include <random>

namespace footprint::test {

// `x` as it is, zero, x·10^e for e uniform in [−30, 30), or x·10⁻³, a quarter of the time each.
inline float extreme_scale(std::mt19937& rng, float x) {
    switch (rng() % 4) {
        case 0:
            return 0.0f;
        case 1:
            return x;
        case 2:
            return x * std::pow(10.0f, std::uniform_real_distribution<float>(-30, 30)(rng));
        default:
            return x * 1e-3f;
    }
}

}  // namespace footprint::test
