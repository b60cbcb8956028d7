/*
 * si.h: the SI front end (docs/model.md §8): a physical set-up in SI units (a particle, a
 * wall, a chute, the charging constants) mapped onto the model's dimensionless scene, and the
 * model's outputs in SI units. Its table is si_quantities.def.
 *
 * Usage:
 *   tribo_si_scene si;
 *   tribo_si_scene_defaults(&si);            // the reference case (si_quantities.def): 0.3 m
 *   si.epsilon = 0.8;
 *   tribo_si_derived d;
 *   char err[512];
 *   if (tribo_si_derive(&si, &d, err, sizeof err) != TRIBO_OK) { puts(err); ... }
 *   tribo_model *m = tribo_create(&d.scene, err, sizeof err);
 *   tribo_advance_fully(m, 1e9);              // to the exit (or rest): TRIBO_ENDED
 *   double q_per_m = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M_STATIC);
 *
 * The model is two-dimensional: the particle is a cylinder of elliptical section; totals
 * are per unit length times the cylinder's depth (cylinder_length).
 */
#ifndef TRIBO_SI_H
#define TRIBO_SI_H

#include "tribo.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The registered charge models (charge_registry.def), which charge_to_mass_model counts
   from 1 in the registry's order. */
enum {
    TRIBO_SI_CHARGE_MODEL_COUNT = 0
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values) +1
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
};

/* stiffness_source: where the contact stiffness k' comes from (si_quantities.def's
   enumeration StiffnessSource, whose values these are: tests/c/test_si.c). */
typedef enum tribo_stiffness_source {
    TRIBO_STIFFNESS_GIVEN = 0, /* contact_stiffness                                      */
    TRIBO_STIFFNESS_MODULI = 1 /* (pi/4) E* from the Young's moduli and Poisson's ratios */
} tribo_stiffness_source;

/* Every parameter of the SI table, one field per row of si_quantities.def. */
typedef struct tribo_si_scene {
#define TRIBO_PARAMETER(name, type, ...) TRIBO_CTYPE_##type name;
#include "si_quantities.def"
} tribo_si_scene;

/* The reference case (si_quantities.def's defaults). */
void tribo_si_scene_defaults(tribo_si_scene *scene);

/* The SI parameters (their rows, for tribo_param_check, tribo_param_read, messages). */
const tribo_param_info *tribo_si_param_table(size_t *count);
const tribo_param_info *tribo_si_param_find(const char *name);
/* Apply "name=value ...", each checked against its range, as tribo_scene_apply. */
tribo_status tribo_si_scene_apply(tribo_si_scene *scene, const char *settings, char *msg,
                                  size_t msg_size);

/* The inputs (enum tribo_si_input order), forces per unit length in N/m. */
typedef enum tribo_si_input {
#define TRIBO_INPUT(id, ...) TRIBO_SI_INPUT_##id,
#include "si_quantities.def"
    TRIBO_SI_INPUT_COUNT
} tribo_si_input;
const tribo_param_info *tribo_si_input_table(size_t *count);

/* What a set-up means to the model (model.md §8), and the model's scene. */
typedef struct tribo_si_derived {
    double a;               /* semi-major axis, m: the model's unit of length        */
    double E_star;          /* effective modulus of particle and wall, Pa            */
    double k_prime;         /* contact stiffness per unit length used, N/m^2         */
    double mass_per_length; /* m' = rho pi a^2 epsilon, kg/m                         */
    double t_star;          /* sqrt(m'/k'), s: the model's unit of time              */
    double velocity;        /* a / t_star, m/s                                       */
    double force;           /* k' a, N/m: the unit of force per unit length          */
    double energy;          /* k' a^2, J/m: the unit of energy per unit length       */
    double sigma_scale;     /* sqrt(kappa k' a), C/m^2: the sliding model's unit of
                               charge density                                        */
    double perimeter;       /* a P(epsilon), m: the boundary of the section          */
    double depth;           /* the cylinder's depth l, m                             */
    double sigma0;          /* C/m^2, its sign the polarity                          */
    int spheroid;           /* the grain is the spheroid (model.md §8c), else the
                               cylinder of depth `depth`                             */
    double grain_mass;      /* kg: (4/3) pi rho a b^2, or m' l                       */
    double grain_area;      /* m^2: the spheroid's surface, or the cylinder's a P l  */
    double paschen_minimum_voltage; /* V: the gas's least breakdown voltage (§8e) */
    double paschen_minimum_gap;     /* m: the gap where it lies                    */
    double grain_charge_limit;      /* C: sigma_P(R_s) A_s, the grain's limit (§8e) */
    int charge_to_mass_model; /* the registry's row (from 1) whose ratio charge_to_mass is:
                                 the parameter's, or with 0 the first row included */
    tribo_scene scene;      /* the model's scene                                     */
    char notice[256];       /* what the set-up asks that is not done, for a warning: a
                               parameter set where nothing uses it; "" when none     */
} tribo_si_derived;

/* Derive: every SI value in its range, the drop on the chute, and every parameter of the
   model's scene in the model's range. A failure (TRIBO_ERR_INVALID_ARGUMENT) names the SI
   variable, its value and its range, or, for a derived parameter, the model's parameter,
   its value and range, and the SI inputs (with their values) that made it. */
tribo_status tribo_si_derive(const tribo_si_scene *si, tribo_si_derived *d, char *msg,
                             size_t msg_size);

/* A tunable SI parameter's new value as the model's parameter it sets (the same conversion
   as tribo_si_derive), checked against the model's range as there. */
tribo_status tribo_si_model_param(const tribo_si_derived *d, const tribo_param_info *p,
                                  double value, const char **model_name, double *model_value,
                                  char *msg, size_t msg_size);

/* The SI inputs as the model's inputs (forces in units of k' a), checked as there. */
tribo_status tribo_si_model_inputs(const tribo_si_derived *d,
                                   const double values[TRIBO_SI_INPUT_COUNT],
                                   double model_values[TRIBO_INPUT_COUNT], char *msg,
                                   size_t msg_size);

/* What can be read: the time, the outputs and the calculated parameters. */
typedef enum tribo_si_quantity {
#define TRIBO_TIME(id, ...) TRIBO_SI_QUANTITY_##id,
#define TRIBO_OUTPUT(id, ...) TRIBO_SI_QUANTITY_##id,
#define TRIBO_CALCULATED(id, ...) TRIBO_SI_QUANTITY_##id,
#include "si_quantities.def"
    TRIBO_SI_QUANTITY_COUNT
} tribo_si_quantity;

/* A quantity of an instance of the derived scene (m may be NULL for the calculated
   parameters, which depend on the set-up alone). */
double tribo_si_get(const tribo_si_derived *d, tribo_model *m, tribo_si_quantity q);
const char *tribo_si_quantity_name(tribo_si_quantity q);

/* The per-segment arrays in C/m^2: the model's (tribo_get_segment_charges) times this. */
double tribo_si_segment_factor(const tribo_si_derived *d, tribo_segment_charge which);

/* The mean charge density of a charge model over the boundary, C/m^2: the mean of its
   per-segment values (tribo_get_mean_charge) times its factor above (0 without the model). */
double tribo_si_sigma_mean(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which);

/* The grain's outputs by the model `which` (model.md §8c: the spheroid from its bands, or
   the cylinder from its segments, whose own value the caller passes; 0 for a model the scene
   leaves out): its charge (C), the charge the breakdown limit took from it (C), the fraction
   of its surface at that limit. */
double tribo_si_grain_charge(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which);
double tribo_si_grain_charge_to_mass(const tribo_si_derived *d, tribo_model *m,
                                     tribo_segment_charge which);
double tribo_si_grain_charge_lost(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which,
                                  double cylinder_lost);
double tribo_si_grain_capped_fraction(const tribo_si_derived *d, tribo_model *m,
                                      tribo_segment_charge which, double cylinder_fraction);

/* The charge per unit length of the cylinder, C/m, of a mean charge density over its
   boundary (model.md §8: Q' = (a P(epsilon) / N) sum sigma_i). */
static inline double tribo_si_charge_per_length(const tribo_si_derived *d, double sigma_mean)
{
    return d->perimeter * sigma_mean;
}

/* A density of the sliding model in C/m^2 (model.md §8: sign(sigma0) Sigma sqrt(kappa k' a);
   sigma0 = 0, a neutral pair, charges nothing). */
static inline double tribo_si_sliding_density(const tribo_si_derived *d, double Sigma)
{
    return (double)((d->sigma0 > 0.0) - (d->sigma0 < 0.0)) * Sigma * d->sigma_scale;
}

#ifdef __cplusplus
}
#endif

#endif
