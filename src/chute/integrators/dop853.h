/* dop853.h: Dormand and Prince's explicit Runge-Kutta pair of order 8(5,3) with its dense
   output of order 7 (DOP853: Hairer, Norsett & Wanner, Solving Ordinary Differential
   Equations I, 2nd ed., Springer 1993, §II.5 and §II.10; the coefficients of Hairer's
   dop853.f). A one-step method: it starts anywhere at no cost beyond its first step's
   estimate, where a multistep method restarts at order 1 (integrator_cvode.c takes a vibrating
   plate's contact phases with it, docs/integrators.md). Steps one at a time; the caller
   locates its events on the dense output. */
#ifndef TRIBO_DOP853_H
#define TRIBO_DOP853_H

/* The most components it integrates. */
#define TRIBO_DOP853_MAX 32

/* The right-hand side dy/dt = f(t, y). */
typedef void (*tribo_rk_rhs)(void *ctx, double t, const double *y, double *dydt);

typedef struct tribo_dop853 {
    tribo_rk_rhs rhs;
    void *ctx;
    int n;
    double rtol;
    const double *atol;        /* per component, the caller's (a huge one leaves it out) */
    double t, h;               /* the point reached, and the step to try from it */
    double y[TRIBO_DOP853_MAX], f[TRIBO_DOP853_MAX];
    /* the last step, from t_old over h_old, and its dense output's coefficients */
    double t_old, h_old;
    double y_old[TRIBO_DOP853_MAX];
    double dense[7][TRIBO_DOP853_MAX];
    double k[16][TRIBO_DOP853_MAX]; /* the stages */
} tribo_dop853;

/* Start at (t, y): the derivative there and a first step (Hairer's estimate, at most hmax).
   The same start gives the same steps: the method holds no other state. */
void tribo_dop853_start(tribo_dop853 *s, tribo_rk_rhs rhs, void *ctx, int n, double t,
                        const double *y, double rtol, const double *atol, double hmax);

/* One accepted step of at most hmax, its error within the tolerances, and its dense output.
   Returns 0, or -1 where the step it needs falls below the rounding of t (s unchanged). */
int tribo_dop853_step(tribo_dop853 *s, double hmax);

/* Component i of the last step's dense output at t (within [t_old, t_old + h_old]). */
static inline double tribo_dop853_dense(const tribo_dop853 *s, double t, int i)
{
    const double x = (t - s->t_old) / s->h_old, w = 1.0 - x;
    const double(*d)[TRIBO_DOP853_MAX] = s->dense;
    return s->y_old[i] +
           x * (d[0][i] + w * (d[1][i] + x * (d[2][i] + w * (d[3][i] + x * (d[4][i] + w * (d[5][i] + x * d[6][i]))))));
}

#endif
