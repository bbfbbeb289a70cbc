// The pass table (pass_table.hpp): one row per pass, in a substep's order.
#include "pass_table.hpp"

#include <algorithm>

namespace clothsim {

bool runs(const PassRow& r, uint16_t features) { return (features & r.need) == r.need && (features & r.unless) == 0; }

const char* stage_name(const PassRow& r) {
  return r.id == PassId::restrict_residuals ? "cycle_levels" : r.id == PassId::stretch_fixed_passes ? "enforce_stretch_limit" : r.name;
}

int dispatches_of(const PassRow& r, const SubstepShape& s) {
  if (!runs(r, s.features)) return 0;
  const int fixed = std::max(s.stretch_passes, 1), settling = s.stretch_passes_max - fixed + 1;
  switch (r.count) {
    case Count::once: return 1;
    case Count::scan: return s.scan_dispatches;
    case Count::iterations_x_colours: return s.iterations * s.enabled_colours;
    case Count::large_levels: return s.large_levels;
    case Count::small_cycle: return s.levels > 0 ? 1 : 0;
    case Count::large_level_sweeps: return s.large_level_colours;
    case Count::fine_colours: return s.fine_colours;
    case Count::fixed_stretch_sweeps:
      return (s.features & kSettling ? fixed - 1 : s.stretch_passes) * s.enabled_colours;
    case Count::arms: return settling;
    case Count::watched_sweeps: return settling * s.enabled_colours;
    case Count::none: return 0;
  }
  return 0;
}

int dispatches_per_substep(const SubstepShape& s) {
  int total = 0;
  for (const PassRow& r : kPasses) total += dispatches_of(r, s);
  return total;
}

std::string pass_list(const SubstepShape& s) {
  std::string out;
  const char* open = nullptr;  // the group whose parenthesis is open
  for (const PassRow& r : kPasses) {
    if (dispatches_of(r, s) == 0 && r.count != Count::scan) continue;
    if (!runs(r, s.features)) continue;
    if (open && (!r.group || std::string(r.group) != open)) out += ")", open = nullptr;
    if (!out.empty()) out += ", ";
    if (r.group && !open) out += std::string(r.group) + " (", open = r.group;
    out += r.name;
  }
  if (open) out += ")";
  return out;
}

}  // namespace clothsim
