/* charging.h: the two charge models over the particle's boundary segments (MODEL §5). */
#ifndef TRIBO_CHARGING_H
#define TRIBO_CHARGING_H

#include "geometry.h"

/* Charging parameters (tunable between steps). */
typedef struct tribo_charge_params {
    double tau0, tau_r, Sigma0, eta;
} tribo_charge_params;

/* The contact held over an interval of the motion: which arc of the boundary touches
   the plate and for how long. Both models are exact given these (MODEL §5): the static
   one is linear with constant coefficients, the sliding one is taken with Sigma_s
   linear over the interval. */
typedef struct tribo_contact_sample {
    double duration;
    int in_contact;
    double s_centre;      /* arc-length coordinate of the contact centre */
    double half_width;    /* Sc = sqrt(rho_c delta_y), MODEL §5 eq. 4 */
    double work_begin, work_end; /* omega at both ends (sliding model) */
    /* Sigma_s over the sample: at its start, middle and end (quadratic in time; the
       middle is the mean of the ends where Sigma_s is taken linear) */
    double Sigma_s_begin, Sigma_s_mid, Sigma_s_end;
} tribo_contact_sample;

/* Exponentials of the last durations seen, so that a run at a fixed step costs no
   transcendental call per step. */
typedef struct tribo_decay_cache {
    double duration, tau, decay, one_minus_decay, phi1;
    double zf1, zf2; /* z F_k(z), F_k(z) = int_0^1 v^k e^{-z v} dv, z = duration / tau */
} tribo_decay_cache;

typedef struct tribo_charging {
    int with_static, with_sliding;
    int n;                    /* segments */
    double segments_per_length; /* n / perimeter */
    tribo_arclength arc;
    double *q;                /* static q_i = sigma_i / sigma_0 (NULL without the model)   */
    double *sigma;            /* sliding Sigma_i (NULL without the model)                  */
    tribo_decay_cache charge_cache, relax_cache;
} tribo_charging;

/* Allocate for the models wanted; returns 0, or -1 if out of memory. */
int tribo_charging_init(tribo_charging *c, double eps, int n, int with_static, int with_sliding);
void tribo_charging_free(tribo_charging *c);
/* All segment charges to 0 (MODEL §7). */
void tribo_charging_reset(tribo_charging *c);

/* Describe the contact at orientation pose with indentation delta_y held for
   `duration` (the segments under [s_c - Sc, s_c + Sc] charge, MODEL §5). */
void tribo_charging_sample(const tribo_charging *c, const tribo_pose *pose, double delta_y,
                           double duration, double work_begin, double work_end,
                           tribo_contact_sample *sample);

/* Advance Sigma_s over the sample (MODEL §5b) and record it in the sample (linear). */
void tribo_charging_saturation(tribo_charging *c, const tribo_charge_params *p,
                               double *Sigma_s, tribo_contact_sample *sample);

/* Charge the segments in contact over the sample (MODEL §5a, §5b). q / sigma may be the
   committed arrays or a copy; a NULL array is skipped. */
void tribo_charging_segments(tribo_charging *c, const tribo_charge_params *p,
                             const tribo_contact_sample *sample, double *q, double *sigma);

/* The contact along an interval of the motion, as an integrator with dense output sees it:
   at time t, the arc-length coordinate of the contact centre (in [0, perimeter)), the
   half-width Sc, the rate of frictional work d omega / dtau (0 if not wanted), and the
   speed of the centre along the boundary. */
typedef struct tribo_contact_probe {
    void (*at)(void *ctx, double t, double *s_centre, double *half_width, double *work_rate,
               double *centre_speed);
    void *ctx;
} tribo_contact_probe;

/* Receives the samples of a sweep; returns 0, or non-zero to stop it. */
typedef int (*tribo_sample_sink)(void *ctx, const tribo_contact_sample *sample);

/* Sweep a contact that lasts over [a, b]: cut it where an edge of the contact crosses a
   segment boundary (located on the probe to ~1e-10 of the interval), so that every
   sample holds a fixed set of segments and the charge models are exact given the probe
   (MODEL §5). With the sliding model, omega is integrated along the way (adaptive
   Simpson to rtol of the work and atol per unit time) and Sigma_s follows it. Advances
   *work and *Sigma_s; each sample goes to the sink. Returns 0, or the sink's non-zero
   value. */
int tribo_charging_sweep(tribo_charging *c, const tribo_charge_params *p,
                         const tribo_contact_probe *probe, double a, double b, double rtol,
                         double atol, double *work, double *Sigma_s, tribo_sample_sink sink,
                         void *sink_ctx);

/* Mean of an array of n values. */
double tribo_charging_mean(const double *v, int n);

#endif
