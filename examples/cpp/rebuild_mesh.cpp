// rebuild_mesh MESH OUT.json [FRAMES]: a triangle mesh (.off .stl .obj .ply .glb) rebuilt as a
// vertex-frame model of about FRAMES frames (default 50): an automatic layout fitted to the
// mesh by the library's rebuild(), the call `pdesurf rebuild MESH --as vertex-frames --frames N`
// makes. Prints the fitted model's RMS distances to the mesh both ways and its storage. Links
// pdesurf::cgal (docs/library.md).
#include <cstdio>
#include <exception>
#include <string>

#include <pdesurf/cgal.hpp>

namespace {

/// Rebuilds the mesh at `meshPath` as about `frames` frames into `outPath`.
void rebuildMesh(const std::string& meshPath, const std::string& outPath, unsigned long frames) {
  pdesurf::RebuildOptions options;  // vertex frames, the automatic layout, the CLI's defaults
  options.source = meshPath;
  options.frames = static_cast<std::uint32_t>(frames);
  const pdesurf::RebuildResult rebuilt = pdesurf::rebuild(pdesurf::readMesh(meshPath), options);
  pdesurf::writeFileAtomically(outPath, pdesurf::serializeModel(rebuilt.model));
  const pdesurf::RebuildReport& report = rebuilt.report;
  std::printf("%s: %zu frames, RMS %.4f %% and %.4f %% of the diagonal, %zu bytes\n",
              outPath.c_str(), report.frames, 100 * report.distance.aToB.rmsRelative,
              100 * report.distance.bToA.rmsRelative, report.storageBytes);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 || argc == 4) {
    try {
      rebuildMesh(argv[1], argv[2], argc == 4 ? std::stoul(argv[3]) : 50);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "rebuild_mesh: %s\n", e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "usage: rebuild_mesh MESH OUT.json [FRAMES]\n");
  return 2;
}
