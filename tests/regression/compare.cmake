# Runs the regression recorder and compares its output with the golden file, byte for
# byte; on a difference, prints the first differing lines. With PART, only that part of
# the record, against the golden file's lines of that part (those PATTERN matches).
#   cmake -DRECORD=<tribo_regression_record> -DGOLDEN=<golden.txt> -DOUT=<file>
#         [-DPART=<part> -DPATTERN=<regex>] -P compare.cmake
set(expected ${GOLDEN})
if(DEFINED PART)
  file(STRINGS ${GOLDEN} lines ENCODING UTF-8 REGEX "${PATTERN}")
  if(NOT lines)
    message(FATAL_ERROR "${GOLDEN} has no line of the part ${PART} (${PATTERN})")
  endif()
  list(JOIN lines "\n" text)
  set(expected ${OUT}.golden)
  file(WRITE ${expected} "${text}\n")
endif()
execute_process(COMMAND ${RECORD} ${PART} OUTPUT_FILE ${OUT} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${RECORD} ${PART} failed with status ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${expected} RESULT_VARIABLE differ)
if(differ)
  execute_process(COMMAND diff ${expected} ${OUT} OUTPUT_VARIABLE d)
  string(SUBSTRING "${d}" 0 4000 d)
  message(FATAL_ERROR "outputs differ from ${GOLDEN}'s ${PART} (< golden, > now):\n${d}")
endif()
