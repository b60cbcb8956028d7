/* geometry.h: the ellipse's contact geometry (model.md §2) and its boundary arc length (model.md §5). */
#ifndef TRIBO_GEOMETRY_H
#define TRIBO_GEOMETRY_H

#include <math.h>
#include <stddef.h>

/* Where the lowest point of the ellipse is, for orientation phi (model.md §2). */
typedef struct tribo_pose {
    double sin_phi, cos_phi;
    double h;  /* depth of the lowest point below the centre, sqrt(Myy) */
    double cx; /* horizontal offset of the lowest point, -Mxy / h; dh/dphi = -cx */
} tribo_pose;

static inline void tribo_pose_at(double eps2, double phi, tribo_pose *g)
{
    const double s = sin(phi), c = cos(phi);
    const double myy = s * s + eps2 * c * c;
    const double mxy = (1.0 - eps2) * s * c;
    g->sin_phi = s;
    g->cos_phi = c;
    g->h = sqrt(myy);
    g->cx = -mxy / g->h;
}

/* kappa = dcx/dphi = (cx^2 - (1 - eps^2) cos 2phi) / h (model.md §3): how fast the contact
   point runs along the plate as the particle turns; kappa Omega^2 is the normal acceleration
   of the contact point that rotation alone gives (h'' = -kappa). */
static inline double tribo_pose_kappa(double eps2, const tribo_pose *g)
{
    const double cos_2phi = g->cos_phi * g->cos_phi - g->sin_phi * g->sin_phi;
    return (g->cx * g->cx - (1.0 - eps2) * cos_2phi) / g->h;
}

/* dkappa/dphi = cx (3 kappa - 4 h) / h, using (1 - eps^2) sin 2phi = -2 cx h. */
static inline double tribo_pose_kappa_slope(const tribo_pose *g, double kappa)
{
    return g->cx * (3.0 * kappa - 4.0 * g->h) / g->h;
}

/* Radius of curvature at the lowest point, rho_c = eps^2 / h^3 (model.md §2). */
static inline double tribo_contact_curvature_radius(double eps2, double h)
{
    return eps2 / (h * h * h);
}

/* Body-frame parametric angle t in [0, 2 pi) of the lowest point: the minimum over t
   of the height sin(phi) cos(t) + eps cos(phi) sin(t) of the point (cos t, eps sin t). */
static inline double tribo_contact_parameter(double eps, const tribo_pose *g)
{
    double t = atan2(-eps * g->cos_phi, -g->sin_phi);
    return t < 0.0 ? t + 2.0 * M_PI : t;
}

/* Speed |d(cos t, eps sin t)/dt| of the boundary's parametrisation. */
static inline double tribo_boundary_speed(double eps2, double t)
{
    const double s = sin(t), c = cos(t);
    return sqrt(s * s + eps2 * c * c);
}

/* Arc length s(t) of the body-frame boundary from t = 0, tabulated on a uniform grid
   in t with the exact speed at each node, so that a cubic Hermite interpolation gives
   s(t) to ~1e-10 of the perimeter at a cost of a few flops (the charging models look
   up the contact centre every step). */
typedef struct tribo_arclength {
    double eps;
    double perimeter;
    size_t n_intervals;
    double dt_grid;   /* 2 pi / n_intervals */
    double *s;        /* s at the n_intervals + 1 nodes      */
    double *speed;    /* ds/dt at the nodes                  */
} tribo_arclength;

/* Build the table; returns 0 on success, -1 if out of memory. The table is a function of
   eps alone, bit for bit: where `like` (NULL for none) holds the table of the same eps, it is
   copied, not computed again (computing it is most of the work of creating an instance). */
int tribo_arclength_init(tribo_arclength *a, double eps, const tribo_arclength *like);
void tribo_arclength_free(tribo_arclength *a);

/* s(t) for t in [0, 2 pi]. */
static inline double tribo_arclength_at(const tribo_arclength *a, double t)
{
    double x = t / a->dt_grid;
    size_t k = (size_t)x;
    if (k >= a->n_intervals)
        k = a->n_intervals - 1;
    const double u = x - (double)k, h = a->dt_grid;
    const double s0 = a->s[k], s1 = a->s[k + 1];
    const double d0 = a->speed[k] * h, d1 = a->speed[k + 1] * h;
    /* cubic Hermite on [0, 1] */
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * s0 + (u3 - 2 * u2 + u) * d0 + (-2 * u3 + 3 * u2) * s1 +
           (u3 - u2) * d1;
}

/* The parametric angle t in [0, 2 pi] at arc length s in [0, perimeter]
   (inverse of tribo_arclength_at, to ~1e-13). */
double tribo_arclength_parameter(const tribo_arclength *a, double s);

/* The perimeter of the ellipse (cos t, eps sin t) by adaptive Gauss-Legendre quadrature. */
double tribo_ellipse_perimeter(double eps);

/* The surface area of the prolate spheroid of semi-axes 1, eps, eps (model.md §8c), in units
   of a^2: 2 pi eps^2 + 2 pi eps asin(e) / e, e = sqrt(1 - eps^2) (4 pi for a sphere). */
double tribo_spheroid_area(double eps);

/* Arc length between parametric angles t0 < t1, by adaptive quadrature (reference
   value for tests and table building). */
double tribo_arc_between(double eps, double t0, double t1);

#endif
