# `format-check` (run by `make -C workflows test`, so CI fails on unformatted code) and `format`
# (rewrites in place): every C++ source of the project against .clang-format. The style is
# pinned to Debian 12's clang-format 14 (installed by `make -C workflows deps`); another
# clang-format version may format a few constructs differently.
find_program(MPPM_CLANG_FORMAT NAMES clang-format-14 clang-format)
file(GLOB_RECURSE MPPM_FORMATTED_SOURCES CONFIGURE_DEPENDS
     LIST_DIRECTORIES false RELATIVE ${PROJECT_SOURCE_DIR}
     ${PROJECT_SOURCE_DIR}/common/*.[ch]pp ${PROJECT_SOURCE_DIR}/preprocess/*.[ch]pp
     ${PROJECT_SOURCE_DIR}/solver/*.[ch]pp ${PROJECT_SOURCE_DIR}/postprocess/*.[ch]pp
     ${PROJECT_SOURCE_DIR}/tests/*.[ch]pp ${PROJECT_SOURCE_DIR}/benchmarks/*.[ch]pp)
if(MPPM_CLANG_FORMAT)
  add_custom_target(format-check
                    COMMAND ${MPPM_CLANG_FORMAT} --dry-run --Werror ${MPPM_FORMATTED_SOURCES}
                    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    COMMENT "clang-format --dry-run --Werror on ${PROJECT_NAME}'s C++ sources" VERBATIM)
  add_custom_target(format
                    COMMAND ${MPPM_CLANG_FORMAT} -i ${MPPM_FORMATTED_SOURCES}
                    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    COMMENT "clang-format -i on ${PROJECT_NAME}'s C++ sources" VERBATIM)
else()
  # A check that cannot run must fail, not pass.
  foreach(target format-check format)
    add_custom_target(${target} COMMAND ${CMAKE_COMMAND} -E echo
                      "clang-format not found: install it (make -C workflows deps)"
                      COMMAND ${CMAKE_COMMAND} -E false VERBATIM)
  endforeach()
endif()
