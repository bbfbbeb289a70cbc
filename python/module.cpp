// The compiled half of `import clothsim` (python/clothsim/__init__.py is the other): Session
// bound with pybind11. Arrays cross as numpy float64 (N, 3) copies, built and read without a
// Python loop; every call that touches the simulation releases the GIL, so other Python
// threads run while a cloth steps. Errors keep the command line's messages: bad input
// (exit 2) is ValueError, no OpenGL 4.3 context (exit 3) RuntimeError, a diverged run
// (exit 1) clothsim.DivergenceError, a subclass of RuntimeError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "session.hpp"

namespace py = pybind11;
using clothsim::ExitError;
using clothsim::Session;

namespace {

PyObject* divergence_error = nullptr;

py::array_t<double> as_array(const std::vector<double>& xyz) {
  py::array_t<double> a({py::ssize_t(xyz.size() / 3), py::ssize_t(3)});
  std::copy(xyz.begin(), xyz.end(), a.mutable_data());
  return a;
}

// Runs f with the GIL released and this Session's calls serialised.
template <class F> auto unlocked(Session& s, F&& f) {
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(s.mutex());
  return f();
}

std::string python_advice(std::string message) {
  // The command line's advice, in this face's words.
  const std::string flag = "--backend cpu";
  if (const size_t at = message.find(flag); at != std::string::npos) message.replace(at, flag.size(), "backend=\"cpu\"");
  return message;
}

std::unique_ptr<Session> open_session(const std::string& scene, bool is_text, const std::string& backend,
                                      const std::vector<std::string>& overrides) {
  if (backend != "gpu" && backend != "cpu")
    throw ExitError(clothsim::kExitBadInput, "backend " + backend + ": expected \"gpu\" or \"cpu\"");
  py::gil_scoped_release release;
  clothsim::Scene s = is_text ? clothsim::parse_scene(scene, "<dict>", overrides) : clothsim::load_scene(scene, overrides);
  return std::make_unique<Session>(std::move(s), clothsim::parse_backend(backend));
}

// The scene after its overrides, every parameter written out and every file it names made
// absolute: a sweep's run keeps it as runs/ID/scene.json, which simulates the same run from
// wherever it is.
std::string resolve_scene(const std::string& scene, bool is_text, const std::vector<std::string>& overrides) {
  clothsim::Scene s = is_text ? clothsim::parse_scene(scene, "<dict>", overrides) : clothsim::load_scene(scene, overrides);
  s.cloth.mesh = s.cloth.mesh.empty() ? "" : std::filesystem::absolute(s.cloth.mesh_path).lexically_normal().string();
  for (auto& c : s.extra_cloths)
    c.mesh = c.mesh.empty() ? "" : std::filesystem::absolute(c.mesh_path).lexically_normal().string();
  for (auto& m : s.meshes) m.file = std::filesystem::absolute(m.file_path).lexically_normal().string();
  return clothsim::scene_to_json(s);
}

}  // namespace

PYBIND11_MODULE(_clothsim, m) {
  m.doc() = "clothsim's simulation core; use the clothsim package, not this module";
  divergence_error = PyErr_NewException("clothsim.DivergenceError", PyExc_RuntimeError, nullptr);
  m.attr("DivergenceError") = py::handle(divergence_error);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ExitError& e) {
      PyObject* type = e.code == clothsim::kExitBadInput    ? PyExc_ValueError
                       : e.code == clothsim::kExitCheckFailed ? divergence_error
                                                              : PyExc_RuntimeError;
      PyErr_SetString(type, python_advice(e.what()).c_str());
    } catch (const clothsim::SceneError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  m.def("resolve_scene", &resolve_scene, py::arg("scene"), py::arg("is_text"), py::arg("overrides"));

  py::class_<Session>(m, "Session")
      .def(py::init(&open_session), py::arg("scene"), py::arg("is_text"), py::arg("backend"), py::arg("overrides"))
      .def("step", [](Session& s, int frames) { unlocked(s, [&] { s.step(frames); }); })
      .def("positions", [](Session& s) { return as_array(unlocked(s, [&] { return s.positions(); })); })
      .def("velocities", [](Session& s) { return as_array(unlocked(s, [&] { return s.velocities(); })); })
      .def("set_positions",
           [](Session& s, py::array_t<double, py::array::c_style | py::array::forcecast> a) {
             if (a.ndim() != 2 || a.shape(1) != 3 || size_t(a.shape(0)) != s.particles())
               throw py::value_error("set_positions: expected an array of shape (" + std::to_string(s.particles()) +
                                     ", 3)");
             std::vector<double> xyz(a.data(), a.data() + a.size());
             unlocked(s, [&] { s.set_positions(xyz); });
           })
      .def("stats", [](Session& s) { return unlocked(s, [&] { return s.stats().dump(); }); })
      .def("export", [](Session& s, const std::string& path) { unlocked(s, [&] { s.export_obj(path); }); })
      .def("render",
           [](Session& s, const std::string& path, const std::string& shader, int w, int h) {
             unlocked(s, [&] { s.render(path, shader, w, h); });
           })
      .def_property_readonly("frame", &Session::frame)
      .def_property_readonly("particles", &Session::particles)
      .def_property_readonly("backend", &Session::backend_name)
      .def_property_readonly("dt", [](const Session& s) { return s.scene().dt(); })
      .def_property_readonly("source", [](const Session& s) { return s.scene().source; });
}
