# Real test meshes from Debian's libcgal-demo (installed by deploy/install-deps.sh),
# extracted once at configure time into the build tree; nothing is downloaded.
set(TESSERA_TESTDATA_DIR ${CMAKE_BINARY_DIR}/testdata)
set(CGAL_DATA_TARBALL /usr/share/doc/libcgal-dev/data.tar.gz)
# double-torus-example.off: quads, pentagons, hexagons and heptagons (the
# Catmull-Clark oracle's real polygon mesh). The check names the last mesh
# added, so that existing build trees extract the new ones.
set(CGAL_MESHES fandisk.off elephant.off hand.off 3torus.off knot1.off mushroom.off double-torus-example.off)
if(NOT EXISTS ${TESSERA_TESTDATA_DIR}/cgal/double-torus-example.off)
  if(NOT EXISTS ${CGAL_DATA_TARBALL})
    message(FATAL_ERROR "${CGAL_DATA_TARBALL} is missing: run deploy/install-deps.sh (package libcgal-demo)")
  endif()
  file(MAKE_DIRECTORY ${TESSERA_TESTDATA_DIR}/cgal)
  set(_members)
  foreach(m ${CGAL_MESHES})
    list(APPEND _members data/meshes/${m})
  endforeach()
  execute_process(
    COMMAND tar xzf ${CGAL_DATA_TARBALL} --strip-components=2 -C ${TESSERA_TESTDATA_DIR}/cgal ${_members}
    RESULT_VARIABLE _tar_result)
  if(NOT _tar_result EQUAL 0)
    message(FATAL_ERROR "could not extract test meshes from ${CGAL_DATA_TARBALL}")
  endif()
endif()

