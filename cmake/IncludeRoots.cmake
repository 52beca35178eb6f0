# Include roots: each library sees the source tree only through a folder of
# its own that holds symbolic links to the source folders it owns
# (build/include_roots/<target>/core/loop -> core/loop, ...). A library
# reaches another's headers only by linking it, so an #include of a folder it
# does not link does not compile (docs/ARCHITECTURE.md, "Layers"; the finer
# rules inside a library are the layering test's, tests/layering).
#
#   tessera_include_root(<target> <folder>...)
function(tessera_include_root target)
  set(root ${PROJECT_BINARY_DIR}/include_roots/${target})
  foreach(folder IN LISTS ARGN)
    if(NOT IS_DIRECTORY ${PROJECT_SOURCE_DIR}/${folder})
      message(FATAL_ERROR "tessera_include_root(${target}): no folder ${folder}")
    endif()
    get_filename_component(parent ${root}/${folder} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(NOT EXISTS ${root}/${folder})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${root}/${folder} SYMBOLIC)
    endif()
  endforeach()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE")
    target_include_directories(${target} PRIVATE ${root})
  else()
    target_include_directories(${target} PUBLIC ${root})
  endif()
endfunction()
