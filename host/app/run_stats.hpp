// The figures of `simulate --stats` as JSON: what `--stats-json FILE` writes, what the Python
// module's Simulation.stats() returns and what a sweep records per run (docs/python.md lists
// the keys). One function, so the three can never disagree.
#pragma once

#include <nlohmann/json.hpp>

#include "backend.hpp"
#include "scene/scene.hpp"

namespace clothsim {

// `frames`: frames stepped by this run (the state's own frame may be later, after a
// --load-state); `wall`: the seconds they took. Reads the state back once and counts the
// self-intersections exactly on the CPU, as --stats does.
nlohmann::json stats_json(const Scene& scene, const ClothModel& model, Backend& backend, int64_t frames, double wall);

// simulate --profile's table: each pass's wall time per frame over `frames` frames, its runs a
// frame and its share of the passes' sum, in the order the passes first ran; and the same as
// JSON ({pass: ms per frame}, what --stats-json adds as "pass_ms_per_frame").
void print_profile(const PassProfile& profile, int64_t frames, const std::string& clock);
nlohmann::json profile_json(const PassProfile& profile, int64_t frames);

// `json` written to `path` (replaced only once complete); std::runtime_error naming the path.
void write_stats_json(const std::string& path, const nlohmann::json& json);

}  // namespace clothsim
