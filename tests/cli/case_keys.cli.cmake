# The generated key reference (docs/case_keys.md, `cgdem keys`) is up to date and covers
# every key that the repository's case files use (tests/cli/case_keys.cmake).
file(GLOB_RECURSE case_key_cases CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/cases/*.toml
     ${PROJECT_SOURCE_DIR}/tests/cli/*.toml ${PROJECT_SOURCE_DIR}/validation/*.toml ${PROJECT_SOURCE_DIR}/papers/*.toml)
list(FILTER case_key_cases EXCLUDE REGEX "/tests/cli/bad/")
# a validation folder's reference.toml holds a check's reference values, not a case
list(FILTER case_key_cases EXCLUDE REGEX "/validation/[^/]+/reference\\.toml$")
add_test(NAME docs.case_keys_up_to_date
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DREFERENCE=${PROJECT_SOURCE_DIR}/docs/case_keys.md
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/case_keys "-DCASES=${case_key_cases}"
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/case_keys.cmake)
set_tests_properties(docs.case_keys_up_to_date PROPERTIES LABELS cli)
