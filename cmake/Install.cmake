# Install rules (issue 14 §1): `cmake --install build [--prefix /usr]` puts
# the binaries, the systemd unit and sysusers entry, the example
# configuration and the operator's guide in place. Components: server
# (tessera-server and its files), cli (tessera), viewer, replay; the
# container image installs the first two. The unit names the binary and the
# configuration by absolute path, so its installed copy is rewritten for the
# prefix.
include(GNUInstallDirs)

foreach(pair "tessera-server:server" "tessera:cli" "tessera-view:viewer" "tessera-replay:replay")
  string(REPLACE ":" ";" pair "${pair}")
  list(GET pair 0 target)
  list(GET pair 1 component)
  if(TARGET ${target})  # the viewer is skipped when its GL packages are missing
    install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT ${component})
  endif()
endforeach()

set(TESSERA_UNIT_DIR ${CMAKE_INSTALL_PREFIX}/lib/systemd/system CACHE PATH "Where the systemd unit is installed")
set(TESSERA_SYSUSERS_DIR ${CMAKE_INSTALL_PREFIX}/lib/sysusers.d CACHE PATH "Where the sysusers.d entry is installed")

file(READ ${PROJECT_SOURCE_DIR}/deploy/tessera-server.service unit)
string(REPLACE "/usr/bin/tessera-server" "${CMAKE_INSTALL_FULL_BINDIR}/tessera-server" unit "${unit}")
string(REPLACE "/etc/tessera/" "${CMAKE_INSTALL_FULL_SYSCONFDIR}/tessera/" unit "${unit}")
file(WRITE ${PROJECT_BINARY_DIR}/deploy/tessera-server.service "${unit}")

install(FILES ${PROJECT_BINARY_DIR}/deploy/tessera-server.service DESTINATION ${TESSERA_UNIT_DIR} COMPONENT server)
install(FILES ${PROJECT_SOURCE_DIR}/deploy/tessera.sysusers DESTINATION ${TESSERA_SYSUSERS_DIR} RENAME tessera.conf
        COMPONENT server)
install(FILES ${PROJECT_SOURCE_DIR}/deploy/tessera-server.conf DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/tessera
        COMPONENT server)
install(FILES ${PROJECT_SOURCE_DIR}/docs/OPERATIONS.md ${PROJECT_SOURCE_DIR}/docs/PROTOCOL.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT server)
