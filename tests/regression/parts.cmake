# Every line of the golden file belongs to one of the parts the regression tests compare
# (its run name starts with PART/), so that the parts together compare the whole record.
#   cmake -DGOLDEN=<golden.txt> "-DPARTS=<part>;<part>..." -P parts.cmake
file(STRINGS ${GOLDEN} all ENCODING UTF-8)
list(LENGTH all n_all)
set(n_parts 0)
foreach(part IN LISTS PARTS)
  file(STRINGS ${GOLDEN} lines ENCODING UTF-8 REGEX "^${part}/")
  list(LENGTH lines n)
  math(EXPR n_parts "${n_parts} + ${n}")
endforeach()
if(NOT n_parts EQUAL n_all)
  message(FATAL_ERROR "${GOLDEN}: ${n_all} lines, ${n_parts} of them in the parts ${PARTS}")
endif()
