// pdesurf._core: models, solved surfaces, meshes, editing sessions, errors and threads, bound
// over the public headers (core.hpp says what this binding may include). tools.cpp binds the
// mesh tools (compare, slice, rebuild's steps, export).
#include "core.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <tbb/global_control.h>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model_info.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/sections.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::python {

namespace {

// ---------------------------------------------------------------------------------------
// Errors: pdesurf::Error and its kinds (pdesurf/error.hpp) as pdesurf.Error and its
// subclasses (python/pdesurf/_errors.py), file, path and message taken from the error's
// accessors; the standard library's out_of_range and length_error (an index or a size past
// a container's) as ValueError.

/// The Python class of a library error: the class of its most derived kind.
const char* pythonClass(const Error& e) {
  if (dynamic_cast<const ModelError*>(&e)) return "ModelError";
  if (dynamic_cast<const MeshIoError*>(&e)) return "MeshIOError";
  if (dynamic_cast<const FileError*>(&e)) return "FileError";
  if (dynamic_cast<const LayoutError*>(&e)) return "LayoutError";
  if (dynamic_cast<const MeshSliceError*>(&e)) return "SliceError";
  if (dynamic_cast<const SectionError*>(&e)) return "SectionError";
  if (dynamic_cast<const InvalidArgument*>(&e)) return "InvalidArgumentError";
  if (dynamic_cast<const CadError*>(&e)) return "CadError";
  if (dynamic_cast<const NurbsToleranceError*>(&e)) return "ToleranceError";
  if (dynamic_cast<const LoftError*>(&e)) return "LoftError";
  return "Error";
}

/// Sets the Python error of class `cls` (pdesurf._errors) with the library's whole text and
/// its parts; a part the error leaves empty is None.
void raise(const char* cls, const Error& e) {
  auto part = [](const std::string& s) { return s.empty() ? py::object(py::none()) : py::str(s); };
  const py::object type = py::module_::import("pdesurf._errors").attr(cls);
  const py::object error =
      type(e.what(), py::arg("message") = py::str(e.message()), py::arg("file") = part(e.file()),
           py::arg("path") = part(e.jsonPath()));
  PyErr_SetObject(type.ptr(), error.ptr());
}

void translate(std::exception_ptr thrown) {
  try {
    std::rethrow_exception(thrown);
  } catch (const py::builtin_exception&) {
    throw;  // the binding's own ValueErrors (badArgument): pybind11 raises them
  } catch (const py::error_already_set&) {
    throw;  // a Python exception (a progress callback's) passes through as it was
  } catch (const Error& e) {
    raise(pythonClass(e), e);
  } catch (const std::out_of_range& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const std::length_error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());  // a size past what a container holds
  } catch (const std::bad_alloc&) {
    PyErr_SetString(PyExc_MemoryError, "pdesurf: out of memory");
  } catch (const std::runtime_error& e) {
    raise("Error", Error(e.what()));  // a dependency's (a file system's): its text alone
  }
}

// ---------------------------------------------------------------------------------------
// Models and surfaces.

/// JSON text from a str, or from a dict through json.dumps.
std::string jsonText(const py::object& value, const char* name) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value))
    return py::module_::import("json").attr("dumps")(value).cast<std::string>();
  badArgument(name, "expected JSON text (str) or a dict, got " +
                        py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

// A type branch kept: the Python properties of vertex frames (vertices, frames, a1, a2) are
// that method's own data.
const VertexFrameModel& framesOf(const Model& model) {
  const auto* frames = model.model->as<VertexFrameModel>();
  if (!frames)
    throw py::type_error(std::string("a vertex-frames model only; this one is ") +
                         modelTypeName(*model.model));
  return *frames;
}

py::array_t<double> vectorRows(std::size_t rows, auto&& row) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows; ++i) {
    const Vec3 p = row(i);
    for (py::ssize_t c = 0; c < 3; ++c) o(static_cast<py::ssize_t>(i), c) = p[c];
  }
  return out;
}

/// A property of Model: a1 or a2 of every frame, (K, 3).
auto frameParameter(Vec3 Frame::*parameter) {
  return [parameter](const Model& self) {
    const VertexFrameModel& f = framesOf(self);
    return vectorRows(f.frames.size(), [&](std::size_t k) { return f.frames[k].*parameter; });
  };
}

SolveOptions solveOptions(const AnyModel& model, const std::string& solver,
                          std::uint32_t seedFrame) {
  if (solver != "global" && solver != "local")
    badArgument("solver", "'" + solver + "' is neither 'global' nor 'local'");
  SolveOptions options;
  options.vertexFrames = {solver == "local" ? Solver::Local : Solver::Global, seedFrame};
  try {
    checkSolveOptions(model, options);
  } catch (const InvalidArgument& e) {
    badArgument("seed_frame", e.what());
  }
  return options;
}

std::shared_ptr<SolvedModel> solve(const Model& model, const std::string& solver,
                                   std::uint32_t seedFrame) {
  const SolveOptions options = solveOptions(*model.model, solver, seedFrame);
  py::gil_scoped_release release;
  return std::make_shared<SolvedModel>(pdesurf::solve(model.model, model.source, options));
}

// The patches of a solved model, their domains and evaluation: the library's solved-model
// interface (SolvedSurface, model.hpp).
std::size_t patchCount(const SolvedModel& solved) { return solved.surface().patchCount(); }

/// Patch k's parameter domain {u0, u1, v0, v1}: the unit square, or a spectral patch's
/// shown u range and v ∈ [0, 2π] (the parameters `sample` spans).
std::array<double, 4> patchDomain(const SolvedModel& solved, std::size_t k) {
  const PatchDomain d = solved.surface().domain(k);
  return {d.u0, d.u1, d.v0, d.v1};
}

SurfacePoint evaluatePatch(const SolvedModel& solved, std::size_t k, double u, double v) {
  return solved.surface().evaluate(k, u, v);
}

py::tuple evaluate(const SolvedModel& solved, const py::object& patch, const py::object& u,
                   const py::object& v) {
  // Broadcast the three to one shape, then check them flat.
  const py::tuple shaped = py::module_::import("numpy").attr("broadcast_arrays")(
      py::array::ensure(patch), py::array::ensure(u), py::array::ensure(v));
  const py::array first = shaped[0];
  const py::ssize_t n = first.size();
  const auto ravel = [&](int i) {
    return py::array(py::module_::import("numpy").attr("reshape")(shaped[i], py::make_tuple(n, 1)));
  };
  const std::vector<std::uint32_t> patches = indexRows(ravel(0), "patch", 1, patchCount(solved));
  const auto us = floatRows(ravel(1), "u", 1), vs = floatRows(ravel(2), "v", 1);
  std::vector<SurfacePoint> out(static_cast<std::size_t>(n));
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = evaluatePatch(solved, patches[i], us.data()[i], vs.data()[i]);
  }
  py::list shape;
  for (py::ssize_t d = 0; d < first.ndim(); ++d) shape.append(first.shape(d));
  shape.append(3);
  const auto rows = [&](Vec3 SurfacePoint::*member) {
    py::array a = vectorRows(out.size(), [&](std::size_t i) { return out[i].*member; });
    return a.attr("reshape")(shape);
  };
  return py::make_tuple(rows(&SurfacePoint::p), rows(&SurfacePoint::du), rows(&SurfacePoint::dv));
}

py::array sampleGrid(const SolvedModel& solved, std::uint32_t grid) {
  if (grid < 2 || grid > 4097)
    badArgument("grid", "must be 2 to 4097, got " + std::to_string(grid));
  std::vector<PatchSamples> samples;
  {
    py::gil_scoped_release release;
    samples = sample(solved, {grid});
  }
  const auto n = static_cast<py::ssize_t>(grid);
  py::array_t<double> out({static_cast<py::ssize_t>(samples.size()), n, n, py::ssize_t{3}});
  double* o = out.mutable_data();
  for (const PatchSamples& p : samples)
    for (const Vec3& q : p.points) {
      o[0] = q.x();
      o[1] = q.y();
      o[2] = q.z();
      o += 3;
    }
  return out;
}

/// The model of arrays: every argument checked here (ValueError naming it), then the whole
/// model by the file parser (ModelError), as if it had been read from a file.
Model vertexFrameModel(const py::object& vertices, const py::object& frames, const py::object& a1,
                       const py::object& a2, const py::list& forces, const py::list& shared,
                       const std::string& name) {
  VertexFrameModel model;
  model.name = name;
  model.vertices = points(floatRows(vertices, "vertices", 3));
  const std::vector<std::uint32_t> corners = indexRows(frames, "frames", 8, model.vertices.size());
  const std::size_t count = corners.size() / 8;
  const std::vector<Vec3> a1s = points(floatRows(a1, "a1", 3)),
                          a2s = points(floatRows(a2, "a2", 3));
  if (a1s.size() != count)
    badArgument("a1", "expected one row per frame (" + std::to_string(count) + ")");
  if (a2s.size() != count)
    badArgument("a2", "expected one row per frame (" + std::to_string(count) + ")");
  model.frames.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t s = 0; s < 8; ++s) model.frames[k].vertices[s] = corners[8 * k + s];
    model.frames[k].a1 = a1s[k];
    model.frames[k].a2 = a2s[k];
  }
  for (const py::handle item : forces) {
    const auto force = item.cast<py::dict>();
    const std::uint32_t frame =
        indexRows(py::make_tuple(force["frame"]), "forces: frame", 0, count)[0];
    FrameForce f;
    f.f0 = points(floatRows(py::make_tuple(force["f0"]), "forces: f0", 3))[0];
    if (force.contains("region")) {
      const auto r = floatRows(py::make_tuple(force["region"]), "forces: region", 4);
      f.region = {r.at(0, 0), r.at(0, 1), r.at(0, 2), r.at(0, 3)};
    }
    model.frames[frame].forces.push_back(f);
  }
  for (const py::handle item : shared) {
    const auto force = item.cast<py::dict>();
    SharedForce f;
    f.f0 = points(floatRows(py::make_tuple(force["f0"]), "shared_forces: f0", 3))[0];
    f.frames = indexRows(force["frames"], "shared_forces: frames", 0, count);
    model.forces.push_back(f);
  }
  const std::string source = "<arrays>";
  return {std::make_shared<const AnyModel>(parseModel(serializeVertexFrameModel(model), source)),
          source};
}

/// A property of Mesh: one of its buffers as a read-only array of rows of `cols` values (0:
/// one dimension) viewing it in place; None for an empty `optional` buffer.
template <class T>
auto bufferView(MeshBuffer<T> Mesh::*buffer, std::size_t cols, bool optional) {
  return [buffer, cols, optional](const py::object& self) -> py::object {
    const MeshBuffer<T>& b = self.cast<const Mesh&>().*buffer;
    if (optional && b.empty()) return py::none();
    return viewRows(b.data(), cols ? b.size() / cols : b.size(), cols, self);
  };
}

// ---------------------------------------------------------------------------------------
// Threads: the CLI's --threads, as a module setting.

struct ThreadLimit {
  std::optional<tbb::global_control> control;
  unsigned count = 0;
};
ThreadLimit& threadLimit() {
  static auto* limit = new ThreadLimit;  // never destroyed: alive until the process ends
  return *limit;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Array arguments.

void badArgument(const char* name, const std::string& problem) {
  throw py::value_error(std::string(name) + ": " + problem);
}

namespace {
std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The argument as a numpy array of the wanted kinds and shape (n, cols), or (n,) for cols 0.
py::array checkedArray(const py::object& value, const char* name, py::ssize_t cols,
                       const std::string& kinds, const char* expected) {
  if (value.is_none()) badArgument(name, std::string("expected ") + expected + ", got None");
  py::array a = py::array::ensure(value);
  if (!a) badArgument(name, std::string("expected ") + expected + " (not an array of numbers)");
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string::npos)
    badArgument(name, std::string("expected ") + expected + ", got dtype " +
                          py::str(a.dtype()).cast<std::string>());
  const bool rows = cols > 0;
  if (a.ndim() != (rows ? 2 : 1) || (rows && a.shape(1) != cols))
    badArgument(name, "expected shape " + (rows ? "(n, " + std::to_string(cols) + ")" : "(n,)") +
                          ", got " + shapeText(a));
  return a;
}
}  // namespace

py::array_t<double, py::array::c_style> floatRows(const py::object& value, const char* name,
                                                  py::ssize_t cols) {
  const py::array a = checkedArray(value, name, cols, "fiu", "an array of real numbers");
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  const double* d = rows.data();
  for (py::ssize_t i = 0; i < rows.size(); ++i)
    if (!std::isfinite(d[i]))
      badArgument(name, "row " + std::to_string(i / cols) + " is not finite (" +
                            py::str(py::float_(d[i])).cast<std::string>() + ")");
  return rows;
}

std::vector<std::uint32_t> indexRows(const py::object& value, const char* name, py::ssize_t cols,
                                     std::uint64_t bound) {
  const py::array a = checkedArray(value, name, cols, "iu", "an array of integers");
  const auto wide = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  std::vector<std::uint32_t> out(static_cast<std::size_t>(wide.size()));
  const std::int64_t* d = wide.data();
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (d[i] < 0 || static_cast<std::uint64_t>(d[i]) >= bound)
      badArgument(name, "index " + std::to_string(d[i]) + " (row " +
                            std::to_string(cols > 0 ? i / static_cast<std::size_t>(cols) : i) +
                            ") is out of range: " +
                            (bound == 0 ? std::string("there is nothing to index")
                                        : "0 to " + std::to_string(bound - 1)));
    out[i] = static_cast<std::uint32_t>(d[i]);
  }
  return out;
}

std::vector<Vec3> points(const py::array_t<double, py::array::c_style>& rows) {
  std::vector<Vec3> out(static_cast<std::size_t>(rows.shape(0)));
  const double* d = rows.data();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
  return out;
}

Mesh meshFromArrays(const py::object& vertices, const py::object& triangles,
                    const py::object& normals) {
  const auto v = floatRows(vertices, "vertices", 3);
  if (static_cast<std::uint64_t>(v.shape(0)) > std::numeric_limits<std::uint32_t>::max())
    badArgument("vertices", "more than 2^32 - 1 vertices");
  Mesh mesh;
  const auto toFloats = [](const py::array_t<double, py::array::c_style>& rows, const char* name,
                           MeshBuffer<float>& out) {
    out.resize(static_cast<std::size_t>(rows.size()));
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] = static_cast<float>(rows.data()[i]);
      if (!std::isfinite(out[i])) badArgument(name, "a value is too large for float32");
    }
  };
  toFloats(v, "vertices", mesh.positions);
  const std::vector<std::uint32_t> t =
      indexRows(triangles, "triangles", 3, static_cast<std::uint64_t>(v.shape(0)));
  mesh.indices.assign(t.begin(), t.end());
  if (!normals.is_none()) {
    const auto n = floatRows(normals, "normals", 3);
    if (n.shape(0) != v.shape(0))
      badArgument("normals", "expected one row per vertex (" + std::to_string(v.shape(0)) +
                                 "), got " + std::to_string(n.shape(0)));
    toFloats(n, "normals", mesh.normals);
  }
  return mesh;
}

void bindCore(py::module_& m) {
  m.doc() =
      "pdesurf's compiled core: models, solved surfaces, meshes and sessions over the C++ "
      "library. Use the package `pdesurf`, which re-exports these with the mesh tools.";
  py::register_exception_translator(&translate);

  py::class_<Mesh, std::shared_ptr<Mesh>>(
      m, "Mesh",
      "A triangle mesh. Its arrays view the library's buffers in place (read-only, no copy):\n"
      "positions (N, 3) float32, normals (N, 3) float32 or None, triangles (M, 3) uint32,\n"
      "patch_ids (M,) uint32 or None; `vertices` is positions as float64 (N, 3).")
      .def(py::init([](const py::object& vertices, const py::object& triangles,
                       const py::object& normals) {
             return std::make_shared<Mesh>(meshFromArrays(vertices, triangles, normals));
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("normals") = py::none(),
           "Mesh(vertices, triangles, normals=None): a mesh of (N, 3) positions, (M, 3) vertex\n"
           "indices (counter-clockwise seen from the front) and optional (N, 3) unit normals.\n"
           "Raises ValueError naming the argument for a wrong shape or dtype, a value that is\n"
           "not finite or an index out of range.")
      .def_property_readonly("positions", bufferView(&Mesh::positions, 3, false),
                             "(N, 3) float32: the vertex positions, a read-only view of the "
                             "mesh's buffer.")
      .def_property_readonly(
          "vertices",
          [](const Mesh& mesh) {
            return vectorRows(mesh.vertexCount(), [&](std::size_t i) {
              return Vec3(mesh.positions[3 * i], mesh.positions[3 * i + 1],
                          mesh.positions[3 * i + 2]);
            });
          },
          "(N, 3) float64: the vertex positions, widened (exactly) from the float32 buffer.")
      .def_property_readonly("normals", bufferView(&Mesh::normals, 3, true),
                             "(N, 3) float32 unit normals (a read-only view), or None when the "
                             "mesh has none.")
      .def_property_readonly("triangles", bufferView(&Mesh::indices, 3, false),
                             "(M, 3) uint32: each triangle's vertex indices (a read-only view).")
      .def_property_readonly("patch_ids", bufferView(&Mesh::patchIds, 0, true),
                             "(M,) uint32: the patch each triangle comes from, or None when "
                             "unknown.")
      .def_property_readonly("vertex_count", &Mesh::vertexCount, "Number of vertices.")
      .def_property_readonly("triangle_count", &Mesh::triangleCount, "Number of triangles.")
      .def(
          "save",
          [](const Mesh& mesh, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            writeMesh(mesh, path.string());
          },
          py::arg("path"),
          "Writes the mesh in the format its extension names (.obj .ply .stl .glb .off), whole\n"
          "or not at all. Raises MeshIOError.")
      .def("__repr__", [](const Mesh& mesh) {
        return "<pdesurf.Mesh: " + countText(mesh.vertexCount(), "vertex") + ", " +
               countText(mesh.triangleCount(), "triangle") + ">";
      });

  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return std::make_shared<Mesh>(readMesh(path.string()));
      },
      py::arg("path"),
      "Reads a mesh file (.obj .ply .stl .glb .off); OBJ, PLY and glb keep their normals.\n"
      "Raises MeshIOError naming the file and the problem.");

  py::class_<Model>(m, "Model",
                    "A model of any type as a file describes it (docs/model-format.md): "
                    "vertex-frames, spectral, cross-sections or bspline-pde. Immutable.")
      .def_property_readonly(
          "type", [](const Model& self) { return modelTypeName(*self.model); },
          "The model's type: 'vertex-frames', 'spectral', 'cross-sections' or 'bspline-pde'.")
      .def_property_readonly(
          "name", [](const Model& self) { return modelNameOf(*self.model); },
          "The name the model gives ('' when none).")
      .def_property_readonly(
          "source", [](const Model& self) { return self.source; },
          "Where the model came from (its file), as errors name it.")
      .def(
          "to_json", [](const Model& self) { return serializeModel(*self.model); },
          "The model as JSON text (a model file), numbers in their shortest round-trip form.")
      .def(
          "save",
          [](const Model& self, const std::filesystem::path& path) {
            writeFileAtomically(path.string(), serializeModel(*self.model));
          },
          py::arg("path"), "Writes the model file (JSON), whole or not at all. Raises FileError.")
      .def("solve", &solve, py::arg("solver") = "global", py::arg("seed_frame") = 0,
           "Solves the model (the GIL is released meanwhile) -> Surface. Vertex frames take\n"
           "solver='global' (each strip minimises its patches' PDE residual) or 'local' (the\n"
           "seed's breadth-first rule from seed_frame), as the CLI's --solver, --seed-frame.\n"
           "Raises ModelError when the solver refuses the model.")
      .def_property_readonly(
          "vertices",
          [](const Model& self) {
            const VertexFrameModel& f = framesOf(self);
            return vectorRows(f.vertices.size(), [&](std::size_t i) { return f.vertices[i]; });
          },
          "Vertex frames: the (N, 3) float64 vertex positions (a copy).")
      .def_property_readonly(
          "frames",
          [](const Model& self) {
            const VertexFrameModel& f = framesOf(self);
            py::array_t<std::uint32_t> out(
                {static_cast<py::ssize_t>(f.frames.size()), py::ssize_t{8}});
            auto o = out.mutable_unchecked<2>();
            for (std::size_t k = 0; k < f.frames.size(); ++k)
              for (py::ssize_t s = 0; s < 8; ++s)
                o(static_cast<py::ssize_t>(k), s) =
                    f.frames[k].vertices[static_cast<std::size_t>(s)];
            return out;
          },
          "Vertex frames: the (K, 8) uint32 vertex indices P1..P8 of each frame.")
      .def_property_readonly("a1", frameParameter(&Frame::a1),
                             "Vertex frames: the (K, 3) a1 of each frame (per component).")
      .def_property_readonly("a2", frameParameter(&Frame::a2),
                             "Vertex frames: the (K, 3) a2 of each frame (per component).")
      .def("__repr__", [](const Model& self) {
        return std::string("<pdesurf.Model ") + modelTypeName(*self.model) + " '" +
               modelDisplayName(modelNameOf(*self.model), self.source) + "'>";
      });

  m.def(
      "load_model",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return Model{std::make_shared<const AnyModel>(loadModel(path)), path};
      },
      py::arg("path"), "Reads and checks a model file of any type. Raises ModelError, FileError.");
  m.def(
      "parse_model",
      [](const py::object& text, const std::string& source) {
        return Model{std::make_shared<const AnyModel>(parseModel(jsonText(text, "model"), source)),
                     source};
      },
      py::arg("model"), py::arg("source") = "<string>",
      "Parses and checks a model from JSON text or a dict; `source` names it in errors.");
  m.def("vertex_frame_model", &vertexFrameModel, py::arg("vertices"), py::arg("frames"),
        py::arg("a1"), py::arg("a2"), py::arg("forces"), py::arg("shared_forces"), py::arg("name"),
        "The vertex-frame model of arrays (pdesurf.vertex_frames wraps it).");

  py::class_<SolvedModel, std::shared_ptr<SolvedModel>>(
      m, "Surface", "A solved model: patches to tessellate, sample and evaluate.")
      .def(
          "tessellate",
          [](const SolvedModel& self, std::uint32_t resolution) {
            if (resolution < 2 || resolution > 4097)
              badArgument("resolution", "must be 2 to 4097, got " + std::to_string(resolution));
            py::gil_scoped_release release;
            return std::make_shared<Mesh>(tessellate(self, {resolution}));
          },
          py::arg("resolution") = 17,
          "The mesh of `resolution` samples per patch side (as `pdesurf build --resolution`):\n"
          "watertight where patches share edges, with normals and patch ids. The GIL is\n"
          "released meanwhile.")
      .def("sample", &sampleGrid, py::arg("grid"),
           "Every patch on a grid x grid lattice -> (patches, grid, grid, 3) float64, where\n"
           "[k, j, i] = S_k(u_i, v_j) at evenly spaced parameters over patch k's domain (as\n"
           "`pdesurf sample --grid`).")
      .def("evaluate", &evaluate, py::arg("patch"), py::arg("u"), py::arg("v"),
           "Points and first derivatives at (patch, u, v) (arrays, broadcast together; u, v\n"
           "in the patch's domain, see `domains`) -> (S, dS/du, dS/dv), each of the broadcast\n"
           "shape + (3,). Raises ValueError for a patch index out of range or a value that is\n"
           "not finite.")
      .def_property_readonly(
          "domains",
          [](const SolvedModel& self) {
            const std::size_t n = patchCount(self);
            py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{4}});
            for (std::size_t k = 0; k < n; ++k) {
              const auto d = patchDomain(self, k);
              for (std::size_t c = 0; c < 4; ++c) out.mutable_at(k, c) = d[c];
            }
            return out;
          },
          "(patches, 4): each patch's parameter domain [u0, u1, v0, v1] (the unit square, or\n"
          "a spectral patch's u range and v in [0, 2 pi]).")
      .def_property_readonly("patch_count", &patchCount, "Number of patches.")
      .def_property_readonly("type", &SolvedModel::type, "The model's type.")
      .def_property_readonly("notes", &SolvedModel::notes,
                             "The solver's notes (vertex frames: strips pinned, ...).")
      .def_property_readonly(
          "model",
          [](const std::shared_ptr<SolvedModel>& self) {
            return Model{std::shared_ptr<const AnyModel>(self, &self->model()), self->source()};
          },
          "The Model this surface solves.")
      .def(
          "report",
          [](const SolvedModel& self) {
            const ModelReport r = report(self);
            return py::dict(py::arg("summary") = r.summary, py::arg("quality") = r.quality);
          },
          "What `pdesurf build` reports: {'summary': ..., 'quality': ...}.")
      .def(
          "info",
          [](const SolvedModel& self) {
            // The values of `pdesurf info --json` (model_info.hpp), each through JSON text.
            const ModelInfo info = modelInfo(self);
            const py::object loads = py::module_::import("json").attr("loads");
            py::dict out(py::arg("model") = info.source, py::arg("name") = info.name);
            for (const InfoFact& fact : info.facts)
              if (!fact.key.empty()) out[py::str(fact.key)] = loads(fact.value.dump());
            if (info.keysSorted)
              out = py::dict(py::module_::import("builtins").attr("sorted")(out.attr("items")()));
            return out;
          },
          "What `pdesurf info --json` prints, as a dict.")
      .def_property_readonly(
          "c0_gap", [](const SolvedModel& self) { return largestC0Gap(self); },
          "The largest distance between two patches where they meet (absolute).")
      .def("__repr__", [](const SolvedModel& self) {
        return std::string("<pdesurf.Surface ") + self.type() + " '" + self.displayName() +
               "': " + countText(patchCount(self), "patch") + ">";
      });

  py::class_<ModelSession>(
      m, "Session",
      "An editing session (as the studio's): edits as JSON (docs/studio.md), undo, redo.")
      .def(py::init([](const Model& model) {
             return std::make_unique<ModelSession>(*model.model, model.source);
           }),
           py::arg("model"), "Starts a session on a copy of `model`.")
      .def(
          "apply",
          [](ModelSession& self, const py::object& edit) {
            const ModelEdit e = parseEdit(jsonText(edit, "edit"), self.model());
            py::gil_scoped_release release;
            self.apply(e);
          },
          py::arg("edit"),
          "Applies an edit (JSON text or a dict): vertex frames take move-vertex,\n"
          "set-parameters, set-forces, extrude, split-frame, ...; the other types\n"
          "move-curve-points, set-fourier, set-operator, ... (include/pdesurf/edit_io.hpp).\n"
          "Raises ModelError (the session unchanged) for an edit that is invalid.")
      .def(
          "transform",
          [](ModelSession& self, const py::object& map) {
            self.transform(parseTransform(jsonText(map, "transform")));
          },
          py::arg("transform"),
          "Moves, turns or scales the whole model: {'translate': [x, y, z], 'rotate':\n"
          "{'axis': [...], 'degrees': d}, 'scale': s, 'center': [...]} (any of them).")
      .def("undo", &ModelSession::undo, "Undoes the last step; False when there is none.")
      .def("redo", &ModelSession::redo, "Redoes the last undone step; False when there is none.")
      .def("end_group", &ModelSession::endGroup,
           "Ends the current group: the next edit starts a new undo step.")
      .def_property_readonly("undo_depth", &ModelSession::undoDepth, "Undo steps held.")
      .def_property_readonly("redo_depth", &ModelSession::redoDepth, "Redo steps held.")
      .def_property_readonly("revision", &ModelSession::revision,
                             "Increases with every change of the model.")
      .def_property_readonly(
          "model",
          [](const ModelSession& self) {
            return Model{std::make_shared<const AnyModel>(self.model()), "session"};
          },
          "The current model (a copy).")
      .def(
          "solve",
          [](ModelSession& self, const std::string& solver, std::uint32_t seedFrame) {
            const SolveOptions options = solveOptions(self.model(), solver, seedFrame);
            py::gil_scoped_release release;
            return std::make_shared<SolvedModel>(self.solved(options));
          },
          py::arg("solver") = "global", py::arg("seed_frame") = 0,
          "The current model solved -> Surface (cached per revision).");

  m.def(
      "set_threads",
      [](unsigned threads) {
        ThreadLimit& limit = threadLimit();
        limit.control.reset();
        if (threads > 0)
          limit.control.emplace(tbb::global_control::max_allowed_parallelism, threads);
        limit.count = threads;
      },
      py::arg("threads"),
      "Threads for tessellation, evaluation, compare and slice (the CLI's --threads);\n"
      "0: every core. The results are the same for any count.");
  m.def(
      "get_threads", [] { return threadLimit().count; },
      "The set_threads setting (0: every core).");
  m.def("release_mesh_memory", &releaseMeshMemory,
        "Returns the memory of freed meshes kept for reuse to the system; the bytes released.");

  bindTools(m);
}

}  // namespace pdesurf::python

PYBIND11_MODULE(_core, m) { pdesurf::python::bindCore(m); }
