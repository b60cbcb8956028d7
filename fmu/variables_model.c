/* variables_model.c: the dimensionless FMUs' variable table, variables_impl.h over
   src/chute/quantities.def. */
#include "variables_impl.h"
