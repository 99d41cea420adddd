# canspec's CMake package: generated protocol headers as an INTERFACE library.
#
#   find_package(canspec CONFIG REQUIRED)   # -Dcanspec_DIR="$(canspec --cmake-dir)", or PATHS/CMAKE_PREFIX_PATH
#   canspec_add_protocol(gateway SPEC spec/canspec.yaml NODE Wire_Car_ECU)
#   target_link_libraries(ecu PRIVATE gateway)
#
# canspec_add_protocol(<target> SPEC <file> [NODE <name>] [OUTPUT_DIR <dir>] [TARGETS <name>...] [STRICT])
#   Runs `canspec gen <SPEC> -o <OUTPUT_DIR> --target c [--node NODE] --depfile ...` at build time,
#   only when a file the spec read changed (the spec files, the schema, ERRATA.md: canspec writes
#   them into a depfile; Ninja and Makefile generators read it). <target> carries the include
#   directory <OUTPUT_DIR>/c; linking it orders the generation before the compile. OUTPUT_DIR
#   defaults to ${CMAKE_CURRENT_BINARY_DIR}/<target>; TARGETS adds other canspec targets (dbc,
#   python, ...) to the same run; STRICT treats spec warnings as errors. A spec error fails the
#   build with canspec's file:line message.
#
# CANSPEC_COMMAND (cache): the command that runs canspec, a list for a launcher
# (-DCANSPEC_COMMAND="python3;-m;canspec"); by default the `canspec` beside this package's Python
# (a virtual environment's bin/), else the one on PATH.

cmake_minimum_required(VERSION 3.20)  # DEPFILE with the Makefile generators

if(NOT CANSPEC_COMMAND)
  get_filename_component(_canspec_site "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
  find_program(CANSPEC_EXECUTABLE canspec
    HINTS "${_canspec_site}/../../bin" "${_canspec_site}/../bin" "${_canspec_site}/../../Scripts"
    DOC "the canspec command")
  unset(_canspec_site)
  if(NOT CANSPEC_EXECUTABLE)
    set(canspec_FOUND FALSE)
    set(canspec_NOT_FOUND_MESSAGE "no canspec command found: install canspec (pip install canspec) or set CANSPEC_COMMAND")
    return()
  endif()
  set(CANSPEC_COMMAND "${CANSPEC_EXECUTABLE}" CACHE STRING "the command that runs canspec (a list for a launcher: python3;-m;canspec)")
endif()

function(canspec_add_protocol target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "STRICT" "SPEC;NODE;OUTPUT_DIR" "TARGETS")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "canspec_add_protocol(${target}): unknown arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_SPEC)
    message(FATAL_ERROR "canspec_add_protocol(${target}): SPEC <file> is required (a bundle such as spec/canspec.yaml, its directory or one spec file)")
  endif()
  get_filename_component(spec "${ARG_SPEC}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${spec}")
    message(FATAL_ERROR "canspec_add_protocol(${target}): SPEC ${spec} does not exist")
  endif()
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/${target}")
  endif()
  get_filename_component(out "${ARG_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set(options)
  list(APPEND ARG_TARGETS c)
  list(REMOVE_DUPLICATES ARG_TARGETS)
  foreach(name IN LISTS ARG_TARGETS)
    list(APPEND options --target "${name}")
  endforeach()
  if(ARG_NODE)
    list(APPEND options --node "${ARG_NODE}")
  endif()
  if(ARG_STRICT)
    list(APPEND options --strict)
  endif()
  # The manifest is the depfile's target: canspec touches it on every successful run, and
  # rewrites a header only when its bytes changed.
  set(stamp "${out}/.canspec-manifest.json")
  set(direct)
  if(NOT IS_DIRECTORY "${spec}")  # a directory's bundle file is in the depfile
    set(direct "${spec}")
  endif()
  set(depfile "${CMAKE_CURRENT_BINARY_DIR}/${target}.canspec.d")
  add_custom_command(
    OUTPUT "${stamp}"
    COMMAND ${CANSPEC_COMMAND} gen "${spec}" -o "${out}" ${options} --quiet --depfile "${depfile}"
    DEPENDS ${direct}
    DEPFILE "${depfile}"
    COMMENT "canspec: generating ${target} from ${ARG_SPEC}"
    VERBATIM)
  add_custom_target(${target}_canspec_gen DEPENDS "${stamp}")
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE "${out}/c")
  add_dependencies(${target} ${target}_canspec_gen)
endfunction()
