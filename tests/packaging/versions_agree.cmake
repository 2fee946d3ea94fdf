# SPDX-License-Identifier: BSD-3-Clause
# cmake -P script run by the ctest packaging.versions_agree: the release
# version is written by hand in files that nothing generates from the CMake
# project's VERSION -- config.hpp (the headers compile without CMake),
# pyproject.toml (read by pip before CMake runs) and CITATION.cff (read by
# citation tools) -- so a release that bumps one and forgets another is
# caught here rather than by a user citing the wrong version.
#   cmake -DSOURCE_DIR=... -DEXPECTED_VERSION=... -P versions_agree.cmake
cmake_minimum_required(VERSION 3.20)

set(wrong "")
function(expect file regex)
  file(READ ${SOURCE_DIR}/${file} text)
  if(NOT text MATCHES "${regex}")
    string(APPEND wrong "\n  ${file}: no line matches '${regex}'")
  elseif(NOT CMAKE_MATCH_1 STREQUAL EXPECTED_VERSION)
    string(APPEND wrong "\n  ${file} says ${CMAKE_MATCH_1}")
  endif()
  set(wrong "${wrong}" PARENT_SCOPE)
endfunction()

expect(include/stickslip/config.hpp "#define STICKSLIP_VERSION_STRING \"([^\"]*)\"")
expect(pyproject.toml "\nversion = \"([^\"]*)\"")
expect(CITATION.cff "\nversion: ([^\n]*)")
if(wrong)
  message(FATAL_ERROR "the CMake project's VERSION is ${EXPECTED_VERSION}, but:${wrong}")
endif()
message(STATUS "config.hpp, pyproject.toml and CITATION.cff all say ${EXPECTED_VERSION}")
