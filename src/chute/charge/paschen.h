/* paschen.h: the Paschen limit of a charged region separating from the wall (docs/model.md
   §8e), in the gas's reduced units, and its table.

   With the reduced gap x = A p d, Paschen's law is Vb = (B/A) G(x), G(x) = x / (ln x - ln K),
   K = ln(1 + 1/gamma), held at its minimum G = e K for x below the minimum's x = e K; a disc
   of radius L charged to sigma has across the gap d to its image (a grounded wall) the
   voltage (sigma / eps0)(c + d - sqrt(d^2 + c^2)) with c = L/2 (the pair form of an
   insulating wall: c = L). So the largest density that never breaks down is

       sigma_P = eps0 B p S(A p c),   S(c) = min over x > 0 of G(x) / F(x; c),
       F(x; c) = c + x - sqrt(x^2 + c^2),

   a function of the reduced size A p c and gamma alone. */
#ifndef TRIBO_PASCHEN_H
#define TRIBO_PASCHEN_H

/* Nodes of the table per decade of c: cubic Hermite in ln S against ln c with the exact
   slopes (tests/c/test_paschen.c measures its error against the minimisation). */
#define TRIBO_PASCHEN_PER_DECADE 8
#define TRIBO_PASCHEN_MAX_NODES 400

/* S(c) over [c_lo, c_hi] for one gamma: ln S and d ln S / d ln c at nodes equally spaced in
   ln c. Below c_lo, S = e K / F(e K; c) to within c_lo / (2 e K) relative; above c_hi, the
   minimisation itself. */
typedef struct tribo_paschen {
    double gamma;          /* the gamma it was built for; 0: not built */
    double log_K, x_min;   /* ln K, e K */
    double c_lo, c_hi;     /* the range of the nodes */
    double v0, dv;         /* node i at ln c = v0 + i dv */
    int n;
    double y[TRIBO_PASCHEN_MAX_NODES], slope[TRIBO_PASCHEN_MAX_NODES];
} tribo_paschen;

/* S(c) by the minimisation over the gap (golden section in ln x on [ln e K, ln(e K + c)],
   where the minimum lies: below e K the voltage is held and the field only falls as the
   gap grows, and beyond e K + c the gap's voltage has saturated). gamma in (0, 1), c > 0. */
double tribo_paschen_reduced(double gamma, double c);

/* The minimum's reduced gap e ln(1 + 1/gamma): its voltage is (B/A) times the same number. */
double tribo_paschen_minimum(double gamma);

/* Lay out the table for gamma over reduced sizes up to c_max (nothing if it is laid out for
   them already): from a ten-thousandth of the minimum's gap, below which the asymptote holds
   to 5e-5. Its nodes are minimised where a size first needs them (tribo_paschen_limit), each
   once: an instance meets a few of them. */
void tribo_paschen_build(tribo_paschen *t, double gamma, double c_max);

/* S(c) from the table (c > 0), minimising the nodes it needs where they are not yet. */
double tribo_paschen_limit(tribo_paschen *t, double c);

#endif
