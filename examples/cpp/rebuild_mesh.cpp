// rebuild_mesh MESH OUT.json [FRAMES]: a triangle mesh (.off .stl .obj .ply .glb) rebuilt as a
// vertex-frame model of about FRAMES frames (default 50): an automatic layout fitted to the
// mesh, as `pdesurf rebuild MESH --as vertex-frames --frames N` does. Prints the fitted
// model's RMS distances to the mesh both ways. Links pdesurf::cgal (docs/library.md).
#include <cstdio>
#include <exception>
#include <string>

#include <pdesurf/cgal.hpp>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: rebuild_mesh MESH OUT.json [FRAMES]\n");
    return 2;
  }
  try {
    const pdesurf::Mesh mesh = pdesurf::readMesh(argv[1]);
    pdesurf::AutoLayoutOptions layout;
    layout.frames = argc == 4 ? static_cast<std::uint32_t>(std::stoul(argv[3])) : 50;
    const std::uint32_t resolution = 17;  // samples per patch side for the measure
    const pdesurf::AutoFit fitted = pdesurf::fitAutoLayout(
        mesh, layout, pdesurf::FitOptions{}, resolution, pdesurf::DistanceOptions{}, argv[1]);
    pdesurf::writeFileAtomically(argv[2], pdesurf::serializeVertexFrameModel(fitted.fit.model));
    std::printf("%s: %zu frames, RMS %.4f %% and %.4f %% of the diagonal\n", argv[2],
                fitted.fit.model.frames.size(), 100 * fitted.distance.aToB.rmsRelative,
                100 * fitted.distance.bToA.rmsRelative);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rebuild_mesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
