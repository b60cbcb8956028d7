/* si.c: the SI front end (si.h): its table, the mapping of model.md §8, the checks of what
   it derives, and the model's outputs in SI units. */
#include "si.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "charge_registry.h"
#include "geometry.h"
#include "param_table.h"
#include "paschen.h"

/* ---- the table ------------------------------------------------------------------------ */

/* Each SI parameter's row. */
enum si_row {
#define TRIBO_PARAMETER(name, ...) ROW_##name,
#include "si_quantities.def"
    ROW_COUNT
};

/* A TRIBO_SAME_PARAMETER row takes its range from the model's row in quantities.def. The
   preprocessor cannot pick one row of a table by name, so every model parameter's row writes
   its range into PARAMS: into the row of the SI parameter that is it unchanged, or else into
   a slot of its own past the table's rows, which nothing reads. */
enum unread_slot {
    LAST_ROW = ROW_COUNT - 1,
#define TRIBO_MAPS(name, model, how) UNREAD_SLOT_##model,
#define TRIBO_DERIVES(model, description) UNREAD_SLOT_##model,
#include "si_quantities.def"
    SLOT_COUNT
};
#define RANGE_SLOT_SAME(si_name, model) ROW_##si_name
#define RANGE_SLOT_LENGTH(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_TIME(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_SPEED(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_RATE(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_DENSITY(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_FORCE(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_LIMIT(si_name, model) UNREAD_SLOT_##model
#define RANGE_SLOT_POLARISED(si_name, model) UNREAD_SLOT_##model
enum range_slot {
#define TRIBO_MAPS(name, model, how) RANGE_SLOT_OF_##model = RANGE_SLOT_##how(name, model),
#define TRIBO_DERIVES(model, description) RANGE_SLOT_OF_##model = UNREAD_SLOT_##model,
#include "si_quantities.def"
};

static const tribo_param_info PARAMS[SLOT_COUNT] = {
#define TRIBO_PARAMETER(name, ...) [ROW_##name] = TRIBO_PARAM_INFO(tribo_si_scene, name, __VA_ARGS__),
#define TRIBO_SAME_PARAMETER(name, type, vr, unit, start, variability, description)               \
    [ROW_##name] = {TRIBO_PARAM_FIELDS_BUT_RANGE(tribo_si_scene, name, type, vr, unit, start,       \
                                                 variability, description)},
#include "si_quantities.def"
#define TRIBO_PARAMETER(name, type, vr, unit, min_, min_end, max_, max_end, start, variability,   \
                        description)                                                            \
    [RANGE_SLOT_OF_##name].min = min_, [RANGE_SLOT_OF_##name].max = max_,                       \
    [RANGE_SLOT_OF_##name].min_inclusive = TRIBO_##min_end,                                     \
    [RANGE_SLOT_OF_##name].max_inclusive = TRIBO_##max_end,
#include "quantities.def"
};
static const tribo_param_retired RETIRED[] = {
#define TRIBO_RETIRED TRIBO_PARAM_RETIRED_ROW
#include "si_quantities.def"
    {NULL, NULL}};
static const tribo_param_table_of TABLE = {PARAMS, ROW_COUNT, RETIRED};

static const tribo_param_info INPUTS[TRIBO_SI_INPUT_COUNT] = {
#define TRIBO_INPUT(id_, ...) [TRIBO_SI_INPUT_##id_] = TRIBO_INPUT_INFO(__VA_ARGS__),
#include "si_quantities.def"
};

void tribo_si_scene_defaults(tribo_si_scene *s) { tribo_table_defaults(TABLE, s, sizeof *s); }

const tribo_param_info *tribo_si_param_table(size_t *count)
{
    if (count)
        *count = TABLE.n;
    return PARAMS;
}

const tribo_param_info *tribo_si_param_find(const char *name) { return tribo_table_find(TABLE, name); }

tribo_status tribo_si_scene_apply(tribo_si_scene *s, const char *settings, char *msg, size_t msg_size)
{
    return tribo_table_apply(TABLE, s, settings, msg, msg_size);
}

const tribo_param_info *tribo_si_input_table(size_t *count)
{
    if (count)
        *count = TRIBO_SI_INPUT_COUNT;
    return INPUTS;
}

/* ---- the mapping (model.md §8) ---------------------------------------------------------- */

/* How an SI parameter (or input) becomes the model's: as it is, or in the model's units. */
typedef enum conversion {
    SAME,    /* the same quantity (dimensionless, an angle, a choice) */
    LENGTH,  /* / a                                            */
    TIME,    /* / t_star                                       */
    SPEED,   /* / (a / t_star)                                 */
    RATE,    /* * t_star                                       */
    DENSITY, /* |sigma| / sqrt(kappa k' a): the sign is the polarity */
    FORCE,   /* / (k' a): a force per unit length              */
    LIMIT,   /* a DENSITY where 0 means none: INF              */
    POLARISED /* sigma / sqrt(kappa k' a) times sign(sigma0)    */
} conversion;

static double convert(const tribo_si_derived *d, conversion how, double v)
{
    switch (how) {
    case SAME: break;
    case LENGTH: return v / d->a;
    case TIME: return v / d->t_star;
    case SPEED: return v / d->velocity;
    case RATE: return v * d->t_star;
    case DENSITY: return fabs(v) / d->sigma_scale;
    case FORCE: return v / d->force;
    /* model.md §8b; a limit too small for a double in the model's units (5e-324 C/m2) is
       the smallest one, not none */
    case LIMIT: return v > 0.0 ? fmax(v / d->sigma_scale, DBL_TRUE_MIN) : INFINITY;
    case POLARISED: return d->sigma0 < 0.0 ? -v / d->sigma_scale : v / d->sigma_scale; /* §8c */
    }
    return v;
}

/* Every parameter of the model's scene that one SI parameter sets, and the inputs: the
   TRIBO_MAPS rows of si_quantities.def. */
static const struct mapping {
    const char *si, *model;
    conversion how;
} MAP[] = {
#define TRIBO_MAPS(name, model, how) {#name, #model, how},
#include "si_quantities.def"
};
#define N_MAP (sizeof MAP / sizeof MAP[0])

/* "name = value unit" of an SI parameter, appended to buf. */
static void append_value(char *buf, size_t n, const tribo_si_scene *si, const char *name,
                         const char *separator)
{
    const tribo_param_info *p = tribo_si_param_find(name);
    const size_t used = strlen(buf);
    snprintf(buf + used, n > used ? n - used : 0, "%s%s = %.6g%s%s", separator, name,
             tribo_param_read(si, p), strcmp(p->unit, "1") ? " " : "",
             strcmp(p->unit, "1") ? p->unit : "");
}

/* Where the contact stiffness comes from, in words. */
static void describe_stiffness(char *buf, size_t n, const tribo_si_scene *si, const tribo_si_derived *d)
{
    const size_t used = strlen(buf);
    if (si->stiffness_source == TRIBO_STIFFNESS_GIVEN) {
        append_value(buf, n, si, "contact_stiffness", ", ");
        return;
    }
    snprintf(buf + used, n > used ? n - used : 0, ", k' = %.6g N/m2 from ", d->k_prime);
    append_value(buf, n, si, "youngs_modulus_particle", "");
    append_value(buf, n, si, "poisson_ratio_particle", ", ");
    append_value(buf, n, si, "youngs_modulus_wall", ", ");
    append_value(buf, n, si, "poisson_ratio_wall", ", ");
}

/* A contact stiffness set where stiffness_source takes it from the moduli is not used: say so
   (a set-up of an earlier interface, where any stiffness given was used, would otherwise
   run on another stiffness than it names). */
static void note_unused_stiffness(const tribo_si_scene *si, tribo_si_derived *d)
{
    const tribo_param_info *p = tribo_si_param_find("contact_stiffness");
    if (si->stiffness_source != TRIBO_STIFFNESS_MODULI || si->contact_stiffness == p->start)
        return;
    snprintf(d->notice, sizeof d->notice,
             "contact_stiffness = %.6g N/m2 is not used: stiffness_source = 1 (moduli) takes "
             "k' = %.6g N/m2 from the Young's moduli; stiffness_source = 0 (given) uses it",
             si->contact_stiffness, d->k_prime);
}

/* The SI inputs of a derived number: its own SI parameter (if any), and what the unit of its
   conversion is made of. */
static void describe_inputs(char *buf, size_t n, const tribo_si_scene *si, const tribo_si_derived *d,
                            const char *own, conversion how)
{
    buf[0] = '\0';
    if (own)
        append_value(buf, n, si, own, "");
    const int time_scale = how == TIME || how == SPEED || how == RATE || how == FORCE;
    if (how == LIMIT || how == POLARISED)
        how = DENSITY;
    if (how == LENGTH || time_scale || how == DENSITY)
        append_value(buf, n, si, "semi_major_axis", own ? ", " : "");
    if (time_scale && how != FORCE) {
        append_value(buf, n, si, "epsilon", ", ");
        append_value(buf, n, si, "density", ", ");
    }
    if (how == DENSITY)
        append_value(buf, n, si, "interface_capacitance", ", ");
    if (time_scale || how == DENSITY)
        describe_stiffness(buf, n, si, d);
}

/* Check a derived value against the model's range; on failure, say what made it. */
static tribo_status check_derived(const tribo_param_info *p, double value, const char *made_of,
                                  char *msg, size_t msg_size)
{
    if (tribo_param_check(p, value, NULL, 0) == TRIBO_OK)
        return TRIBO_OK;
    if (msg && msg_size) {
        char range[128];
        tribo_param_range_text(p, range, sizeof range);
        snprintf(msg, msg_size,
                 "%s = %.6g, the model's parameter derived from %s, is outside the model's "
                 "valid range %s (docs/model.md §8)",
                 p->name, value, made_of, range);
    }
    return TRIBO_ERR_INVALID_ARGUMENT;
}

static const struct mapping *mapping_of(const char *si_name)
{
    for (size_t i = 0; i < N_MAP; i++)
        if (strcmp(MAP[i].si, si_name) == 0)
            return &MAP[i];
    return NULL;
}

/* The model charge_to_mass carries: the one charge_to_mass_model names, or with 0 the first
   the scene includes (registry order), so that switching a model off alone never leaves the
   output to the wrong law. A model named must run where another one does, else the
   coupling's one connection would carry a ratio of 0 while the grain charges by the other
   law, silently. A scene with no charge model at all charges nothing: its charge_to_mass is
   0, and right. */
static tribo_status charge_to_mass_model_included(const tribo_si_scene *si, tribo_si_derived *d,
                                                  char *msg, size_t msg_size)
{
    const unsigned included = tribo_charge_selection(&d->scene);
    int slot = si->charge_to_mass_model - 1;
    if (slot < 0) {
        slot = 0;
        while (slot + 1 < TRIBO_SI_CHARGE_MODEL_COUNT && !(included & (1u << slot)))
            slot++;
    }
    d->charge_to_mass_model = slot + 1;
    if (included == 0u || (included & (1u << slot)))
        return TRIBO_OK;
    if (msg && msg_size) {
        const char *name = TRIBO_CHARGE_MODELS[slot]->name;
        snprintf(msg, msg_size,
                 "charge_to_mass_model = %d names the %s charge model, which charge_model_%s = 0 "
                 "leaves out of the scene: switch it on, or choose an included model",
                 si->charge_to_mass_model, name, name);
    }
    return TRIBO_ERR_INVALID_ARGUMENT;
}

/* A grain that arrives charged (model.md §8c): the spheroid's surface, of a pair that
   charges (its polarity gives the density's sign in the model; above what air holds, the
   model keeps what it holds). */
static tribo_status check_initial_charge(const tribo_si_scene *si, char *msg, size_t msg_size)
{
    const double q = si->initial_charge_density;
    if (q == 0.0)
        return TRIBO_OK;
    const char *why = NULL;
    if (si->grain_geometry != TRIBO_GRAIN_SPHEROID)
        why = "the initial surface charge is the spheroid's: set grain_geometry = 1 (spheroid)";
    else if (si->sigma0 == 0.0)
        why = "a neutral pair (sigma0 = 0) charges nothing and the model cannot carry a charge "
              "without a pair's polarity: give the pair's sigma0";
    if (!why)
        return TRIBO_OK;
    if (msg && msg_size)
        snprintf(msg, msg_size,
                 "initial_charge_density = %.6g C/m2 is invalid with grain_geometry = %d, sigma0 = "
                 "%.6g C/m2: %s",
                 q, si->grain_geometry, si->sigma0, why);
    return TRIBO_ERR_INVALID_ARGUMENT;
}

/* The Paschen limit's numbers (model.md §8e): the model's A p a and eps0 B p in its unit of
   density, and what they mean in SI units. The declared ranges of A, B, p and gamma keep the
   curve's minimum, at A p d = e ln(1 + 1/gamma), finite and positive: a curve without one
   (A or B not positive, gamma at 1 or beyond) is refused with its parameter's range. */
static tribo_status derive_paschen(const tribo_si_scene *si, tribo_si_derived *d, char *made_of,
                                   size_t made_of_size, char *msg, size_t msg_size)
{
    const double eps0 = 8.8541878128e-12, p = si->gas_pressure;
    const double x_min = tribo_paschen_minimum(si->secondary_emission);
    d->paschen_minimum_gap = x_min / (si->paschen_A * p);
    d->paschen_minimum_voltage = x_min * si->paschen_B / si->paschen_A;
    /* the sphere of the grain's area; a pair's field (an insulating wall) is the image's at
       twice the size */
    const double radius = sqrt(d->grain_area / (4.0 * M_PI));
    const double c = si->paschen_A * p * radius * (si->wall_conducting ? 0.5 : 1.0);
    d->grain_charge_limit = eps0 * si->paschen_B * p *
                            tribo_paschen_reduced(si->secondary_emission, c) * d->grain_area;
    d->scene.paschen_gap_scale = si->paschen_A * p * d->a;
    d->scene.Sigma_paschen = eps0 * si->paschen_B * p / d->sigma_scale;
    static const char *const derived[] = {"paschen_gap_scale", "Sigma_paschen"};
    const double values[] = {d->scene.paschen_gap_scale, d->scene.Sigma_paschen};
    for (int i = 0; i < 2; i++) {
        const tribo_param_info *model = tribo_param_find(derived[i]);
        if (tribo_param_check(model, values[i], NULL, 0) == TRIBO_OK)
            continue;
        made_of[0] = '\0';
        append_value(made_of, made_of_size, si, i ? "paschen_B" : "paschen_A", "");
        append_value(made_of, made_of_size, si, "gas_pressure", ", ");
        strncat(made_of, ", ", made_of_size - strlen(made_of) - 1);
        describe_inputs(made_of + strlen(made_of), made_of_size - strlen(made_of), si, d, NULL,
                        i ? DENSITY : LENGTH);
        return check_derived(model, values[i], made_of, msg, msg_size);
    }
    return TRIBO_OK;
}

tribo_status tribo_si_derive(const tribo_si_scene *si, tribo_si_derived *d, char *msg,
                             size_t msg_size)
{
    tribo_status st = tribo_table_validate(TABLE, si, msg, msg_size);
    if (st != TRIBO_OK)
        return st;
    if (!d) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "the derived set-up's struct is NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    if (!(si->x0 < si->chute_length)) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "x0 = %.15g m is invalid with chute_length = %.15g m: the particle must start "
                     "before the end of the chute, x0 < chute_length",
                     si->x0, si->chute_length);
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    if ((st = check_initial_charge(si, msg, msg_size)) != TRIBO_OK)
        return st;
    const double a = si->semi_major_axis;
    memset(d, 0, sizeof *d);
    d->a = a;
    d->depth = si->cylinder_length;
    d->sigma0 = si->sigma0;
    /* the 2D Hertz load with the paper's contact width (model.md §8) */
    d->E_star = 1.0 / ((1.0 - si->poisson_ratio_particle * si->poisson_ratio_particle) /
                           si->youngs_modulus_particle +
                       (1.0 - si->poisson_ratio_wall * si->poisson_ratio_wall) /
                           si->youngs_modulus_wall);
    d->k_prime = si->stiffness_source == TRIBO_STIFFNESS_GIVEN ? si->contact_stiffness
                                                                : (M_PI / 4.0) * d->E_star;
    note_unused_stiffness(si, d);
    d->mass_per_length = si->density * M_PI * a * a * si->epsilon;
    d->t_star = sqrt(d->mass_per_length / d->k_prime);
    d->velocity = a / d->t_star;
    d->force = d->k_prime * a;
    d->energy = d->k_prime * a * a;
    d->sigma_scale = sqrt(si->interface_capacitance * d->k_prime * a);
    d->perimeter = a * tribo_ellipse_perimeter(si->epsilon);
    d->spheroid = si->grain_geometry == TRIBO_GRAIN_SPHEROID;
    const double b = si->epsilon * a;
    d->grain_mass = d->spheroid ? (4.0 / 3.0) * M_PI * si->density * a * b * b
                                : d->mass_per_length * d->depth;
    d->grain_area = d->spheroid ? a * a * tribo_spheroid_area(si->epsilon) : d->perimeter * d->depth;

    tribo_scene_defaults(&d->scene);
    char made_of[400];
    for (size_t i = 0; i < N_MAP; i++) {
        if (MAP[i].how == FORCE)
            continue; /* an input */
        const tribo_param_info *model = tribo_param_find(MAP[i].model);
        const double v = convert(d, MAP[i].how, tribo_param_read(si, tribo_si_param_find(MAP[i].si)));
        if (MAP[i].how == DENSITY && v == 0.0)
            continue; /* a neutral pair: the model's default, every charge output times 0 */
        /* what made a value is written out only for a message (each derive would pay for it) */
        if (tribo_param_check(model, v, NULL, 0) != TRIBO_OK) {
            describe_inputs(made_of, sizeof made_of, si, d, MAP[i].si, MAP[i].how);
            return check_derived(model, v, made_of, msg, msg_size);
        }
        tribo_param_write(&d->scene, model, v);
    }
    /* model.md §8: Gamma = m' g / (k' a) */
    d->scene.Gamma = d->mass_per_length * si->gravity / d->force;
    const tribo_param_info *gamma = tribo_param_find("Gamma");
    if (tribo_param_check(gamma, d->scene.Gamma, NULL, 0) != TRIBO_OK) {
        describe_inputs(made_of, sizeof made_of, si, d, "gravity", SPEED);
        return check_derived(gamma, d->scene.Gamma, made_of, msg, msg_size);
    }
    if ((st = derive_paschen(si, d, made_of, sizeof made_of, msg, msg_size)) != TRIBO_OK)
        return st;
    if ((st = tribo_scene_validate(&d->scene, msg, msg_size)) != TRIBO_OK)
        return st;
    return charge_to_mass_model_included(si, d, msg, msg_size);
}

tribo_status tribo_si_model_param(const tribo_si_derived *d, const tribo_param_info *p,
                                  double value, const char **model_name, double *model_value,
                                  char *msg, size_t msg_size)
{
    if (!d || !p || !model_name || !model_value) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "tribo_si_model_param: a NULL argument");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    const struct mapping *map = mapping_of(p->name);
    if (!map || map->how == FORCE) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "%s is not a parameter of the model", p->name);
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    *model_name = map->model;
    *model_value = convert(d, map->how, value);
    char made_of[400];
    snprintf(made_of, sizeof made_of, "%s = %.6g %s and the set-up's t_star = %.6g s", p->name, value,
             p->unit, d->t_star);
    return check_derived(tribo_param_find(map->model), *model_value, made_of, msg, msg_size);
}

tribo_status tribo_si_model_inputs(const tribo_si_derived *d,
                                   const double values[TRIBO_SI_INPUT_COUNT],
                                   double model_values[TRIBO_INPUT_COUNT], char *msg, size_t msg_size)
{
    if (!d || !values || !model_values) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "tribo_si_model_inputs: a NULL argument");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    const tribo_param_info *model = tribo_input_table(NULL);
    for (int i = 0; i < TRIBO_SI_INPUT_COUNT; i++) {
        if (tribo_param_check(&INPUTS[i], values[i], msg, msg_size) != TRIBO_OK)
            return TRIBO_ERR_INVALID_ARGUMENT;
        model_values[i] = convert(d, FORCE, values[i]);
        char made_of[400];
        snprintf(made_of, sizeof made_of, "%s = %.6g N/m and the unit of force k' a = %.6g N/m",
                 INPUTS[i].name, values[i], d->force);
        const tribo_status st = check_derived(&model[i], model_values[i], made_of, msg, msg_size);
        if (st != TRIBO_OK)
            return st;
    }
    return TRIBO_OK;
}

/* ---- what can be read ------------------------------------------------------------------- */

double tribo_si_get(const tribo_si_derived *d, tribo_model *m, tribo_si_quantity q)
{
    if (!d)
        return NAN;
#define Q(id) tribo_get(m, TRIBO_QUANTITY_##id)
    switch (q) {
#define TRIBO_TIME(id, name, vr, unit, description, value) \
    case TRIBO_SI_QUANTITY_##id: return (value);
#define TRIBO_OUTPUT(id, name, type, vr, unit, description, value) \
    case TRIBO_SI_QUANTITY_##id: return (value);
#define TRIBO_CALCULATED(id, name, vr, unit, variability, description, value) \
    case TRIBO_SI_QUANTITY_##id: return (value);
#include "si_quantities.def"
    case TRIBO_SI_QUANTITY_COUNT: break;
    }
#undef Q
    return NAN;
}

const char *tribo_si_quantity_name(tribo_si_quantity q)
{
    static const char *const names[TRIBO_SI_QUANTITY_COUNT] = {
#define TRIBO_TIME(id, name, ...) [TRIBO_SI_QUANTITY_##id] = name,
#define TRIBO_OUTPUT(id, name, ...) [TRIBO_SI_QUANTITY_##id] = name,
#define TRIBO_CALCULATED(id, name, ...) [TRIBO_SI_QUANTITY_##id] = name,
#include "si_quantities.def"
    };
    return (unsigned)q < TRIBO_SI_QUANTITY_COUNT ? names[q] : NULL;
}

double tribo_si_sigma_mean(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which)
{
    return tribo_si_segment_factor(d, which) * tribo_get_mean_charge(m, which);
}

double tribo_si_segment_factor(const tribo_si_derived *d, tribo_segment_charge which)
{
    if (!d || (unsigned)which >= TRIBO_SEGMENTS_COUNT)
        return NAN;
    /* each model declares the unit of its values (charge_interface.h, model.md §8) */
    switch (TRIBO_CHARGE_MODELS[which]->si_unit) {
    case TRIBO_CHARGE_PER_SIGMA0: return d->sigma0;
    case TRIBO_CHARGE_PER_SIGMA_SCALE: return tribo_si_sliding_density(d, 1.0);
    }
    return NAN;
}

/* ---- the grain (model.md §8c) ---------------------------------------------------------- */

/* The grain's quantities are the model's times a^2 (its bands' areas) and the model's SI
   factor: the same rule as segment_sigma_<name>. */
double tribo_si_grain_charge(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which)
{
    if ((unsigned)which >= (unsigned)TRIBO_SEGMENTS_COUNT)
        return 0.0; /* no model included: charge_to_mass reads 0 */
    if (!d->spheroid)
        return d->depth * tribo_si_charge_per_length(d, tribo_si_sigma_mean(d, m, which));
    return d->a * d->a * tribo_si_segment_factor(d, which) * tribo_get_grain_charge(m, which);
}

double tribo_si_grain_charge_to_mass(const tribo_si_derived *d, tribo_model *m,
                                     tribo_segment_charge which)
{
    if (!d->spheroid && (unsigned)which < (unsigned)TRIBO_SEGMENTS_COUNT)
        return tribo_si_charge_per_length(d, tribo_si_sigma_mean(d, m, which)) / d->mass_per_length;
    return tribo_si_grain_charge(d, m, which) / d->grain_mass;
}

double tribo_si_grain_charge_lost(const tribo_si_derived *d, tribo_model *m, tribo_segment_charge which,
                                  double cylinder_lost)
{
    const double factor = tribo_si_segment_factor(d, which);
    if (!d->spheroid)
        return d->depth * tribo_si_charge_per_length(d, factor * cylinder_lost);
    return d->a * d->a * factor * tribo_get_grain_charge_lost(m, which);
}

double tribo_si_grain_capped_fraction(const tribo_si_derived *d, tribo_model *m,
                                      tribo_segment_charge which, double cylinder_fraction)
{
    if (!d->spheroid)
        return cylinder_fraction;
    return d->a * d->a * tribo_get_grain_capped_area(m, which) / d->grain_area;
}
