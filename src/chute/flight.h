/* flight.h: the motion between contacts in closed form (model.md §4 without a contact force):
   the centre's uniform acceleration under the steady loads (gravity and the inputs), a free
   rotation at constant spin; and where a flight ends: the lowest point reaching the plate, or
   the centre passing the end of the chute (model.md §9).

   An event-driven integrator takes a flight as one piece: exact (no integration error, so
   the clearance of the lowest point G = Y - h(phi) is exact to rounding however the particle
   spins) and, where the particle bounces or tumbles, far cheaper than integrating it. */
#ifndef TRIBO_FLIGHT_H
#define TRIBO_FLIGHT_H

#include "dynamics.h"

/* A flight from the state y0 at time t0 (in flight: no contact force). */
typedef struct tribo_flight {
    double t0;
    double y0[TRIBO_NSTATE_MAX];
    int n;            /* components of the state in use */
    double a_t, a_n;  /* the centre's acceleration along and normal to the plate under the
                         steady loads (gravity and the inputs) */
    /* on a vibrating plate (model.md §9b) the inertial force adds a sinusoid: its phase at t0 */
    double vib_sin0, vib_cos0;
} tribo_flight;

void tribo_flight_start(tribo_flight *f, const tribo_dyn_params *p, double t0, const double *y0, int n);

/* The state at time t (every component: the motion, G, the work done by the inputs and by the
   plate's inertial force; the contact's and the charges' do not change in flight). */
void tribo_flight_state(const tribo_flight *f, const tribo_dyn_params *p, double t, double *y);

/* How a flight's piece ends. */
typedef enum {
    TRIBO_FLIGHT_GOES_ON, /* at the piece's end, with neither below */
    TRIBO_FLIGHT_CONTACT, /* the lowest point reaches the plate: approaching it, or at rest on
                             it and pressed in (a touch that moves away is not a contact,
                             model.md §3b) */
    TRIBO_FLIGHT_EXIT     /* the centre passes X = chute_length */
} tribo_flight_end;

/* The end of the flight's piece from t_from (>= f->t0) to at most t_max: the first contact
   or exit, else t_max, or earlier where `budget` evaluations of the clearance have not
   reached either (the piece then ends there, TRIBO_FLIGHT_GOES_ON, and the next one goes on
   from it). Returns the piece's end time; *why says which; *used receives the evaluations
   spent. The search cannot miss a contact: between evaluations it steps only as far as the
   clearance's second derivative, bounded by (1 - eps^2)/eps Omega^2 + Gamma cos(beta) -
   F_N (+ Lambda_v |sin psi_v| on a vibrating plate, model.md §9b), allows the lowest point to
   stay off the plate; on a vibrating plate the exit too is found so, its bound on the centre's
   acceleration along the plate Gamma sin(beta) + F_T + Lambda_v |cos psi_v|. */
double tribo_flight_end_of(const tribo_flight *f, const tribo_dyn_params *p, double t_from,
                           double t_max, long budget, tribo_flight_end *why, long *used);

#endif
