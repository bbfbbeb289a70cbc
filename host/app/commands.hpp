// Each command registers its subcommand; its callback stores the work to run after parsing.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace clothsim {

void add_simulate_command(CLI::App& app, std::function<int()>& run);
void add_validate_command(CLI::App& app, std::function<int()>& run);
void add_render_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);
void add_static_command(CLI::App& app, std::function<int()>& run);
void add_sweep_command(CLI::App& app, std::function<int()>& run);
// The viewer is the default command: options on the top level, no subcommand.
void add_viewer_options(CLI::App& app, std::function<int()>& run);

}  // namespace clothsim
