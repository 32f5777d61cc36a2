# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The Debian 12 package `implicit-fairing` (CPack DEB), included from the top CMakeLists.txt.
# It holds what `cmake --install` installs for the components
#   meshlab2020  the 2020.09 plugin -> /usr/lib/x86_64-linux-gnu/meshlab/plugins/
#   cli          /usr/bin/implicit-fairing and its man page (help2man, from --help)
#   debian       /usr/share/doc/implicit-fairing/{copyright,changelog.Debian.gz}; package only
# scripts/package.sh builds it from the normal build dir; tests/package installs it (label
# package). Needs the targets filter_implicit_fairing and implicit-fairing (MESHLAB_2020_SOURCE).
if(NOT TARGET filter_implicit_fairing OR NOT TARGET implicit-fairing)
  return()
endif()

# Dates in the man page and the changelog: the last commit's when built from git (the same
# bytes on every rebuild of one commit), else now.
execute_process(COMMAND git -C ${PROJECT_SOURCE_DIR} log -1 --format=%ct%n%aD
                OUTPUT_VARIABLE git_dates OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE git_rc)
if(git_rc EQUAL 0 AND git_dates MATCHES "^([0-9]+)\n(.+)$")
  set(FAIRING_SOURCE_DATE_EPOCH ${CMAKE_MATCH_1})
  set(FAIRING_DEB_DATE "${CMAKE_MATCH_2}")
else()
  string(TIMESTAMP FAIRING_SOURCE_DATE_EPOCH "%s" UTC)
  string(TIMESTAMP FAIRING_DEB_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)
endif()

# ---- man page: help2man runs the freshly built tool at build time -------------------------------
find_program(HELP2MAN_EXECUTABLE help2man)
find_program(GZIP_EXECUTABLE gzip)
set(FAIRING_MAN_NAME_LINE "smooth a triangle mesh by implicit fairing (Desbrun et al. 1999)")
set(FAIRING_MAN_PAGE ${CMAKE_BINARY_DIR}/man/implicit-fairing.1.gz)
if(HELP2MAN_EXECUTABLE AND GZIP_EXECUTABLE)
  # gzip -n: no time stamp in the archive (reproducible; lintian checks it).
  add_custom_command(OUTPUT ${FAIRING_MAN_PAGE}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/man
    COMMAND ${CMAKE_COMMAND} -E env SOURCE_DATE_EPOCH=${FAIRING_SOURCE_DATE_EPOCH}
            ${HELP2MAN_EXECUTABLE} --no-info --section=1
            --name=${FAIRING_MAN_NAME_LINE} --output=${CMAKE_BINARY_DIR}/man/implicit-fairing.1
            $<TARGET_FILE:implicit-fairing>
    COMMAND ${GZIP_EXECUTABLE} -9nf ${CMAKE_BINARY_DIR}/man/implicit-fairing.1
    DEPENDS implicit-fairing
    COMMENT "Generating the man page implicit-fairing.1 from implicit-fairing --help"
    VERBATIM)
  add_custom_target(implicit-fairing-man ALL DEPENDS ${FAIRING_MAN_PAGE})
  install(FILES ${FAIRING_MAN_PAGE} DESTINATION share/man/man1 COMPONENT cli)
else()
  message(WARNING "help2man not found: no man page for implicit-fairing, and scripts/package.sh "
                  "refuses to build the .deb (apt-get install help2man; scripts/setup.sh does)")
endif()

# ---- Debian files: copyright (machine-readable) and a changelog matching the version ----------
set(FAIRING_DEB_NAME implicit-fairing)
set(FAIRING_DEB_REVISION 1 CACHE STRING "Debian revision of the .deb (version ${PROJECT_VERSION}-N)")
set(FAIRING_DEB_MAINTAINER
    "filter_implicit_fairing maintainers <maintainers@users.noreply.h-seed-20853493.example>"
    CACHE STRING "Maintainer field of the .deb")
set(deb_doc ${CMAKE_BINARY_DIR}/packaging)
file(WRITE ${deb_doc}/changelog.Debian
"${FAIRING_DEB_NAME} (${PROJECT_VERSION}-${FAIRING_DEB_REVISION}) bookworm; urgency=medium

  * Built with CPack from filter_implicit_fairing ${PROJECT_VERSION} for Debian 12's
    MeshLab 2020.09.

 -- ${FAIRING_DEB_MAINTAINER}  ${FAIRING_DEB_DATE}
")
if(GZIP_EXECUTABLE)
  add_custom_command(OUTPUT ${deb_doc}/changelog.Debian.gz
    COMMAND ${GZIP_EXECUTABLE} -9nc ${deb_doc}/changelog.Debian > ${deb_doc}/changelog.Debian.gz
    DEPENDS ${deb_doc}/changelog.Debian VERBATIM)
  add_custom_target(implicit-fairing-changelog ALL DEPENDS ${deb_doc}/changelog.Debian.gz)
  # EXCLUDE_FROM_ALL: only the package (or --component debian) installs these.
  install(FILES ${deb_doc}/changelog.Debian.gz
          DESTINATION share/doc/${FAIRING_DEB_NAME} COMPONENT debian EXCLUDE_FROM_ALL)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright
        DESTINATION share/doc/${FAIRING_DEB_NAME} COMPONENT debian EXCLUDE_FROM_ALL)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/lintian-overrides
        DESTINATION share/lintian/overrides RENAME ${FAIRING_DEB_NAME}
        COMPONENT debian EXCLUDE_FROM_ALL)
# Debian's default hardening (dpkg-buildflags): a read-only GOT once loaded (lintian:
# hardening-no-bindnow). Both are linked with every symbol resolved already.
foreach(t filter_implicit_fairing implicit-fairing)
  target_link_options(${t} PRIVATE -Wl,-z,relro -Wl,-z,now)
endforeach()
# and fortified libc calls (hardening-no-fortify-functions; the plugin has none to fortify).
target_compile_definitions(implicit-fairing PRIVATE _FORTIFY_SOURCE=2)

# ---- CPack --------------------------------------------------------------------------------------
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ${FAIRING_DEB_NAME})
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "filter_implicit_fairing")
set(CPACK_PACKAGE_CONTACT "${FAIRING_DEB_MAINTAINER}")
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)     # implicit-fairing_<version>-<rev>_amd64.deb
set(CPACK_DEBIAN_PACKAGE_RELEASE ${FAIRING_DEB_REVISION})
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "implicit fairing of triangle meshes: MeshLab plugin and command-line tool")
# The extended description only (CPack puts the summary on the first line).
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
"Smooths triangle meshes by implicit integration of diffusion and curvature
flow, after Desbrun, Meyer, Schroeder and Barr: Implicit Fairing of
Irregular Meshes using Diffusion and Curvature Flow (SIGGRAPH 1999).
Umbrella, scale-dependent and curvature-flow operators, first order or
L-squared, with exact volume preservation and hard and soft constraints.
.
This package contains the MeshLab 2020.09 filter plugin (three filters in
Filters > Smoothing, Fairing and Deformation, also usable from
meshlabserver scripts) and the command-line tool implicit-fairing.")
# The plugin is built against the C++ headers of MeshLab 2020.09+dfsg1-2 (Debian 12) and calls
# into libmeshlab-common.so, which has no versioned SONAME and no shlibs file, and MeshLab
# 2020.09 loads plugins without any version check: another MeshLab, or a Debian revision that
# patches its headers, would crash at load time or on first use instead of refusing the
# plugin. So: that revision, plus binNMUs (+bN) and stable updates (+deb12uN), which by
# Debian policy rebuild or patch without changing interfaces.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "meshlab (>= 2020.09+dfsg1-2), meshlab (<< 2020.09+dfsg1-3~)")
# Qt, libstdc++, libgomp, libc...: from dpkg-shlibdeps. libmeshlab-common.so is MeshLab's
# private library (found in its folder, no shlibs entry): the Depends above covers it.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${MESHLAB_2020_LIBDIR})
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_STRIP_FILES ON)
# One package holding these components (component install, all in one).
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL meshlab2020 cli debian)
# The plugin's destination is absolute (MeshLab 2020.09 looks only in its own folder, whatever
# CMAKE_INSTALL_PREFIX is): DESTDIR staging puts it, and the /usr-relative files, in the package.
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
include(CPack)

if(FAIRING_BUILD_TESTS)
  add_subdirectory(${PROJECT_SOURCE_DIR}/tests/package ${CMAKE_BINARY_DIR}/tests/package)
endif()
