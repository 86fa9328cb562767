# cmake -P script of the package test (tests/package/tests.cmake). Inputs: BUILD_DIR, WORK,
# SOURCE_DIR, GENERATOR, MAKE_PROGRAM, CXX, VERSION, SANITIZE.
set(prefix ${WORK}/prefix)
set(build ${WORK}/build)
file(REMOVE_RECURSE ${WORK})

function(run what)  # run(<what> COMMAND ...): exit 0 required; output in ${what}_out
  cmake_parse_arguments(PARSE_ARGV 1 A "" "" "COMMAND")
  execute_process(COMMAND ${A_COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (exit ${rc}):\n${A_COMMAND}\n${out}\n${err}")
  endif()
  set(${what}_out "${out}" PARENT_SCOPE)
endfunction()

# 1. install the build tree
run(install COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f include/fdem/fdem.hpp include/fdem/version.hpp lib/cmake/fdem/fdemConfig.cmake
          lib/cmake/fdem/fdemConfigVersion.cmake lib/cmake/fdem/fdemTargets.cmake bin/fdem)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
# nothing of the source or build tree may leak into the installed package
file(READ ${prefix}/lib/cmake/fdem/fdemTargets.cmake targets)
foreach(tree ${SOURCE_DIR} ${BUILD_DIR})
  string(FIND "${targets}" "${tree}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "fdemTargets.cmake names ${tree}")
  endif()
endforeach()
# consumers compile with C++20 and -ffp-contract=off only (not the build's warnings or sanitizers);
# an instrumented library (FDEM_SANITIZE) asks for the sanitizer runtimes at link time only
string(REGEX MATCH "INTERFACE_COMPILE_OPTIONS \"([^\"]*)\"" _ "${targets}")
set(compile_options "${CMAKE_MATCH_1}")
if(NOT compile_options STREQUAL "-ffp-contract=off" OR NOT targets MATCHES "cxx_std_20"
   OR targets MATCHES "-W[a-z]" OR (targets MATCHES "-fsanitize" AND NOT SANITIZE))
  message(FATAL_ERROR "fdemTargets.cmake: wrong usage requirements for consumers:\n${targets}")
endif()

# 2. the version policy of fdemConfigVersion.cmake (SameMinorVersion while 0.x)
function(check_version requested expected)
  set(PACKAGE_FIND_VERSION ${requested})
  string(REPLACE "." ";" parts "${requested}.0.0")
  list(GET parts 0 PACKAGE_FIND_VERSION_MAJOR)
  list(GET parts 1 PACKAGE_FIND_VERSION_MINOR)
  list(GET parts 2 PACKAGE_FIND_VERSION_PATCH)
  include(${prefix}/lib/cmake/fdem/fdemConfigVersion.cmake)
  if(NOT PACKAGE_VERSION STREQUAL VERSION)
    message(FATAL_ERROR "fdemConfigVersion.cmake says ${PACKAGE_VERSION}, project says ${VERSION}")
  endif()
  if((PACKAGE_VERSION_COMPATIBLE AND NOT expected) OR (expected AND NOT PACKAGE_VERSION_COMPATIBLE))
    message(FATAL_ERROR "find_package(fdem ${requested}) compatible = ${PACKAGE_VERSION_COMPATIBLE}"
                        " with fdem ${PACKAGE_VERSION}, expected ${expected}")
  endif()
endfunction()
string(REGEX MATCH "^([0-9]+)\\.([0-9]+)" mm "${VERSION}")
set(major ${CMAKE_MATCH_1})
set(minor ${CMAKE_MATCH_2})
math(EXPR next_minor "${minor} + 1")
math(EXPR next_major "${major} + 1")
check_version(${major}.${minor} TRUE)
check_version(${VERSION} TRUE)
check_version(${major}.${next_minor} FALSE)
check_version(${next_major}.${minor} FALSE)

# 3. a fresh CMake project finds the package in the prefix only, and builds
run(configure COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/api -B ${build} -G ${GENERATOR}
                      -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_CXX_COMPILER=${CXX}
                      -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
                      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS ${build}/CMakeCache.txt fdem_dir REGEX "^fdem_DIR:")
if(NOT fdem_dir STREQUAL "fdem_DIR:PATH=${prefix}/lib/cmake/fdem")
  message(FATAL_ERROR "found the package elsewhere: ${fdem_dir}")
endif()
run(build COMMAND ${CMAKE_COMMAND} --build ${build})

# 4. the consumer and the installed CLI step the same scenario: the same hash
set(scenario ${SOURCE_DIR}/examples/03_contact_slide/scenario.toml)
set(end_time 0.05)  # s: 9068 steps, the first landing (0.02 s) included
run(consumer COMMAND ${build}/fdem_api_demo ${scenario} ${end_time})
run(cli COMMAND ${prefix}/bin/fdem run ${scenario} --end-time ${end_time} --out ${WORK}/cli_out
                --quiet --print-hash)
string(REGEX MATCH "hash ([0-9a-f]+)" _ "${consumer_out}")
set(consumer_hash "${CMAKE_MATCH_1}")
string(REGEX MATCH "^hash ([0-9a-f]+)" _ "${cli_out}")
set(cli_hash "${CMAKE_MATCH_1}")
if(consumer_hash STREQUAL "" OR NOT consumer_hash STREQUAL cli_hash)
  message(FATAL_ERROR "consumer hash '${consumer_hash}' != CLI hash '${cli_hash}'\n"
                      "consumer:\n${consumer_out}\nCLI:\n${cli_out}")
endif()
# the version the consumer's headers carry is the CLI's
run(cli_version COMMAND ${prefix}/bin/fdem --version)
if(NOT consumer_out MATCHES "fdem +${VERSION} \\(headers ${VERSION}\\)"
   OR NOT cli_version_out MATCHES "^fdem ${VERSION}")
  message(FATAL_ERROR "versions differ from ${VERSION}:\n${consumer_out}\n${cli_version_out}")
endif()

# 5. the model built in code runs, with the energy balance of an undamped frictionless contact
run(built_in COMMAND ${build}/fdem_api_demo)
string(REGEX MATCH "= ([0-9.e+-]+) % of" _ "${built_in_out}")
set(energy_error "${CMAKE_MATCH_1}")
if(energy_error STREQUAL "" OR NOT energy_error LESS 1.0)
  message(FATAL_ERROR "built-in model: energy error '${energy_error}' %, not < 1 %:\n${built_in_out}")
endif()

# 6. errors cross the library boundary as the typed exceptions: bad input -> exit 2, message
execute_process(COMMAND ${build}/fdem_api_demo ${WORK}/no_such.toml
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "no_such.toml")
  message(FATAL_ERROR "missing scenario: expected exit 2 naming the file, got ${rc}:\n${err}")
endif()

message("consumer:\n${consumer_out}built in code:\n${built_in_out}")
message("OK: consumer hash ${consumer_hash} = CLI hash ${cli_hash}")
