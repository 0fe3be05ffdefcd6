// Writing a file whole or not at all: the one way pdesurf writes files (meshes, models,
// autosaves, slices, STEP and IGES).
#pragma once

#include <string>
#include <string_view>

#include "pdesurf/error.hpp"

namespace pdesurf {

/// Writes `data` to `path` whole or not at all: the bytes go to a hidden temporary file in
/// the same folder (".NAME.tmp-XXXXXX"), are synced to disk and renamed over `path`, so a
/// reader sees the old file or the new one, never a part. Permissions are those of a write
/// in place: a file that is replaced keeps its mode, a new file gets 0666 minus the umask.
/// Throws FileError naming `path` (and leaves no temporary file) on failure.
void writeFileAtomically(const std::string& path, std::string_view data);

}  // namespace pdesurf
