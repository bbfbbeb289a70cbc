// The machinery of the scene parameter table (scene_table.cpp holds the rows).
//
// Every scene parameter is one row: its JSON key, valid range, unit, meaning and how the viewer
// shows it, plus the struct member it lives in. Everything that deals with parameters one by
// one (the loader, scene_to_json, the viewer's Simulation panel, the fuzz property, the
// generated docs/parameters.md) walks the rows with a ParamVisitor, so none of them names a
// parameter and a new row reaches all of them at once.
//
// A visitor always gets the member by reference: the loader writes it, the others read it
// (const callers visit a copy). Nested objects and lists of objects reach the visitor as an
// ObjectRef / ListRef that can visit the rows of the element, so a visitor never needs to know
// the element's C++ type.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

namespace clothsim {

// How the viewer's Simulation panel shows a row. Values are shown as value * scale, so that a
// parameter can be edited in the unit people think in (density in g/cm^2, scale 0.1).
struct Widget {
  enum Style { Hidden, Drag, Checkbox, ReadOnly };  // ReadOnly: changing it rebuilds the cloth
  // A list row (the cloths): Hidden, the panel shows none of its elements (colliders: edit the
  // file); any other style, it shows the rows of each element.
  Style style = Hidden;
  float speed = 1;        // drag speed, in shown units per pixel
  double lo = 0, hi = 0;  // drag and clamp range in shown units (lo == hi: unclamped)
  const char* format = "%.3f";
  double scale = 1;
  const char* unit = nullptr;  // shown unit when it differs from the row's (nullptr: the row's)
};

// Which kind of cloth a row belongs to. A cloth object that has the key kMeshKey is a mesh
// cloth, any other a grid: a row of the other kind must be absent (the loader names both keys,
// with the row's `instead`), is never required, and is not written.
enum class Shape : unsigned char { Any, Grid, Mesh };
inline constexpr const char* kMeshKey = "mesh";

// A name a choice row took once and now refuses with `message` (what to use instead).
struct RemovedChoice {
  const char* name;
  const char* message;
};

// Everything about a row but the member it lives in.
struct ParamInfo {
  const char* key;              // JSON key, also the C++ member name and the viewer's label
  bool required = false;        // else absent means the struct's default member initialiser;
                                // a required list (the cloths) needs at least one element
  double lo = -HUGE_VAL;        // valid range of a number or integer, inclusive
  double hi = HUGE_VAL;
  const char* expected = "";    // a number out of range: "expected <this>, got 5" (the loader's message)
  const char* unit = "";        // for docs and labels; empty when dimensionless
  const char* meaning = "";     // one line for docs/parameters.md
  Widget widget = {};
  std::span<const char* const> choices = {};  // an enum stored as a JSON string: its names, by value
  std::span<const RemovedChoice> removed_choices = {};  // names no longer taken, each with its message
  bool one_or_many = false;     // a list that may also be written as a single object (sphere, plane)
  bool single_as_object = false;  // one_or_many, and a list of one is written as that object (cloth)
  Shape shape = Shape::Any;
  // A row of one Shape given to a cloth of the other: the end of the loader's message, after
  // "cloth.mesh and cloth.width: " (a grid row) or "cloth.scale is for a mesh cloth
  // (cloth.mesh); " (a mesh row). "{}" stands for the cloth's key path and a dot ("cloth.").
  const char* instead = "";
  // A rule the range cannot say (the plane normal), run by the loader right after a vec3 row is
  // read: may adjust the value, and returns the "expected ..." message of a bad one, else nullptr.
  const char* (*after_read)(glm::dvec3&) = nullptr;
  // A text row that also takes a non-negative integer, kept as its digits (mesh.animation).
  bool index_or_name = false;
  // An object row that may also be written as a string: the string is the value of this key of
  // the object (cloth.material: "cotton" is {"preset": "cotton"}).
  const char* string_as = nullptr;
};

class ParamVisitor;

// A nested object: visit its rows. `present` is false for an optional object the scene leaves
// out (the rows of a default element can still be visited, for docs).
class ObjectRef {
 public:
  virtual bool optional() const = 0;
  virtual bool present() const = 0;
  virtual void set_present(bool) = 0;          // creates a default element, or drops it
  virtual void visit(ParamVisitor& v) = 0;     // the rows of the element (present, or a default)
 protected:
  ~ObjectRef() = default;
};

// A list of objects (colliders): visit the rows of element i, or of a default element.
class ListRef {
 public:
  virtual size_t size() const = 0;
  virtual void resize(size_t n) = 0;
  virtual void visit(size_t i, ParamVisitor& v) = 0;
  virtual void visit_default(ParamVisitor& v) = 0;
 protected:
  ~ListRef() = default;
};

using GridIndices = std::vector<std::array<int, 2>>;
struct Keyframe;
using Keyframes = std::vector<Keyframe>;

// One method per kind of value a row can hold.
class ParamVisitor {
 public:
  virtual void number(const ParamInfo&, double&) = 0;
  virtual void integer(const ParamInfo&, int&) = 0;
  virtual void boolean(const ParamInfo&, bool&) = 0;
  virtual void vec3(const ParamInfo&, glm::dvec3&) = 0;
  virtual void choice(const ParamInfo&, int& index) = 0;  // index into info.choices
  // A string (the mesh file, as the scene writes it): UTF-8, non-empty when present.
  virtual void text(const ParamInfo&, std::string&) = 0;
  // `[warp, weft]`, or one number for both (a material's stretch and bending).
  virtual void pair(const ParamInfo&, std::array<double, 2>&) = 0;
  // `[i, ...]`: integers in [info.lo, info.hi] (pinned_vertices: >= 0; the mesh builder checks
  // them against the mesh).
  virtual void indices(const ParamInfo&, std::vector<int>&) = 0;
  // Special case: `pinned`, a list of [x, y] indices into the owner's nw x nh grid.
  virtual void grid_indices(const ParamInfo&, GridIndices&, int nw, int nh) = 0;
  // `[[t, [x, y, z]], ...]`: times finite, >= 0 and strictly ascending, values finite.
  virtual void keyframes(const ParamInfo&, Keyframes&) = 0;
  virtual void object(const ParamInfo&, ObjectRef&) = 0;
  virtual void list(const ParamInfo&, ListRef&) = 0;
 protected:
  ~ParamVisitor() = default;
};

// A row: the info and the function that hands the member to a visitor.
template <class S>
struct Param {
  ParamInfo info;
  void (*visit)(S&, const ParamInfo&, ParamVisitor&);
};

// The rows of a struct, in the order the loader reads them (so the first error reported is the
// same one as before the table). Defined for each scene struct in scene_table.cpp.
template <class S>
std::span<const Param<S>> param_rows();

template <class S>
void visit_rows(S& s, ParamVisitor& v) {
  for (const Param<S>& p : param_rows<S>()) p.visit(s, p.info, v);
}

namespace detail {

template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type {};
template <class T> struct is_vector : std::false_type {};
template <class T> struct is_vector<std::vector<T>> : std::true_type {};

template <class M> struct member_traits;
template <class S, class T> struct member_traits<T S::*> { using owner = S; using type = T; };

template <class Sub>
class OptionalObject final : public ObjectRef {
 public:
  explicit OptionalObject(std::optional<Sub>& o) : o_(o) {}
  bool optional() const override { return true; }
  bool present() const override { return o_.has_value(); }
  void set_present(bool p) override { if (!p) o_.reset(); else if (!o_) o_.emplace(); }
  void visit(ParamVisitor& v) override {
    if (o_) { visit_rows(*o_, v); return; }
    Sub d{};
    visit_rows(d, v);
  }
 private:
  std::optional<Sub>& o_;
};

template <class Sub>
class PlainObject final : public ObjectRef {
 public:
  explicit PlainObject(Sub& o) : o_(o) {}
  bool optional() const override { return false; }
  bool present() const override { return true; }
  void set_present(bool) override {}
  void visit(ParamVisitor& v) override { visit_rows(o_, v); }
 private:
  Sub& o_;
};

template <class Sub>
class VectorList final : public ListRef {
 public:
  explicit VectorList(std::vector<Sub>& l) : l_(l) {}
  size_t size() const override { return l_.size(); }
  void resize(size_t n) override { l_.resize(n); }
  void visit(size_t i, ParamVisitor& v) override { visit_rows(l_[i], v); }
  void visit_default(ParamVisitor& v) override { Sub d{}; visit_rows(d, v); }
 private:
  std::vector<Sub>& l_;
};

template <auto M>
void visit_member(typename member_traits<decltype(M)>::owner& s, const ParamInfo& info, ParamVisitor& v) {
  using T = typename member_traits<decltype(M)>::type;
  T& m = s.*M;
  if constexpr (std::is_same_v<T, double>) v.number(info, m);
  else if constexpr (std::is_same_v<T, int>) v.integer(info, m);
  else if constexpr (std::is_same_v<T, bool>) v.boolean(info, m);
  else if constexpr (std::is_same_v<T, glm::dvec3>) v.vec3(info, m);
  else if constexpr (std::is_same_v<T, std::string>) v.text(info, m);
  else if constexpr (std::is_same_v<T, std::array<double, 2>>) v.pair(info, m);
  else if constexpr (std::is_same_v<T, std::vector<int>>) v.indices(info, m);  // before the list of objects
  else if constexpr (std::is_same_v<T, GridIndices>) v.grid_indices(info, m, s.num_width_points, s.num_height_points);
  else if constexpr (std::is_same_v<T, Keyframes>) v.keyframes(info, m);  // before the list of objects
  else if constexpr (std::is_enum_v<T>) {
    // An enum is a JSON string when the row names its values, else its integer (orientation 0/1).
    int i = int(m);
    if (info.choices.empty()) v.integer(info, i); else v.choice(info, i);
    m = T(i);
  } else if constexpr (is_optional<T>::value) {
    OptionalObject<typename T::value_type> ref(m);
    v.object(info, ref);
  } else if constexpr (is_vector<T>::value) {
    VectorList<typename T::value_type> ref(m);
    v.list(info, ref);
  } else {
    PlainObject<T> ref(m);
    v.object(info, ref);
  }
}

}  // namespace detail

// A row for member M: `row<&ClothParams::ks>({.key = "ks", ...})`.
template <auto M>
constexpr Param<typename detail::member_traits<decltype(M)>::owner> row(ParamInfo info) {
  return {info, &detail::visit_member<M>};
}

}  // namespace clothsim
