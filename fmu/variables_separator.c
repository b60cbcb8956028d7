/* variables_separator.c: the separator FMUs' variable table, variables_impl.h over
   src/separator/separator_quantities.def. Selected here rather than by a compiler flag, as
   variables_si.c is. */
#define TRIBO_FMU_SEPARATOR
#include "variables_impl.h"
