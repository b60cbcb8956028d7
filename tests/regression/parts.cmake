# Every line of the golden file belongs to one of the parts the regression tests compare
# (PATTERNS: their regular expressions joined by |), so that the parts together compare the
# whole record.
#   cmake -DGOLDEN=<golden.txt> "-DPATTERNS=<regex>|<regex>..." -P parts.cmake
file(STRINGS ${GOLDEN} all ENCODING UTF-8)
file(STRINGS ${GOLDEN} in_parts ENCODING UTF-8 REGEX "${PATTERNS}")
list(LENGTH all n_all)
list(LENGTH in_parts n_parts)
if(NOT n_parts EQUAL n_all)
  message(FATAL_ERROR "${GOLDEN}: ${n_all} lines, ${n_parts} of them in the parts (${PATTERNS})")
endif()
