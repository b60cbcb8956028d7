/* motion.h: the motion class of the motion, in the paper's terms, and the checks of the
   contact model's assumptions along the run. */
#ifndef TRIBO_MOTION_H
#define TRIBO_MOTION_H

/* The classes of motion the paper tells apart. Continuous contact: ROCKING (quasi-fixed orientation,
   sliding with rocking) or ROLLING (the orientation turns with the travel); intermittent
   contact: BOUNCING (flights, no turning over) or TUMBLING (turning over with flights);
   FLIGHT when the particle has not touched the plate within the window. */
typedef enum tribo_motion_class {
    TRIBO_MOTION_FLIGHT = 0,
    TRIBO_MOTION_ROCKING = 1,
    TRIBO_MOTION_ROLLING = 2,
    TRIBO_MOTION_TUMBLING = 3,
    TRIBO_MOTION_BOUNCING = 4,
    TRIBO_MOTION_CLASSES
} tribo_motion_class;

/* The recent history the classification needs: averages over the last ~window time
   units (exponentially weighted), and the time spent in each class so far. */
typedef struct tribo_motion {
    double contact;   /* average of the contact indicator           */
    double spin;      /* average dphi/dtau                          */
    int current;      /* tribo_motion_class at the end of the last update */
    double class_time[TRIBO_MOTION_CLASSES];
    int outside_assumptions; /* the contact was outside them at the last update */
    long long impacts;       /* contacts made after a flight */
    long long touchdowns;    /* contacts made, after a flight or not: the contact episodes
                                begun (model.md §8e) */
} tribo_motion;

/* Window of the averages: long enough to span the flights between the paper's bounces
   (tens of time units) so that bouncing is not taken for flight. */
#define TRIBO_MOTION_WINDOW 20.0

/* The contact model (line contact of a rigid curvature against a linear spring) assumes a
   small indentation: delta_y <= this fraction of both the semi-minor axis (epsilon) and
   the radius of curvature at the contact (rho_c). Beyond it the contact width
   Sc = sqrt(rho_c delta_y) exceeds ~0.3 rho_c and the law is not meaningful. */
#define TRIBO_INDENTATION_LIMIT 0.1

/* Update the history over an interval of length h ending at a state with the given
   contact, over which phi moved by dphi. decay = exp(-h / window). */
void tribo_motion_update(tribo_motion *m, double h, double decay, int in_contact, double dphi);

/* The fraction of the time t so far spent in a class. */
static inline double tribo_motion_fraction(const tribo_motion *m, tribo_motion_class c, double t)
{
    return t > 0.0 ? m->class_time[c] / t : 0.0;
}

/* Whether a contact is outside the model's assumptions (TRIBO_INDENTATION_LIMIT). */
int tribo_indentation_too_deep(double delta_y, double epsilon, double rho_c);

#endif
