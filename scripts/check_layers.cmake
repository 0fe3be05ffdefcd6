# Shows that the layer rules of CMakeLists.txt fail the build when broken (docs/architecture.md):
# a one-line source that includes a header of a higher layer, or a private header of another
# layer, does not compile with a layer's own include directories (the ones its sources build
# with), and the same source including a header the layer may use does (the control, so that a
# failure means the header was not found, nothing else).
# Run by ctest (tests/CMakeLists.txt: layers_enforced):
#   cmake -DCXX=COMPILER -DWORK=DIR -DEIGEN=DIRS -DGEOMETRY=DIRS -DENGINES=DIRS -DMODEL=DIRS
#         -DIO=DIRS -P scripts/check_layers.cmake       (DIRS: include directories joined by |)
if(NOT CXX OR NOT WORK)
  message(FATAL_ERROR "usage: cmake -DCXX=... -DWORK=... -DEIGEN=... -DGEOMETRY=... "
                      "-DENGINES=... -DMODEL=... -DIO=... -P scripts/check_layers.cmake")
endif()
file(MAKE_DIRECTORY ${WORK})
set(failures 0)

# probe(LAYER HEADER EXPECT): compiles `#include "HEADER"` with LAYER's include directories;
# EXPECT is "fails" (the header must not be found) or "compiles".
function(probe layer header expect)
  string(REPLACE "|" ";" dirs "${${layer}}|${EIGEN}")
  set(flags)
  foreach(dir IN LISTS dirs)
    if(dir)
      list(APPEND flags -I${dir})
    endif()
  endforeach()
  set(source ${WORK}/probe.cpp)
  file(WRITE ${source} "#include \"${header}\"\nint main() { return 0; }\n")
  execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${flags} ${source}
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(expect STREQUAL "fails")
    string(FIND "${err}" "${header}: No such file" notFound)
    if(rc EQUAL 0 OR notFound EQUAL -1)
      message(SEND_ERROR "check_layers: the ${layer} layer can include ${header} "
                         "(it must not be found):\n${err}")
      math(EXPR failures "${failures} + 1")
    else()
      message(STATUS "check_layers: ${layer} cannot include ${header}, as it must not")
    endif()
  elseif(NOT rc EQUAL 0)
    message(SEND_ERROR "check_layers: the ${layer} layer cannot include ${header}:\n${err}")
    math(EXPR failures "${failures} + 1")
  else()
    message(STATUS "check_layers: ${layer} includes ${header}")
  endif()
  set(failures ${failures} PARENT_SCOPE)
endfunction()

# Upwards: a layer never sees a header of a layer above it.
probe(GEOMETRY "pdesurf/vertex_frames.hpp" fails)
probe(ENGINES "pdesurf/nurbs.hpp" fails)
probe(ENGINES "pdesurf/model.hpp" fails)
probe(ENGINES "pdesurf/spectral_io.hpp" fails)
probe(MODEL "pdesurf/session.hpp" fails)
probe(MODEL "pdesurf/model_io.hpp" fails)
# Sideways into private headers: another layer's src/ is not there.
probe(ENGINES "io/json_reader.hpp" fails)
probe(MODEL "spectral/internal.hpp" fails)
# The controls: a layer's own and lower layers' headers compile.
probe(GEOMETRY "pdesurf/geometry.hpp" compiles)
probe(ENGINES "pdesurf/spectral_model.hpp" compiles)
probe(ENGINES "spectral/internal.hpp" compiles)
probe(MODEL "pdesurf/model.hpp" compiles)
probe(IO "pdesurf/session.hpp" compiles)
if(failures GREATER 0)
  message(FATAL_ERROR "check_layers: ${failures} probe(s) broke the layer rules")
endif()
