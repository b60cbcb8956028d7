/* The free-fall separator (docs/model.md §10, src/separator/separator.h) against the checks §10 names:
   no field and no drag, a parabola; no field with drag, the terminal velocity of the
   Schiller-Naumann balance (solved here by bisection); the field alone, x - x0 = ½ (q/m) E t²
   with the analytic fall time. Then the bins, the electrodes, the hold before the release,
   the entry's frame, refusals, the work limit and the state.

   Tolerances: the errors measured at the defaults' rtol = 1e-8, atol = 1e-12 (printed by
   SEPARATOR_VERBOSE=1), with the margin stated at each. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "separator.h"

static const double G = 9.81;

static tribo_separator_scene scene_of(const char *settings)
{
    tribo_separator_scene s;
    char err[512];
    tribo_separator_scene_defaults(&s);
    cr_assert_eq(tribo_separator_scene_apply(&s, settings, err, sizeof err), TRIBO_OK, "%s", err);
    return s;
}

static tribo_separator *make(const tribo_separator_scene *sc)
{
    char err[512];
    tribo_separator *s = tribo_separator_create(sc, err, sizeof err);
    cr_assert(s, "%s", err);
    return s;
}

static void release(tribo_separator *s, double u, double v, double q_per_m)
{
    double in[TRIBO_SEPARATOR_INPUT_COUNT] = {0};
    in[TRIBO_SEPARATOR_INPUT_RELEASED] = 1;
    in[TRIBO_SEPARATOR_INPUT_U_ENTRY] = u;
    in[TRIBO_SEPARATOR_INPUT_V_ENTRY] = v;
    in[TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS] = q_per_m;
    cr_assert_eq(tribo_separator_set_inputs(s, in), TRIBO_OK, "%s", tribo_separator_last_error(s));
}

static tribo_status advance(tribo_separator *s, double t)
{
    tribo_status st;
    while ((st = tribo_separator_advance(s, t)) == TRIBO_INCOMPLETE) {
    }
    cr_assert(st == TRIBO_OK || st == TRIBO_ENDED, "%d: %s", st, tribo_separator_last_error(s));
    return st;
}

static double get(const tribo_separator *s, tribo_separator_quantity q) { return tribo_separator_get(s, q); }

/* |a - b| / scale, printed when SEPARATOR_VERBOSE is set (to measure the tolerances) */
static double err_of(const char *what, double a, double b, double scale)
{
    const double e = fabs(a - b) / scale;
    if (getenv("SEPARATOR_VERBOSE"))
        fprintf(stderr, "%-40s %.3e\n", what, e);
    return e;
}

#define NO_AIR "air_density=0 air_viscosity=0 "

Test(separator, no_field_no_drag_is_a_parabola)
{
    /* thrown across the gap from a chute tilted by 30 degrees: u down-slope, v off the chute */
    const double beta = M_PI / 6, u = 0.4, v = 0.1, x0 = -0.02, H = 0.5;
    tribo_separator_scene sc = scene_of(NO_AIR "voltage=0 chute_direction=1 gap=0.5 x_entry=-0.02");
    tribo_separator *s = make(&sc);
    release(s, u, v, 1e-5);
    const double vx0 = u * cos(beta) + v * sin(beta), vz0 = -u * sin(beta) + v * cos(beta);
    /* on the way: x = x0 + vx0 t, z = vz0 t - g t²/2. Errors over H measured up to 4e-8
       (z; rtol 1e-8 per step, accumulated), bound 1e-6: margin 25 */
    for (double t = 0.05; t < 0.3; t += 0.05) {
        cr_assert_eq(advance(s, t), TRIBO_OK);
        cr_expect(err_of("parabola x(t)", get(s, TRIBO_SEPARATOR_Q_X), x0 + vx0 * t, H) < 1e-6);
        cr_expect(err_of("parabola z(t)", get(s, TRIBO_SEPARATOR_Q_Z), vz0 * t - G * t * t / 2, H) < 1e-6);
        cr_expect(err_of("parabola vz(t)", get(s, TRIBO_SEPARATOR_Q_VZ), vz0 - G * t, 1.0) < 1e-9);
        cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_Y), 0.0);
    }
    /* the bins at t_f = (vz0 + sqrt(vz0² + 2 g H)) / g */
    cr_assert_eq(advance(s, 10.0), TRIBO_ENDED);
    const double tf = (vz0 + sqrt(vz0 * vz0 + 2 * G * H)) / G;
    cr_expect(err_of("parabola fall time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-6);
    cr_expect(err_of("parabola x at the bins", get(s, TRIBO_SEPARATOR_Q_X_END), x0 + vx0 * tf, H) < 1e-6);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_Z_END), -H);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_LANDED), 1.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_ELECTRODE), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_BIN), tribo_separator_bin_of(&sc, x0 + vx0 * tf));
    tribo_separator_free(s);
}

Test(separator, a_chute_along_the_plates_moves_the_grain_along_them_only)
{
    const double beta = 0.4, u = 0.5, v = -0.05;
    tribo_separator_scene sc = scene_of(NO_AIR "voltage=0 tilt=0.4 x_entry=0.01");
    tribo_separator *s = make(&sc);
    release(s, u, v, 0);
    cr_assert_eq(advance(s, 0.1), TRIBO_OK);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_X), 0.01);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_VX), 0.0);
    cr_expect(err_of("along: y(t)", get(s, TRIBO_SEPARATOR_Q_Y), (u * cos(beta) + v * sin(beta)) * 0.1, 1) < 1e-9);
    cr_expect(err_of("along: vz(t)", get(s, TRIBO_SEPARATOR_Q_VZ), -u * sin(beta) + v * cos(beta) - G * 0.1, 1) < 1e-9);
    tribo_separator_free(s);
}

/* The terminal velocity where m g = F_drag (model.md §10), by bisection on |v|. */
static double terminal_velocity(const tribo_separator_scene *sc, const tribo_separator_derived *d)
{
    double lo = 0, hi = 1e3;
    for (int i = 0; i < 200; i++) {
        const double mid = (lo + hi) / 2, v[3] = {0, 0, -mid};
        double drag[3];
        tribo_separator_drag(sc, d, v, drag);
        if (-drag[2] < sc->gravity)
            lo = mid;
        else
            hi = mid;
    }
    return (lo + hi) / 2;
}

/* The same balance written out independently of the model's code: Stokes' 3 pi mu d v
   times (1 + 0.15 Re^0.687) below Re = 1000, ½ rho 0.44 A v² above. */
static double drag_force(double rho, double mu, double d, double v)
{
    const double re = rho * v * d / mu;
    return re < 1000 ? 3 * M_PI * mu * d * v * (1 + 0.15 * pow(re, 0.687))
                     : 0.5 * rho * 0.44 * M_PI * d * d / 4 * v * v;
}

static void check_terminal(const char *settings, double height, double re_lo, double re_hi,
                           const char *what)
{
    tribo_separator_scene sc = scene_of(settings);
    tribo_separator *s = make(&sc);
    const tribo_separator_derived *d = tribo_separator_get_derived(s);
    /* bisection on the independent balance */
    double lo = 0, hi = 1e3;
    for (int i = 0; i < 200; i++) {
        const double mid = (lo + hi) / 2;
        if (drag_force(sc.air_density, sc.air_viscosity, d->diameter, mid) < d->mass * G)
            lo = mid;
        else
            hi = mid;
    }
    const double vt = (lo + hi) / 2;
    cr_expect(fabs(terminal_velocity(&sc, d) - vt) <= 1e-12 * vt, "%s: the model's drag", what);
    const double re = sc.air_density * vt * d->diameter / sc.air_viscosity;
    cr_assert(re > re_lo && re < re_hi, "%s: Re = %g", what, re);
    release(s, 0, 0, 0);
    cr_assert_eq(advance(s, 1e3), TRIBO_ENDED);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_Z_END), -height);
    char label[80];
    snprintf(label, sizeof label, "terminal velocity, %s", what);
    /* measured 6e-13 (Re ~ 1.6) and 2e-10 (Re ~ 1500); margin 50 */
    cr_expect(err_of(label, -get(s, TRIBO_SEPARATOR_Q_VZ), vt, vt) < 1e-8, "%s: vz %.17g, vt %.17g",
              what, get(s, TRIBO_SEPARATOR_Q_VZ), vt);
    cr_expect(fabs(get(s, TRIBO_SEPARATOR_Q_REYNOLDS) - re) < 1e-6 * re);
    tribo_separator_free(s);
}

Test(separator, no_field_with_drag_reaches_the_terminal_velocity)
{
    /* a 100 µm sphere of 950 kg/m3 (Re ~ 1.6, 70 relaxation times over the fall) */
    check_terminal("voltage=0 semi_major_axis=50e-6 epsilon=1", 0.5, 1, 10, "Re ~ 1.6");
    /* a 1 cm sphere of 20 kg/m3: Newton's regime (C_D = 0.44, Re ~ 1500) */
    check_terminal("voltage=0 semi_major_axis=5e-3 epsilon=1 density=20 height=10", 10, 1000, 3000,
                   "Re ~ 1500");
}

Test(separator, the_field_alone_moves_x_by_half_q_over_m_E_t_squared)
{
    /* E_x = -U/w = -3e5 V/m; q/m = 1e-6 C/kg: 0.3 m/s² towards the negative plate */
    const double H = 0.5, x0 = 0.01, qm = 1e-6, E = -30e3 / 0.1;
    tribo_separator_scene sc = scene_of(NO_AIR "x_entry=0.01");
    tribo_separator *s = make(&sc);
    cr_expect(fabs(tribo_separator_calculated(tribo_separator_get_derived(s), TRIBO_SEPARATOR_Q_FIELD) - E) <= 1e-15 * -E);
    release(s, 0, 0, qm);
    cr_assert_eq(advance(s, 0.2), TRIBO_OK);
    /* x measured 2e-13 over H on the way, 7e-18 at the bins; bound 1e-9 */
    cr_expect(err_of("field x(t)", get(s, TRIBO_SEPARATOR_Q_X), x0 + 0.5 * qm * E * 0.04, H) < 1e-9);
    cr_assert_eq(advance(s, 10), TRIBO_ENDED);
    const double tf = sqrt(2 * H / G), xf = x0 + 0.5 * qm * E * tf * tf;
    /* measured 5e-9 relative; margin 20 */
    cr_expect(err_of("field fall time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-7);
    cr_expect(err_of("field x at the bins", get(s, TRIBO_SEPARATOR_Q_X_END), xf, H) < 1e-9);
    /* x = -0.0053: the fifth of ten 1 cm bins from the plate at -w/2 */
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_BIN), 5.0);
    tribo_separator_free(s);

    /* a negative grain drifts the other way, by as much */
    s = make(&sc);
    release(s, 0, 0, -qm);
    cr_assert_eq(advance(s, 10), TRIBO_ENDED);
    cr_expect(err_of("field x, negative grain", get(s, TRIBO_SEPARATOR_Q_X_END), x0 - 0.5 * qm * E * tf * tf, H) < 1e-9);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_BIN), 8.0); /* x = 0.0253 */
    tribo_separator_free(s);
}

Test(separator, a_grain_drawn_to_a_plate_is_caught_there)
{
    /* q/m = 1e-5: 3 m/s² towards -x; the plate's limit -(w/2 - a) = -0.0495 m is reached at
       t_c = sqrt(2 * 0.0495 / 3), before the bins (sqrt(2 H / g) = 0.32 s) */
    const double limit = 0.05 - 5e-4, tc = sqrt(2 * limit / 3.0);
    tribo_separator_scene sc = scene_of(NO_AIR);
    tribo_separator *s = make(&sc);
    release(s, 0, 0, 1e-5);
    cr_assert_eq(advance(s, 10), TRIBO_ENDED);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_ELECTRODE), -1.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_LANDED), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_BIN), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_ENDED), 1.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_X_END), -limit);
    /* measured 1.3e-11; margin 75 */
    cr_expect(err_of("caught: time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tc, tc) < 1e-9);
    cr_expect(err_of("caught: z", get(s, TRIBO_SEPARATOR_Q_Z_END), -G * tc * tc / 2, 0.5) < 1e-9);
    /* the run is over: a later advance changes nothing */
    const double t = get(s, TRIBO_SEPARATOR_Q_TIME);
    cr_expect_eq(tribo_separator_advance(s, 20), TRIBO_ENDED);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_TIME), t);
    tribo_separator_free(s);

    /* a negative one on the other plate */
    s = make(&sc);
    release(s, 0, 0, -1e-5);
    cr_assert_eq(advance(s, 10), TRIBO_ENDED);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_ELECTRODE), 1.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_X_END), limit);
    tribo_separator_free(s);
}

Test(separator, the_grain_is_held_at_the_entry_until_released)
{
    tribo_separator_scene sc = scene_of(NO_AIR "voltage=0 x_entry=0.02");
    tribo_separator *s = make(&sc);
    double in[TRIBO_SEPARATOR_INPUT_COUNT] = {0};
    in[TRIBO_SEPARATOR_INPUT_U_ENTRY] = 1.0; /* not released: no effect */
    cr_assert_eq(tribo_separator_set_inputs(s, in), TRIBO_OK);
    cr_assert_eq(advance(s, 0.5), TRIBO_OK);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_TIME), 0.5);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_X), 0.02);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_Z), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_VY), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_RELEASED_OUT), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), 0.0);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_X_END), 0.02);
    release(s, 0, 0, 0);
    cr_assert_eq(advance(s, 10), TRIBO_ENDED);
    const double tf = sqrt(2 * 0.5 / G);
    /* measured 8e-12; margin 125 */
    cr_expect(err_of("held: landing time", get(s, TRIBO_SEPARATOR_Q_TIME), 0.5 + tf, tf) < 1e-9);
    cr_expect(err_of("held: flight time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-9);
    tribo_separator_free(s);
}

Test(separator, bins_are_numbered_from_the_plate_at_minus_half_the_gap)
{
    tribo_separator_scene sc = scene_of("gap=1 n_bins=4 semi_major_axis=1e-3");
    cr_expect_eq(tribo_separator_bin_of(&sc, -0.5), 1);
    cr_expect_eq(tribo_separator_bin_of(&sc, -0.2500001), 1);
    cr_expect_eq(tribo_separator_bin_of(&sc, -0.25), 2);
    cr_expect_eq(tribo_separator_bin_of(&sc, 0.0), 3);
    cr_expect_eq(tribo_separator_bin_of(&sc, 0.4999), 4);
    cr_expect_eq(tribo_separator_bin_of(&sc, 0.5), 4);
    sc.n_bins = 1;
    cr_expect_eq(tribo_separator_bin_of(&sc, 0.3), 1);
}

Test(separator, refusals_name_the_variable_its_value_and_range)
{
    char err[512];
    tribo_separator_scene sc;
    tribo_separator_scene_defaults(&sc);
    cr_expect_eq(tribo_separator_scene_set(&sc, "gap", 0, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "gap = 0 is invalid") && strstr(err, "0.002 <= gap <= 10"), "%s", err);
    sc = scene_of("x_entry=0.0485 semi_major_axis=2e-3");
    cr_expect_null(tribo_separator_create(&sc, err, sizeof err));
    cr_expect(strstr(err, "x_entry = 0.0485") && strstr(err, "< x_entry < 0.048"), "%s", err);
    sc = scene_of("gap=2e-3 semi_major_axis=1e-3");
    cr_expect_null(tribo_separator_create(&sc, err, sizeof err));
    cr_expect(strstr(err, "semi_major_axis = 0.001") && strstr(err, "2 semi_major_axis < gap"), "%s", err);
    sc = scene_of("");
    sc.air_density = NAN;
    cr_expect_null(tribo_separator_create(&sc, err, sizeof err));
    cr_expect(strstr(err, "air_density = nan is invalid"), "%s", err);

    sc = scene_of("");
    tribo_separator *s = make(&sc);
    double in[TRIBO_SEPARATOR_INPUT_COUNT] = {0};
    in[TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS] = 2;
    cr_expect_eq(tribo_separator_set_inputs(s, in), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(tribo_separator_last_error(s), "charge_to_mass = 2 is invalid: the valid range is -1 <= charge_to_mass <= 1"),
              "%s", tribo_separator_last_error(s));
    in[TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS] = 0;
    in[TRIBO_SEPARATOR_INPUT_RELEASED] = 0.5;
    cr_expect_eq(tribo_separator_set_inputs(s, in), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(tribo_separator_last_error(s), "released = 0.5"), "%s", tribo_separator_last_error(s));
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_RELEASED_OUT), 0.0); /* nothing changed */
    cr_expect_eq(tribo_separator_advance(s, 1), TRIBO_OK);
    cr_expect_eq(tribo_separator_advance(s, 0.5), TRIBO_ERR_TIME);
    cr_expect(strstr(tribo_separator_last_error(s), "t = 0.5 s is invalid"), "%s", tribo_separator_last_error(s));
    cr_expect_eq(tribo_separator_advance(s, NAN), TRIBO_ERR_TIME);
    cr_expect_eq(get(s, TRIBO_SEPARATOR_Q_TIME), 1.0);
    tribo_separator_free(s);
}

Test(separator, the_work_limit_stops_an_advance_early_and_it_goes_on)
{
    tribo_separator_scene sc = scene_of("work_limit=3 semi_major_axis=50e-6 epsilon=1");
    tribo_separator *s = make(&sc);
    release(s, 0.3, 0, 1e-6);
    int stops = 0;
    tribo_status st;
    while ((st = tribo_separator_advance(s, 100)) == TRIBO_INCOMPLETE)
        stops++;
    cr_assert_eq(st, TRIBO_ENDED, "%s", tribo_separator_last_error(s));
    cr_expect_gt(stops, 10);
    tribo_separator_scene free_sc = sc;
    free_sc.work_limit = 100000;
    tribo_separator *f = make(&free_sc);
    release(f, 0.3, 0, 1e-6);
    cr_assert_eq(advance(f, 100), TRIBO_ENDED);
    /* the restarts move the result within the tolerances: measured 9e-9 relative; margin 10 */
    const double tf = get(f, TRIBO_SEPARATOR_Q_FLIGHT_TIME);
    cr_expect(err_of("work limit: flight time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-7);
    cr_expect(err_of("work limit: x", get(s, TRIBO_SEPARATOR_Q_X_END), get(f, TRIBO_SEPARATOR_Q_X_END), 0.1) < 1e-7);
    tribo_separator_free(s);
    tribo_separator_free(f);
}

Test(separator, a_saved_state_continues_bit_for_bit)
{
    tribo_separator_scene sc = scene_of("semi_major_axis=50e-6 epsilon=1");
    tribo_separator *a = make(&sc);
    cr_assert_eq(advance(a, 0.05), TRIBO_OK);
    release(a, 0.2, 0.01, 3e-6);
    cr_assert_eq(advance(a, 0.3), TRIBO_OK);
    const size_t n = tribo_separator_state_size(a);
    unsigned char *bytes = malloc(n), *again = malloc(n);
    cr_assert_eq(tribo_separator_state_save(a, bytes, n), TRIBO_OK);

    tribo_separator *b = make(&sc);
    /* refused states change nothing: truncated, another scene's, a motion not finite */
    cr_expect_eq(tribo_separator_state_load(b, bytes, n - 1), TRIBO_ERR_STATE);
    tribo_separator_scene other = sc;
    other.voltage = 1;
    tribo_separator *c = make(&other);
    cr_expect_eq(tribo_separator_state_load(c, bytes, n), TRIBO_ERR_STATE);
    tribo_separator_free(c);
    unsigned char *bad = malloc(n);
    memcpy(bad, bytes, n);
    const double nan = NAN;
    memcpy(bad + n - 8 - 6 * 8, &nan, 8); /* x */
    cr_expect_eq(tribo_separator_state_load(b, bad, n), TRIBO_ERR_STATE);
    cr_expect_eq(get(b, TRIBO_SEPARATOR_Q_RELEASED_OUT), 0.0);
    free(bad);

    cr_assert_eq(tribo_separator_state_load(b, bytes, n), TRIBO_OK, "%s", tribo_separator_last_error(b));
    cr_assert_eq(tribo_separator_state_save(b, again, n), TRIBO_OK);
    cr_expect_eq(memcmp(bytes, again, n), 0);
    cr_assert_eq(advance(a, 10), TRIBO_ENDED);
    cr_assert_eq(advance(b, 10), TRIBO_ENDED);
    for (int q = 0; q < TRIBO_SEPARATOR_Q_COUNT; q++)
        cr_expect_eq(get(a, q), get(b, q), "%s", tribo_separator_quantity_name(q));
    free(bytes);
    free(again);
    tribo_separator_free(a);
    tribo_separator_free(b);
}

Test(separator, communication_steps_move_the_result_within_the_tolerance)
{
    /* every advance restarts CVODE: 1 ms steps against one advance */
    tribo_separator_scene sc = scene_of("semi_major_axis=50e-6 epsilon=1");
    tribo_separator *one = make(&sc), *many = make(&sc);
    release(one, 0.3, 0, 2e-6);
    release(many, 0.3, 0, 2e-6);
    cr_assert_eq(advance(one, 100), TRIBO_ENDED);
    int k = 1;
    while (advance(many, 1e-3 * k) == TRIBO_OK)
        k++;
    const double tf = get(one, TRIBO_SEPARATOR_Q_FLIGHT_TIME);
    /* measured 6e-10 relative; margin 15 */
    cr_expect(err_of("steps: flight time", get(many, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-8);
    cr_expect(err_of("steps: x", get(many, TRIBO_SEPARATOR_Q_X_END), get(one, TRIBO_SEPARATOR_Q_X_END), 0.1) < 1e-8);
    tribo_separator_free(one);
    tribo_separator_free(many);
}

Test(separator, the_equivalent_sphere_has_the_spheroid_s_volume)
{
    tribo_separator_scene sc = scene_of("semi_major_axis=1e-3 epsilon=0.5 density=1000");
    tribo_separator *s = make(&sc);
    const tribo_separator_derived *d = tribo_separator_get_derived(s);
    const double b = 0.5e-3, volume = 4.0 / 3.0 * M_PI * 1e-3 * b * b;
    cr_expect(fabs(M_PI * pow(d->diameter, 3) / 6 - volume) < 1e-14 * volume);
    cr_expect(fabs(d->mass - 1000 * volume) < 1e-14 * d->mass);
    cr_expect(fabs(d->relaxation_time - d->mass / (3 * M_PI * 1.81e-5 * d->diameter)) < 1e-15);
    tribo_separator_free(s);
}

/* Every parameter at both ends of its range (an open end: the nearest value inside) and
   just inside them (the next double, or integer: air_viscosity = 5e-324 overflowed the
   relaxation time and the Reynolds number), with the inputs at theirs: refused only for a
   combination, naming it; otherwise finite outputs at a cost bounded by the work limit, as
   the FMUs' importers need. */
static void run_hostile(tribo_separator_scene sc, const char *what)
{
    char err[512];
    tribo_separator *s = tribo_separator_create(&sc, err, sizeof err);
    if (!s) {
        cr_expect(strstr(err, "x_entry") || strstr(err, "semi_major_axis"), "%s: %s", what, err);
        return;
    }
    const double ends[][3] = {{1e3, 1e3, 1}, {-1e3, -1e3, -1}, {0, 0, 0}};
    for (size_t e = 0; e < sizeof ends / sizeof ends[0]; e++) {
        tribo_separator *r = tribo_separator_create(&sc, err, sizeof err);
        release(r, ends[e][0], ends[e][1], ends[e][2]);
        const tribo_status st = tribo_separator_advance(r, 10.0);
        cr_expect(st == TRIBO_OK || st == TRIBO_ENDED || st == TRIBO_INCOMPLETE, "%s: %d %s", what,
                  st, tribo_separator_last_error(r));
        for (int q = 0; q < TRIBO_SEPARATOR_Q_COUNT; q++)
            cr_expect(isfinite(get(r, q)), "%s: %s = %g", what, tribo_separator_quantity_name(q), get(r, q));
        tribo_separator_free(r);
    }
    tribo_separator_free(s);
}

Test(separator, every_parameter_at_the_ends_of_its_range_gives_finite_outputs)
{
    size_t n;
    const tribo_param_info *p = tribo_separator_param_table(&n);
    for (size_t i = 0; i < n; i++) {
        if (!strcmp(p[i].name, "work_limit"))
            continue; /* its top is 2^31 steps: the bound's own size, not a case */
        const double lo = p[i].min_inclusive ? p[i].min : nextafter(p[i].min, INFINITY);
        const double hi = p[i].max_inclusive ? p[i].max : nextafter(p[i].max, -INFINITY);
        const int real = p[i].type == TRIBO_TYPE_REAL;
        const double at[4] = {lo, real ? nextafter(lo, hi) : fmin(lo + 1, hi),
                              real ? nextafter(hi, lo) : fmax(hi - 1, lo), hi};
        for (int k = 0; k < 4; k++) {
            tribo_separator_scene sc = scene_of("work_limit=2000");
            tribo_param_write(&sc, &p[i], at[k]);
            char what[96];
            snprintf(what, sizeof what, "%s = %g", p[i].name, at[k]);
            run_hostile(sc, what);
        }
    }
}

Test(separator, an_advance_too_short_for_cvode_moves_the_grain_by_a_taylor_step)
{
    /* an importer's steps of 1e-300 s, or of one rounding of the time: CVODE refuses both */
    tribo_separator_scene sc = scene_of("");
    tribo_separator *s = make(&sc), *plain = make(&sc);
    release(s, 0.3, 0.1, 2e-6);
    release(plain, 0.3, 0.1, 2e-6);
    cr_assert_eq(advance(s, 1e-300), TRIBO_OK, "%s", tribo_separator_last_error(s));
    cr_assert_eq(advance(s, 0.1), TRIBO_OK);
    cr_assert_eq(advance(s, nextafter(0.1, 1.0)), TRIBO_OK, "%s", tribo_separator_last_error(s));
    cr_assert_eq(advance(s, nextafter(nextafter(0.1, 1.0), 1.0) + 1e-17), TRIBO_OK);
    cr_assert_eq(advance(plain, 0.1), TRIBO_OK);
    cr_assert_eq(advance(s, 100), TRIBO_ENDED);
    cr_assert_eq(advance(plain, 100), TRIBO_ENDED);
    /* the same run, to the integration's tolerance: one restart more */
    const double tf = get(plain, TRIBO_SEPARATOR_Q_FLIGHT_TIME);
    cr_expect(err_of("flight time", get(s, TRIBO_SEPARATOR_Q_FLIGHT_TIME), tf, tf) < 1e-7);
    cr_expect(err_of("x", get(s, TRIBO_SEPARATOR_Q_X_END), get(plain, TRIBO_SEPARATOR_Q_X_END), 0.1) <
              1e-7);
    tribo_separator_free(s);
    tribo_separator_free(plain);
}
