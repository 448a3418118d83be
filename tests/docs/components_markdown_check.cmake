# docs/user/components.md is what `uampc components --markdown` prints: one source for every
# parameter's name, default, bounds and meaning (the components' declarations). Run with
#   cmake -DUAMPC=path/to/uampc -DPAGE=docs/user/components.md -P components_markdown_check.cmake
execute_process(COMMAND "${UAMPC}" components --markdown OUTPUT_VARIABLE printed RESULT_VARIABLE rc
                ERROR_VARIABLE errors)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "uampc components --markdown failed (${rc}): ${errors}")
endif()
file(READ "${PAGE}" committed)
if(NOT printed STREQUAL committed)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/components.md.printed" "${printed}")
  message(FATAL_ERROR "${PAGE} differs from what `uampc components --markdown` prints (written to "
                      "${CMAKE_CURRENT_BINARY_DIR}/components.md.printed); regenerate it with\n"
                      "  ./build/bin/uampc components --markdown > docs/user/components.md")
endif()
