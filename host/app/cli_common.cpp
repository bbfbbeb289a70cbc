#include "cli_common.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "export/checkpoint.hpp"
#include "colliders/mesh_collider.hpp"
#include "export/output_plan.hpp"
#include "io/input_file.hpp"

namespace clothsim {

void SceneOptions::add_to(CLI::App& cmd, bool positional_required) {
  option = cmd.add_option("scene", path, "scene JSON file (classic CS184 format or extended)");
  if (positional_required) option->required();
  cmd.add_option("--set", sets, "override a scene value, e.g. --set cloth.ks=500 (repeatable; keys: docs/parameters.md)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  add_no_cache_flag(cmd);
}

void add_no_cache_flag(CLI::App& cmd) {
  cmd.add_flag_callback("--no-cache", disable_field_cache,
                        "neither read nor keep mesh colliders' fields in the cache folder ($XDG_CACHE_HOME/clothsim)");
}

// An empty name given as the scene is refused (load_scene says so), not taken for "no scene".
Scene SceneOptions::load() const {
  const bool given = option && option->count() > 0;
  return path.empty() && !given ? default_scene(sets) : load_scene(path, sets);
}

namespace {

// The number in `text` if all of it is one (as CLI11 would read it), else nothing.
std::optional<double> as_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0') return std::nullopt;
  return v;
}

std::string readable(double v) { return fmt::format("{:g}", v); }

// "" when `text` is fine; what is wrong with it otherwise. Not a number at all is left to
// CLI11's conversion, which names the option and the type.
std::string check_value(const std::string& text, double lo, double hi, const std::string& expected) {
  const std::optional<double> v = as_number(text);
  if (!v) return {};
  if (std::isnan(*v)) return fmt::format("expected {}, got {} (NaN is not a number here)", expected, text);
  if (std::isinf(*v)) return fmt::format("expected {}, got {} (infinity is not accepted)", expected, text);
  if (*v < lo || *v > hi) return fmt::format("expected {}, got {}", expected, text);
  return {};
}

CLI::Validator range_validator(double lo, double hi, std::string expected) {
  return CLI::Validator([lo, hi, expected](std::string& text) { return check_value(text, lo, hi, expected); },
                        expected);
}

}  // namespace

CLI::Validator number_in(double lo, double hi) {
  return range_validator(lo, hi, fmt::format("a number in [{}, {}]", readable(lo), readable(hi)));
}
CLI::Validator positive_number() { return range_validator(std::nextafter(0.0, 1.0), HUGE_VAL, "a number > 0"); }
CLI::Validator non_negative_number() { return range_validator(0.0, HUGE_VAL, "a number >= 0"); }
CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& text) { return text.empty() ? std::string("an empty path (expected a file name)") : std::string(); },
      "");
}

void refuse_non_finite(CLI::App& app) {
  // CLI11 names a numeric option's type FLOAT, INT or UINT (also for vectors and with a
  // delimiter, whose parts are checked one by one); TEXT, BOOLEAN and the like are left alone:
  // a file may well be called "nan".
  const CLI::Validator finite(
      [](std::string& text) { return check_value(text, -HUGE_VAL, HUGE_VAL, "a finite number"); }, "");
  for (CLI::Option* opt : app.get_options()) {
    const std::string type = opt->get_type_name();
    if (type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos) opt->check(finite);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_non_finite(*sub);
}

BackendKind parse_backend(const std::string& name) {
  if (name == "cpu") return BackendKind::Cpu;
  if (name == "gpu") return BackendKind::Gpu;
  throw ExitError(kExitBadInput, fmt::format("--backend: expected gpu or cpu, got '{}'", name));
}

void check_outputs(const OutputPlan& plan) {
  try {
    plan.check();
  } catch (const OutputError& e) {
    throw ExitError(kExitBadInput, e.what());
  }
}

// Reads and checks --load-state, then hands it to the backend; every failure is exit 2.
int64_t load_state(const std::string& path, const Scene& scene, const ClothModel& model, Backend& backend) {
  try {
    const Checkpoint c = read_checkpoint(path);
    check_fits(c, path, scene, model, backend.scalar_bytes(), backend.name());
    backend.load_state(c.state);
    fmt::print("loaded {}: frame {} ({:.4g} s simulated), saved by backend {} from {}\n", path, c.state.frame,
               c.state.time, printable(c.backend), printable(c.scene));
    // The displacements are per substep: another substep length rescales them (the cloth keeps
    // its velocity); a version-1 file did not record its length, so it is taken as this one.
    if (c.state.dt == 0)
      fmt::print("  (a version-1 state, which does not record its substep length: taken as this scene's {:.6g} s)\n",
                 scene.dt());
    else if (c.state.dt != scene.dt())
      fmt::print("  saved with substeps of {:.6g} s, this scene's are {:.6g} s: displacements scaled by {:.6g}\n",
                 c.state.dt, scene.dt(), scene.dt() / c.state.dt);
    return c.state.frame;
  } catch (const CheckpointError& e) {
    throw ExitError(kExitBadInput, fmt::format("--load-state {}", e.what()));
  }
}

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(total), tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(int done) {
  if (!tty_) return;
  auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  double secs = std::chrono::duration<double>(now - start_).count();
  double rate = secs > 0 ? done / secs : 0;
  double eta = rate > 0 ? (total_ - done) / rate : 0;
  fmt::print(stderr, "\r{} {}/{}  {:.1f} frames/s  ETA {:.0f} s   ", label_, done, total_, rate, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (tty_) fmt::print(stderr, "\r\033[K");
}

}  // namespace clothsim
