# ctest gltf_validator_export (see tests/validator.cmake): writes the sample
# GLBs with WRITER into OUT_DIR, then runs the Khronos glTF-Validator on them.
# Fails if either step fails, i.e. on any validator error.
foreach(var WRITER NODE VALIDATOR_DIR OUT_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_gltf_validator.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
execute_process(COMMAND "${WRITER}" "${OUT_DIR}" RESULT_VARIABLE writer_result)
if(NOT writer_result EQUAL 0)
  message(FATAL_ERROR "${WRITER} failed (exit ${writer_result})")
endif()

file(GLOB glbs "${OUT_DIR}/*.glb")
list(LENGTH glbs glb_count)
if(glb_count LESS 4)
  message(FATAL_ERROR "expected 4 GLB files in ${OUT_DIR}, found ${glb_count}")
endif()
execute_process(
  COMMAND "${NODE}" "${VALIDATOR_DIR}/validate.js" ${glbs}
  RESULT_VARIABLE validator_result)
if(NOT validator_result EQUAL 0)
  message(FATAL_ERROR "glTF-Validator reported errors (exit ${validator_result})")
endif()
