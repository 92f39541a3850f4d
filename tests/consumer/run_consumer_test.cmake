# The installed package as a user meets it (cmake -P; tests/CMakeLists.txt passes the -D's):
#   1. install the build into a fresh prefix (WORK/prefix);
#   2. check what was installed: no header includes CHOLMOD or a private header, the tool
#      reports the project's version, the CMake package and pkg-config file are there;
#   3. configure, build and run tests/consumer (find_package(strictmin CONFIG REQUIRED))
#      against that prefix: it reads a mesh, solves L-infinity and prints the maximum;
#   4. compile and link the same program with pkg-config's flags alone.
# Inputs: BUILD_DIR SOURCE_DIR WORK_DIR VERSION LIBDIR CXX_COMPILER [CXX_LAUNCHER] [PKG_CONFIG]
cmake_minimum_required(VERSION 3.20)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

# 1. Install.
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# 2. What was installed.
foreach(f include/strictmin/version.h include/strictmin/tasks/deform.h
          ${LIBDIR}/cmake/strictmin/strictmin-config.cmake
          ${LIBDIR}/cmake/strictmin/strictmin-config-version.cmake
          ${LIBDIR}/cmake/strictmin/FindCHOLMOD.cmake ${LIBDIR}/pkgconfig/strictmin.pc bin/strictmin)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/*)
foreach(h ${headers})
  if(NOT h MATCHES "^strictmin/.*\\.h$")
    message(FATAL_ERROR "installed include/${h}: only strictmin/**/*.h belong there")
  endif()
  file(STRINGS ${prefix}/include/${h} includes REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${includes})
    if(line MATCHES "<(cholmod|suitesparse/|SuiteSparse|tbb/|oneapi/|nlohmann/|png\\.h|CLI/)")
      message(FATAL_ERROR "installed header ${h} includes a private dependency: ${line}")
    endif()
    if(line MATCHES "\"([^\"]+)\"" AND NOT EXISTS ${prefix}/include/${CMAKE_MATCH_1})
      message(FATAL_ERROR "installed header ${h} includes a header that is not installed: ${line}")
    endif()
  endforeach()
endforeach()
run(${prefix}/bin/strictmin --version)
string(STRIP "${run_output}" tool_version)
if(NOT tool_version STREQUAL "strictmin ${VERSION}")
  message(FATAL_ERROR "strictmin --version says '${tool_version}', CMake's version is ${VERSION}")
endif()

# 3. A CMake project using the package.
set(launcher "")
if(CXX_LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${launcher} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer ${SOURCE_DIR}/tests/consumer/strip.obj)
message(STATUS "consumer (CMake package):\n${run_output}")
if(NOT run_output MATCHES "strictmin ${VERSION} \\(headers ${VERSION}\\)")
  message(FATAL_ERROR "the consumer did not report version ${VERSION}")
endif()
if(NOT run_output MATCHES "status solved\nmax ([0-9.e+-]+)")
  message(FATAL_ERROR "the consumer did not solve the strip")
endif()
set(cmake_max ${CMAKE_MATCH_1})

# 4. The same program built with pkg-config's flags (a static library: --static).
if(PKG_CONFIG)
  set(ENV{PKG_CONFIG_PATH} ${prefix}/${LIBDIR}/pkgconfig)
  run(${PKG_CONFIG} --modversion strictmin)
  string(STRIP "${run_output}" pc_version)
  if(NOT pc_version STREQUAL VERSION)
    message(FATAL_ERROR "pkg-config says version '${pc_version}', CMake's is ${VERSION}")
  endif()
  run(${PKG_CONFIG} --cflags --libs --static strictmin)
  string(STRIP "${run_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run(${CXX_LAUNCHER} ${CXX_COMPILER} -std=c++20 -O1 ${SOURCE_DIR}/tests/consumer/main.cpp -o ${WORK_DIR}/consumer_pc ${flags})
  set(ENV{LD_LIBRARY_PATH} ${prefix}/${LIBDIR})  # a shared libstrictmin: pkg-config gives no RPATH
  run(${WORK_DIR}/consumer_pc ${SOURCE_DIR}/tests/consumer/strip.obj)
  if(NOT run_output MATCHES "max ${cmake_max}")
    message(FATAL_ERROR "the pkg-config build printed another result:\n${run_output}")
  endif()
  message(STATUS "consumer (pkg-config): same result")
endif()
