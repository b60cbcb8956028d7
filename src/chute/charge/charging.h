/* charging.h: an instance's charge models over the particle's boundary segments
   (docs/model.md §5): which segments touch the plate and for how long, and the calls of
   each selected model's rate law (charge_interface.h) over them. */
#ifndef TRIBO_CHARGING_H
#define TRIBO_CHARGING_H

#include "charge_interface.h"
#include "geometry.h"
#include "paschen.h"

/* The smaller and the larger of two numbers that are not NaN (fmin and fmax are calls where
   the hot loops need a compare). */
static inline double tribo_min(double a, double b) { return a < b ? a : b; }
static inline double tribo_max(double a, double b) { return a > b ? a : b; }

/* A point of the contact patch (docs/model.md §8c), in segments from a sample's first: the
   contact centre, the half-length Sc along the boundary, and the depth h of the contact point
   below the centre (the patch's half-width across the plane of motion is h Sc). */
typedef struct tribo_patch_point {
    double centre, half, depth;
} tribo_patch_point;
#define TRIBO_PATCH_POINTS 5

/* The contact held over an interval of the motion: which segments touch the plate and
   for how long, and what drives the charge there (the global states of every model at the
   interval's start, middle and end, at the models' offsets). */
typedef struct tribo_contact_sample {
    double duration;
    /* the run of segments in contact: count of them from first, around the ring of n
       (first in [0, n), count in [0, n]; 0: no contact) */
    long first, count;
    /* the patch along the interval, at n_patch times in order (the path between them taken
       linear), for the grain's bands (§8c); set only where the instance keeps them, or where
       leave_by_edges needs them */
    int n_patch;
    tribo_patch_point patch[TRIBO_PATCH_POINTS];
    /* instantaneous transfer over a whole piece whose globals move (§5c): the patch holds its
       TRIBO_PATCH_POINTS points at equal steps of time, and each segment takes the
       saturation at the globals of the time it left the contact (where an edge crossed its
       far boundary), or of the end */
    int leave_by_edges;
    /* the contact episode it belongs to (model.md §8e): 1 + the touch-downs before it; 0 the
       committed point's (tribo_charge_sample stamps it) */
    long long episode;
    double globals_begin[TRIBO_CHARGE_MAX_GLOBALS];
    double globals_mid[TRIBO_CHARGE_MAX_GLOBALS];
    double globals_end[TRIBO_CHARGE_MAX_GLOBALS];
} tribo_contact_sample;

/* A compensated sum (Neumaier): the sum, and what the additions rounded off. */
typedef struct tribo_compensated {
    double sum, c;
} tribo_compensated;
static inline double tribo_compensated_value(const tribo_compensated *x) { return x->sum + x->c; }
/* Add v to a compensated sum. */
void tribo_compensated_add(tribo_compensated *x, double v);

/* What samples changed: per model the sum of its values and the charge its breakdown limit
   took (its own units), the same for its bands weighted by their areas (own units times
   a^2), and the grain's charged area (a^2). */
typedef struct tribo_charge_totals {
    double sum[TRIBO_CHARGE_MAX_MODELS], lost[TRIBO_CHARGE_MAX_MODELS];
    double band_charge[TRIBO_CHARGE_MAX_MODELS], band_lost[TRIBO_CHARGE_MAX_MODELS];
    double area;
} tribo_charge_totals;

/* One model of an instance's set. */
typedef struct tribo_charge_slot {
    const tribo_charge_model *model;
    int selected;
    int globals_at;     /* its global states in a point's charge_globals */
    int quadratures_at; /* its quadratures after the motion in a point's y */
    double *segments;   /* committed values (NULL when not selected) */
    double *segments_out; /* a copy with the pending updates applied, made when read */
    /* the band densities of the grain (§8c; NULL without bands), and their copy */
    double *bands, *bands_out;
    /* its breakdown limit, for the scene's Sigma_bd and Sigma0 it was taken at */
    int cap_taken;
    double cap, cap_Sigma_bd, cap_Sigma0;
    void *cache;
} tribo_charge_slot;

/* The grain's bands (model.md §8c): per segment the width W_i across the plane of motion
   (units of a) and the hull of the overlaps seen along it, as fractions [lo, hi] of the
   segment (empty: lo = 1, hi = 0). */
typedef struct tribo_band_geometry {
    double *width, *lo, *hi;
    /* with the Paschen limit (§8e): the limit of the episode that last touched each band, in
       the sliding model's unit of density (INF: none yet); NULL without it */
    double *limit;
} tribo_band_geometry;

/* The gas's limit as the samples meet it (model.md §8e): the contact episode under way, its
   region radius L_e (units of a) and limit sigma_P(L_e) (the sliding model's unit), the run
   of bands it has touched ([first, first + count) around the ring), and each model's grain
   charge Q (its own units times a^2), which the grain's limit bounds. */
typedef struct tribo_gas_state {
    long long episode;
    double radius, limit;
    long first, count;
    double grain[TRIBO_CHARGE_MAX_MODELS];
} tribo_gas_state;

typedef struct tribo_charging {
    int n_models;
    tribo_charge_slot slot[TRIBO_CHARGE_MAX_MODELS];
    int n_globals, n_quadratures; /* over the whole set, selected or not */
    int any_selected;
    /* the boundary cut into n segments of equal arc length (only with a model selected) */
    int n;
    double segments_per_length; /* n / perimeter */
    double segment_length;      /* perimeter / n */
    tribo_arclength arc;
    tribo_decay_cache decay; /* the models' shared one (tribo_charge_forcing) */
    /* the committed totals: each model's sums (compensated, kept up to date with each
       sample, so that a mean costs nothing to read) and the grain's charged area */
    tribo_compensated sum[TRIBO_CHARGE_MAX_MODELS], lost[TRIBO_CHARGE_MAX_MODELS];
    tribo_compensated band_charge[TRIBO_CHARGE_MAX_MODELS], band_lost[TRIBO_CHARGE_MAX_MODELS];
    tribo_compensated area;
    /* the grain's bands (grain_geometry = spheroid, model.md §8c; NULLs otherwise), their
       copy with the pending updates applied, and the scratch of a window of the ring */
    int keep_bands;
    tribo_band_geometry bands, bands_out;
    double *window;
    size_t window_cap;
    double *scratch; /* per-segment areas of a sample's run, and band densities before it */
    /* the Paschen limit (breakdown_model = paschen on the spheroid, §8e; paschen 0 else):
       S of the gas's gamma, a region's reduced size per unit radius (A p a, halved for the
       image of a grounded wall), the grain's limit in the sliding model's unit times a^2,
       and the gas's state, committed and with the pending samples applied */
    int paschen;
    tribo_paschen table;
    double region_scale, grain_limit;
    double surface_limit; /* grain_limit / A_s: what an arriving surface keeps (INF without) */
    tribo_gas_state gas, gas_out;
    double *targets; /* per model, each segment's saturation (n_models x n) */
} tribo_charging;

/* Where a sample's charge goes: into the committed charges (and their sums), or queued for
   the output point, which applies it to copies of them when they are read. */
typedef enum { TRIBO_CHARGE_COMMIT, TRIBO_CHARGE_PENDING } tribo_charge_destination;

/* The Paschen limit of a region of radius L (units of a) in the sliding model's unit of
   density (§8e). */
double tribo_charging_region_limit(tribo_charging *c, const tribo_scene *s, double radius);

/* The Paschen limit's constants for the scene (§8e), where it acts (breakdown_model =
   paschen, with the grain's bands): the table of the gas's gamma over the regions up to the
   sphere of the grain's area (a larger one is minimised where it comes), and the grain's
   limit; the gas's state stays. */
void tribo_charging_setup_gas(tribo_charging *c, const tribo_scene *s);

/* Set up the models[0..n_models) (selected by bit i of `selection`) over n segments of
   the ellipse of roundness eps, with the grain's bands where keep_bands (§8c); the boundary's
   arc-length table copied from like_arc where that is the table of the same eps (NULL: none).
   Returns 0, -1 if out of memory, or -2 if the set does not fit a point (TRIBO_CHARGE_MAX_*). */
int tribo_charging_init(tribo_charging *c, const tribo_charge_model *const *models, int n_models,
                        unsigned selection, double eps, int n, int keep_bands,
                        const tribo_arclength *like_arc);
void tribo_charging_free(tribo_charging *c);
/* All segment charges to 0 (§7), the bands empty at the scene's initial density (§8c), and
   the caches emptied. */
void tribo_charging_reset(tribo_charging *c, const tribo_scene *s);
/* Every model's global states at the start of a run. */
void tribo_charging_start(const tribo_charging *c, const tribo_scene *s, double *globals);

/* The run of segments a contact covers, into a sample: those whose arc [i L, (i+1) L)
   overlaps [s_centre - half_width, s_centre + half_width] (§5), periodic; a contact wider
   than the boundary (or not a number) covers all of it. */
void tribo_charging_locate(const tribo_charging *c, double s_centre, double half_width,
                           tribo_contact_sample *sample);
/* The same, and where the instance keeps the grain's bands, the patch there as the sample's
   one point (§8c): its half-width across the plane of motion is depth times half_width. */
void tribo_charging_patch(const tribo_charging *c, double s_centre, double half_width, double depth,
                          tribo_contact_sample *sample);
/* The same from the segments (floor values, unwrapped: any integers) holding the contact's
   lower and upper edges. */
void tribo_charging_run(const tribo_charging *c, double lo_segment, double hi_segment,
                        tribo_contact_sample *sample);

/* The rates of every quadrature in contact (0 for models not selected). */
void tribo_charging_quadrature_rates(const tribo_charging *c, const tribo_contact_kinematics *k,
                                     double *rates);

/* The sample of one fixed step of length h that ends with the contact (pose, delta_y):
   the step is charged at its end point's contact, as the paper does. Advances the globals
   from g0 to g1 given the quadratures q0 -> q1 at the step's ends. */
void tribo_charging_step(tribo_charging *c, const tribo_scene *s, const tribo_pose *pose,
                         double delta_y, double h, const double *q0, const double *q1,
                         const double *g0, double *g1, tribo_contact_sample *sample);

/* Charge the segments under a sample (the overlap of [s_c - Sc, s_c + Sc], §5) with each
   selected model, each value then held within the model's breakdown limit (§8b), and, where
   the instance keeps them, the grain's bands under the patch (§8c), in the committed arrays
   (with their totals) or, for a pending sample, in the output copies. Returns the number of
   segment values updated. */
long tribo_charging_apply(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                          tribo_charge_destination where);

/* The committed totals. */
static inline double tribo_charging_sum(const tribo_charging *c, int k) { return tribo_compensated_value(&c->sum[k]); }
static inline double tribo_charging_lost(const tribo_charging *c, int k) { return tribo_compensated_value(&c->lost[k]); }
/* How many of values[0..n) stand at a slot's breakdown limit (0 without one). */
long tribo_charging_capped(const tribo_charge_slot *slot, const tribo_scene *s, const double *values,
                           long n);
/* The area (a^2) of the bands whose density stands at a slot's breakdown limit (§8c, §8b). */
double tribo_charging_capped_area(const tribo_charging *c, const tribo_charge_slot *slot,
                                  const tribo_scene *s, const double *bands,
                                  const tribo_band_geometry *g);
/* The grain's initial density (scene Sigma_init, §8c) in a model's own units (0 for a model
   whose values are no densities). */
double tribo_charging_initial_value(const tribo_charging *c, const tribo_charge_model *model,
                                    const tribo_scene *s);

/* What the samples (in order, not committed) would add to the committed totals (0 for slots
   not selected). Costs the segments they touch, not n. Returns 0, or -1 if out of memory. */
int tribo_charging_pending_totals(tribo_charging *c, const tribo_scene *s,
                                  const tribo_contact_sample *samples, size_t n_samples,
                                  tribo_charge_totals *totals);

/* The output copies of every array (values, bands, band geometry) made equal to the
   committed ones, before the pending samples are applied to them. Returns 0, or -1 if out of
   memory. */
int tribo_charging_copy_out(tribo_charging *c);

/* The contact along an interval of the motion, as an integrator with dense output sees it
   at time t: the arc-length coordinate of the contact centre, the half-width Sc, the speed
   of the centre along the boundary, and the kinematics the quadratures' rates need. */
typedef struct tribo_contact_probe {
    void (*at)(void *ctx, double t, double *s_centre, double *half_width, double *centre_speed,
               tribo_contact_kinematics *k);
    void *ctx;
} tribo_contact_probe;

/* Receives the samples of a sweep; returns 0, or non-zero to stop it. */
typedef int (*tribo_sample_sink)(void *ctx, const tribo_contact_sample *sample);

/* Sweep a contact that lasts over [a, b]: cut it where an edge of the contact crosses a
   segment boundary (located on the probe to ~1e-10 of the interval), so that every sample
   holds a fixed set of segments and the charge models are exact given the probe (§5). The
   quadratures are integrated along the way (adaptive Simpson to rtol of their increment
   and atol per unit time) and the global states follow them. Advances quadratures[] and
   globals[] (the whole set's); each sample goes to the sink. Returns 0, or the sink's
   non-zero value.
   The sweep ends early, after the piece in which its cost (a probe counts 1, a sample
   cell_cost per segment it covers: TRIBO_SWEEP_CELL_COST where a segment costs one value
   charged per model) reaches budget, and says where in *reached
   (b when it went all the way; reached may be NULL). A sweep over [a, b'] with b' > *reached
   takes the same pieces up to *reached, so the point where a budget ends it does not depend
   on how far it was asked to go. */
#define TRIBO_SWEEP_CELL_COST (1.0 / 150.0)
int tribo_charging_sweep(tribo_charging *c, const tribo_scene *s, const tribo_contact_probe *probe,
                         double a, double b, double rtol, double atol, double *quadratures,
                         double *globals, tribo_sample_sink sink, void *sink_ctx, double budget,
                         double cell_cost, double *reached);

#endif
