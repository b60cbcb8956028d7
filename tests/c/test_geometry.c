/* Geometry of model.md §2 and the equal-arc segments of model.md §5. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geometry.h"

static const double EPSILONS[] = {0.01, 0.1, 0.3, 0.5, 0.9, 1.0};
#define N_EPS (sizeof EPSILONS / sizeof EPSILONS[0])

Test(geometry, closed_forms_lying_flat_and_on_a_tip)
{
    for (size_t i = 0; i < N_EPS; i++) {
        const double e = EPSILONS[i], e2 = e * e;
        tribo_pose g;
        tribo_pose_at(e2, 0.0, &g);
        cr_expect_float_eq(g.h, e, 1e-15, "h(0) = eps for eps = %g", e);
        cr_expect_float_eq(g.cx, 0.0, 1e-15);
        cr_expect_float_eq(tribo_contact_curvature_radius(e2, g.h), 1.0 / e, 1e-12 / e,
                           "rho_c(0) = 1/eps for eps = %g", e);
        tribo_pose_at(e2, 0.5 * M_PI, &g);
        cr_expect_float_eq(g.h, 1.0, 1e-15, "h(pi/2) = 1 for eps = %g", e);
        cr_expect(fabs(g.cx) < 1e-15);
        cr_expect_float_eq(tribo_contact_curvature_radius(e2, g.h), e2, 1e-15,
                           "rho_c(pi/2) = eps^2 for eps = %g", e);
    }
}

Test(geometry, dh_dphi_is_minus_cx)
{
    const double step = 1e-6;
    for (size_t i = 0; i < N_EPS; i++) {
        const double e2 = EPSILONS[i] * EPSILONS[i];
        for (double phi = -3.0; phi < 3.2; phi += 0.37) {
            tribo_pose a, b, g;
            tribo_pose_at(e2, phi + step, &a);
            tribo_pose_at(e2, phi - step, &b);
            tribo_pose_at(e2, phi, &g);
            const double dh = (a.h - b.h) / (2 * step);
            cr_expect(fabs(dh + g.cx) < 1e-8, "eps = %g phi = %g: dh/dphi = %.12g, -cx = %.12g",
                      EPSILONS[i], phi, dh, -g.cx);
        }
    }
}

/* The lowest point: the body point at the contact parameter, rotated by phi, sits at
   (cx, -h), and no other point of the boundary is lower. */
Test(geometry, contact_parameter_is_the_lowest_point)
{
    for (size_t i = 0; i < N_EPS; i++) {
        const double e = EPSILONS[i];
        for (double phi = -2.9; phi < 3.2; phi += 0.23) {
            tribo_pose g;
            tribo_pose_at(e * e, phi, &g);
            const double t = tribo_contact_parameter(e, &g);
            cr_assert(t >= 0.0 && t < 2 * M_PI);
            const double x = cos(phi) * cos(t) - sin(phi) * e * sin(t);
            const double y = sin(phi) * cos(t) + cos(phi) * e * sin(t);
            cr_expect(fabs(y + g.h) < 1e-14 && fabs(x - g.cx) < 1e-14,
                      "eps = %g phi = %g: contact at (%g, %g), expected (%g, %g)", e, phi, x, y,
                      g.cx, -g.h);
            for (int k = 0; k < 720; k++) {
                const double u = 2 * M_PI * k / 720;
                cr_assert(sin(phi) * cos(u) + cos(phi) * e * sin(u) >= y - 1e-15);
            }
        }
    }
}

/* Gauss-Kummer series: P = pi (a + b) sum_n binom(1/2, n)^2 h^n, h = ((a-b)/(a+b))^2. */
static double perimeter_series(double eps)
{
    const double h = pow((1 - eps) / (1 + eps), 2);
    double term = 1.0, sum = 1.0, coef = 1.0;
    for (int n = 1; n < 200; n++) {
        coef *= (0.5 - (n - 1)) / n; /* binom(1/2, n) */
        term = coef * coef * pow(h, n);
        sum += term;
        if (fabs(term) < 1e-18)
            break;
    }
    return M_PI * (1 + eps) * sum;
}

Test(geometry, perimeter)
{
    cr_expect(fabs(tribo_ellipse_perimeter(1.0) - 2 * M_PI) < 1e-13, "circle: %.17g",
              tribo_ellipse_perimeter(1.0));
    const double p = tribo_ellipse_perimeter(0.5), ref = perimeter_series(0.5);
    cr_expect(fabs(p - ref) < 1e-9, "eps = 0.5: %.17g, series %.17g", p, ref);
    /* the series converges slowly as eps -> 0, but still far below 1e-9 at 0.1 */
    cr_expect(fabs(tribo_ellipse_perimeter(0.1) - perimeter_series(0.1)) < 1e-9);
}

/* Independent of the library's quadrature: composite Simpson, many points. */
static double simpson_arc(double eps, double a, double b, int n)
{
    const double h = (b - a) / n;
    double s = tribo_boundary_speed(eps * eps, a) + tribo_boundary_speed(eps * eps, b);
    for (int i = 1; i < n; i++)
        s += (i % 2 ? 4.0 : 2.0) * tribo_boundary_speed(eps * eps, a + i * h);
    return s * h / 3.0;
}

Test(geometry, segments_have_equal_arc_length)
{
    const double eps_list[] = {0.05, 0.3, 1.0};
    const int n_seg = 64;
    for (int e = 0; e < 3; e++) {
        tribo_arclength arc;
        cr_assert_eq(tribo_arclength_init(&arc, eps_list[e], NULL), 0);
        const double len = arc.perimeter / n_seg;
        double t_prev = 0.0, total = 0.0;
        for (int k = 1; k <= n_seg; k++) {
            const double t = tribo_arclength_parameter(&arc, k * len);
            const double piece = simpson_arc(eps_list[e], t_prev, t, 20000);
            total += piece;
            cr_expect(fabs(piece - len) < 1e-10 * arc.perimeter,
                      "eps = %g segment %d: arc %.15g, expected %.15g", eps_list[e], k, piece,
                      len);
            t_prev = t;
        }
        cr_expect(fabs(total - arc.perimeter) < 1e-10 * arc.perimeter);
        tribo_arclength_free(&arc);
    }
}

/* The table's interpolation against direct quadrature, for a needle and a round shape. */
Test(geometry, arclength_table_interpolation)
{
    const double eps_list[] = {0.01, 0.5};
    for (int e = 0; e < 2; e++) {
        tribo_arclength arc;
        cr_assert_eq(tribo_arclength_init(&arc, eps_list[e], NULL), 0);
        for (double t = 0.0; t <= 2 * M_PI; t += 0.0137) {
            const double exact = tribo_arc_between(eps_list[e], 0.0, t);
            cr_expect(fabs(tribo_arclength_at(&arc, t) - exact) < 1e-10,
                      "eps = %g t = %g: %.15g vs %.15g", eps_list[e], t,
                      tribo_arclength_at(&arc, t), exact);
        }
        tribo_arclength_free(&arc);
    }
}

/* A table made like another of the same roundness is that table, bit for bit; like one of
   another roundness, it is its own (computed, as without). */
Test(geometry, a_table_made_like_another_is_the_one_computed)
{
    tribo_arclength computed, other, copied, not_copied;
    cr_assert_eq(tribo_arclength_init(&computed, 0.37, NULL), 0);
    cr_assert_eq(tribo_arclength_init(&other, 0.71, NULL), 0);
    cr_assert_eq(tribo_arclength_init(&copied, 0.37, &computed), 0);
    cr_assert_eq(tribo_arclength_init(&not_copied, 0.37, &other), 0);
    const size_t bytes = (computed.n_intervals + 1) * sizeof(double);
    for (int k = 0; k < 2; k++) {
        const tribo_arclength *a = k ? &not_copied : &copied;
        cr_expect(a->s != computed.s && a->speed != computed.speed, "its own arrays");
        cr_expect_eq(a->n_intervals, computed.n_intervals);
        cr_expect(a->perimeter == computed.perimeter && a->dt_grid == computed.dt_grid &&
                  a->eps == computed.eps);
        cr_expect_eq(memcmp(a->s, computed.s, bytes), 0);
        cr_expect_eq(memcmp(a->speed, computed.speed, bytes), 0);
    }
    cr_expect(other.perimeter != computed.perimeter);
    tribo_arclength_free(&computed);
    tribo_arclength_free(&other);
    tribo_arclength_free(&copied);
    tribo_arclength_free(&not_copied);
}
