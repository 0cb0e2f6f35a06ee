# Writes the release version (-DVERSION) and the git revision (with a dirty flag) into a
# header; rewritten only when it changes.
execute_process(COMMAND git -C ${SRC} describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE rev OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT rev)
  set(rev "unknown")
endif()
set(text "#pragma once\nnamespace cgdem {\ninline constexpr const char* kVersion = \"${VERSION}\";\ninline constexpr const char* kGitRevision = \"${rev}\";\n}  // namespace cgdem\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUT} "${text}")
endif()
