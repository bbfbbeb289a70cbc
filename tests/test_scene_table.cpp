// The parameter table's machinery on kinds of rows the scene does not use yet (an enum stored
// as a string, optional nested objects): the loader, the writer and the docs handle them from
// the rows alone, so the upcoming solver and wind parameters are one row each.
#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/param_doc.hpp"
#include "scene/scene_table.hpp"

namespace clothsim {
namespace {

enum class DemoSolver { Classic, Fabric };
constexpr const char* kSolverNames[] = {"classic", "fabric"};
constexpr RemovedChoice kRemovedNames[] = {{"xpbd", "removed: use \"fabric\""}};

struct Gust {
  double strength = 1;
  double period = 2;
  bool operator==(const Gust&) const = default;
};
struct Wind {
  glm::dvec3 velocity{0.0};
  std::optional<Gust> gust;
  bool operator==(const Wind&) const = default;
};
struct Demo {
  DemoSolver solver = DemoSolver::Classic;
  std::optional<Wind> wind;
  int iterations = 3;
  bool operator==(const Demo&) const = default;
};

}  // namespace

template <> std::span<const Param<Gust>> param_rows<Gust>() {
  static const Param<Gust> rows[] = {
      row<&Gust::strength>({.key = "strength", .lo = 0, .expected = "a strength >= 0"}),
      row<&Gust::period>({.key = "period", .lo = 1e-9, .expected = "a period > 0 (seconds)", .unit = "s"}),
  };
  return rows;
}
template <> std::span<const Param<Wind>> param_rows<Wind>() {
  static const Param<Wind> rows[] = {
      row<&Wind::velocity>({.key = "velocity", .required = true, .unit = "m/s"}),
      row<&Wind::gust>({.key = "gust"}),
  };
  return rows;
}
template <> std::span<const Param<Demo>> param_rows<Demo>() {
  static const Param<Demo> rows[] = {
      row<&Demo::solver>({.key = "solver", .choices = kSolverNames, .removed_choices = kRemovedNames}),
      row<&Demo::wind>({.key = "wind"}),
      row<&Demo::iterations>({.key = "iterations", .lo = 1, .hi = 10}),
  };
  return rows;
}

namespace {

Demo read(const std::string& text) {
  Demo d;
  read_params(nlohmann::json::parse(text), "t.json", "", d);
  return d;
}

std::string error(const std::string& text) {
  try {
    read(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  FAIL("expected a SceneError for " << text);
  return {};
}

}  // namespace

TEST_CASE("table rows: absent keys keep the struct's defaults, optional objects stay absent", "[scene][table]") {
  const Demo d = read("{}");
  CHECK(d == Demo{});
  CHECK_FALSE(d.wind.has_value());
  CHECK(write_params(d) == nlohmann::json{{"solver", "classic"}, {"iterations", 3}});
}

TEST_CASE("table rows: an enum as a string and nested optional objects load and write back", "[scene][table]") {
  const Demo d = read(R"({"solver": "fabric", "wind": {"velocity": [1, 0, 2], "gust": {"strength": 3}}})");
  CHECK(d.solver == DemoSolver::Fabric);
  REQUIRE(d.wind.has_value());
  CHECK(d.wind->velocity == glm::dvec3(1, 0, 2));
  REQUIRE(d.wind->gust.has_value());
  CHECK(d.wind->gust->strength == 3);
  CHECK(d.wind->gust->period == 2);  // the default inside a present object
  const nlohmann::json j = write_params(d);
  CHECK(j["solver"] == "fabric");
  CHECK(j["wind"]["gust"]["period"] == 2.0);
  Demo back;
  read_params(j, "back.json", "", back);
  CHECK(back == d);
  CHECK_FALSE(read(R"({"wind": {"velocity": [0, 0, 0]}})").wind->gust.has_value());
}

TEST_CASE("table rows: errors name the key path of nested rows", "[scene][table]") {
  CHECK(error(R"({"solver": "fast"})") == R"(t.json: solver: expected one of "classic", "fabric", got string "fast")");
  CHECK(error(R"({"solver": 1})") == R"(t.json: solver: expected one of "classic", "fabric", got number 1)");
  // A removed name: its own message, then what is taken.
  CHECK(error(R"({"solver": "xpbd"})") == R"(t.json: solver: "xpbd": removed: use "fabric"; expected one of "classic", "fabric")");
  CHECK(error(R"({"wind": {}})") == "t.json: wind.velocity: missing required key (expected an array of 3 numbers)");
  CHECK(error(R"({"wind": {"velocity": [0, 0, 0], "gust": {"strength": -1}}})") ==
        "t.json: wind.gust.strength: expected a strength >= 0, got -1");
  CHECK(error(R"({"wind": {"velocity": [0, 0, 0], "gust": {"colour": 1}}})") == "t.json: wind.gust.colour: unknown key");
  CHECK(error(R"({"wind": 5})") == "t.json: wind: expected an object, got number 5");
  CHECK(error(R"({"iterations": 11})") == "t.json: iterations: expected an integer in [1, 10], got 11");
}

TEST_CASE("the parameter reference lists every scene key with its default", "[scene][table]") {
  const std::string md = parameters_markdown();
  for (const char* row : {"| `ks` | number | 5000 |", "| `gravity` | [x, y, z] | [0, -9.8, 0] |",
                          "| `radius` | number | **required** |", "| `self_collision` | boolean | true |",
                          "## `sphere`", "## `simulation`", "in g/cm^2 (= density × 0.1)"})
    CHECK_THAT(md, Catch::Contains(row));
}

}  // namespace clothsim
