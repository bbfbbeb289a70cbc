// Input checks below the command line (issue 41): the file-kind check every reader uses, the
// escaping of names read from files, the PLY header check, the self-collision cost bound and
// the divergence guard's limit and advice for a cloth that is not the default grid.
#include <catch2/catch.hpp>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <fmt/format.h>

#include "cloth/cloth.hpp"
#include "analysis/divergence.hpp"
#include "io/input_file.hpp"
#include "io/ply_check.hpp"
#include "reference/reference.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace clothsim;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("clothsim_test_inputs_" + std::to_string(getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { std::error_code ec; fs::remove_all(path, ec); }
};

void write(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

std::string ply(const std::string& format, int vertices, int faces, const std::string& body) {
  return "ply\r\nformat " + format + " 1.0\ncomment a comment\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n" + body;
}

template <class T> std::string bytes(T v, bool big) {
  std::string b(sizeof v, '\0');
  std::memcpy(b.data(), &v, sizeof v);
  if (big) std::reverse(b.begin(), b.end());
  return b;
}

std::string binary_square(bool big) {
  std::string out;
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (auto& p : v)
    for (float c : p) out += bytes(c, big);
  const int32_t f[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (auto& t : f) {
    out += char(3);
    for (int32_t i : t) out += bytes(i, big);
  }
  return out;
}

}  // namespace

TEST_CASE("input_file_problem names every kind of file that is not a regular one", "[inputs]") {
  TempDir dir;
  CHECK(input_file_problem("").value() == "an empty path (expected the name of a file)");
  CHECK(input_file_problem(dir.path / "none").value() == "does not exist");
  CHECK(input_file_problem(dir.path).value() == "is a directory, not a regular file");
  CHECK(input_file_problem("/dev/zero").value() == "is a character device, not a regular file");
  REQUIRE(mkfifo((dir.path / "fifo").c_str(), 0600) == 0);
  CHECK(input_file_problem(dir.path / "fifo").value() == "is a FIFO (named pipe), not a regular file");
  const int s = socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock = (dir.path / "sock").string();
  REQUIRE(sock.size() < sizeof addr.sun_path);
  std::strcpy(addr.sun_path, sock.c_str());
  REQUIRE(bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  CHECK(input_file_problem(sock).value() == "is a socket, not a regular file");
  close(s);
  write(dir.path / "plain", "12345");
  uint64_t size = 0;
  CHECK_FALSE(input_file_problem(dir.path / "plain", &size));
  CHECK(size == 5);
  CHECK(read_input_file(dir.path / "plain", 5) == "12345");
  CHECK_THROWS_WITH(read_input_file(dir.path / "plain", 4), Catch::Contains("more than the 4 accepted"));
  CHECK_THROWS_WITH(read_input_file(dir.path / "fifo", 100), Catch::Contains("FIFO"));
}

TEST_CASE("printable escapes control characters and keeps everything else", "[inputs]") {
  CHECK(printable("a\x1b[31mb\x07\x7f\tc\n") == "a\\x1b[31mb\\x07\\x7f\\x09c\\x0a");
  CHECK(printable("line\nnext", /*keep_newlines=*/true) == "line\nnext");
  CHECK(printable("ünïcode ok") == "ünïcode ok");
}

TEST_CASE("sound PLY files pass the header check, ASCII and binary of either byte order", "[inputs][mesh]") {
  TempDir dir;
  const std::string ascii = ply("ascii", 4, 2, "0 0 0\n1 0 0\n1 1 0\n0 1 0\n\n3 0 1 2\n3 0 2 3\n");
  const std::pair<std::string, std::string> files[] = {
      {"a.ply", ascii},
      {"le.ply", ply("binary_little_endian", 4, 2, binary_square(false))},
      {"be.ply", ply("binary_big_endian", 4, 2, binary_square(true))},
      {"not_ply.obj", "v 0 0 0\n"},
  };
  for (const auto& [name, text] : files) {
    write(dir.path / name, text);
    const auto problem = ply_problem(dir.path / name, text.size());
    INFO(name << ": " << problem.value_or("none"));
    CHECK_FALSE(problem);
  }
}

TEST_CASE("PLY headers that lie and data that is cut short are named", "[inputs][mesh]") {
  TempDir dir;
  auto problem = [&](const std::string& text) {
    write(dir.path / "m.ply", text);
    return ply_problem(dir.path / "m.ply", text.size()).value_or("none");
  };
  CHECK_THAT(problem(ply("ascii", 4, 2, "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2\n")),
             Catch::Contains("face 1 has 3 values, the header's properties need 4"));
  CHECK_THAT(problem(ply("ascii", 4, 2, "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n")),
             Catch::Contains("truncated: the header promises 2 face elements"));
  CHECK_THAT(problem(ply("ascii", 4, 2, "0 0 0\n1 0 0\n1 1 0 7\n0 1 0\n3 0 1 2\n3 0 2 3\n")),
             Catch::Contains("vertex 2 has 4 values, the header's properties need 3"));
  CHECK_THAT(problem(ply("binary_little_endian", 40000000, 2, binary_square(false))),
             Catch::Contains("the header claims 40000000 vertex elements"));
  const std::string cut = binary_square(true);
  CHECK_THAT(problem(ply("binary_big_endian", 4, 2, cut.substr(0, cut.size() - 1))), Catch::Contains("truncated"));
  CHECK_THAT(problem("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n"), Catch::Contains("count of \"-3\""));
  CHECK_THAT(problem("ply\nformat ascii 1.0\nelement vertex 3\n"), Catch::Contains("without end_header"));
}

TEST_CASE("self-collision with a thickness many times the spacing is refused with its cost", "[inputs]") {
  // 41 x 41 over 1 m: spacing 0.025 m; a thickness of 0.75 m is 30 spacings.
  const std::string scene = R"({"cloth": {"width": 1, "height": 1, "num_width_points": 41, "num_height_points": 41,
      "orientation": 0, "thickness": THICK}, "simulation": {"self_collision": true}})";
  auto with = [&](const std::string& t) { return parse_scene(std::regex_replace(scene, std::regex("THICK"), t), "t.json"); };
  auto check = [](const Scene& s) { check_self_collision_cost(s, build_cloth(s)); };
  try {
    // make_constants does this for every run of either backend.
    make_constants<double>(with("0.75"), build_cloth(with("0.75")));
    FAIL("expected a SceneError");
  } catch (const SceneError& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Catch::Contains("t.json: cloth.thickness: 0.75 m is 30 x the particle spacing (0.025 m)"));
    CHECK_THAT(m, Catch::Contains("compare each particle with about 1681 others"));
    CHECK_THAT(m, Catch::Contains("expected a thickness of at most 0.132 m"));
  }
  CHECK_NOTHROW(check(with("0.13")));  // the largest accepted, as the message says
  // Without self-collision the thickness costs nothing.
  CHECK_NOTHROW(check(parse_scene(std::regex_replace(scene, std::regex("THICK"), "0.75"), "t.json",
                                  {"simulation.self_collision=false"})));
}

TEST_CASE("the divergence guard measures a mesh cloth by its own extent and masses", "[inputs][divergence]") {
  TempDir dir;
  // A 3 m x 3 m square modelled in millimetres, two triangles: nothing moves, nothing diverged.
  write(dir.path / "mm.obj", "v 0 0 0\nv 3000 0 0\nv 3000 3000 0\nv 0 3000 0\nf 1 2 3\nf 1 3 4\n");
  write(dir.path / "mm.json", R"({"cloth": {"mesh": "mm.obj", "thickness": 0.01, "ks": 1e20, "pinned_vertices": [0]}})");
  const Scene scene = load_scene(dir.path / "mm.json");
  const ClothModel model = build_cloth(scene);
  std::vector<Vec4<double>> start;
  for (const glm::dvec3& p : model.initial) start.emplace_back(p.x, p.y, p.z, 1.0);
  FrameCheck still{1, {}};
  still.bounds = check_divergence(start);
  const auto said = divergence_message(scene, model, still);
  CHECK_FALSE(said);
  // Blown up: the advice names the model's lightest free mass, not the grid's default.
  FrameCheck nan{2, {}};
  nan.bounds.finite = false;
  const std::string m = divergence_message(scene, model, nan).value_or("");
  double lightest = HUGE_VAL;
  for (size_t i = 1; i < model.mass.size(); ++i) lightest = std::min(lightest, model.mass[i]);
  INFO(m);
  CHECK_THAT(m, Catch::Contains(fmt::format("on {:.3g} kg particles", lightest)));
}

TEST_CASE("divergence advice never suggests a value the loader refuses", "[inputs][divergence]") {
  const std::string text = R"({"cloth": {"width": 1, "height": 1, "num_width_points": 5, "num_height_points": 7,
      "orientation": 0, "thickness": 0.01, "ks": 1e15}, "simulation": {"simulation_steps": STEPS}})";
  for (const char* steps : {"30", "60000", "100000"}) {
    const Scene scene = parse_scene(std::regex_replace(text, std::regex("STEPS"), steps), "d.json");
    const ClothModel model = build_cloth(scene);
    FrameCheck nan{1, {}};
    nan.bounds.finite = false;
    const std::string m = divergence_message(scene, model, nan).value_or("");
    INFO(m);
    std::smatch set;
    if (std::regex_search(m, set, std::regex("--set ([a-z_.]+=[0-9.e+]+)")))
      CHECK_NOTHROW(parse_scene(std::regex_replace(text, std::regex("STEPS"), steps), "d.json", {set[1].str()}));
    else
      CHECK(std::string(steps) == "100000");  // at the largest: only a softer cloth is advised
    CHECK_THAT(m, Catch::Contains("Lower cloth.ks"));
  }
}
