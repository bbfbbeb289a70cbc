// `clothsim sweep SCENE --vary KEY=V1,V2,... [--seeds N] --frames F --out DIR [--workers N |
//  --scheduler tcp://HOST:PORT]`: the sweep is Python on Dask (python/clothsim/sweeps.py,
// docs/sweeps.md), so this command hands its arguments, unread, to Debian's Python running
// that module: by execv, never through a shell. It finds the module beside the executable
// (build/python) and tells it where clothsim-headless is, which each run executes.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "commands.hpp"

namespace clothsim {

void add_sweep_command(CLI::App& app, std::function<int()>& run) {
  CLI::App* cmd = app.add_subcommand("sweep", "run a scene over parameter variations on Dask (docs/sweeps.md); "
                                              "`clothsim sweep --help` lists its options");
  cmd->prefix_command();     // everything after `sweep` is the Python module's
  cmd->set_help_flag();      // --help included: argparse answers it
  cmd->callback([cmd, &run] {
    const std::vector<std::string> args = cmd->remaining();
    run = [args]() -> int {
      namespace fs = std::filesystem;
      std::error_code ec;
      const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
      const fs::path build = ec ? fs::current_path() : exe.parent_path();
      const fs::path package = build / "python" / "clothsim" / "sweeps.py";
      if (!fs::exists(package))
        throw ExitError(kExitBadInput, fmt::format("sweep: the Python module is not built ({} is missing): "
                                                   "./scripts/build builds it", package.string()));
      const char* python_env = std::getenv("CLOTHSIM_PYTHON");
      const std::string python = python_env && *python_env ? python_env : "/usr/bin/python3";
      std::string path = (build / "python").string();
      if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
      setenv("PYTHONPATH", path.c_str(), 1);
      if (!std::getenv("CLOTHSIM_BINARY")) setenv("CLOTHSIM_BINARY", (build / "clothsim-headless").c_str(), 1);
      std::vector<std::string> argv_s = {python, "-m", "clothsim.sweeps"};
      argv_s.insert(argv_s.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (std::string& a : argv_s) argv.push_back(a.data());
      argv.push_back(nullptr);
      std::fflush(stdout);
      execv(python.c_str(), argv.data());
      throw ExitError(kExitBadInput, fmt::format("sweep: cannot run {} ({}); install python3-distributed and "
                                                 "python3-numpy (./scripts/install-deps), or set CLOTHSIM_PYTHON",
                                                 python, std::strerror(errno)));
    };
  });
}

}  // namespace clothsim
