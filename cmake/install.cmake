# Install rules (included by CMakeLists.txt): `cmake --install build --prefix P` puts
#   P/include/pdesurf/            the public headers of the core and of every module built
#   P/lib/libpdesurf*.a (or .so)  the core and the modules (static unless BUILD_SHARED_LIBS)
#   P/lib/cmake/pdesurf/          pdesurfConfig.cmake, its version file and exported targets:
#                                 pdesurf::pdesurf, components cgal, occt, studio
#   P/lib/pkgconfig/pdesurf.pc    the core for pkg-config
#   P/bin/pdesurf                 the CLI (when every module is built)
# (docs/library.md shows a consumer of each.)
include(CMakePackageConfigHelpers)
set(PDESURF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pdesurf)

# Headers: the core's, and each module's where it is built. include/pdesurf/ holds the public
# headers alone; the private ones live under src/ and are never installed (the test
# public_headers: no installed header includes one).
set(PDESURF_INSTALL_HEADERS)
foreach(header IN LISTS PDESURF_PUBLIC_HEADERS)
  if(header IN_LIST PDESURF_CGAL_MODULE_HEADERS)
    set(module CGAL)
  elseif(header IN_LIST PDESURF_OCCT_HEADERS OR header STREQUAL "occt.hpp")
    set(module OCCT)
  else()
    set(module CORE)
  endif()
  if(module STREQUAL "CORE" OR PDESURF_${module})
    list(APPEND PDESURF_INSTALL_HEADERS include/pdesurf/${header})
  endif()
endforeach()
install(FILES ${PDESURF_INSTALL_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pdesurf)
if(PDESURF_STUDIO)
  install(FILES apps/studio/server.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pdesurf/studio)
endif()

install(TARGETS ${PDESURF_INSTALL_TARGETS} EXPORT pdesurfTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The CLI, not exported (its target name would be pdesurf::pdesurf's).
if(TARGET pdesurf)
  if(BUILD_SHARED_LIBS)
    # The installed CLI finds the installed libraries wherever the prefix is.
    set_target_properties(pdesurf PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
  endif()
  install(TARGETS pdesurf RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT pdesurfTargets NAMESPACE pdesurf:: DESTINATION ${PDESURF_CMAKE_DIR})

# The package's config: the dependencies the installed libraries need found (static ones link
# their private dependencies into the consumer), the components this build has.
set(PDESURF_OCCT_COMPONENT_LIST "${PDESURF_OCCT_COMPONENTS}")
configure_package_config_file(cmake/pdesurfConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/pdesurfConfig.cmake
                              INSTALL_DESTINATION ${PDESURF_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pdesurfConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pdesurfConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/pdesurfConfigVersion.cmake
        DESTINATION ${PDESURF_CMAKE_DIR})

# pkg-config: the core, relocatable (the prefix found from the file's own folder). A static
# libpdesurf names what it links in Requires and Libs (so that `pkg-config --libs pdesurf` is
# enough); a shared one in Requires.private and Libs.private.
file(RELATIVE_PATH PDESURF_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
set(PDESURF_PC_REQUIRES "Requires: eigen3")
set(PDESURF_PC_LIBS "Libs: -L\${libdir} -lpdesurf")
if(BUILD_SHARED_LIBS)
  string(APPEND PDESURF_PC_REQUIRES "\nRequires.private: nlohmann_json fmt tbb tinygltf")
  string(APPEND PDESURF_PC_LIBS "\nLibs.private: -lquadmath")
else()
  string(APPEND PDESURF_PC_REQUIRES " nlohmann_json fmt tbb tinygltf")
  string(APPEND PDESURF_PC_LIBS " -lquadmath")
endif()
set(PDESURF_PC_CFLAGS "")
if(PDESURF_NATIVE)
  string(JOIN " " PDESURF_PC_CFLAGS ${PDESURF_ARCH_FLAGS})
endif()
configure_file(cmake/pdesurf.pc.in ${CMAKE_CURRENT_BINARY_DIR}/pdesurf.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pdesurf.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
