"""pdesurf's exceptions: one class a kind of the C++ library's errors, all under Error.

The compiled core (pdesurf._core) raises these for the library's exceptions (pdesurf::Error
and its kinds, include/pdesurf/error.hpp), with the parts the C++ error carries; a bad
argument the binding itself checks (a wrong array shape or dtype, a value that is not
finite, an index out of range, an unknown option) raises ValueError naming the argument.
"""


class Error(Exception):
    """Any error of the pdesurf library.

    str(error) is the library's whole message ("FILE: $.json.path: what is wrong" for a
    model); `message` is what is wrong alone, `file` and `path` (the JSON path inside the
    file) are set where the library names them, else None.
    """

    def __init__(self, text, *, message=None, file=None, path=None):
        super().__init__(text)
        self.message = text if message is None else message
        self.file = file
        self.path = path


class ModelError(Error):
    """A model (file, JSON text, arrays, an edit) is malformed, invalid or cannot be solved."""


class FileError(Error):
    """A file could not be written (models, STEP/IGES) or read."""


class MeshIOError(FileError):
    """A mesh file could not be read or written, or its extension names no mesh format."""


class LayoutError(Error):
    """A mesh cannot serve as a layout of frames (rebuild: grid, quads, tube)."""


class SliceError(Error):
    """A mesh cannot be sliced as asked: a plane misses it or cuts no closed loop."""


class InvalidArgumentError(Error, ValueError):
    """An argument the library cannot use (a count below its minimum, a value that is not
    finite, curves that do not close); a ValueError as well."""


class SectionError(InvalidArgumentError):
    """A section of a cross-section rebuild cannot be used (it names the section)."""


class CadError(Error):
    """A STEP or IGES file could not be written (or its extension is neither)."""


class ToleranceError(Error):
    """A face of an export missed the tolerance asked for within max_spans."""


class LoftError(Error):
    """Open CASCADE could not loft the sections (the peer of a cross-section rebuild)."""
