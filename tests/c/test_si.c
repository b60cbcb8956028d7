/* The SI front end (docs/model.md §8, src/si/si.h): the mapping onto the model's scene, the
   refusal of every SI value out of range and of every set-up whose derived parameters leave
   the model's ranges (naming what made them), and the outputs as the model's in SI units. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geometry.h"
#include "si.h"
#include "support.h"

static tribo_si_scene si_of(const char *settings)
{
    tribo_si_scene s;
    char err[512];
    tribo_si_scene_defaults(&s);
    cr_assert_eq(tribo_si_scene_apply(&s, settings, err, sizeof err), TRIBO_OK, "%s", err);
    return s;
}

static tribo_si_derived derived_of(const tribo_si_scene *s)
{
    tribo_si_derived d;
    char err[512];
    cr_assert_eq(tribo_si_derive(s, &d, err, sizeof err), TRIBO_OK, "%s", err);
    return d;
}

static int close_to(double a, double b, double rel) { return fabs(a - b) <= rel * fabs(b); }

Test(si, the_reference_case_maps_as_model_md_section_8_says)
{
    /* 1 mm polyethylene (a = 0.5 mm, eps 0.6, 950 kg/m3, E 1 GPa, nu 0.46) on steel (200 GPa,
       0.29): the numbers worked by hand (Python, the formulas of model.md §8) */
    const tribo_si_scene s = si_of("");
    const tribo_si_derived d = derived_of(&s);
    cr_expect(close_to(d.E_star, 1261066648.0028803, 1e-13), "E* %.17g", d.E_star);
    cr_expect(close_to(d.k_prime, 990439429.2632385, 1e-13), "k' %.17g", d.k_prime);
    cr_expect(close_to(d.mass_per_length, 4.4767695313654553e-4, 1e-13), "m' %.17g", d.mass_per_length);
    cr_expect(close_to(d.t_star, 6.723081994145245e-07, 1e-13), "t* %.17g", d.t_star);
    cr_expect(close_to(d.scene.Gamma, 8.8682069403e-09, 1e-10), "Gamma %.17g", d.scene.Gamma);
    /* instantaneous transfer (model.md §5c); the back-flow keeps its 1 ms */
    cr_expect_eq(d.scene.tau0, 0.0);
    cr_expect(close_to(d.scene.tau_r, 1487.4130657202218, 1e-13), "tau_r %.17g", d.scene.tau_r);
    cr_expect_eq(d.scene.grain_geometry, TRIBO_GRAIN_SPHEROID);
    cr_expect_eq(d.scene.gap0, 0.01 / 5e-4);
    cr_expect_eq(d.scene.beta, s.tilt);
    cr_expect_eq(d.scene.chute_length, 0.3 / 5e-4);
    cr_expect_eq(d.scene.mu_roll, 0.01);
    cr_expect(close_to(d.sigma_scale, sqrt(s.interface_capacitance * d.k_prime * 5e-4), 1e-15));
    cr_expect(close_to(d.scene.Sigma0, 1e-5 / d.sigma_scale, 1e-15));
    cr_expect_eq(d.perimeter, 5e-4 * tribo_ellipse_perimeter(0.6));
    /* the dimensionless choices pass through */
    cr_expect_eq(d.scene.n_segments, 2000);
    cr_expect_eq(d.scene.integrator, TRIBO_INTEGRATOR_CVODE);
    cr_expect(d.scene.charge_model_static == 1 && d.scene.charge_model_sliding == 1);
    cr_expect_str_empty(d.notice);
    /* a stiffness given is the one used where stiffness_source says so */
    tribo_si_scene k = si_of("stiffness_source=0 contact_stiffness=2e9");
    const tribo_si_derived dk = derived_of(&k);
    cr_expect_eq(dk.k_prime, 2e9);
    cr_expect(close_to(dk.t_star, sqrt(dk.mass_per_length / 2e9), 1e-15));
    cr_expect_str_empty(dk.notice);
    /* given at its smallest, where Gamma = m' g / (k' a) is still within the model's range */
    tribo_si_scene soft = si_of("stiffness_source=0 contact_stiffness=1");
    cr_expect_eq(derived_of(&soft).k_prime, 1.0);
}

/* A stiffness set while stiffness_source takes the moduli's is not used, and the set-up says
   so, naming both and the stiffness used. */
Test(si, a_stiffness_set_but_not_used_is_noticed)
{
    tribo_si_scene defaults = si_of("");
    const double moduli = derived_of(&defaults).k_prime;
    tribo_si_scene k = si_of("contact_stiffness=2e9");
    const tribo_si_derived dk = derived_of(&k);
    cr_expect_eq(dk.k_prime, moduli);
    cr_expect(strstr(dk.notice, "contact_stiffness = 2e+09 N/m2 is not used") != NULL, "%s", dk.notice);
    cr_expect(strstr(dk.notice, "stiffness_source = 1 (moduli)") != NULL, "%s", dk.notice);
}

/* stiffness_source's values are si_quantities.def's enumeration StiffnessSource's. */
Test(si, the_stiffness_sources_are_the_tables)
{
    int items = 0;
#define TRIBO_ENUM_ITEM(id, name, value, description)                                            \
    if (strcmp(#id, "StiffnessSource") == 0) {                                                    \
        items++;                                                                                 \
        cr_expect_eq(value, strcmp(name, "given") == 0 ? TRIBO_STIFFNESS_GIVEN : TRIBO_STIFFNESS_MODULI); \
    }
#include "si_quantities.def"
    cr_expect_eq(items, 2);
}

/* The TRIBO_MAPS and TRIBO_DERIVES rows of the SI table. */
static const struct {
    const char *si, *model, *how;
} MAPS[] = {
#define TRIBO_MAPS(name, model, how) {#name, #model, #how},
#define TRIBO_DERIVES(model, description) {NULL, #model, "DERIVED"},
#include "si_quantities.def"
};
#define N_MAPS (sizeof MAPS / sizeof MAPS[0])

Test(si, every_model_parameter_is_reached_by_exactly_one_si_row)
{
    size_t n;
    const tribo_param_info *model = tribo_param_table(&n);
    for (size_t i = 0; i < n; i++) {
        int reached = 0;
        for (size_t k = 0; k < N_MAPS; k++)
            reached += strcmp(MAPS[k].model, model[i].name) == 0;
        cr_expect_eq(reached, 1, "the model's %s is reached by %d rows of the SI table", model[i].name,
                     reached);
    }
    for (size_t k = 0; k < N_MAPS; k++)
        cr_expect(MAPS[k].si == NULL || tribo_si_param_find(MAPS[k].si) ||
                      strcmp(MAPS[k].how, "FORCE") == 0,
                  "%s is not an SI parameter", MAPS[k].si);
}

/* The SI parameters whose range is the model's (TRIBO_SAME_PARAMETER rows). */
static const char *const SAME_ROWS[] = {
#define TRIBO_SAME_PARAMETER(name, ...) #name,
#include "si_quantities.def"
};

Test(si, a_parameter_that_takes_the_models_range_says_which_model_parameter_it_is)
{
    /* without its TRIBO_MAPS row the range it takes would be no model parameter's */
    for (size_t i = 0; i < sizeof SAME_ROWS / sizeof SAME_ROWS[0]; i++) {
        int same = 0;
        for (size_t k = 0; k < N_MAPS; k++)
            same += MAPS[k].si && strcmp(MAPS[k].si, SAME_ROWS[i]) == 0 && strcmp(MAPS[k].how, "SAME") == 0;
        cr_expect_eq(same, 1, "%s takes the model's range but has %d TRIBO_MAPS rows with SAME",
                     SAME_ROWS[i], same);
    }
}

Test(si, a_parameter_mapped_as_it_is_has_the_models_type_range_unit_and_variability)
{
    for (size_t k = 0; k < N_MAPS; k++) {
        if (strcmp(MAPS[k].how, "SAME") != 0)
            continue;
        const tribo_param_info *si = tribo_si_param_find(MAPS[k].si);
        const tribo_param_info *model = tribo_param_find(MAPS[k].model);
        cr_assert(si && model, "%s -> %s", MAPS[k].si, MAPS[k].model);
        cr_expect(si->type == model->type && si->min == model->min && si->max == model->max &&
                      si->min_inclusive == model->min_inclusive &&
                      si->max_inclusive == model->max_inclusive &&
                      si->variability == model->variability && strcmp(si->unit, model->unit) == 0,
                  "%s differs from the model's %s", si->name, model->name);
    }
}

Test(si, a_neutral_pair_runs_and_charges_nothing)
{
    tribo_si_scene si = si_of("sigma0=0 drop_height=0");
    const tribo_si_derived d = derived_of(&si);
    char err[512];
    tribo_model *m = tribo_create(&d.scene, err, sizeof err);
    cr_assert(m, "%s", err);
    cr_assert_eq(tribo_advance_fully(m, 2000.0), TRIBO_OK, "%s", tribo_last_error(m));
    cr_expect(tribo_get(m, TRIBO_QUANTITY_STATIC) != 0.0, "the model charged in its own units");
    /* every output that is a charge or a charge density, each model's and the coupling's (the
       calculated parameters, such as the unit sigma_scale, follow the outputs) */
    int charges = 0;
    for (int q = 0; q < TRIBO_SI_QUANTITY_T_STAR; q++) {
        const char *name = tribo_si_quantity_name((tribo_si_quantity)q);
        if ((strncmp(name, "charge", 6) == 0 && strcmp(name, "charged_area") != 0) ||
            strncmp(name, "sigma", 5) == 0) {
            cr_expect_eq(tribo_si_get(&d, m, (tribo_si_quantity)q), 0.0, "%s", name);
            charges++;
        }
    }
    /* per model: charge, per length, to mass, sigma_mean, charge lost; charge_to_mass, sigma_s */
    cr_expect_eq(charges, 5 * TRIBO_SEGMENTS_COUNT + 2);
    tribo_free(m);
}

Test(si, every_si_value_out_of_range_is_refused_with_its_message)
{
    size_t n;
    const tribo_param_info *table = tribo_si_param_table(&n);
    for (size_t i = 0; i < n; i++) {
        const tribo_param_info *p = &table[i];
        const double below = p->min_inclusive ? nextafter(p->min, -INFINITY) - (p->type != TRIBO_TYPE_REAL)
                                              : p->min;
        tribo_si_scene s;
        tribo_si_scene_defaults(&s);
        tribo_param_write(&s, p, below);
        tribo_si_derived d;
        char err[512] = "";
        cr_expect_eq(tribo_si_derive(&s, &d, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT, "%s", p->name);
        char range[128];
        tribo_param_range_text(p, range, sizeof range);
        cr_expect(strstr(err, p->name) == err && strstr(err, range), "%s: '%s'", p->name, err);
    }
}

/* A set-up refused, with the words its message must hold. */
static void expect_refused(const char *settings, const char *const *words)
{
    tribo_si_scene s = si_of(settings);
    tribo_si_derived d;
    char err[600] = "";
    cr_expect_eq(tribo_si_derive(&s, &d, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT, "%s", settings);
    for (int i = 0; words[i]; i++)
        cr_expect(strstr(err, words[i]) != NULL, "%s: '%s' lacks '%s'", settings, err, words[i]);
}

Test(si, a_derived_parameter_out_of_the_models_range_names_what_made_it)
{
    /* a grain so small and stiff that its weight is beyond the model's smallest Gamma */
    expect_refused("semi_major_axis=1e-7 youngs_modulus_particle=1e13 youngs_modulus_wall=1e13",
                   (const char *const[]){"Gamma = ", "valid range 1e-12 <= Gamma <= 10",
                                         "semi_major_axis = 1e-07 m", "density = 950 kg/m3",
                                         "gravity = 9.81 m/s2", "youngs_modulus_particle = 1e+13 Pa",
                                         "poisson_ratio_wall = 0.29", NULL});
    /* so soft that it would sink: Gamma above 10 */
    expect_refused("semi_major_axis=1 density=1e5 youngs_modulus_particle=1e3 youngs_modulus_wall=1e3",
                   (const char *const[]){"Gamma = ", "<= 10", NULL});
    /* a charging time beyond the model's 1e9 t_star (t_star = 0.13 ns for a = 0.1 um) */
    expect_refused("charging_time=100 semi_major_axis=1e-7",
                   (const char *const[]){"tau0 = ", "charging_time = 100 s", "semi_major_axis", NULL});
    /* a saturation density below the model's smallest Sigma0 (0 is a neutral pair) */
    expect_refused("sigma0=1e-12", (const char *const[]){"Sigma0 = ", "sigma0 = 1e-12 C/m2",
                                                         "interface_capacitance", NULL});
    /* the given stiffness is named as given */
    expect_refused("stiffness_source=0 contact_stiffness=1e12 semi_major_axis=1e-7",
                   (const char *const[]){"the model's parameter derived from",
                                         "contact_stiffness = 1e+12 N/m2", NULL});
    /* a drop too fast for the model (more than 10 a / t_star; a / t_star = 23 m/s for E = 1 MPa) */
    expect_refused("drop_speed=1000 youngs_modulus_particle=1e6",
                   (const char *const[]){"drop_speed = ", "drop_speed = 1000 m/s", "youngs_modulus_particle = 1e+06 Pa", NULL});
    /* a start beyond the chute's end (x0's declared range ends at the default chute's end:
       a shorter chute) */
    expect_refused("chute_length=0.1 x0=0.2", (const char *const[]){"x0 = 0.2 m", "chute_length = 0.1", NULL});
    /* a start too far up the chute in the model's lengths (X0 = x0 / a beyond -1e6) */
    expect_refused("x0=-100 semi_major_axis=1e-7", (const char *const[]){"X0 = ", "x0 = -100 m", NULL});
}

Test(si, tunables_and_inputs_convert_as_the_set_up_does)
{
    /* a = 0.1 mm: 10 k' a (9.9e5 N/m) inside the inputs' declared range */
    const tribo_si_scene s = si_of("charging_time=2e-3 semi_major_axis=1e-4");
    const tribo_si_derived d = derived_of(&s);
    const char *name;
    double v;
    char err[512];
    cr_assert_eq(tribo_si_model_param(&d, tribo_si_param_find("charging_time"), 2e-3, &name, &v, err, sizeof err),
                 TRIBO_OK, "%s", err);
    cr_expect(strcmp(name, "tau0") == 0 && v == d.scene.tau0, "%s = %.17g", name, v);
    cr_assert_eq(tribo_si_model_param(&d, tribo_si_param_find("mu"), 0.7, &name, &v, err, sizeof err), TRIBO_OK);
    cr_expect(strcmp(name, "mu") == 0 && v == 0.7);
    cr_expect_eq(tribo_si_model_param(&d, tribo_si_param_find("backflow_time"), 1e-20, &name, &v, err, sizeof err),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "tau_r = ") && strstr(err, "backflow_time = 1e-20 s"), "%s", err);
    /* forces per unit length in units of k' a, at most 10 of them */
    const double in[TRIBO_SI_INPUT_COUNT] = {d.force, -2.5 * d.force};
    double out[TRIBO_INPUT_COUNT];
    cr_assert_eq(tribo_si_model_inputs(&d, in, out, err, sizeof err), TRIBO_OK, "%s", err);
    cr_expect(out[TRIBO_INPUT_F_T] == 1.0 && out[TRIBO_INPUT_F_N] == -2.5);
    const double big[TRIBO_SI_INPUT_COUNT] = {0.0, 11 * d.force};
    cr_expect_eq(tribo_si_model_inputs(&d, big, out, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "F_N_ext = 11") && strstr(err, "k' a = "), "%s", err);
}

Test(si, the_outputs_are_the_models_in_si_units)
{
    /* a 0.5 mm grain dropped from 0.5 mm: its first impacts (tau to 1000), the cylinder's
       charges (the spheroid's: the test below) */
    tribo_si_scene s = si_of("drop_height=5e-4 n_segments=200 grain_geometry=0");
    const tribo_si_derived d = derived_of(&s);
    tribo_model *m = make(&d.scene);
    cr_assert_eq(tribo_advance_fully(m, 2e4), TRIBO_OK, "%s", tribo_last_error(m));
    cr_assert(tribo_get(m, TRIBO_QUANTITY_STATIC) > 0.0 && tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN) > 0.0);
    const double a = 5e-4, t = d.t_star;
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_TIME), t * tribo_get(m, TRIBO_QUANTITY_TIME));
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_X), a * tribo_get(m, TRIBO_QUANTITY_X));
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_U), (a / t) * tribo_get(m, TRIBO_QUANTITY_U));
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_OMEGA), tribo_get(m, TRIBO_QUANTITY_OMEGA) / t);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_ENERGY),
                 d.k_prime * a * a * 1e-3 * tribo_get(m, TRIBO_QUANTITY_ENERGY));
    /* the charges: sigma0 Q_static, and the sliding density with sigma0's sign */
    const double static_density = -1e-5 * tribo_get(m, TRIBO_QUANTITY_STATIC);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_SIGMA_MEAN_STATIC), static_density);
    cr_expect(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_SIGMA_MEAN_SLIDING) < 0.0);
    cr_expect(close_to(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_SIGMA_MEAN_SLIDING),
                       -1e-5 * tribo_get(m, TRIBO_QUANTITY_SLIDING), 1e-14));
    const double per_length = d.perimeter * static_density;
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_CHARGE_PER_LENGTH_STATIC), per_length);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_CHARGE_STATIC), 1e-3 * per_length);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M_STATIC), per_length / d.mass_per_length);
    cr_expect_eq(tribo_si_segment_factor(&d, TRIBO_SEGMENTS_STATIC), -1e-5);
    /* the calculated parameters need no instance */
    cr_expect_eq(tribo_si_get(&d, NULL, TRIBO_SI_QUANTITY_T_STAR), t);
    cr_expect_eq(tribo_si_get(&d, NULL, TRIBO_SI_QUANTITY_GAMMA), d.scene.Gamma);
    cr_expect_eq(tribo_si_get(&d, NULL, TRIBO_SI_QUANTITY_MASS), d.mass_per_length * 1e-3);

    /* the charge-to-mass ratio does not depend on the cylinder's depth; the charge does */
    s.cylinder_length = 0.25;
    const tribo_si_derived deep = derived_of(&s);
    cr_expect_eq(tribo_si_get(&deep, m, TRIBO_SI_QUANTITY_Q_PER_M_STATIC), tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M_STATIC));
    cr_expect_eq(tribo_si_get(&deep, m, TRIBO_SI_QUANTITY_CHARGE_STATIC), 0.25 * per_length);
    tribo_free(m);
}

Test(si, every_registered_model_has_its_charge_from_the_mean_of_its_values)
{
    tribo_si_scene s = si_of("drop_height=5e-4 n_segments=200 grain_geometry=0");
    /* every registered model, the ones off by default too */
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values) s.charge_model_##name = 1;
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
    const tribo_si_derived d = derived_of(&s);
    tribo_model *m = make(&d.scene);
    cr_assert_eq(tribo_advance_fully(m, 2e4), TRIBO_OK, "%s", tribo_last_error(m));
    static const struct {
        tribo_segment_charge which;
        tribo_si_quantity charge, per_length, to_mass, sigma_mean;
    } MODELS[] = {
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values)                                   \
    {TRIBO_SEGMENTS_##id, TRIBO_SI_QUANTITY_CHARGE_##id, TRIBO_SI_QUANTITY_CHARGE_PER_LENGTH_##id, \
     TRIBO_SI_QUANTITY_Q_PER_M_##id, TRIBO_SI_QUANTITY_SIGMA_MEAN_##id},
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
    };
    double values[200];
    for (size_t k = 0; k < sizeof MODELS / sizeof *MODELS; k++) {
        const tribo_segment_charge w = MODELS[k].which;
        /* the mean of the values tribo_get_segment_charges gives, without copying them */
        cr_assert_eq(tribo_get_segment_charges(m, w, values, 200), TRIBO_OK);
        double sum = 0.0;
        for (int i = 0; i < 200; i++)
            sum += values[i];
        const double mean = tribo_get_mean_charge(m, w);
        cr_expect(mean != 0.0 && close_to(mean, sum / 200, 1e-12), "%g %g", mean, sum / 200);
        /* in SI units: times the model's factor, then over the boundary, the depth, the mass */
        const double sigma = tribo_si_segment_factor(&d, w) * mean;
        const double per_length = d.perimeter * sigma;
        cr_expect_eq(tribo_si_get(&d, m, MODELS[k].sigma_mean), sigma);
        cr_expect_eq(tribo_si_get(&d, m, MODELS[k].per_length), per_length);
        cr_expect_eq(tribo_si_get(&d, m, MODELS[k].charge), 1e-3 * per_length);
        cr_expect_eq(tribo_si_get(&d, m, MODELS[k].to_mass), per_length / d.mass_per_length);
        /* and charge_to_mass carries it where charge_to_mass_model names it */
        tribo_si_derived named = d;
        named.charge_to_mass_model = (int)w + 1;
        cr_expect_eq(tribo_si_get(&named, m, TRIBO_SI_QUANTITY_Q_PER_M),
                     tribo_si_get(&d, m, MODELS[k].to_mass));
    }
    /* the means are the models' own outputs, exactly */
    cr_expect_eq(tribo_get_mean_charge(m, TRIBO_SEGMENTS_STATIC), tribo_get(m, TRIBO_QUANTITY_STATIC));
    cr_expect_eq(tribo_get_mean_charge(m, TRIBO_SEGMENTS_SLIDING), tribo_get(m, TRIBO_QUANTITY_SLIDING));
    cr_expect(isnan(tribo_get_mean_charge(m, TRIBO_SEGMENTS_COUNT)));
    tribo_free(m);
}

Test(si, charge_to_mass_carries_the_one_model_charge_to_mass_model_names)
{
    /* both models run (the defaults); each choice is that model's ratio, not their sum, and
       the default (0) is the first included: the static model's */
    tribo_si_scene s = si_of("drop_height=5e-4 n_segments=50");
    cr_expect_eq(s.charge_to_mass_model, 0);
    const tribo_si_derived d = derived_of(&s);
    cr_expect_eq(d.charge_to_mass_model, 1);
    tribo_model *m = make(&d.scene);
    cr_assert_eq(tribo_advance_fully(m, 2e4), TRIBO_OK, "%s", tribo_last_error(m));
    const double q_static = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M_STATIC),
                 q_sliding = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M_SLIDING);
    cr_assert(q_static != 0.0 && q_sliding != 0.0);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M), q_static);
    s.charge_to_mass_model = 2;
    const tribo_si_derived d2 = derived_of(&s);
    cr_expect_eq(tribo_si_get(&d2, m, TRIBO_SI_QUANTITY_Q_PER_M), q_sliding);
    tribo_free(m);

    /* the range is the registry's rows */
    const tribo_param_info *p = tribo_si_param_find("charge_to_mass_model");
    cr_expect(p->min == 0.0 && p->max == TRIBO_SEGMENTS_COUNT && p->type == TRIBO_TYPE_INTEGER);
    char err[512];
    char past_the_rows[64];
    snprintf(past_the_rows, sizeof past_the_rows, "charge_to_mass_model=%d",
             TRIBO_SEGMENTS_COUNT + 1);
    cr_expect_eq(tribo_si_scene_apply(&s, past_the_rows, err, sizeof err),
                 TRIBO_ERR_INVALID_ARGUMENT);

    /* a model switched off cannot be the one carried: one line naming both */
    tribo_si_scene off = si_of("charge_model_sliding=0 charge_to_mass_model=2");
    tribo_si_derived dd;
    cr_expect_eq(tribo_si_derive(&off, &dd, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "charge_to_mass_model = 2") && strstr(err, "charge_model_sliding = 0") &&
                  !strchr(err, '\n'),
              "%s", err);
    /* the selection as one enumeration of subsets is gone: each model has its switch */
    cr_expect_eq(tribo_si_scene_apply(&s, "charge_model=3", err, sizeof err),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "charge_model was removed") && strstr(err, "charge_model_sliding"), "%s",
              err);
    tribo_si_scene fine = si_of("charge_model_static=0");
    fine.charge_to_mass_model = 2;
    cr_expect_eq(tribo_si_derive(&fine, &dd, err, sizeof err), TRIBO_OK, "%s", err);
    /* a model switched off alone, the default carries the other: the first included */
    tribo_si_scene first = si_of("charge_model_static=0");
    cr_expect_eq(tribo_si_derive(&first, &dd, err, sizeof err), TRIBO_OK, "%s", err);
    cr_expect_eq(dd.charge_to_mass_model, 2);
    /* no model at all: nothing charges, and charge_to_mass is 0 whichever it names */
    tribo_si_scene none = si_of("charge_model_static=0 charge_model_sliding=0");
    cr_expect_eq(tribo_si_derive(&none, &dd, err, sizeof err), TRIBO_OK, "%s", err);
    tribo_model *uncharged = tribo_create(&dd.scene, err, sizeof err);
    cr_assert(uncharged, "%s", err);
    cr_expect_eq(tribo_advance(uncharged, 1e4), TRIBO_OK, "%s", tribo_last_error(uncharged));
    cr_expect_eq(tribo_si_get(&dd, uncharged, TRIBO_SI_QUANTITY_Q_PER_M), 0.0);
    tribo_free(uncharged);
}

Test(si, an_impact_episode_ends_at_its_liftoff_and_the_motion_fractions_pass_through)
{
    /* the reference grain thrown straight down at 2 m/s onto the chute (tilted 30 degrees), with
       run_end = first_liftoff: the run ends in flight after one contact; lifted_off, impacts
       and the motion-class fractions are the model's */
    tribo_si_scene s = si_of("drop_height=0 drop_speed=2 run_end=1 "
                             "n_segments=200");
    const tribo_si_derived d = derived_of(&s);
    cr_expect_eq(d.scene.run_end, TRIBO_RUN_END_FIRST_LIFTOFF);
    tribo_model *m = make(&d.scene);
    const tribo_status st = tribo_advance_fully(m, 1e4);
    cr_assert_eq(st, TRIBO_ENDED, "status %d: %s, t = %g", st, tribo_last_error(m), tribo_get(m, TRIBO_QUANTITY_TIME));
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_LIFTED_OFF), 1.0);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_EXITED), 0.0);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_IMPACTS), 1.0);
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_IN_CONTACT), 0.0);
    cr_expect(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_V) > 0.0, "rebound v = %g", tribo_si_get(&d, m, TRIBO_SI_QUANTITY_V));
    const tribo_si_quantity si_fractions[] = {TRIBO_SI_QUANTITY_FRACTION_FLIGHT, TRIBO_SI_QUANTITY_FRACTION_ROCKING,
                                              TRIBO_SI_QUANTITY_FRACTION_ROLLING, TRIBO_SI_QUANTITY_FRACTION_TUMBLING,
                                              TRIBO_SI_QUANTITY_FRACTION_BOUNCING};
    const tribo_quantity fractions[] = {TRIBO_QUANTITY_FRACTION_FLIGHT, TRIBO_QUANTITY_FRACTION_ROCKING,
                                        TRIBO_QUANTITY_FRACTION_ROLLING, TRIBO_QUANTITY_FRACTION_TUMBLING,
                                        TRIBO_QUANTITY_FRACTION_BOUNCING};
    double sum = 0.0;
    for (int i = 0; i < 5; i++) {
        cr_expect_eq(tribo_si_get(&d, m, si_fractions[i]), tribo_get(m, fractions[i]));
        sum += tribo_si_get(&d, m, si_fractions[i]);
    }
    cr_expect(fabs(sum - 1.0) < 1e-12, "fractions sum to %.17g", sum);
    tribo_free(m);
}

Test(si, a_contact_lost_at_another_switch_is_left_and_the_run_stays_cheap)
{
    /* A grain of the population benchmark (seed 1, particle 590): at tau ~ 5.1e5 a tangent
       switch fired where the lowest point had already lifted off (by less than the root
       finding's resolution), the phase stayed "contact" with no force, its contact root
       negative from then on, and its tangent switch fired at every rounding of the stretch:
       4.9 million events in 1000 tau, 168 s of CPU. Since the fix the whole run to the exit
       takes 856 events (measured); the bound leaves a margin of 10x and fails within about
       a second without the fix. */
    const tribo_si_scene s = si_of("chute_length=0.3 epsilon=0.9906745512219763 "
                                   "semi_major_axis=0.000402668449168971 phi0=1.6799303799904879");
    tribo_si_derived d = derived_of(&s);
    d.scene.work_limit = 100000;
    char err[512];
    tribo_model *m = tribo_create(&d.scene, err, sizeof err);
    cr_assert_not_null(m, "%s", err);
    tribo_status st = TRIBO_INCOMPLETE;
    tribo_stats stats = {0};
    while (st == TRIBO_INCOMPLETE && stats.events <= 8560) {
        st = tribo_advance(m, 1e9);
        tribo_get_stats(m, &stats);
    }
    cr_expect_eq(st, TRIBO_ENDED, "status %d after %lld events: %s", st, stats.events, tribo_last_error(m));
    cr_expect_leq(stats.events, 8560, "%lld events", stats.events);
    tribo_free(m);
}

/* A breakdown limit too small for a double in the model's units (breakdown_density =
   5e-324 C/m2, inside its range) is the smallest one the model takes, not none, and not 0,
   which the model refuses. */
Test(si, the_smallest_breakdown_density_is_the_smallest_limit)
{
    tribo_si_scene si = si_of("breakdown_density=5e-324");
    tribo_si_derived d;
    char err[512];
    cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
    cr_expect_eq(d.scene.Sigma_bd, DBL_TRUE_MIN);
}
