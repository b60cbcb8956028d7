/* variables_si.c: the SI FMUs' variable table, variables_impl.h over src/si/si_quantities.def.
   Selected here rather than by a compiler flag: FMI 2.0's <SourceFiles> cannot give one to
   an importer compiling the FMU's sources/. */
#define TRIBO_FMU_SI
#include "variables_impl.h"
