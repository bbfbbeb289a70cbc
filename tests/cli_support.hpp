// Running the built `clothsim` binary from a test: its exit code, stdout and stderr apart.
// Shared by the command-line tests (test_cli.cpp, test_cli_inputs.cpp).
#pragma once

#include <catch2/catch.hpp>

#include "bad_scenes.hpp"
#include "file_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace clothsim::test {

namespace fs = std::filesystem;

inline const fs::path kSource = CLOTHSIM_SOURCE_DIR;
inline const fs::path kBinary = CLOTHSIM_BINARY;
inline const fs::path kBad = kBadScenes;

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// A scratch path unique to this process, removed when the test ends.
struct TempFile {
  fs::path path;
  explicit TempFile(const std::string& name)
      : path(fs::temp_directory_path() / ("clothsim_test_cli_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove(path);
  }
  ~TempFile() { std::error_code ec; fs::remove_all(path, ec); }
};

// ASan reserves terabytes of address space for its shadow memory, so a process it instruments
// cannot even start under `ulimit -v`: the sanitizer build (scripts/test-sanitizers) runs
// without the limit, and a test that needs one to run out of memory is the normal build's.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
inline std::string address_space_limit(const std::string& kib) {
  return kAddressSanitizer ? std::string() : "ulimit -v " + kib + ";";
}

struct Result {
  int code = -1;
  std::string out, err;
  std::string both() const { return out + err; }
};

// Runs `clothsim ARGS...` with stdout and stderr captured separately. `limits` is a fixed shell
// prefix of the test's own (e.g. "ulimit -v 2000000;" or "timeout 20"), never user text.
inline Result run(const std::vector<std::string>& args, const std::string& limits = "") {
  TempFile err_file("stderr.txt");
  std::string cmd = limits.empty() ? std::string() : limits + " ";
  cmd += quote(kBinary.string());
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " 2>" + quote(err_file.path.string()) + " </dev/null";
  INFO("$ " << cmd);
  Result r;
  std::FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  REQUIRE(WIFEXITED(status));
  r.code = WEXITSTATUS(status);
  r.err = slurp(err_file.path);
  return r;
}

}  // namespace clothsim::test
