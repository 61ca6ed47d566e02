// envmap/latlong_path.h — (private to envmap) where a lat-long line of probes lies.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include "envmap/env_layout.h"

namespace footprint {

// The lat-long probes' great circle without trigonometry per probe: placed exactly at both ends
// (environment_map.cpp's TangentProbes) and interpolated quadratically through them and the centre
// in (s, t), p(u) = c + u·h + u²·q, u ∈ [−1, 1]. Over the extent of a probe line away from the
// poles (the pole fallback takes footprints that reach one) the cubic remainder is a small fraction
// of a texel; probes that would cross a pole are placed exactly.
struct QuadraticPath {
    bool valid = false;
    Vec2 centre, h, q;  // (s, t), and the linear and quadratic terms

    // Through the centre c and the ends a (u = 1) and b (u = −1), placed exactly.
    static QuadraticPath through(const EnvCoords& c, const EnvCoords& a, const EnvCoords& b) {
        auto unwrapped = [](float ds) { return ds - std::nearbyint(ds); };  // across the seam
        const Vec2 da{unwrapped(a.s - c.s), a.t - c.t}, db{unwrapped(b.s - c.s), b.t - c.t};
        QuadraticPath p;
        p.centre = {c.s, c.t};
        p.h = 0.5f * (da - db);
        p.q = 0.5f * (da + db);
        p.valid = true;
        return p;
    }

    // Probe i of n, (s, t) before the seam wraps s.
    Vec2 position(int i, int n) const {
        const float half = 0.5f * static_cast<float>(n - 1);
        const float u = (static_cast<float>(i) - half) / half;
        return {centre.x + u * (h.x + u * q.x), centre.y + u * (h.y + u * q.y)};
    }

    // Probe i of n; false when it would leave t ∈ [0, 1] (over a pole).
    bool place(int i, int n, EnvCoords& out) const {
        const Vec2 p = position(i, n);
        if (!(p.y >= 0.0f && p.y <= 1.0f)) return false;
        out = {0, p.x - std::floor(p.x), p.y};
        return true;
    }

    // The box that holds p(u) for every u ∈ [−1, 1] (its ends, and its vertex u = −h/2q where
    // that lies between them): lower and upper corners.
    std::pair<Vec2, Vec2> bounds() const {
        auto range = [](float c, float h, float q) {
            float lo = std::min(c - h + q, c + h + q), hi = std::max(c - h + q, c + h + q);
            if (std::fabs(h) < 2 * std::fabs(q)) {
                const float vertex = c - h * h / (4 * q);
                lo = std::min(lo, vertex);
                hi = std::max(hi, vertex);
            }
            return std::pair{lo, hi};
        };
        const auto [s_lo, s_hi] = range(centre.x, h.x, q.x);
        const auto [t_lo, t_hi] = range(centre.y, h.y, q.y);
        return {{s_lo, t_lo}, {s_hi, t_hi}};
    }
};

}  // namespace footprint
