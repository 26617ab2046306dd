# The CTest test InstalledPackageBuildsAConsumer (registered in tests/CMakeLists.txt):
#   1. cmake --install the build tree into a fresh prefix under WORK_DIR;
#   2. configure this directory's consumer project against it (CMAKE_PREFIX_PATH only,
#      no package registry; lafair must be found there), with the build's generator
#      and compiler;
#   3. build it and 4. run it (it fits a noisy wave and checks tolerance and G2).
# Any failing step fails the test with a message naming the step. It installs what is
# built: run it after building (scripts/test.sh does).
#
# cmake -DBUILD_DIR=<lafair build> -DCONSUMER_SOURCE_DIR=<tests/install> -DWORK_DIR=<dir>
#       -DCONFIG=<config> -DGENERATOR=<generator> [-DGENERATOR_PLATFORM=..]
#       [-DGENERATOR_TOOLSET=..] [-DMAKE_PROGRAM=..] -DCXX_COMPILER=<c++>
#       -P run_consumer.cmake

foreach(var BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
set(consumer_build ${WORK_DIR}/consumer-build)
file(REMOVE_RECURSE ${prefix} ${consumer_build})
file(MAKE_DIRECTORY ${prefix} ${consumer_build})

# Runs one step; when it fails, prints its output as it is and stops the test.
function(run_step name hint)
  list(JOIN ARGN " " command_line)
  message(STATUS "${name}: ${command_line}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT result EQUAL 0)
    message("${out}")
    message(FATAL_ERROR "${name} failed (${result}). ${hint}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(config_args)
if(NOT "${CONFIG}" STREQUAL "")
  set(config_args --config ${CONFIG})
endif()

run_step("Step 1, install" "Is the build complete (cmake --build ${BUILD_DIR})?"
         ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} ${config_args})
foreach(installed include/lafair/core/la_segment.h include/lafair/fitting/pipeline.h)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "Step 1, install: ${installed} is missing from ${prefix}")
  endif()
endforeach()

set(configure_args -S ${CONSUMER_SOURCE_DIR} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(NOT "${GENERATOR_PLATFORM}" STREQUAL "")
  list(APPEND configure_args -A ${GENERATOR_PLATFORM})
endif()
if(NOT "${GENERATOR_TOOLSET}" STREQUAL "")
  list(APPEND configure_args -T ${GENERATOR_TOOLSET})
endif()
if(NOT "${MAKE_PROGRAM}" STREQUAL "")
  list(APPEND configure_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(NOT "${CONFIG}" STREQUAL "")
  list(APPEND configure_args -DCMAKE_BUILD_TYPE=${CONFIG})
endif()
run_step("Step 2, configure the consumer" "The installed package or a dependency it finds is broken."
         ${CMAKE_COMMAND} ${configure_args})

# The package must come from the fresh prefix, not from the build or source tree.
file(STRINGS ${consumer_build}/CMakeCache.txt lafair_dir REGEX "^lafair_DIR:")
string(REGEX REPLACE "^lafair_DIR:[A-Z]+=" "" lafair_dir "${lafair_dir}")
file(REAL_PATH ${prefix} real_prefix)
file(REAL_PATH "${lafair_dir}" real_lafair_dir)
string(FIND "${real_lafair_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "Step 2, configure the consumer: lafair was found in '${lafair_dir}', not under ${prefix}")
endif()

run_step("Step 3, build the consumer" "The installed headers or libraries are broken."
         ${CMAKE_COMMAND} --build ${consumer_build} ${config_args})

# Single-config generators put the program in the build directory, multi-config ones
# in a directory per configuration.
set(program ${consumer_build}/fit_wave)
if(NOT EXISTS ${program} AND NOT EXISTS ${program}.exe)
  set(program ${consumer_build}/${CONFIG}/fit_wave)
endif()
run_step("Step 4, run the consumer" "The fit did not meet the checks above (FAIL lines)."
         ${program})
message("${step_output}")
