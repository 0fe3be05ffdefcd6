// The errors pdesurf throws: one base, pdesurf::Error (file, JSON path, message), and one
// class a kind beneath it (docs/library.md, "Errors"). Every error of bad input that a
// library function throws is an Error; `catch (const pdesurf::Error&)` takes them all.
// What is left outside the hierarchy: std::bad_alloc (memory), std::logic_error (a broken
// internal invariant or an API called out of turn, never input) and the exceptions of
// callbacks the caller gives.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace pdesurf {

/// Any error of bad input. what() reads "FILE: $.json.path: message", each of the three
/// parts left out (with its ": ") where it is empty: a model's error names all three, a
/// mesh file's the file and the message, a bad argument the message alone.
class Error : public std::runtime_error {
 public:
  /// An error that names no file.
  explicit Error(const std::string& message);
  /// An error of a file (or a source) with no JSON path: a mesh file, a layout, a CAD file.
  Error(const std::string& file, const std::string& message) : Error(file, "", message) {}
  Error(const std::string& file, const std::string& jsonPath, const std::string& message);
  /// The file (or the source a text was read as, e.g. "edit"), or empty.
  const std::string& file() const { return file_; }
  /// Where in the file's JSON ("$.frames[2].vertex"), or empty.
  const std::string& jsonPath() const { return jsonPath_; }
  /// What is wrong, alone: what() without the file and the path.
  const std::string& message() const { return message_; }

 private:
  std::string file_, jsonPath_, message_;
};

/// A library function's argument that it cannot use (a count below its minimum, a value
/// that is not finite, curves that do not close, a singular map, a resolution whose mesh
/// would not fit in 32-bit indices): what std::invalid_argument said before, as an Error.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A model (a file, a JSON text, an edit) that is malformed, invalid or cannot be solved:
/// thrown by the model files' parsers and by the solvers' wrappers that name the model.
/// what() reads "FILE: $.json.path: what is wrong".
class ModelError : public Error {
 public:
  ModelError(const std::string& file, const std::string& jsonPath, const std::string& problem)
      : Error(file, jsonPath, problem) {}
  /// The same as message() (its name before Error existed).
  const std::string& problem() const { return message(); }
};

/// A file could not be written (pdesurf/atomic_file.hpp) or read; what() names the file
/// and the reason.
class FileError : public Error {
 public:
  using Error::Error;
};

/// A mesh file could not be read or written, or its extension names no mesh format
/// (pdesurf/mesh_io.hpp); what() names the file and the problem.
class MeshIoError : public FileError {
 public:
  using FileError::FileError;
};

/// A mesh cannot serve as a layout of frames (pdesurf/rebuild.hpp: a face that is no quad,
/// an edge of three faces, a mesh that is no disk); what() names the file (or the mesh's
/// source), the face or the edge, and the problem.
class LayoutError : public Error {
 public:
  using Error::Error;
};

/// A section of a cross-section chain cannot be used (pdesurf/sections.hpp): message()
/// and what() read "section 3: REASON". A bad argument, so an InvalidArgument.
class SectionError : public InvalidArgument {
 public:
  SectionError(std::uint32_t section, const std::string& reason);
  std::uint32_t section() const { return section_; }
  /// The reason alone, without "section i: ".
  const std::string& reason() const { return reason_; }

 private:
  std::uint32_t section_;
  std::string reason_;
};

/// A mesh cannot be sliced as asked (pdesurf/mesh_slice.hpp): a plane misses it, or cuts
/// it only in open chains. what() names the plane (index and coordinate) and the mesh's
/// extent along the axis.
class MeshSliceError : public Error {
 public:
  using Error::Error;
};

/// Open CASCADE could not loft the sections (pdesurf/occt_loft.hpp); what() carries its
/// message.
class LoftError : public Error {
 public:
  using Error::Error;
};

/// A path pdesurf cannot write as STEP or IGES (its extension), or a file Open CASCADE
/// failed to write (pdesurf/cad_export.hpp).
class CadError : public Error {
 public:
  using Error::Error;
};

/// A B-spline approximation that did not reach the tolerance within
/// ApproximationOptions::maxSpans (pdesurf/nurbs.hpp).
class NurbsToleranceError : public Error {
 public:
  using Error::Error;
};

}  // namespace pdesurf
