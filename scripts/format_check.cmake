# Fails when any C++ source differs from what clang-format makes of it.
file(GLOB_RECURSE files
  ${ROOT}/include/*.hpp ${ROOT}/src/*.cpp ${ROOT}/src/*.hpp ${ROOT}/apps/*.cpp ${ROOT}/apps/*.hpp
  ${ROOT}/tests/*.cpp ${ROOT}/tests/*.hpp ${ROOT}/bench/*.cpp ${ROOT}/examples/*.cpp)
execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror ${files} RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "clang-format: these files need formatting (run `make format`):\n${err}")
endif()
message(STATUS "format check: ${CMAKE_ARGC} ok")
