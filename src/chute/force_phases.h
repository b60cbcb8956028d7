/* force_phases.h: the force law of model.md §3 cut into smooth pieces (phases) and the
   switches between them, for an event-driven integrator: which functions of the state
   cross zero at a switch, which way, and the phase (with the resets of model.md §3) after it. */
#ifndef TRIBO_FORCE_PHASES_H
#define TRIBO_FORCE_PHASES_H

#include "dynamics.h"

/* The switch functions: contact made or lost (delta_y = 0); the normal sign's damped
   velocity = 0 (vn, or V for the centre dashpot), or the two edges of the normal lock's
   band; stick -> slip at either edge of the Coulomb limit, or slip -> stick; the factor
   A of a slipping normal lock reaching 0 (model.md §3); the spin Omega reaching 0, or the
   torque that holds the rolling lock reaching either edge of its band (§3c); and, in every
   phase, the centre
   passing the end of the chute, X = chute_length (model.md §9): not a switch of the force law
   but the end of the run, which the integrator handles (no phase follows it). Unused ones
   read 1. */
enum {
    TRIBO_SWITCH_CONTACT,
    TRIBO_SWITCH_NORMAL_A,
    TRIBO_SWITCH_NORMAL_B,
    TRIBO_SWITCH_TANGENT_A,
    TRIBO_SWITCH_TANGENT_B,
    TRIBO_SWITCH_LOCK_FACTOR,
    TRIBO_SWITCH_ROLL_A,
    TRIBO_SWITCH_ROLL_B,
    TRIBO_SWITCH_EXIT,
    TRIBO_N_SWITCHES
};

/* A phase is a force law whose set-valued parts are resolved one way: flight (contact
   OFF), or contact (ON) with the normal SIGN or LOCK, the tangent STICK or SLIP, and, with
   rolling resistance, the spin TURNING one way or in the rolling LOCK. */
extern const tribo_force_law TRIBO_PHASE_FLIGHT;

static inline int tribo_touching(const tribo_force_law *phase)
{
    return phase->contact == TRIBO_CONTACT_ON;
}

/* Whether a phase holds the grain at rest (model.md §3c): the normal lock, the rigid stick and
   the rolling lock at once, each of its holding forces within its band (a phase is entered only
   so). Under constant inputs nothing in it changes: its switch functions are constant. */
static inline int tribo_at_rest(const tribo_force_law *phase)
{
    return phase->contact == TRIBO_CONTACT_ON && phase->normal == TRIBO_NORMAL_LOCK &&
           phase->tangent == TRIBO_TANGENT_RIGID && phase->roll == TRIBO_ROLL_LOCK;
}

/* The switch functions of the phase at state y. */
void tribo_switch_functions(const tribo_dyn_params *p, const tribo_force_law *phase, const double *y,
                            double *g);

/* The crossing direction of each switch function that means a switch in the phase
   (0: not a switch of this phase). */
void tribo_switch_directions(const tribo_dyn_params *p, const tribo_force_law *phase, int *dir);

/* The phase after a switch (fired: the switch functions found crossing, as CVODE's root
   info) or, with fired = NULL, the phase a state is in when integration (re)starts there.
   Adjusts y: applies the resets of model.md §3, puts the switched boundary exactly on it
   (Y = h, damped velocity 0, delta_x = +-limit) so that switch functions start at 0 and
   follow the motion, and books the energy the adjustments take out as dissipated work. */
tribo_force_law tribo_phase_after(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                                 const int *fired);

#endif
