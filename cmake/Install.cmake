# Install rules (docs/OPERATIONS.md "Install"): `cmake --install build [--prefix /usr]` puts
# the binaries, the systemd unit and sysusers entry, the example
# configuration and the operator's guide in place. Components: server
# (tessera-server and its files), cli (tessera), viewer, replay; the
# container image installs the first two. The unit names the binary and the
# configuration by absolute path, so its installed copy is rewritten for the
# prefix chosen at configure time: /usr unless -DCMAKE_INSTALL_PREFIX says
# otherwise (a server's unit and /etc configuration belong with /usr, and
# GNUInstallDirs maps that prefix's configuration to /etc).
if(CMAKE_INSTALL_PREFIX_INITIALIZED_TO_DEFAULT)
  set(CMAKE_INSTALL_PREFIX /usr CACHE PATH "Install prefix" FORCE)
endif()
include(GNUInstallDirs)

foreach(pair "tessera-server:server" "tessera:cli" "tessera-view:viewer" "tessera-replay:replay")
  string(REPLACE ":" ";" pair "${pair}")
  list(GET pair 0 target)
  list(GET pair 1 component)
  if(TARGET ${target})  # the viewer is skipped when its GL packages are missing
    install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT ${component})
  endif()
endforeach()

# Relative to the prefix unless set to an absolute path.
set(TESSERA_UNIT_DIR lib/systemd/system CACHE STRING "Where the systemd unit is installed")
set(TESSERA_SYSUSERS_DIR lib/sysusers.d CACHE STRING "Where the sysusers.d entry is installed")

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

# The browser viewer's files (docs/WEB_VIEWER.md): tessera-server finds them
# at PREFIX/share/tessera/web, beside its own PREFIX/bin, when its build tree
# is gone.
if(TESSERA_BUILD_WEB)
  install(DIRECTORY ${TESSERA_WEB_DIR}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tessera/web COMPONENT server)
endif()
