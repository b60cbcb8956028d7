# Runs the regression recorder and compares its output with the golden file, byte for
# byte; on a difference, prints the first differing lines.
#   cmake -DRECORD=<tribo_regression_record> -DGOLDEN=<golden.txt> -DOUT=<file> -P compare.cmake
execute_process(COMMAND ${RECORD} OUTPUT_FILE ${OUT} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${RECORD} failed with status ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${GOLDEN} RESULT_VARIABLE differ)
if(differ)
  execute_process(COMMAND diff ${GOLDEN} ${OUT} OUTPUT_VARIABLE d)
  string(SUBSTRING "${d}" 0 4000 d)
  message(FATAL_ERROR "outputs differ from ${GOLDEN} (< golden, > now):\n${d}")
endif()
