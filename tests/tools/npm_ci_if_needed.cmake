# ctest fixture (see tests/validator.cmake): installs the pinned glTF-Validator
# into DIR with `npm ci`, unless DIR/node_modules already holds an install of
# this exact package-lock.json. The stamp makes repeated runs instant and
# offline; a changed lock file triggers a clean reinstall.
#   cmake -DNPM=/usr/bin/npm -DDIR=<build>/gltf-validator -P npm_ci_if_needed.cmake
foreach(var NPM DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "npm_ci_if_needed.cmake: -D${var}=... is required")
  endif()
endforeach()

file(SHA256 "${DIR}/package-lock.json" lock_hash)
set(stamp "${DIR}/node_modules/.tessera-lock-sha256")
if(EXISTS "${stamp}" AND EXISTS "${DIR}/node_modules/gltf-validator/package.json")
  file(READ "${stamp}" installed_hash)
  if(installed_hash STREQUAL lock_hash)
    message(STATUS "gltf-validator already installed in ${DIR}")
    return()
  endif()
endif()

execute_process(
  COMMAND "${NPM}" ci --no-audit --no-fund
  WORKING_DIRECTORY "${DIR}"
  RESULT_VARIABLE npm_result)
if(NOT npm_result EQUAL 0)
  message(FATAL_ERROR "npm ci failed in ${DIR} (exit ${npm_result}); the npm registry must be reachable once")
endif()
file(WRITE "${stamp}" "${lock_hash}")
