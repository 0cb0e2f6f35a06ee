# The plot scripts beside the executable, and `cmake --install BUILD [--prefix PREFIX]`.
#
# The analysis commands find their Python plot scripts relative to the running executable
# (scaling/plot_script.hpp): BUILD/share/cgdem/scripts in a build tree, PREFIX/share/cgdem/
# scripts once installed. configure_file copies them here and makes CMake re-run (and
# re-copy) when one of them changes.
file(GLOB CGDEM_PLOT_SCRIPTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scaling/*.py)
foreach(script ${CGDEM_PLOT_SCRIPTS})
  get_filename_component(name ${script} NAME)
  configure_file(${script} ${PROJECT_BINARY_DIR}/share/cgdem/scripts/${name} COPYONLY)
endforeach()

include(GNUInstallDirs)
install(TARGETS cgdem RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${CGDEM_PLOT_SCRIPTS} DESTINATION ${CMAKE_INSTALL_DATADIR}/cgdem/scripts)
# The die-filling cases and the example cases, so that an installed cgdem can run them.
file(GLOB CGDEM_DIE_CASES ${PROJECT_SOURCE_DIR}/validation/die_filling/case_*.toml)
install(FILES ${CGDEM_DIE_CASES} ${PROJECT_SOURCE_DIR}/validation/die_filling/README.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/cgdem/cases/die_filling)
file(GLOB CGDEM_EXAMPLE_CASES ${PROJECT_SOURCE_DIR}/cases/*.toml)
install(FILES ${CGDEM_EXAMPLE_CASES} DESTINATION ${CMAKE_INSTALL_DATADIR}/cgdem/cases/examples)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CITATION.cff
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
