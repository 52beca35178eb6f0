# The Khronos glTF-Validator run on Tessera's GLB export (plain and Draco).
# Included from tests/CMakeLists.txt:  include(${CMAKE_CURRENT_SOURCE_DIR}/validator.cmake)
#
# The validator is the npm package gltf-validator, pinned by
# tests/tools/gltf-validator/package-lock.json. Two ctest tests:
#   gltf_validator_npm_ci   FIXTURES_SETUP: `npm ci` into
#                           ${CMAKE_BINARY_DIR}/gltf-validator, skipped when that
#                           lock file is already installed there (offline after
#                           the first run);
#   gltf_validator_export   writes a plain and a Draco GLB with
#                           write_sample_glbs and fails on any validator error.
# Without node and npm configuring fails: deploy/install-deps.sh installs them.

find_program(TESSERA_NODE_EXECUTABLE node)
find_program(TESSERA_NPM_EXECUTABLE npm)
if(NOT TESSERA_NODE_EXECUTABLE OR NOT TESSERA_NPM_EXECUTABLE)
  # The validator test is part of the suite: never skip it silently.
  message(FATAL_ERROR "node and npm are needed for the glTF-Validator tests: run deploy/install-deps.sh")
endif()

set(_validator_source_dir ${CMAKE_CURRENT_LIST_DIR}/tools/gltf-validator)
set(_validator_dir ${CMAKE_BINARY_DIR}/gltf-validator)
# COPYONLY copies re-run configure when a source changes, so an edited lock
# file reaches the cache (and the stamp check then reinstalls).
foreach(_file package.json package-lock.json validate.js)
  configure_file(${_validator_source_dir}/${_file} ${_validator_dir}/${_file} COPYONLY)
endforeach()

add_executable(write_sample_glbs ${CMAKE_CURRENT_LIST_DIR}/tools/write_sample_glbs.cc)
target_link_libraries(write_sample_glbs PRIVATE tessera_core)
target_include_directories(write_sample_glbs PRIVATE ${CMAKE_CURRENT_LIST_DIR})
# ctest does not build; tie the tool to the core suite so building that
# suite is enough to run the validator test too.
if(TARGET tessera_core_tests)
  add_dependencies(tessera_core_tests write_sample_glbs)
endif()

add_test(NAME gltf_validator_npm_ci
  COMMAND ${CMAKE_COMMAND} -DNPM=${TESSERA_NPM_EXECUTABLE} -DDIR=${_validator_dir}
          -P ${CMAKE_CURRENT_LIST_DIR}/tools/npm_ci_if_needed.cmake)
set_tests_properties(gltf_validator_npm_ci PROPERTIES
  FIXTURES_SETUP gltf_validator
  TIMEOUT 600
  LABELS validator)

add_test(NAME gltf_validator_export
  COMMAND ${CMAKE_COMMAND}
          -DWRITER=$<TARGET_FILE:write_sample_glbs>
          -DNODE=${TESSERA_NODE_EXECUTABLE}
          -DVALIDATOR_DIR=${_validator_dir}
          -DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/gltf_validator_export
          -P ${CMAKE_CURRENT_LIST_DIR}/tools/run_gltf_validator.cmake)
set_tests_properties(gltf_validator_export PROPERTIES
  FIXTURES_REQUIRED gltf_validator
  TIMEOUT 300
  LABELS validator)
