/* variables.c: the table of the FMU's variables (see variables.h). */
#include "variables.h"

#include <string.h>

#define REAL FMU_TYPE_REAL
#define INTEGER FMU_TYPE_INTEGER
#define COUNT FMU_TYPE_COUNT
#define FIXED FMU_VARIABILITY_FIXED
#define TUNABLE FMU_VARIABILITY_TUNABLE

/* A scene parameter: description, unit, range and start value come from the core. */
#define PARAM(vr, name, type, variability) \
    { vr, #name, type, FMU_CAUSALITY_PARAMETER, variability, FMU_MAPS_TO_PARAMETER, 0, FMU_IN_BOTH, NULL, NULL }
#define STRUCTURAL_PARAM(vr, name, type) \
    { vr, #name, type, FMU_CAUSALITY_STRUCTURAL_PARAMETER, FIXED, FMU_MAPS_TO_PARAMETER, 0, FMU_IN_BOTH, \
      NULL, NULL }
#define INPUT(vr, name, which, unit, description) \
    { vr, name, REAL, FMU_CAUSALITY_INPUT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_INPUT, which, \
      FMU_IN_BOTH, description, unit }
#define OUTPUT(vr, name, quantity, unit, description) \
    { vr, name, REAL, FMU_CAUSALITY_OUTPUT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_QUANTITY, quantity, \
      FMU_IN_BOTH, description, unit }
#define SEGMENTS(vr, name, which, unit, description) \
    { vr, name, REAL, FMU_CAUSALITY_OUTPUT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_SEGMENTS, which, \
      FMU_IN_FMI3, description, unit }

/* Value references are grouped (parameters from 1, inputs from 101, outputs from 201,
   arrays from 301) so that a row can be added to a group without renumbering. */
static const fmu_variable VARIABLES[] = {
    { 0, "time", REAL, FMU_CAUSALITY_INDEPENDENT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_TIME, 0,
      FMU_IN_BOTH, "simulation time (dimensionless, in units of sqrt(m/k))", "1" },

    /* every parameter of the core's table, in its order (MODEL §1) */
    PARAM(1, epsilon, REAL, FIXED),
    PARAM(2, mu, REAL, TUNABLE),
    PARAM(3, nu, REAL, TUNABLE),
    PARAM(4, Gamma, REAL, FIXED),
    PARAM(5, beta, REAL, FIXED),
    PARAM(6, tau0, REAL, TUNABLE),
    PARAM(7, Sigma0, REAL, TUNABLE),
    PARAM(8, eta, REAL, TUNABLE),
    PARAM(9, tau_r, REAL, TUNABLE),
    STRUCTURAL_PARAM(10, n_segments, COUNT),
    PARAM(11, v_reg, REAL, FIXED),
    PARAM(12, X0, REAL, FIXED),
    PARAM(13, gap0, REAL, FIXED),
    PARAM(14, phi0, REAL, FIXED),
    PARAM(15, drop_speed, REAL, FIXED),
    PARAM(16, Omega0, REAL, FIXED),
    PARAM(17, charge_model, INTEGER, FIXED),
    PARAM(18, integrator, INTEGER, FIXED),
    PARAM(19, dt, REAL, FIXED),
    PARAM(20, rtol, REAL, FIXED),
    PARAM(21, atol, REAL, FIXED),

    INPUT(101, "F_T_ext", FMU_INPUT_F_T, "1",
          "external force along the plate (down-slope positive), held over each step"),
    INPUT(102, "F_N_ext", FMU_INPUT_F_N, "1",
          "external force normal to the plate (away from it positive), held over each step"),

    OUTPUT(201, "X", TRIBO_Q_X, "1", "position of the centre along the plate, down-slope positive"),
    OUTPUT(202, "Y", TRIBO_Q_Y, "1", "height of the centre above the plate"),
    OUTPUT(203, "phi", TRIBO_Q_PHI, "rad", "orientation of the long axis, anticlockwise from the plate"),
    OUTPUT(204, "U", TRIBO_Q_U, "1", "velocity along the plate, dX/dtau"),
    OUTPUT(205, "V", TRIBO_Q_V, "1", "velocity normal to the plate, dY/dtau"),
    OUTPUT(206, "Omega", TRIBO_Q_OMEGA, "rad", "spin, dphi/dtau"),
    OUTPUT(207, "delta_y", TRIBO_Q_DELTA_Y, "1", "indentation of the contact (0 in flight)"),
    OUTPUT(208, "delta_x", TRIBO_Q_DELTA_X, "1", "stretch of the tangential contact spring"),
    OUTPUT(209, "in_contact", TRIBO_Q_IN_CONTACT, "1", "1 while the particle touches the plate, else 0"),
    OUTPUT(210, "slipping", TRIBO_Q_SLIPPING, "1", "1 while the contact slips, else 0"),
    OUTPUT(211, "Psi_N", TRIBO_Q_PSI_N, "1", "normal contact force"),
    OUTPUT(212, "Psi_T", TRIBO_Q_PSI_T, "1", "tangential contact force"),
    OUTPUT(213, "Q_static", TRIBO_Q_STATIC, "1",
           "static charge, mean of q_i = sigma_i/sigma_0 over the segments (0 without the static model)"),
    OUTPUT(214, "Q_sliding", TRIBO_Q_SLIDING, "1",
           "sliding charge, mean of Sigma_i/Sigma0 over the segments (0 without the sliding model)"),
    OUTPUT(215, "Sigma_s", TRIBO_Q_SIGMA_S, "1",
           "dynamic saturation charge density of the sliding model (Sigma0 without it)"),
    OUTPUT(216, "omega_work", TRIBO_Q_OMEGA_WORK, "1", "cumulative frictional work per unit contact area"),
    OUTPUT(217, "energy", TRIBO_Q_ENERGY, "1", "mechanical energy E (MODEL section 6)"),
    OUTPUT(218, "work_dissipated", TRIBO_Q_WORK_DISSIPATED, "1", "work dissipated by the contact so far"),
    OUTPUT(219, "work_external", TRIBO_Q_WORK_EXTERNAL, "1", "work done by F_T_ext and F_N_ext so far"),
    OUTPUT(220, "contact_time", TRIBO_Q_CONTACT_TIME, "1", "time spent in contact so far"),
    OUTPUT(221, "contact_fraction", TRIBO_Q_CONTACT_FRACTION, "1",
           "contact_time divided by the time run so far (0 at the start)"),
    OUTPUT(222, "turns", TRIBO_Q_TURNS, "1", "revolutions made, |phi - phi0| / (2 pi)"),
    OUTPUT(223, "contact_mode", TRIBO_Q_CONTACT_MODE, "1",
           "contact mode over the last ~20 time units: 0 flight, 1 sliding (quasi-fixed orientation, with rocking), 2 rolling, 3 tumbling, 4 bouncing"),
    OUTPUT(224, "fraction_flight", TRIBO_Q_FRACTION_FLIGHT, "1",
           "fraction of the time so far in flight (no contact within the window)"),
    OUTPUT(225, "fraction_sliding", TRIBO_Q_FRACTION_SLIDING, "1",
           "fraction of the time so far sliding with a quasi-fixed orientation (rocking)"),
    OUTPUT(226, "fraction_rolling", TRIBO_Q_FRACTION_ROLLING, "1",
           "fraction of the time so far rolling (continuous contact, turning)"),
    OUTPUT(227, "fraction_tumbling", TRIBO_Q_FRACTION_TUMBLING, "1",
           "fraction of the time so far tumbling (turning over, with flights)"),
    OUTPUT(228, "fraction_bouncing", TRIBO_Q_FRACTION_BOUNCING, "1",
           "fraction of the time so far bouncing (flights, no turning over)"),
    OUTPUT(229, "assumption_warnings", TRIBO_Q_ASSUMPTION_WARNINGS, "1",
           "times the contact went outside the model's assumptions (delta_y > 0.1 min(epsilon, rho_c)), each logged as a warning (the first 10)"),

    SEGMENTS(301, "segment_charge_static", TRIBO_SEGMENTS_STATIC, "1",
             "static charge q_i = sigma_i/sigma_0 of each boundary segment (zeros without the static model)"),
    SEGMENTS(302, "segment_charge_sliding", TRIBO_SEGMENTS_SLIDING, "1",
             "sliding charge Sigma_i/Sigma0 of each boundary segment (zeros without the sliding model)"),
};

#define N_VARIABLES (sizeof VARIABLES / sizeof VARIABLES[0])

const fmu_variable *fmu_variables(size_t *count)
{
    if (count)
        *count = N_VARIABLES;
    return VARIABLES;
}

int fmu_variable_in_version(const fmu_variable *v, int fmi_version)
{
    return (v->versions & (fmi_version == 2 ? FMU_IN_FMI2 : FMU_IN_FMI3)) != 0;
}

const fmu_variable *fmu_variable_find(fmu_vr vr, int fmi_version)
{
    for (size_t i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].vr == vr)
            return fmu_variable_in_version(&VARIABLES[i], fmi_version) ? &VARIABLES[i] : NULL;
    return NULL;
}

const fmu_variable *fmu_variable_named(const char *name)
{
    for (size_t i = 0; name && i < N_VARIABLES; i++)
        if (strcmp(VARIABLES[i].name, name) == 0)
            return &VARIABLES[i];
    return NULL;
}

const tribo_param_info *fmu_variable_param(const fmu_variable *v)
{
    return v->maps_to == FMU_MAPS_TO_PARAMETER ? tribo_param_find(v->name) : NULL;
}

const char *fmu_variable_description(const fmu_variable *v)
{
    const tribo_param_info *p = fmu_variable_param(v);
    return p ? p->description : v->description;
}

const char *fmu_variable_unit(const fmu_variable *v)
{
    const tribo_param_info *p = fmu_variable_param(v);
    return p ? p->unit : v->unit;
}

const char *fmu_type_name(fmu_type type, int fmi_version)
{
    switch (type) {
    case FMU_TYPE_REAL: return fmi_version == 2 ? "Real" : "Float64";
    case FMU_TYPE_INTEGER: return fmi_version == 2 ? "Integer" : "Int32";
    case FMU_TYPE_COUNT: return fmi_version == 2 ? "Integer" : "UInt64";
    }
    return "?";
}

const char *fmu_causality_name(fmu_causality causality, int fmi_version)
{
    switch (causality) {
    case FMU_CAUSALITY_INDEPENDENT: return "independent";
    case FMU_CAUSALITY_PARAMETER: return "parameter";
    case FMU_CAUSALITY_STRUCTURAL_PARAMETER:
        return fmi_version == 2 ? "parameter" : "structuralParameter";
    case FMU_CAUSALITY_INPUT: return "input";
    case FMU_CAUSALITY_OUTPUT: return "output";
    }
    return "?";
}

const char *fmu_variability_name(fmu_variability variability)
{
    switch (variability) {
    case FMU_VARIABILITY_FIXED: return "fixed";
    case FMU_VARIABILITY_TUNABLE: return "tunable";
    case FMU_VARIABILITY_CONTINUOUS: return "continuous";
    }
    return "?";
}
