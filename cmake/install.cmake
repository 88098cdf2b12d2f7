# Installation (issue 16 item 1): `cmake --install build --prefix P` or `make install PREFIX=P` puts
#   P/bin/lucent                          the command (linked statically against the library)
#   P/include/lucent/*.h                  the public headers (C11 and C++)
#   P/lib/liblucent.so.X.Y.Z, .a          the shared library (soname liblucent.so.X.Y) and the static one
#   P/lib/pkgconfig/lucent.pc             pkg-config: `pkg-config --cflags --libs lucent` (shared),
#                                         `pkg-config --static --libs lucent` (static, with the private deps)
#   P/lib/cmake/Lucent/                   find_package(Lucent) -> Lucent::lucent (the shared library)
#   P/lib/python3/site-packages/lucent/   the Python package (ctypes over liblucent.so), when present
#   P/share/man/man1/lucent.1, lucent-CMD.1  a man page per command, made from its --help
#   P/share/bash-completion/completions/lucent  bash completion, made from the same --help text
#   P/share/lucent/                       the example scenes (and the sample meshes when fetched),
#                                         example materials and MCML inputs (share/lucent/README)
# Everything is relocatable: lucent.pc finds its prefix from its own place (${pcfiledir}), the CMake
# package from its own, the Python package looks for ../../../liblucent.so.
include(CMakePackageConfigHelpers)

# The header's version must be the project's.
file(STRINGS ${CMAKE_SOURCE_DIR}/include/lucent/base.h LUCENT_HEADER_VERSION
     REGEX "#define LUCENT_VERSION_STRING")
if(NOT LUCENT_HEADER_VERSION MATCHES "\"${PROJECT_VERSION}\"")
  message(FATAL_ERROR "include/lucent/base.h says ${LUCENT_HEADER_VERSION}, CMakeLists.txt ${PROJECT_VERSION}")
endif()

install(TARGETS lucent RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS lucent_lib ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS lucent_shared EXPORT LucentTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Unspecified)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/lucent DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")

# pkg-config. Libs carry an rpath to the prefix's lib so that a program built against a prefix
# outside the loader's path runs as built (no LD_LIBRARY_PATH).
get_filename_component(LUCENT_OPENEXR_CORE_NAME ${OPENEXR_CORE_LIBRARY} NAME_WE)
string(REGEX REPLACE "^lib" "" LUCENT_OPENEXR_CORE_NAME ${LUCENT_OPENEXR_CORE_NAME})
file(RELATIVE_PATH LUCENT_PC_TO_PREFIX ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig
     ${CMAKE_INSTALL_PREFIX})
set(LUCENT_PC_MPI "")
if(LUCENT_MPI)
  set(LUCENT_PC_MPI " ompi-c") # Open MPI's C library (Debian: libopenmpi-dev)
endif()
configure_file(${CMAKE_SOURCE_DIR}/cmake/lucent.pc.in ${CMAKE_BINARY_DIR}/lucent.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/lucent.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# CMake package.
set_target_properties(lucent_shared PROPERTIES EXPORT_NAME lucent)
install(EXPORT LucentTargets NAMESPACE Lucent:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Lucent)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/LucentConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/LucentConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Lucent)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/LucentConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/LucentConfig.cmake ${CMAKE_BINARY_DIR}/LucentConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Lucent)

# Python package (python/lucent), pure Python: installed beside the library it loads.
if(EXISTS ${CMAKE_SOURCE_DIR}/python/lucent)
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/python/lucent
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/python3/site-packages
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
endif()

# Man pages and bash completion from the command's own --help (cmake/docs_from_help.sh), remade
# whenever the command is.
set(LUCENT_HELP_DIR ${CMAKE_BINARY_DIR}/help)
add_custom_command(OUTPUT ${LUCENT_HELP_DIR}/man/lucent.1 ${LUCENT_HELP_DIR}/completion/lucent
                   COMMAND ${CMAKE_SOURCE_DIR}/cmake/docs_from_help.sh $<TARGET_FILE:lucent> ${LUCENT_HELP_DIR}
                           ${PROJECT_VERSION}
                   DEPENDS lucent ${CMAKE_SOURCE_DIR}/cmake/docs_from_help.sh
                   COMMENT "Man pages and bash completion from lucent --help")
add_custom_target(lucent_help_docs ALL DEPENDS ${LUCENT_HELP_DIR}/man/lucent.1 ${LUCENT_HELP_DIR}/completion/lucent)
install(DIRECTORY ${LUCENT_HELP_DIR}/man/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 FILES_MATCHING PATTERN "*.1")
install(FILES ${LUCENT_HELP_DIR}/completion/lucent DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/bash-completion/completions)

# What a newcomer runs first: the default scenes (their meshes beside them, as ../meshes, when
# `make setup` fetched them), example materials and MCML inputs.
set(LUCENT_SHARE ${CMAKE_INSTALL_DATAROOTDIR}/lucent)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/data/scenes DESTINATION ${LUCENT_SHARE} FILES_MATCHING PATTERN "*.json")
file(REAL_PATH ${CMAKE_SOURCE_DIR}/data/meshes LUCENT_MESHES) # the folder itself, also where it is a link
install(DIRECTORY ${LUCENT_MESHES}/ DESTINATION ${LUCENT_SHARE}/meshes OPTIONAL
        FILES_MATCHING PATTERN "*.ply" PATTERN "*.ply.gz" PATTERN "README*")
install(FILES ${CMAKE_SOURCE_DIR}/tests/fixtures/materials/jade.json ${CMAKE_SOURCE_DIR}/tests/fixtures/materials/two.json
        DESTINATION ${LUCENT_SHARE}/examples/materials)
install(FILES ${CMAKE_SOURCE_DIR}/tests/fixtures/mcml/vanhulst.mci ${CMAKE_SOURCE_DIR}/tests/fixtures/mcml/two_runs.mci
              ${CMAKE_SOURCE_DIR}/tests/fixtures/mcml/three_layers.mci ${CMAKE_SOURCE_DIR}/tests/fixtures/mcml/giovanelli.mci
        DESTINATION ${LUCENT_SHARE}/examples/mcml)
install(FILES ${CMAKE_SOURCE_DIR}/tests/fixtures/scenes/sphere.json ${CMAKE_SOURCE_DIR}/tests/fixtures/scenes/trace-small.json
        DESTINATION ${LUCENT_SHARE}/examples/scenes)
install(FILES ${CMAKE_SOURCE_DIR}/cmake/share-README.md DESTINATION ${LUCENT_SHARE} RENAME README.md)
