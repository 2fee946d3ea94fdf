# SPDX-License-Identifier: BSD-3-Clause
# cmake -P script run by the ctest packaging.find_package_consumer:
# install the build tree into a scratch prefix, then configure, build and run
# a consumer project that uses find_package(stickslip) with only
# CMAKE_PREFIX_PATH pointing there.
#
# Inputs (-D): BUILD_DIR, CONFIG, CONSUMER_SOURCE, WORK_DIR, GENERATOR,
# MAKE_PROGRAM, CXX_COMPILER, EXPECTED_VERSION.
cmake_minimum_required(VERSION 3.20)

foreach(var BUILD_DIR CONSUMER_SOURCE WORK_DIR GENERATOR CXX_COMPILER EXPECTED_VERSION)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "consumer_test.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

set(prefix ${WORK_DIR}/prefix)
set(consumer_build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

function(step name)
  # A time limit per step, so that a hang is reported as such, with the step's name.
  execute_process(COMMAND ${ARGN} TIMEOUT 300
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} failed (${rc}):\n${ARGN}\n--- stdout\n${out}\n--- stderr\n${err}")
  endif()
  message(STATUS "${name}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# 1. Install.
step("install into ${prefix}"
     ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --config ${CONFIG})
# GNUInstallDirs may choose lib, lib64 or a multiarch libdir: search for the config.
file(GLOB_RECURSE config_file ${prefix}/stickslipConfig.cmake)
foreach(f include/stickslip/diffusivity.hpp bin/stickslip share/doc/stickslip/LICENSE share/stickslip/report.schema.json)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "installed tree lacks ${f}")
  endif()
endforeach()
if(NOT config_file)
  message(FATAL_ERROR "installed tree lacks stickslipConfig.cmake")
endif()

# 2. Configure the consumer against the prefix only (no package registry).
set(make_program)
if(MAKE_PROGRAM)
  set(make_program -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
step("configure consumer"
     ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${consumer_build} -G ${GENERATOR} ${make_program}
       -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=${CONFIG}
       -DCMAKE_PREFIX_PATH=${prefix}
       -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
       -DSTICKSLIP_EXPECTED_VERSION=${EXPECTED_VERSION})

# The package must come from the scratch prefix, not from a build tree.
file(STRINGS ${consumer_build}/CMakeCache.txt dir_line REGEX "^stickslip_DIR:")
string(REGEX REPLACE "^stickslip_DIR:[A-Z]*=" "" stickslip_dir "${dir_line}")
string(FIND "${stickslip_dir}" "${prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "consumer found stickslip in '${stickslip_dir}', not under ${prefix}")
endif()
message(STATUS "stickslip_DIR = ${stickslip_dir}")

# 3. Build.
step("build consumer" ${CMAKE_COMMAND} --build ${consumer_build} --config ${CONFIG})

# 4. Run.
find_program(consumer_exe NAMES stickslip_consumer
             PATHS ${consumer_build} ${consumer_build}/${CONFIG} NO_DEFAULT_PATH REQUIRED)
step("run consumer" ${consumer_exe})
message(STATUS "consumer output:\n${step_output}")
foreach(expect "stickslip ${EXPECTED_VERSION}" "nondimensional tau' = 1\\.47456"
               "dry-friction D = [0-9][0-9.e+-]* m\\^2/s" "pdmp D = [0-9][0-9.e+-]* m\\^2/s from 128 excursions, json ok"
               "philox ok")
  if(NOT step_output MATCHES "${expect}")
    message(FATAL_ERROR "consumer output does not match '${expect}':\n${step_output}")
  endif()
endforeach()

# 5. The installed command runs too.
step("installed stickslip --version" ${prefix}/bin/stickslip --version)
if(NOT step_output MATCHES "${EXPECTED_VERSION}")
  message(FATAL_ERROR "installed stickslip --version printed '${step_output}'")
endif()

file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "find_package(stickslip) consumer: PASSED")
