// core/suggest.h — "did you mean …?" for a misspelt name: the closest of the names that a scene
// key, a command-line option or a value accepts.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace footprint {

// Optimal string alignment distance (Levenshtein with adjacent transpositions).
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::size_t> d((n + 1) * (m + 1));
    auto at = [m, &d](std::size_t i, std::size_t j) -> std::size_t& { return d[i * (m + 1) + j]; };
    for (std::size_t i = 0; i <= n; ++i) at(i, 0) = i;
    for (std::size_t j = 0; j <= m; ++j) at(0, j) = j;
    for (std::size_t i = 1; i <= n; ++i) {
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
        }
    }
    return at(n, m);
}

// The candidate closest to `word` within a third of the word's length (at least 1, at most 3
// edits), or one that starts with the word or the word with it ("rotation" → "rotation_deg",
// "cubemap" → "cube"); nullopt when none is that close (a guess that far off misleads).
inline std::optional<std::string_view> closest_name(std::string_view word,
                                                    std::span<const std::string_view> candidates) {
    std::string_view best;
    std::size_t best_distance = std::numeric_limits<std::size_t>::max();
    const std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
    for (std::string_view c : candidates) {
        std::size_t dist = edit_distance(word, c);
        const bool prefix =
            std::min(word.size(), c.size()) >= 3 && (c.starts_with(word) || word.starts_with(c));
        if (prefix) dist = std::min(dist, limit);
        if (dist < best_distance) best = c, best_distance = dist;
    }
    if (best_distance <= limit) return best;
    return std::nullopt;
}

}  // namespace footprint
