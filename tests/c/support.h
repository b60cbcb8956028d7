/* support.h: helpers the C tests share. */
#ifndef TRIBO_TEST_SUPPORT_H
#define TRIBO_TEST_SUPPORT_H

#include <criterion/criterion.h>
#include <math.h>

#include "tribo.h"

/* A new instance of the scene; the test fails with the reason if there is none. */
static inline tribo_model *make(const tribo_scene *s)
{
    char err[512];
    tribo_model *m = tribo_create(s, err, sizeof err);
    cr_assert(m, "%s", err);
    return m;
}

/* The largest difference of two instances' motion: X, Y, phi, U, V, Omega. */
static inline double state_distance(tribo_model *a, tribo_model *b)
{
    const tribo_quantity q[] = {TRIBO_Q_X, TRIBO_Q_Y, TRIBO_Q_PHI, TRIBO_Q_U, TRIBO_Q_V, TRIBO_Q_OMEGA};
    double d = 0.0;
    for (int i = 0; i < 6; i++)
        d = fmax(d, fabs(tribo_get(a, q[i]) - tribo_get(b, q[i])));
    return d;
}

#endif
