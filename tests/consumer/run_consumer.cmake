# ctest's driver of tests/consumer: cmake -DBUILD=<mbsopt build tree> -DPREFIX=<scratch directory>
#   -DSOURCE=<tests/consumer> -DCXX=<compiler> -DFLAGS=<CMAKE_CXX_FLAGS> -DLINKER_FLAGS=<...>
#   [-DPYTHON=<interpreter> -DPYTHON_DIR=<MBSOPT_PYTHON_INSTALL_DIR>] [-DREADME=<README.md>] -P run_consumer.cmake
# Installs BUILD into PREFIX/install (fresh), configures SOURCE against it with the compiler and the
# flags given (the build's own CMAKE_CXX_FLAGS: empty in Release, the sanitizers' in the sanitizer
# build; never -march=native, which the libraries' directory adds for themselves), builds, runs.
# With README, the README's C++ example (its ```cpp block) is built and run beside it, as its reader
# would build it.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${step} failed (${result})")
  endif()
endfunction()

file(REMOVE_RECURSE ${PREFIX})
set(readme_example "")
if(DEFINED README)
  file(READ ${README} readme)
  string(REGEX MATCH "```cpp\n([^`]*)```" block "${readme}")
  if(NOT CMAKE_MATCH_1)
    message(FATAL_ERROR "${README} has no ```cpp block")
  endif()
  file(WRITE ${PREFIX}/readme_example.cpp "${CMAKE_MATCH_1}")
  set(readme_example -DREADME_EXAMPLE=${PREFIX}/readme_example.cpp)
endif()
run("install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX}/install)
run("configure" ${CMAKE_COMMAND} -S ${SOURCE} -B ${PREFIX}/build -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${PREFIX}/install -DCMAKE_CXX_COMPILER=${CXX} "-DCMAKE_CXX_FLAGS=${FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}" ${readme_example})
run("build" ${CMAKE_COMMAND} --build ${PREFIX}/build)
run("run" ${PREFIX}/build/consumer)
if(DEFINED README)
  run("run the README's example" ${PREFIX}/build/readme_example)
endif()
if(DEFINED PYTHON)
  run("import the installed module" ${CMAKE_COMMAND} -E env --unset=PYTHONPATH
      ${PYTHON} ${SOURCE}/installed_module.py ${PREFIX}/install/${PYTHON_DIR})
endif()
