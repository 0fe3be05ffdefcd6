// The Python package's compiled core (pdesurf._core): what its two source files share. The
// binding is thin: every function it defines calls the public headers in include/pdesurf/
// and converts arguments and results between numpy arrays and the library's types; nothing
// under src/ is included. docs/python.md describes the package.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "pdesurf/geometry.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/model.hpp"

namespace pdesurf::python {

namespace py = pybind11;

/// A parsed model (any type) and the name it goes by in messages (its file, or "<string>").
struct Model {
  std::shared_ptr<const AnyModel> model;
  std::string source;
};

/// Rows of a float array argument, checked: `name` is the argument's name in the ValueError
/// raised for anything but a real (float or integer) array of shape (n, cols) with finite
/// values. The result is C-contiguous float64 (a copy only where the input is not already).
py::array_t<double, py::array::c_style> floatRows(const py::object& value, const char* name,
                                                  py::ssize_t cols);

/// An integer array argument of shape (n, cols) (cols 0: one dimension) with every value in
/// [0, bound), checked as floatRows does; the values as uint32.
std::vector<std::uint32_t> indexRows(const py::object& value, const char* name, py::ssize_t cols,
                                     std::uint64_t bound);

/// The points of float rows as the library's vectors.
std::vector<Vec3> points(const py::array_t<double, py::array::c_style>& rows);

/// A ValueError naming the argument: "NAME: PROBLEM".
[[noreturn]] void badArgument(const char* name, const std::string& problem);

/// A numpy array (rows × cols; cols 0: one dimension of rows) of `data`, read-only, viewing
/// `data` in place: it keeps `owner` (the Python object whose C++ value holds the buffer)
/// alive as its base.
template <class T>
py::array viewRows(const T* data, std::size_t rows, std::size_t cols, const py::object& owner) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)}, strides;
  if (cols > 0) {
    shape.push_back(static_cast<py::ssize_t>(cols));
    strides.push_back(static_cast<py::ssize_t>(cols * sizeof(T)));
  }
  strides.push_back(static_cast<py::ssize_t>(sizeof(T)));
  py::array out(py::dtype::of<T>(), shape, strides, data, owner);
  out.attr("setflags")(py::arg("write") = false);
  return out;
}

/// The mesh of (vertices, triangles[, normals]) arrays, every argument checked.
Mesh meshFromArrays(const py::object& vertices, const py::object& triangles,
                    const py::object& normals);

/// The part of the module in tools.cpp: compare, slice, rebuild's steps, export.
void bindTools(py::module_& m);

}  // namespace pdesurf::python
