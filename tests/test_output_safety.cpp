// Nothing clobbered (docs/export.md, "Before the run"): temporaries are created exclusively under
// unguessable names and removed on SIGINT/SIGTERM; an output that is not a regular file, that
// two outputs share, or that the run reads is refused with exit 2 before anything runs; the
// field cache lives in the cache folder and is checked before it is trusted. Each case here
// failed on 12cc68b (a file replaced, followed, lost or left behind; a run that blocked).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "io/output_file.hpp"
#include "mesh_collider_cases.hpp"
#include "colliders/sdf.hpp"
#include "output_support.hpp"
#include "test_helpers.hpp"

extern char** environ;

using namespace clothsim;
namespace fs = std::filesystem;
using test::kDiverging;
using test::kSmall;
using test::listing;
using test::run_binary;
using test::put_file;
using test::slurp;

namespace {

struct TempDir : test::TempDir {
  explicit TempDir(const std::string& name) : test::TempDir("output_safety", name) {}
};

// A socket file at `path` (bound, then the descriptor closed: the file stays).
void make_socket(const std::string& path) {
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  REQUIRE(path.size() < sizeof a.sun_path);
  std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path.c_str());
  REQUIRE(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
  close(fd);
}

}  // namespace

TEST_CASE("temporaries are created exclusively, never through a file already at their name", "[outputs]") {
  TempDir dir("exclusive");
  const std::string out = dir / "x.obj", victim = dir / "victim";
  put_file(victim, "someone's file");
  // 12cc68b named the temporary NAME.PID.tmp: a symlink planted there was written through.
  fs::create_symlink(victim, fmt::format("{}.{}.tmp", out, getpid()));
  write_text_replacing(out, "new");
  CHECK(slurp(victim) == "someone's file");
  CHECK(slurp(out) == "new");
  CHECK_FALSE(fs::is_symlink(out));

  // Unguessable and distinct: two temporaries of one name in one process differ.
  const std::string a = create_temporary(out), b = create_temporary(out);
  CHECK(a != b);
  CHECK(a.find(fmt::format(".{}.", getpid())) == std::string::npos);
  CHECK(fs::is_regular_file(a));
  // The usual permissions of a new file, not mkstemp's 0600.
  const mode_t mask = umask(022);
  umask(mask);
  struct stat st {};
  REQUIRE(stat(a.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == (0666 & ~mask));
  remove_quietly(a);
  remove_quietly(b);
  CHECK_FALSE(fs::exists(a));
}

TEST_CASE("a symlink at NAME.pc2.partial is replaced, never followed", "[outputs][cli]") {
  TempDir dir("partial_link");
  const std::string pc2 = dir / "run.pc2", victim = dir / "victim";
  put_file(victim, "someone's file");
  fs::create_symlink(victim, pc2 + ".partial");
  std::string out;
  CHECK(run_binary(fmt::format("simulate {} --frames 100 --export '{}'", kDiverging, pc2), &out) == 1);
  CHECK(slurp(victim) == "someone's file");
  CHECK(fs::is_regular_file(fs::symlink_status(pc2 + ".partial")));  // the frames before the divergence
  CHECK_THAT(out, Catch::Contains("kept " + pc2 + ".partial"));
  // A successful run leaves a link there alone, and writes nothing through it.
  fs::remove(pc2 + ".partial");
  fs::create_symlink(victim, pc2 + ".partial");
  CHECK(run_binary(fmt::format("simulate {} --frames 2 --export '{}'", kSmall, pc2), &out) == 0);
  CHECK(slurp(victim) == "someone's file");
  CHECK(fs::is_symlink(pc2 + ".partial"));
}

TEST_CASE("an output that is not a regular file is refused before the run and left as it was", "[outputs][cli]") {
  TempDir dir("special");
  const std::string fifo = dir / "fifo", sock = dir / "sock", sub = dir / "sub";
  REQUIRE(mkfifo(fifo.c_str(), 0644) == 0);
  make_socket(sock);
  fs::create_directory(sub);
  fs::create_symlink(fifo, dir / "to_fifo");
  fs::create_symlink("/proc/self/fd/1", dir / "to_stdout");
  fs::create_symlink(dir / "nothing", dir / "dangling");
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"--export '" + fifo + "'", "is a FIFO"},
      {"--save-state '" + fifo + "'", "is a FIFO"},
      {"--export '" + (dir / "to_fifo") + "'", "is a FIFO"},
      {"--export '" + sock + "'", "is a socket"},
      {"--export '" + (dir / "to_stdout") + "'", "symlink into /proc"},
      {"--export '" + (dir / "dangling") + "'", "symlink to nothing"},
      {"--save-state '" + sub + "'", "is a directory"},
      {"--export '" + (dir / "r.pc2") + "' --export-mesh '" + fifo + "'", "is a FIFO"},
      // The companions too: the mesh beside a PC2 and its .partial.
      {"--export '" + (dir / "c.pc2") + "'", "c.obj (the mesh written beside --export"},
      {"--export '" + (dir / "d.pc2") + "'", "d.pc2.partial (where --export"},
  };
  REQUIRE(mkfifo((dir / "c.obj").c_str(), 0644) == 0);
  REQUIRE(mkfifo((dir / "d.pc2.partial").c_str(), 0644) == 0);
  for (const Case& c : cases) {
    INFO(c.args);
    std::string out;
    CHECK(run_binary(fmt::format("simulate {} --frames 2 {}", kSmall, c.args), &out) == 2);
    CHECK_THAT(out, Catch::Contains(c.expect));
    CHECK_THAT(out, !Catch::Contains("backend cpu"));  // refused before the cloth was built
  }
  CHECK(fs::is_fifo(fifo));
  CHECK(fs::is_fifo(dir / "c.obj"));
  CHECK(fs::is_socket(sock));
  CHECK(fs::is_symlink(dir / "to_stdout"));
  CHECK(listing(dir.path) ==
        std::set<std::string>{"fifo", "sock", "sub", "to_fifo", "to_stdout", "dangling", "c.obj", "d.pc2.partial"});
}

TEST_CASE("two outputs of one run naming the same file are refused before the run", "[outputs][cli]") {
  TempDir dir("same");
  fs::create_directory(dir.path / "seq");
  const std::vector<std::string> cases = {
      // the OBJ beside the cache is the state
      fmt::format("--export '{}' --save-state '{}'", dir / "x.pc2", dir / "x.obj"),
      // one file, spelled two ways
      fmt::format("--export '{}' --save-state '{}'", dir / "a.obj", dir / "seq/../a.obj"),
      // the cache's own mesh named as the cache
      fmt::format("--export '{}' --export-mesh '{}'", dir / "m.pc2", dir / "m.pc2"),
      // a frame of the sequence is the state
      fmt::format("--export '{}/' --save-state '{}'", dir / "seq", dir / "seq/frame_0002.obj"),
      // anything else inside a sequence's folder
      fmt::format("--export '{}/' --save-state '{}'", dir / "seq", dir / "seq/state.bin"),
  };
  for (const std::string& args : cases) {
    INFO(args);
    std::string out;
    CHECK(run_binary(fmt::format("simulate {} --frames 3 {}", kSmall, args), &out) == 2);
    CHECK_THAT(out, Catch::Contains("name the same file") || Catch::Contains("holds only its frames"));
  }
  CHECK(listing(dir.path) == std::set<std::string>{"seq"});
  CHECK(listing(dir.path / "seq").empty());
  // A hard link is the same file too.
  put_file(dir / "h1.obj", "mine");
  fs::create_hard_link(dir / "h1.obj", dir / "h2.obj");
  std::string out;
  CHECK(run_binary(fmt::format("simulate {} --frames 1 --export '{}' --save-state '{}'", kSmall, dir / "h1.obj",
                               dir / "h2.obj"),
                   &out) == 2);
  CHECK(slurp(dir / "h1.obj") == "mine");
}

TEST_CASE("an output naming an input of its run is refused and the input kept", "[outputs][cli]") {
  TempDir dir("inputs");
  const std::string scene = dir / "s.json";
  fs::copy_file(fmt::format("{}/scenes/pinned2.json", CLOTHSIM_SOURCE_DIR), scene);
  const std::string original = slurp(scene);
  const std::string small = fmt::format(
      "'{}' --set cloth.num_width_points=7 --set cloth.num_height_points=5 --set 'cloth.pinned=[[0,0],[6,0]]' "
      "--backend cpu",
      scene);
  std::string out;
  REQUIRE(run_binary(fmt::format("simulate {} --frames 2 --save-state '{}'", small, dir / "st.bin"), &out) == 0);
  const std::string state = slurp(dir / "st.bin");
  fs::create_symlink(scene, dir / "link.obj");
  const std::vector<std::string> cases = {
      fmt::format("simulate {} --frames 1 --export '{}'", small, scene),
      fmt::format("simulate {} --frames 1 --save-state '{}'", small, scene),
      fmt::format("simulate {} --frames 1 --export '{}'", small, dir / "link.obj"),  // a symlink to it
      fmt::format("simulate {} --frames 1 --load-state '{}' --save-state '{}'", small, dir / "st.bin", dir / "st.bin"),
      fmt::format("static {} --export '{}'", small.substr(0, small.find(" --backend")), scene),
      // the scene's mesh collider (Debian's bull; the check comes before its field is built)
      fmt::format("simulate '{}/scenes/drape_wuson.json' --backend cpu --frames 1 --export "
                  "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
                  CLOTHSIM_SOURCE_DIR),
      // the renderer's texture (checked before a GL context is asked for)
      fmt::format("render {} --frames 1 --out '{}/textures/fabric.png'", small, CLOTHSIM_SOURCE_DIR),
  };
  for (const std::string& args : cases) {
    INFO(args);
    CHECK(run_binary(args, &out) == 2);
    CHECK_THAT(out, Catch::Contains("an output never replaces an input"));
  }
  CHECK(slurp(scene) == original);
  CHECK(slurp(dir / "st.bin") == state);
  CHECK(fs::is_symlink(dir / "link.obj"));
}

TEST_CASE("a sequence's frames are checked before the first is written", "[outputs][cli]") {
  TempDir dir("frames");
  fs::create_directory(dir.path / "seq");
  REQUIRE(mkfifo((dir / "seq/frame_0002.obj").c_str(), 0644) == 0);
  std::string out;
  CHECK(run_binary(fmt::format("simulate {} --frames 3 --export '{}/'", kSmall, dir / "seq"), &out) == 2);
  CHECK_THAT(out, Catch::Contains("frame_0002.obj (a frame of --export") && Catch::Contains("is a FIFO"));
  CHECK(listing(dir.path / "seq") == std::set<std::string>{"frame_0002.obj"});  // nothing written
  // An export folder that is a file.
  put_file(dir / "plain", "x");
  CHECK(run_binary(fmt::format("simulate {} --frames 3 --export '{}/'", kSmall, dir / "plain"), &out) == 2);
  CHECK(slurp(dir / "plain") == "x");
}

TEST_CASE("SIGINT and SIGTERM leave no temporary behind", "[outputs][cli]") {
  for (const int sig : {SIGINT, SIGTERM}) {
    TempDir dir(fmt::format("signal_{}", sig));
    const std::string pc2 = dir / "long.pc2";
    // A run of minutes on the CPU: stopped as soon as its cache's temporary exists.
    std::vector<std::string> args = {CLOTHSIM_BINARY, "simulate", fmt::format("{}/scenes/pinned2.json", CLOTHSIM_SOURCE_DIR),
                                     "--backend", "cpu", "--frames", "100000", "--export", pc2};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    REQUIRE(posix_spawn(&pid, CLOTHSIM_BINARY, &actions, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
    // The cache's temporary (the mesh's comes and goes first).
    auto temporaries = [&] {
      int n = 0;
      for (const std::string& name : listing(dir.path))
        n += name.rfind("long.pc2.", 0) == 0 && name.size() > 4 && name.substr(name.size() - 4) == ".tmp";
      return n;
    };
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (temporaries() == 0 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    CHECK(temporaries() == 1);
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK(WIFSIGNALED(status));  // ended as the signal ends a process: a shell sees it so
    CHECK(WTERMSIG(status) == sig);
    CHECK(listing(dir.path) == std::set<std::string>{"long.obj"});  // the mesh, written whole at the start
  }
}

TEST_CASE("a cached field carries a checksum: a corrupted one is rebuilt, not trusted", "[mesh_collider][outputs]") {
  TempDir dir("sdf_checksum");
  const SurfaceMesh mesh = test::torus_mesh(0.22, 0.08, 24, 12);
  const SdfGrid g = build_sdf(mesh, 0.02);
  const std::string file = dir / "t.sdf";
  write_sdf_cache(file, mesh_hash(mesh), g);
  SdfGrid back;
  std::string problem;
  REQUIRE(read_sdf_cache(file, mesh_hash(mesh), 0.02, back, &problem));
  CHECK(problem.empty());
  // One value's low bit flipped: still a finite number, which 12cc68b read back as valid.
  std::string bytes = slurp(file);
  bytes[bytes.size() / 2] ^= 1;
  put_file(file, bytes);
  CHECK_FALSE(read_sdf_cache(file, mesh_hash(mesh), 0.02, back, &problem));
  CHECK_THAT(problem, Catch::Contains("checksum"));
  put_file(file, bytes.substr(0, bytes.size() - 3));
  CHECK_FALSE(read_sdf_cache(file, mesh_hash(mesh), 0.02, back, &problem));
  CHECK_THAT(problem, Catch::Contains("truncated"));
  CHECK_FALSE(read_sdf_cache(dir / "absent.sdf", mesh_hash(mesh), 0.02, back, &problem));
  CHECK(problem.empty());  // no cache yet is not a problem
}

TEST_CASE("the field cache lives in $XDG_CACHE_HOME/clothsim, never beside the scene", "[mesh_collider][outputs][cli][long]") {
  TempDir dir("sdf_folder");
  const std::string scene = dir / "bull.json";
  fs::copy_file(fmt::format("{}/scenes/drape_wuson.json", CLOTHSIM_SOURCE_DIR), scene);
  // A field fine enough to take over the second that makes a build worth keeping.
  const std::string args = fmt::format(
      "simulate '{}' --backend cpu --frames 0 --set mesh.voxel_size=0.003 --set cloth.num_width_points=5 "
      "--set cloth.num_height_points=5 --stats",
      scene);
  const std::string env = fmt::format("XDG_CACHE_HOME='{}'", dir / "xdg");
  std::string out;
  REQUIRE(run_binary(args, &out, env) == 0);
  CHECK(listing(dir.path) == std::set<std::string>{"bull.json", "xdg"});  // nothing beside the scene
  const auto kept = listing(dir.path / "xdg/clothsim");
  REQUIRE(kept.size() == 1);
  const std::string cached = (dir.path / "xdg/clothsim" / *kept.begin()).string();
  CHECK_THAT(out, Catch::Contains("kept in " + cached));
  // Read back on the next run...
  REQUIRE(run_binary(args, &out, env) == 0);
  CHECK_THAT(out, Catch::Contains("read from " + cached));
  // ...rebuilt, with a note, once corrupted.
  std::string bytes = slurp(cached);
  bytes[bytes.size() / 3] ^= 4;
  put_file(cached, bytes);
  REQUIRE(run_binary(args, &out, env) == 0);
  CHECK_THAT(out, Catch::Contains("failed its check (its checksum does not match its content); building it again"));
  CHECK(slurp(cached) != bytes);  // written again, whole
  // --no-cache neither reads nor writes it.
  fs::remove_all(dir.path / "xdg");
  REQUIRE(run_binary(args + " --no-cache", &out, env) == 0);
  CHECK_FALSE(fs::exists(dir.path / "xdg"));
}
