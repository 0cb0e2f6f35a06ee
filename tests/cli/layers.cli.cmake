# The include rules between layers (scripts/check_layers.py: src building blocks below
# solvers/, below src/app, below scaling/ and bench/, below the command line), and the
# script's own self-test (a planted upward include and a folder cycle are caught).
find_package(Python3 COMPONENTS Interpreter REQUIRED)
add_test(NAME layers.include_rules COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/check_layers.py
                                           ${PROJECT_SOURCE_DIR})
add_test(NAME layers.check_catches_violations
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/check_layers.py --self-test)
set_tests_properties(layers.include_rules layers.check_catches_violations PROPERTIES LABELS cli)
