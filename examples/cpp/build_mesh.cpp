// build_mesh MODEL.json OUT.obj [RESOLUTION]: a model file of any type solved and written as a
// mesh (.obj .ply .stl .glb .off), as `pdesurf build MODEL.json -o OUT --resolution N` does.
// Links pdesurf::pdesurf, the core (docs/library.md).
#include <cstdio>
#include <exception>
#include <string>

#include <pdesurf/pdesurf.hpp>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: build_mesh MODEL.json OUT.obj [RESOLUTION]\n");
    return 2;
  }
  try {
    const pdesurf::SolvedModel solved = pdesurf::solve(pdesurf::loadModel(argv[1]), argv[1]);
    pdesurf::TessellateOptions options;
    if (argc == 4) options.resolution = static_cast<std::uint32_t>(std::stoul(argv[3]));
    const pdesurf::Mesh mesh = pdesurf::tessellate(solved, options);
    pdesurf::writeMesh(mesh, argv[2]);
    std::printf("%s: %zu vertices, %zu triangles\n", argv[2], mesh.vertexCount(),
                mesh.triangleCount());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "build_mesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
