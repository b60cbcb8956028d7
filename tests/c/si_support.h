/* si_support.h: the SI front end's set-ups for the C tests that run physical grains. */
#ifndef TRIBO_TEST_SI_SUPPORT_H
#define TRIBO_TEST_SI_SUPPORT_H

#include <criterion/criterion.h>

#include "si.h"

/* The SI defaults with settings "name=value ..." applied, derived; the test fails with the
   front end's reason where it refuses them. */
static inline tribo_si_derived derived(const char *settings)
{
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    char err[512];
    cr_assert_eq(tribo_si_scene_apply(&si, settings, err, sizeof err), TRIBO_OK, "%s", err);
    tribo_si_derived d;
    cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
    return d;
}

#endif
