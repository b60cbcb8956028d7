/* variables_model.c: the dimensionless FMUs' variable table, variables_impl.h over
   src/quantities.def. */
#include "variables_impl.h"
