/* The contact force law of model.md §3, unit by unit and inside the fixed-step integrator. */
#include <criterion/criterion.h>
#include <math.h>

#include "contact.h"
#include "dynamics.h"
#include "support.h"
#include "tribo.h"

static const tribo_force_law LAW = {.contact = TRIBO_CONTACT_BY_GEOMETRY,
                                    .normal = TRIBO_NORMAL_REGULARISED,
                                    .tangent = TRIBO_TANGENT_CLAMP};

static tribo_dyn_params params(double eps, double mu, double nu)
{
    tribo_dyn_params p = {0};
    p.eps = eps;
    p.eps2 = eps * eps;
    p.mu = mu;
    p.nu = nu;
    p.Gamma = 1e-3;
    p.g_t = p.g_n = 1e-3 * sqrt(0.5);
    p.inv_inertia = 4.0 / (1.0 + eps * eps);
    p.v_reg = 1e-6;
    p.chute_length = INFINITY;
    return p;
}

/* A state at orientation phi whose lowest point is `depth` below the plate. */
static void state(double *y, double eps, double phi, double depth, double U, double V,
                  double Om, double dx)
{
    tribo_pose g;
    tribo_pose_at(eps * eps, phi, &g);
    for (int i = 0; i < TRIBO_NSTATE_MAX; i++)
        y[i] = 0.0;
    y[TRIBO_IY] = g.h - depth;
    y[TRIBO_IGAP] = -depth;
    y[TRIBO_IPHI] = phi;
    y[TRIBO_IU] = U;
    y[TRIBO_IV] = V;
    y[TRIBO_IOMEGA] = Om;
    y[TRIBO_IDX] = dx;
}

Test(forces, flight_has_no_contact_force)
{
    tribo_dyn_params p = params(0.5, 0.3, 0.2);
    double y[TRIBO_NSTATE_MAX], dydt[TRIBO_NSTATE_MAX];
    tribo_contact_eval ev;
    state(y, 0.5, 0.4, -1e-3, 0.1, -0.1, 0.3, 0.05);
    tribo_dynamics_rhs(&p, &LAW, y, dydt, &ev);
    cr_expect_eq(ev.in_contact, 0);
    cr_expect_eq(ev.psi_n, 0.0);
    cr_expect_eq(ev.psi_t, 0.0);
    cr_expect_float_eq(dydt[TRIBO_IU], p.g_t, 1e-18);
    cr_expect_float_eq(dydt[TRIBO_IV], -p.g_n, 1e-18);
    cr_expect_eq(dydt[TRIBO_IOMEGA], 0.0);
    cr_expect_eq(dydt[TRIBO_IDX], 0.0, "the stretch does not move in flight");
}

Test(forces, normal_force_opposes_the_normal_velocity)
{
    const double dy = 0.01, nu = 0.2;
    tribo_dyn_params p = params(0.5, 0.3, nu);
    double y[TRIBO_NSTATE_MAX];
    tribo_contact_eval ev;
    state(y, 0.5, 0.0, dy, 0.0, -0.1, 0.0, 0.0); /* moving into the plate */
    tribo_contact_at(&p, &LAW, y, &ev);
    cr_expect_float_eq(ev.delta_y, dy, 1e-15);
    cr_expect_float_eq(ev.psi_n, dy * (1 + nu), 1e-15);
    state(y, 0.5, 0.0, dy, 0.0, +0.1, 0.0, 0.0); /* moving out */
    tribo_contact_at(&p, &LAW, y, &ev);
    cr_expect_float_eq(ev.psi_n, dy * (1 - nu), 1e-15);
    state(y, 0.5, 0.0, dy, 0.0, 0.0, 0.0, 0.0); /* regularised sign at V = 0 (model.md §3) */
    tribo_contact_at(&p, &LAW, y, &ev);
    cr_expect_float_eq(ev.psi_n, dy, 1e-15);
    /* no adhesion: nu > 1 moving out gives 0, not a pull */
    p.nu = 3.0;
    state(y, 0.5, 0.0, dy, 0.0, +0.1, 0.0, 0.0);
    tribo_contact_at(&p, &LAW, y, &ev);
    cr_expect_eq(ev.psi_n, 0.0);
}

/* The dashpot takes the contact point's normal velocity vn = V + cx Omega (model.md §3): a
   centre at rest whose contact point moves into the plate by rotation is damped as pressing
   in; with damping_point = 1 the centre's V = 0 gives the spring alone. */
Test(forces, the_dashpot_takes_the_contact_points_velocity)
{
    const double dy = 0.01, nu = 0.2, phi = 0.4;
    tribo_dyn_params p = params(0.5, 0.3, nu);
    double y[TRIBO_NSTATE_MAX];
    tribo_contact_eval ev;
    state(y, 0.5, phi, dy, 0.0, 0.0, 0.1, 0.0);
    tribo_contact_at(&p, &LAW, y, &ev);
    const double vn = 0.1 * ev.pose.cx;
    cr_assert(fabs(vn) > 1e3 * p.v_reg, "vn = %g", vn);
    cr_expect_float_eq(ev.psi_n, dy * (1.0 - nu * (vn > 0.0 ? 1.0 : -1.0)), 1e-15,
                       "vn = %g: Psi_N = %g", vn, ev.psi_n);
    p.damping_point = TRIBO_DAMPING_CENTRE;
    tribo_contact_at(&p, &LAW, y, &ev);
    cr_expect_float_eq(ev.psi_n, dy, 1e-15, "the centre's V = 0: Psi_N = %g", ev.psi_n);
}

Test(forces, stick_and_slip_branches)
{
    const double dy = 0.01, mu = 0.3;
    tribo_dyn_params p = params(0.5, mu, 0.0);
    double y[TRIBO_NSTATE_MAX], dydt[TRIBO_NSTATE_MAX];
    tribo_contact_eval ev;
    /* stick: |dx| below mu Psi_N = 3e-3 */
    state(y, 0.5, 0.3, dy, 0.02, 0.0, 0.1, 1e-3);
    tribo_dynamics_rhs(&p, &LAW, y, dydt, &ev);
    cr_expect_float_eq(ev.psi_n, dy, 1e-15);
    cr_expect_float_eq(ev.psi_t, -1e-3, 1e-18, "stick: Psi_T = -dx");
    cr_expect_float_eq(ev.vs, 0.02 + ev.pose.h * 0.1, 1e-15, "vs = U + h Omega");
    cr_expect_float_eq(dydt[TRIBO_IDX], ev.vs, 1e-15, "the stretch follows vs");
    /* slip: the stretch beyond the limit, either way */
    state(y, 0.5, 0.3, dy, 0.02, 0.0, 0.1, 5e-3);
    tribo_dynamics_rhs(&p, &LAW, y, dydt, &ev);
    cr_expect_float_eq(ev.psi_t, -mu * dy, 1e-15, "slip: Psi_T = -mu Psi_N");
    state(y, 0.5, 0.3, dy, -0.02, 0.0, -0.1, -5e-3);
    tribo_dynamics_rhs(&p, &LAW, y, dydt, &ev);
    cr_expect_float_eq(ev.psi_t, mu * dy, 1e-15);
    /* equations of motion (model.md §4) */
    cr_expect_float_eq(dydt[TRIBO_IU], p.g_t + ev.psi_t, 1e-15);
    cr_expect_float_eq(dydt[TRIBO_IV], -p.g_n + ev.psi_n, 1e-15);
    cr_expect_float_eq(dydt[TRIBO_IOMEGA],
                       4.0 / 1.25 * (ev.pose.h * ev.psi_t + ev.pose.cx * ev.psi_n), 1e-15);
}

Test(forces, clamp)
{
    cr_expect_eq(tribo_clamp(0.5, 1.0), 0.5);
    cr_expect_eq(tribo_clamp(1.5, 1.0), 1.0);
    cr_expect_eq(tribo_clamp(-1.5, 1.0), -1.0);
    cr_expect_eq(tribo_clamp(0.3, 0.0), 0.0);
}

/* Inside the integrator: a disc spun hard and dropped onto the plate slips at once;
   through the whole run the stretch never exceeds the Coulomb limit, Psi_T sits on the
   limit whenever the contact slips, and the stretch is 0 throughout every flight. */
Test(forces, integrator_holds_the_coulomb_limit_and_resets_the_stretch)
{
    tribo_scene s = scene_of("epsilon=0.6 mu=0.3 nu=0.3 gap0=0.002 Omega0=4.0 drop_speed=0.05 dt=1e-3");
    no_charge_models(&s);
    s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    char err[256];
    tribo_model *m = tribo_create(&s, err, sizeof err);
    cr_assert(m, "%s", err);
    int slip_steps = 0, flight_steps = 0, contacts_regained = 0, was_in_contact = 0;
    for (int k = 1; k <= 60000; k++) {
        cr_assert_eq(tribo_advance(m, k * s.dt), TRIBO_OK);
        const double psi_n = tribo_get(m, TRIBO_QUANTITY_PSI_N), psi_t = tribo_get(m, TRIBO_QUANTITY_PSI_T);
        const double dx = tribo_get(m, TRIBO_QUANTITY_DELTA_X);
        const int in_contact = tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0;
        cr_assert(fabs(dx) <= s.mu * psi_n * (1 + 1e-12) + 1e-300, "k = %d: |dx| = %g > %g", k,
                  fabs(dx), s.mu * psi_n);
        cr_assert_eq(psi_t, -dx);
        if (tribo_get(m, TRIBO_QUANTITY_SLIPPING) != 0.0) {
            slip_steps++;
            cr_assert(fabs(fabs(psi_t) - s.mu * psi_n) <= 1e-15,
                      "slipping but |Psi_T| = %g, mu Psi_N = %g", fabs(psi_t), s.mu * psi_n);
        }
        if (!in_contact) {
            flight_steps++;
            cr_assert_eq(dx, 0.0, "stretch %g in flight at k = %d", dx, k);
        } else if (!was_in_contact) {
            /* first step of a new contact: the stretch built from 0 over at most one step */
            contacts_regained++;
            const double vs_bound = fabs(tribo_get(m, TRIBO_QUANTITY_U)) + 1.2 * fabs(tribo_get(m, TRIBO_QUANTITY_OMEGA));
            cr_assert(fabs(dx) <= vs_bound * s.dt * 1.01, "new contact starts at dx = %g", dx);
        }
        was_in_contact = in_contact;
    }
    cr_expect(slip_steps > 100, "the spun disc slipped for %d steps", slip_steps);
    cr_expect(flight_steps > 100 && contacts_regained >= 2,
              "it bounced: %d flight steps, %d contacts", flight_steps, contacts_regained);
    tribo_free(m);
}
