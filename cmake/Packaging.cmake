# `cpack` builds rpsd_<version>_amd64.deb: the rpsd binary, the module libraries, headers and
# CMake package, and under share/rpsd the example scenarios with the records, servo files and
# DDS configurations they name (their relative paths hold there as in the source tree), and the
# docs under share/doc/rpsd. Runtime dependencies come from dpkg-shlibdeps (libcpp-httplib for
# `rpsd monitor`, whose page is built into the binary), plus gnuplot for the plots, and for the
# Python module (python/, in /usr/lib/python3/dist-packages) the python3 it was built for with
# NumPy, h5py and PyYAML; building against the CMake package needs the -dev packages it recommends.
set(RPSD_SHARE_DIR ${CMAKE_INSTALL_DATADIR}/rpsd)
install(DIRECTORY examples/ DESTINATION ${RPSD_SHARE_DIR}/examples)
install(DIRECTORY data/ground-motions/ DESTINATION ${RPSD_SHARE_DIR}/data/ground-motions)
install(DIRECTORY transport/config/ DESTINATION ${RPSD_SHARE_DIR}/transport/config)
install(FILES README.md LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rpsd)
set(CPACK_PACKAGE_VENDOR "rpsd developers")
set(CPACK_PACKAGE_CONTACT "rpsd developers <maintainers@users.noreply.github.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "Coordinator, simulated servo-hydraulic rig and servo nodes over Cyclone DDS for real-time pseudodynamic tests.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "gnuplot-nox | gnuplot")
if(RPSD_PYTHON_VERSION)
  # The extension is built for one minor version of Python (its ABI).
  string(REPLACE "." ";" python_version_parts ${RPSD_PYTHON_VERSION})
  list(GET python_version_parts 0 python_major)
  list(GET python_version_parts 1 python_minor)
  math(EXPR python_next_minor "${python_minor} + 1")
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", python3 (>= ${RPSD_PYTHON_VERSION}), python3 (<< ${python_major}.${python_next_minor}),"
         " python3-numpy, python3-h5py, python3-yaml")
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libeigen3-dev, libspectra-dev, libyaml-cpp-dev, nlohmann-json3-dev, libcli11-dev, cyclonedds-dev, libssl-dev, libcpp-httplib-dev, pkg-config")
include(CPack)
