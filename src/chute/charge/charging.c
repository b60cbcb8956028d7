/* charging.c: an instance's charge models over the boundary segments (docs/model.md §5), and
   the grain's bands under the contact patch (§8c). */
#include "charging.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void free_geometry(tribo_band_geometry *g)
{
    free(g->width);
    free(g->lo);
    free(g->hi);
    free(g->limit);
    g->width = g->lo = g->hi = g->limit = NULL;
}

static int alloc_geometry(tribo_band_geometry *g, int n)
{
    const size_t bytes = (size_t)n * sizeof(double);
    g->width = malloc(bytes);
    g->lo = malloc(bytes);
    g->hi = malloc(bytes);
    g->limit = malloc(bytes);
    return g->width && g->lo && g->hi && g->limit ? 0 : -1;
}

int tribo_charging_init(tribo_charging *c, const tribo_charge_model *const *models, int n_models,
                        unsigned selection, double eps, int n, int keep_bands,
                        const tribo_arclength *like_arc)
{
    memset(c, 0, sizeof *c);
    if (n_models > TRIBO_CHARGE_MAX_MODELS)
        return -2;
    c->n_models = n_models;
    c->n = n;
    for (int i = 0; i < n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        slot->model = models[i];
        slot->selected = (selection >> i) & 1u;
        slot->globals_at = c->n_globals;
        slot->quadratures_at = c->n_quadratures;
        c->n_globals += models[i]->n_globals;
        c->n_quadratures += models[i]->n_quadratures;
        c->any_selected |= slot->selected;
    }
    if (c->n_globals > TRIBO_CHARGE_MAX_GLOBALS || c->n_quadratures > TRIBO_CHARGE_MAX_QUADRATURES)
        return -2;
    /* Without a selected model no segment table is built, and no segment is touched. */
    if (!c->any_selected)
        return 0;
    c->keep_bands = keep_bands;
    if (tribo_arclength_init(&c->arc, eps, like_arc) != 0)
        goto fail;
    c->segments_per_length = (double)n / c->arc.perimeter;
    c->segment_length = c->arc.perimeter / (double)n;
    const size_t bytes = (size_t)n * sizeof(double);
    for (int i = 0; i < n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        if (!slot->selected)
            continue;
        /* uncharged until tribo_charging_reset gives them the grain's initial charge */
        if (!(slot->segments = calloc((size_t)n, sizeof(double))))
            goto fail;
        if (keep_bands && !(slot->bands = calloc((size_t)n, sizeof(double))))
            goto fail;
        if (slot->model->cache_size && !(slot->cache = malloc(slot->model->cache_size)))
            goto fail;
    }
    if (keep_bands && (alloc_geometry(&c->bands, n) != 0 || !(c->scratch = malloc(3 * bytes))))
        goto fail;
    if (!(c->targets = malloc((size_t)n_models * bytes)))
        goto fail;
    return 0;
fail:
    tribo_charging_free(c);
    return -1;
}

void tribo_charging_free(tribo_charging *c)
{
    tribo_arclength_free(&c->arc);
    for (int i = 0; i < c->n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        free(slot->segments);
        free(slot->segments_out);
        free(slot->bands);
        free(slot->bands_out);
        free(slot->cache);
        slot->segments = slot->segments_out = slot->bands = slot->bands_out = NULL;
        slot->cache = NULL;
    }
    free_geometry(&c->bands);
    free_geometry(&c->bands_out);
    free(c->window);
    free(c->scratch);
    free(c->targets);
    c->window = c->scratch = c->targets = NULL;
    c->window_cap = 0;
}

double tribo_charging_initial_value(const tribo_charging *c, const tribo_charge_model *model,
                                    const tribo_scene *s)
{
    if (!model->density_unit || s->Sigma_init == 0.0)
        return 0.0;
    /* a surface arriving above what air holds keeps what it holds: Sigma_bd under §8b, the
       grain's own limit under §8e, which replaces Sigma_bd on the spheroid's bands */
    const double unit = model->density_unit(s);
    const double cap = (c->paschen ? c->surface_limit : s->Sigma_bd) / unit;
    return tribo_min(tribo_max(s->Sigma_init / unit, -cap), cap);
}

/* The bands empty: no width, no length, the initial density (§8c). */
static void empty_bands(tribo_charging *c, const tribo_scene *s)
{
    for (int i = 0; i < c->n; i++) {
        c->bands.width[i] = 0.0;
        c->bands.lo[i] = 1.0;
        c->bands.hi[i] = 0.0;
        c->bands.limit[i] = INFINITY;
    }
    for (int k = 0; k < c->n_models; k++) {
        tribo_charge_slot *slot = &c->slot[k];
        if (!slot->bands)
            continue;
        const double init = tribo_charging_initial_value(c, slot->model, s);
        for (int i = 0; i < c->n; i++)
            slot->bands[i] = init;
    }
}

double tribo_charging_region_limit(tribo_charging *c, const tribo_scene *s, double radius)
{
    return s->Sigma_paschen * tribo_paschen_limit(&c->table, c->region_scale * radius);
}

void tribo_charging_setup_gas(tribo_charging *c, const tribo_scene *s)
{
    c->paschen = c->keep_bands && s->breakdown_model == TRIBO_BREAKDOWN_PASCHEN;
    c->surface_limit = INFINITY;
    if (!c->paschen)
        return;
    /* a grounded wall's image halves the region's size (the pair form: L/2 -> L) */
    c->region_scale = s->paschen_gap_scale * (s->wall_conducting ? 0.5 : 1.0);
    const double area = tribo_spheroid_area(c->arc.eps);
    const double radius = sqrt(area / (4.0 * M_PI));
    tribo_paschen_build(&c->table, s->secondary_emission, c->region_scale * radius);
    c->grain_limit = tribo_charging_region_limit(c, s, radius) * area;
    c->surface_limit = c->grain_limit / area;
}

/* No episode under way, the grain at its initial charge (§8e). */
static void reset_gas(tribo_charging *c, const tribo_scene *s)
{
    c->gas = (tribo_gas_state){.limit = INFINITY};
    const double area = tribo_spheroid_area(c->arc.eps);
    for (int k = 0; k < c->n_models && c->paschen; k++)
        if (c->slot[k].bands)
            c->gas.grain[k] = tribo_charging_initial_value(c, c->slot[k].model, s) * area;
}

void tribo_charging_reset(tribo_charging *c, const tribo_scene *s)
{
    for (int i = 0; i < c->n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        if (slot->segments)
            memset(slot->segments, 0, (size_t)c->n * sizeof *slot->segments);
        if (slot->cache)
            memset(slot->cache, 0, slot->model->cache_size);
        c->sum[i] = c->lost[i] = c->band_charge[i] = c->band_lost[i] = (tribo_compensated){0};
    }
    c->area = (tribo_compensated){0};
    tribo_charging_setup_gas(c, s);
    if (c->keep_bands && c->bands.width)
        empty_bands(c, s);
    reset_gas(c, s);
    memset(&c->decay, 0, sizeof c->decay);
}

void tribo_charging_start(const tribo_charging *c, const tribo_scene *s, double *globals)
{
    for (int i = 0; i < c->n_models; i++)
        if (c->slot[i].model->start)
            c->slot[i].model->start(s, globals + c->slot[i].globals_at);
}

void tribo_charging_quadrature_rates(const tribo_charging *c, const tribo_contact_kinematics *k,
                                     double *rates)
{
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        for (int q = 0; q < slot->model->n_quadratures; q++)
            rates[slot->quadratures_at + q] =
                slot->selected ? slot->model->quadrature_rate(q, k) : 0.0;
    }
}

void tribo_charging_step(tribo_charging *c, const tribo_scene *s, const tribo_pose *pose,
                         double delta_y, double h, const double *q0, const double *q1,
                         const double *g0, double *g1, tribo_contact_sample *sample)
{
    sample->duration = h;
    sample->n_patch = 0;
    sample->leave_by_edges = 0;
    const int in_contact = delta_y > 0.0;
    if (in_contact) {
        const double eps = c->arc.eps;
        const double rho_c = tribo_contact_curvature_radius(eps * eps, pose->h);
        const double s_c = tribo_arclength_at(&c->arc, tribo_contact_parameter(eps, pose));
        /* the step is charged at its end point's contact: Sc (§5, paper eq. 4), one point of
           the patch */
        tribo_charging_patch(c, s_c, sqrt(rho_c * delta_y), pose->h, sample);
    } else {
        sample->first = sample->count = 0;
    }
    memcpy(g1, g0, (size_t)c->n_globals * sizeof *g1);
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        if (slot->selected && slot->model->n_globals)
            slot->model->step_globals(slot->cache, s, h, in_contact,
                                      q0 + slot->quadratures_at, q1 + slot->quadratures_at,
                                      g0 + slot->globals_at, g1 + slot->globals_at);
    }
    /* the globals taken linear over the step */
    for (int k = 0; k < c->n_globals; k++) {
        sample->globals_begin[k] = g0[k];
        sample->globals_mid[k] = 0.5 * (g0[k] + g1[k]);
        sample->globals_end[k] = g1[k];
    }
}

void tribo_compensated_add(tribo_compensated *x, double v)
{
    const double t = x->sum + v;
    x->c += fabs(x->sum) >= fabs(v) ? (x->sum - t) + v : (v - t) + x->sum;
    x->sum = t;
}

void tribo_charging_run(const tribo_charging *c, double lo_segment, double hi_segment,
                        tribo_contact_sample *sample)
{
    /* in doubles until the values are known to fit a long */
    const double n = (double)c->n;
    if (!(hi_segment - lo_segment + 1.0 < n)) {
        sample->first = 0;
        sample->count = c->n;
        return;
    }
    double wrapped = lo_segment - n * floor(lo_segment / n);
    if (!(wrapped >= 0.0 && wrapped < n))
        wrapped = 0.0;
    sample->first = (long)wrapped;
    sample->count = (long)(hi_segment - lo_segment + 1.0);
}

void tribo_charging_locate(const tribo_charging *c, double s_centre, double half_width,
                           tribo_contact_sample *sample)
{
    const double lo = (s_centre - half_width) * c->segments_per_length;
    const double hi = (s_centre + half_width) * c->segments_per_length;
    if (!(hi - lo < (double)c->n)) { /* wider than the boundary, or not a number */
        sample->first = 0;
        sample->count = c->n;
        return;
    }
    tribo_charging_run(c, floor(lo), floor(hi), sample);
}

void tribo_charging_patch(const tribo_charging *c, double s_centre, double half_width, double depth,
                          tribo_contact_sample *sample)
{
    tribo_charging_locate(c, s_centre, half_width, sample);
    sample->n_patch = 0;
    sample->leave_by_edges = 0;
    if (c->keep_bands) {
        const double lo = (s_centre - half_width) * c->segments_per_length;
        sample->n_patch = 1;
        sample->patch[0] = (tribo_patch_point){s_centre * c->segments_per_length - floor(lo),
                                               half_width * c->segments_per_length, depth};
    }
}

/* The run of segments a sample charges: none for an empty interval. */
static long segment_run(const tribo_contact_sample *sample, long *first)
{
    if (!(sample->duration > 0.0) || sample->count <= 0)
        return 0;
    *first = sample->first;
    return sample->count;
}

/* ---- one sample on a ring of arrays ------------------------------------------------------ */

/* Everything a sample changes, over a ring of len segments: the instance's arrays, their
   output copies, or a window of them. */
typedef struct ring {
    long len;
    int wraps; /* the whole ring (a window shorter than it: no run wraps) */
    tribo_gas_state *gas; /* the gas's state the samples meet (§8e) */
    double *values[TRIBO_CHARGE_MAX_MODELS];
    double *bands[TRIBO_CHARGE_MAX_MODELS]; /* NULL without bands */
    tribo_band_geometry geometry;
} ring;

/* Hold values[0..count) within +-cap (§8b: charging that would raise a segment above the
   limit leaves it there); returns the charge so taken. The rate laws approach their
   saturation monotonically over a sample, so a value above the cap at its end reached it
   within the sample and stays: the excess at the end is what went to the gas. */
static double hold_at_cap(double *values, long count, double cap)
{
    double taken = 0.0;
    for (long i = 0; i < count; i++) {
        if (values[i] > cap) {
            taken += values[i] - cap;
            values[i] = cap;
        } else if (values[i] < -cap) {
            taken += values[i] + cap;
            values[i] = -cap;
        }
    }
    return taken;
}

/* The sum of values[0..count) in four interleaved partial sums: the additions do not wait on
   each other, so that a sum over a sample costs little beside charging it. */
static double sum_of(const double *values, long count)
{
    double s[4] = {0.0, 0.0, 0.0, 0.0};
    long i = 0;
    for (; i + 4 <= count; i += 4)
        for (int k = 0; k < 4; k++)
            s[k] += values[i + k];
    for (; i < count; i++)
        s[0] += values[i];
    return (s[0] + s[1]) + (s[2] + s[3]);
}

/* The bound on a slot's values (INF: none). */
static double cap_of(const tribo_charge_slot *slot, const tribo_scene *s)
{
    return slot->model->density_unit ? s->Sigma_bd / slot->model->density_unit(s) : INFINITY;
}

/* The same, kept in the slot: a sample takes it without a call (or the division a model's
   units may cost) while Sigma_bd and Sigma0 stay. */
static double slot_cap(tribo_charge_slot *slot, const tribo_scene *s)
{
    if (!slot->cap_taken || slot->cap_Sigma_bd != s->Sigma_bd || slot->cap_Sigma0 != s->Sigma0) {
        slot->cap = cap_of(slot, s);
        slot->cap_Sigma_bd = s->Sigma_bd;
        slot->cap_Sigma0 = s->Sigma0;
        slot->cap_taken = 1;
    }
    return slot->cap;
}

/* Instantaneous transfer (§5c) on values[0..count): each at its saturation at once, held
   within the cap. A value that reaches the cap loses the excess once, where it reaches it
   (a segment already there is at its transfer's end and loses nothing more); weights (NULL:
   1 each) weigh each value's change and loss. Returns the weighted change of the values, and
   adds what the cap took to *lost. */
static double saturate(double *values, const double *weights, long count, double target, double cap,
                       double *lost)
{
    const double held = tribo_min(tribo_max(target, -cap), cap);
    const double excess = target - held;
    double change = 0.0;
    for (long i = 0; i < count; i++) {
        if (values[i] != held) {
            const double w = weights ? weights[i] : 1.0;
            change += (held - values[i]) * w;
            values[i] = held;
            *lost += excess * w;
        }
    }
    return change;
}

/* The same with a target per value. */
static double saturate_each(double *values, const double *weights, long count, const double *targets,
                            double cap, double *lost)
{
    double change = 0.0;
    for (long i = 0; i < count; i++) {
        const double held = tribo_min(tribo_max(targets[i], -cap), cap);
        if (values[i] != held) {
            const double w = weights ? weights[i] : 1.0;
            change += (held - values[i]) * w;
            values[i] = held;
            *lost += (targets[i] - held) * w;
        }
    }
    return change;
}

/* ---- when a segment left the contact, for a whole instantaneous piece (§5c) ----------------- */

/* One edge of the patch over a sample's points (at u = 0, 1/4, .., 1): its values and the
   weights of its inverse interpolating quartic u(e) (Lagrange), where it moves strictly
   one way. */
typedef struct edge_inverse {
    int direction; /* +1 up, -1 down, 0 neither strictly */
    double e[TRIBO_PATCH_POINTS], w[TRIBO_PATCH_POINTS];
} edge_inverse;

static void invert_edge(edge_inverse *f, const tribo_contact_sample *s, int hi_edge)
{
    const int n = TRIBO_PATCH_POINTS;
    for (int i = 0; i < n; i++)
        f->e[i] = s->patch[i].centre + (hi_edge ? s->patch[i].half : -s->patch[i].half);
    const int up = f->e[n - 1] > f->e[0];
    f->direction = up ? 1 : f->e[n - 1] < f->e[0] ? -1 : 0;
    for (int i = 1; i < n && f->direction; i++)
        if ((f->e[i] - f->e[i - 1]) * f->direction <= 0.0)
            f->direction = 0;
    for (int i = 0; i < n && f->direction; i++) {
        double d = 1.0;
        for (int j = 0; j < n; j++)
            if (j != i)
                d *= f->e[i] - f->e[j];
        f->w[i] = ((double)i / (n - 1)) / d;
    }
}

/* u at which the edge is at x (within its range), by the inverse quartic, held in [0, 1]. */
static double inverse_at_edge(const edge_inverse *f, double x)
{
    const int n = TRIBO_PATCH_POINTS;
    double u = 0.0;
    for (int i = 0; i < n; i++) {
        double p = f->w[i];
        for (int j = 0; j < n; j++)
            if (j != i)
                p *= x - f->e[j];
        u += p;
    }
    return tribo_min(tribo_max(u, 0.0), 1.0);
}

/* The fraction of the sample at which segment k (from its first) left the contact: where the
   lower edge, moving up, passed its upper end, or the upper edge, moving down, its lower end;
   1 where it is in contact at the end (or the edges do not move one way). */
static double leave_fraction(const edge_inverse *lo, const edge_inverse *hi, double k)
{
    const int n = TRIBO_PATCH_POINTS;
    double u = 1.0;
    if (lo->direction > 0 && lo->e[n - 1] >= k + 1.0)
        u = inverse_at_edge(lo, k + 1.0);
    if (hi->direction < 0 && hi->e[n - 1] <= k)
        u = tribo_min(u, inverse_at_edge(hi, k));
    return u;
}

/* Each model's saturation at the time each segment at[0..count) (offsets k0.. from the
   sample's first) left the contact, the globals quadratic over the sample, into targets[m]. */
static void leave_targets(const tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                          long count, long k0, double *const *targets)
{
    edge_inverse lo, hi;
    invert_edge(&lo, sample, 0);
    invert_edge(&hi, sample, 1);
    double c1[TRIBO_CHARGE_MAX_GLOBALS], c2[TRIBO_CHARGE_MAX_GLOBALS];
    const double *S0 = sample->globals_begin, *S1 = sample->globals_mid, *S2 = sample->globals_end;
    for (int g = 0; g < c->n_globals; g++) {
        c1[g] = -3.0 * S0[g] + 4.0 * S1[g] - S2[g];
        c2[g] = 2.0 * (S0[g] - 2.0 * S1[g] + S2[g]);
    }
    double g[TRIBO_CHARGE_MAX_GLOBALS];
    for (long j = 0; j < count; j++) {
        const double u = leave_fraction(&lo, &hi, (double)(k0 + j));
        for (int q = 0; q < c->n_globals; q++)
            g[q] = u == 1.0 ? S2[q] : S0[q] + u * (c1[q] + u * c2[q]);
        for (int m = 0; m < c->n_models; m++)
            if (targets[m])
                targets[m][j] = c->slot[m].model->saturation(s, g + c->slot[m].globals_at);
    }
}

/* hold_at_cap with each value's excess weighted. */
static double hold_at_cap_weighted(double *values, const double *weights, long count, double cap)
{
    double taken = 0.0;
    for (long i = 0; i < count; i++) {
        if (values[i] > cap) {
            taken += (values[i] - cap) * weights[i];
            values[i] = cap;
        } else if (values[i] < -cap) {
            taken += (values[i] + cap) * weights[i];
            values[i] = -cap;
        }
    }
    return taken;
}

/* The distance of a centre (in segments) from segment k's arc [k, k + 1]. */
static double distance_to(double centre, double k)
{
    return centre < k ? k - centre : centre > k + 1.0 ? centre - (k + 1.0) : 0.0;
}

/* The patch's half-width (in segments) across the plane of motion over segment k, h sqrt(Sc^2
   - d^2), the largest at the points of the patch and where its centre's path enters the
   segment (§8c: the largest seen; the path between the points taken linear). */
static double half_width_over(const tribo_contact_sample *sample, double k)
{
    const tribo_patch_point *p = sample->patch;
    double w2 = 0.0;
    for (int i = 0; i < sample->n_patch; i++) {
        const double d = distance_to(p[i].centre, k);
        const double x = p[i].half * p[i].half - d * d;
        if (x > 0.0)
            w2 = tribo_max(w2, p[i].depth * p[i].depth * x);
        if (i + 1 == sample->n_patch)
            break;
        const double c0 = p[i].centre, c1 = p[i + 1].centre;
        const double lo = tribo_min(c0, c1), hi = tribo_max(c0, c1);
        if (!(hi > lo) || hi <= k || lo >= k + 1.0)
            continue;
        /* the path meets the arc between the points: where it enters it and leaves it, d = 0 */
        const double ends[2] = {tribo_max(k, lo), tribo_min(k + 1.0, hi)};
        for (int e = 0; e < 2; e++) {
            const double u = (ends[e] - c0) / (c1 - c0);
            const double half = p[i].half + u * (p[i + 1].half - p[i].half);
            const double depth = p[i].depth + u * (p[i + 1].depth - p[i].depth);
            w2 = tribo_max(w2, depth * depth * half * half);
        }
    }
    return sqrt(w2);
}

/* The slices of a sample's largest patch point over consecutive segments (§8e): the integral
   of the unit ellipse's half-chord, (u sqrt(1 - u^2) + asin u) / 2, at each segment boundary,
   kept for the next segment, which shares it; the full width the sample's patch reaches. */
typedef struct slicer {
    const tribo_patch_point *largest;
    double full;
    double k_next, chord_next; /* the boundary last reached, and its integral */
} slicer;

static slicer slicer_of(const tribo_contact_sample *sample)
{
    const tribo_patch_point *p = sample->patch;
    int largest = 0;
    double full = 0.0;
    for (int i = 0; i < sample->n_patch; i++) {
        const double w = 2.0 * p[i].depth * p[i].half;
        if (w * p[i].half > full * p[largest].half)
            largest = i;
        full = tribo_max(full, w);
    }
    return (slicer){&p[largest], full, NAN, 0.0};
}

/* The half-chord's integral up to boundary x (segments) of the patch point's ellipse. */
static double chord_to(const tribo_patch_point *p, double x)
{
    const double u = (x - p->centre) / p->half;
    if (!(u > -1.0))
        return -M_PI / 4.0;
    if (!(u < 1.0))
        return M_PI / 4.0;
    return 0.5 * (u * sqrt(1.0 - u * u) + asin(u));
}

/* The area (segments^2) of the largest point's ellipse over segment k's arc [k, k + 1]. */
static double slice_area(slicer *sl, double k)
{
    const tribo_patch_point *p = sl->largest;
    if (!(p->half > 0.0))
        return 0.0;
    const double lo = k == sl->k_next ? sl->chord_next : chord_to(p, k);
    const double hi = chord_to(p, k + 1.0);
    sl->k_next = k + 1.0;
    sl->chord_next = hi;
    return 2.0 * p->depth * p->half * p->half * (hi - lo);
}

/* The patch's mean width (segments) over the part [k + a, k + b] of segment k it covers in a
   sample, so that the band's area W L is the patch's own over the segment (§8e's refinement
   of §8c's band, where the patch is not much longer than a segment): the slice of its largest
   point (the sample's points are a short stretch of a smooth contact: the largest holds the
   others, exactly so where the patch grows or shrinks in place, as in an impact), or, where
   the centre's path crosses the segment, that and the strip of the full width it sweeps
   there; at most the full width. */
static double mean_width_over(const tribo_contact_sample *sample, slicer *sl, double k, double a,
                              double b)
{
    const tribo_patch_point *p = sample->patch;
    const double slice = slice_area(sl, k);
    double area = slice;
    for (int i = 0; i + 1 < sample->n_patch; i++) {
        const double lo = tribo_min(p[i].centre, p[i + 1].centre);
        const double hi = tribo_max(p[i].centre, p[i + 1].centre);
        const double inside = tribo_min(hi, k + 1.0) - tribo_max(lo, k);
        if (inside > 0.0)
            area = tribo_max(area, slice + sl->full * inside);
    }
    return tribo_min(area / (b - a), sl->full);
}

/* The bands of segments at[0..count) of the ring, offsets k0.. from the sample's first: each
   widened and lengthened by the patch (§8c), each model's band density diluted where its area
   grew (the new part at the initial density). The areas (a^2) before and after go to
   before[] and after[]; the growth of the total to *area. */
static void widen_bands(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                        const ring *r, long at, long count, long k0, double *before, double *after,
                        double *area)
{
    const tribo_patch_point *p = sample->patch;
    const int whole_ring = sample->count >= c->n; /* a patch wider than the boundary */
    double lo_all = INFINITY, hi_all = -INFINITY, bound = 0.0;
    for (int i = 0; i < sample->n_patch; i++) {
        lo_all = tribo_min(lo_all, p[i].centre - p[i].half);
        hi_all = tribo_max(hi_all, p[i].centre + p[i].half);
        bound = tribo_max(bound, 2.0 * p[i].depth * p[i].half);
    }
    const double seg = c->segment_length;
    double init[TRIBO_CHARGE_MAX_MODELS];
    for (int m = 0; m < c->n_models; m++)
        init[m] = r->bands[m] ? tribo_charging_initial_value(c, c->slot[m].model, s) : 0.0;
    slicer slices = slicer_of(sample);
    for (long j = 0; j < count; j++) {
        const long i = at + j;
        const double k = (double)(k0 + j);
        double *W = &r->geometry.width[i], *lo = &r->geometry.lo[i], *hi = &r->geometry.hi[i];
        const double old_area = *hi > *lo ? *W * (*hi - *lo) * seg : 0.0;
        before[j] = old_area;
        /* a band already as wide as the patch can make it, over its whole segment, stays */
        if (!(*lo == 0.0 && *hi == 1.0 && *W >= bound * seg)) {
            const double a = whole_ring ? 0.0 : tribo_min(tribo_max(lo_all - k, 0.0), 1.0);
            const double b = whole_ring ? 1.0 : tribo_min(tribo_max(hi_all - k, 0.0), 1.0);
            if (b > a) { /* (a run's end segment may be touched only to rounding) */
                *lo = tribo_min(*lo, a);
                *hi = tribo_max(*hi, b);
                const double w = whole_ring  ? bound
                                 : c->paschen ? mean_width_over(sample, &slices, k, a, b)
                                              : 2.0 * half_width_over(sample, k);
                *W = tribo_max(*W, w * seg);
            }
        }
        const double new_area = *hi > *lo ? *W * (*hi - *lo) * seg : 0.0;
        after[j] = new_area;
        if (new_area > old_area) {
            *area += new_area - old_area;
            const double kept = old_area / new_area;
            for (int m = 0; m < c->n_models; m++)
                if (r->bands[m])
                    r->bands[m][i] = init[m] + (r->bands[m][i] - init[m]) * kept;
        }
    }
}

/* The slices of a run on a ring: [first, first + head) and [0, count - head). */
typedef struct slices {
    long at[2], count[2], k0[2];
    int n;
} slices;

static slices slices_of(const ring *r, long first, long count)
{
    const long head = count < r->len - first ? count : r->len - first;
    slices sl = {{first, 0}, {head, count - head}, {0, head}, count > head ? 2 : 1};
    return sl;
}

/* A model's cylinder values under a sample: the rate law (tau0 > 0) or instantaneous
   transfer (tau0 = 0, §5c), held within the cap (§8b). */
static void charge_values(tribo_charge_slot *slot, const tribo_scene *s, const tribo_charge_forcing *f,
                          double *values, const slices *sl, const double *targets, double cap,
                          double *sum, double *lost)
{
    if (s->tau0 == 0.0) {
        const double target = slot->model->saturation(s, f->end);
        for (int i = 0; i < sl->n; i++)
            *sum += targets ? saturate_each(values + sl->at[i], NULL, sl->count[i],
                                            targets + sl->k0[i], cap, lost)
                            : saturate(values + sl->at[i], NULL, sl->count[i], target, cap, lost);
        return;
    }
    double delta = 0.0, before = 0.0;
    if (isfinite(cap))
        for (int i = 0; i < sl->n; i++)
            before += sum_of(values + sl->at[i], sl->count[i]);
    for (int i = 0; i < sl->n; i++)
        delta += slot->model->charge(slot->cache, s, f, values + sl->at[i], sl->count[i]);
    if (isfinite(cap)) { /* (without a limit, nothing more: the paper's model, bit for bit) */
        double taken = 0.0, after = 0.0;
        for (int i = 0; i < sl->n; i++)
            taken += hold_at_cap(values + sl->at[i], sl->count[i], cap);
        *lost += taken;
        if (taken != 0.0) {
            /* the sum's change from the held values themselves: the model's change less what
               the cap took rounds at the scale the values reach unheld, which a small Sigma_bd
               (1e-14 and below) makes all of the held values' sum */
            for (int i = 0; i < sl->n; i++)
                after += sum_of(values + sl->at[i], sl->count[i]);
            delta = after - before;
        }
    }
    *sum += delta;
}

/* A model's bands under a sample (§8c), weighted by their areas after[] (before[]: before
   the patch widened them). */
static void charge_bands(tribo_charge_slot *slot, const tribo_scene *s, const tribo_charge_forcing *f,
                         double *bands, const slices *sl, const double *before, const double *after,
                         const double *targets, double init, double cap, double *charge,
                         double *lost)
{
    for (int i = 0; i < sl->n; i++) {
        double *b = bands + sl->at[i];
        const long count = sl->count[i];
        const double *w0 = before + sl->k0[i], *w1 = after + sl->k0[i];
        /* the widening kept each band's charge, the new part at the initial density */
        for (long j = 0; j < count; j++)
            *charge += init * (w1[j] - w0[j]);
        if (s->tau0 == 0.0) {
            *charge += targets ? saturate_each(b, w1, count, targets + sl->k0[i], cap, lost)
                               : saturate(b, w1, count, slot->model->saturation(s, f->end), cap, lost);
            continue;
        }
        double old = 0.0;
        for (long j = 0; j < count; j++)
            old += b[j] * w1[j];
        slot->model->charge(slot->cache, s, f, b, count);
        if (isfinite(cap))
            *lost += hold_at_cap_weighted(b, w1, count, cap);
        double now = 0.0;
        for (long j = 0; j < count; j++)
            now += b[j] * w1[j];
        *charge += now - old;
    }
}

/* ---- the Paschen limit (§8e) ------------------------------------------------------------ */

/* The episode's run of bands joined by the run [first, first + count) of a ring. */
static void join_run(tribo_gas_state *g, const ring *r, long first, long count)
{
    if (g->count == 0) {
        g->first = first;
        g->count = count;
        return;
    }
    const long len = r->len;
    if (g->count >= len)
        return;
    long offset = first - g->first;
    if (r->wraps) { /* the nearer way round */
        offset %= len;
        if (offset < 0)
            offset += len;
        if (offset > len / 2)
            offset -= len;
    }
    const long lo = offset < 0 ? offset : 0;
    const long hi = offset + count > g->count ? offset + count : g->count;
    if (hi - lo >= len) {
        g->first = 0;
        g->count = len;
        return;
    }
    g->first += lo;
    if (g->first < 0)
        g->first += len;
    g->count = hi - lo;
}

/* Every band of ring indices [first, first + count) (around the ring) at most limit
   (sliding model's unit) and marked with it; what came down, per model, into t. */
static void bring_down(tribo_charging *c, const tribo_scene *s, const ring *r, long first,
                       long count, double limit, tribo_charge_totals *t)
{
    const double seg = c->segment_length;
    const tribo_band_geometry *geo = &r->geometry;
    for (long j = 0; j < count; j++) {
        const long i = (first + j) % r->len;
        geo->limit[i] = limit;
        const double area = geo->hi[i] > geo->lo[i] ? geo->width[i] * (geo->hi[i] - geo->lo[i]) * seg : 0.0;
        for (int m = 0; m < c->n_models; m++) {
            double *b = r->bands[m];
            if (!b || !c->slot[m].model->density_unit)
                continue;
            const double cap = limit / c->slot[m].model->density_unit(s);
            if (fabs(b[i]) > cap) {
                const double held = b[i] > 0.0 ? cap : -cap;
                t->band_charge[m] -= (b[i] - held) * area;
                t->band_lost[m] += (b[i] - held) * area;
                b[i] = held;
            }
        }
    }
}

/* The episode a sample belongs to (§8e): a new one starts with no region; the sample's run
   joins it; where the sample's largest patch, as the equal-area radius sqrt(Sc S_perp) =
   Sc sqrt(h), widens the region, its limit falls and every other band of the episode comes
   down to it (the run's own are charged within it next, their transfer's excess lost there).
   Returns the bands so visited. */
static long meet_episode(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                         const ring *r, long first, long count, tribo_charge_totals *t)
{
    tribo_gas_state *g = r->gas;
    if (sample->episode != g->episode) {
        g->episode = sample->episode;
        g->radius = 0.0;
        g->limit = INFINITY;
        g->count = 0;
    }
    join_run(g, r, first, count);
    double r2 = 0.0; /* (Sc^2 h in segments^2: one root, where the region grows) */
    for (int i = 0; i < sample->n_patch; i++)
        r2 = tribo_max(r2, sample->patch[i].half * sample->patch[i].half * sample->patch[i].depth);
    const double radius = sqrt(r2) * c->segment_length;
    long visited = 0;
    if (radius > g->radius) {
        g->radius = radius;
        g->limit = tribo_charging_region_limit(c, s, radius);
        /* the run lies in the episode's: [g->first + ahead, + count) */
        long ahead = first - g->first;
        if (ahead < 0)
            ahead += r->len;
        bring_down(c, s, r, g->first, ahead, g->limit, t);
        bring_down(c, s, r, (first + count) % r->len, g->count - ahead - count, g->limit, t);
        visited = g->count - count;
    }
    for (long j = 0; j < count; j++)
        r->geometry.limit[(first + j) % r->len] = g->limit;
    return visited;
}

/* The grain's limit (§8e) on model m after a sample: its charge Q, moved by the sample's
   change of the band charges (less the initial density's share of the area it widened, which
   the uncharged surface gave up), at most grain_limit; the excess is taken back from the
   sample's bands in proportion to what each of them gained (old[]: their densities before
   it), and lost. */
static void hold_grain(const tribo_charging *c, double unit, const ring *r, const slices *sl,
                       int m, double change, const double *old, const double *weights,
                       tribo_charge_totals *t)
{
    tribo_gas_state *g = r->gas;
    const double q = g->grain[m] + change, limit = c->grain_limit / unit;
    g->grain[m] = q;
    if (!(fabs(q) > limit))
        return;
    const double sign = q > 0.0 ? 1.0 : -1.0;
    /* (only from the bands that gained: one the sample brought down stays within its limit) */
    double gained = 0.0;
    for (int i = 0; i < sl->n; i++)
        for (long j = 0; j < sl->count[i]; j++) {
            const long k = sl->k0[i] + j;
            gained += tribo_max(0.0, sign * (r->bands[m][sl->at[i] + j] - old[k])) * weights[k];
        }
    if (!(gained > 0.0))
        return;
    const double f = tribo_min(1.0, (fabs(q) - limit) / gained);
    for (int i = 0; i < sl->n; i++)
        for (long j = 0; j < sl->count[i]; j++) {
            double *b = &r->bands[m][sl->at[i] + j];
            *b -= f * sign * tribo_max(0.0, sign * (*b - old[sl->k0[i] + j]));
        }
    const double taken = sign * f * gained;
    t->band_charge[m] -= taken;
    t->band_lost[m] += taken;
    g->grain[m] = q - taken;
}

/* Charge a sample's run of count segments from ring index first; adds what it changed to t.
   Returns the number of segment values updated. */
static long charge_run(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                       const ring *r, long first, long count, tribo_charge_totals *t)
{
    const slices sl = slices_of(r, first, count);
    /* the sample's own change of the totals, for the grain's limit (§8e) */
    const int paschen = c->paschen && r->geometry.width;
    const double area0 = t->area;
    double band0[TRIBO_CHARGE_MAX_MODELS];
    for (int m = 0; m < c->n_models; m++)
        band0[m] = t->band_charge[m];
    double *before = NULL, *after = NULL;
    if (r->geometry.width) {
        before = c->scratch;
        after = c->scratch + count;
        for (int i = 0; i < sl.n; i++)
            widen_bands(c, s, sample, r, sl.at[i], sl.count[i], sl.k0[i], before + sl.k0[i],
                        after + sl.k0[i], &t->area);
    }
    /* instantaneous transfer where the globals move: each segment's own saturation */
    double *targets[TRIBO_CHARGE_MAX_MODELS] = {0};
    if (s->tau0 == 0.0 && sample->leave_by_edges) {
        for (int m = 0; m < c->n_models; m++)
            targets[m] = r->values[m] ? c->targets + (size_t)m * (size_t)c->n : NULL;
        leave_targets(c, s, sample, count, 0, targets);
    }
    long updates = 0;
    if (paschen)
        updates += meet_episode(c, s, sample, r, first, count, t);
    for (int m = 0; m < c->n_models; m++) {
        tribo_charge_slot *slot = &c->slot[m];
        if (!r->values[m])
            continue;
        const tribo_charge_forcing f = {sample->duration, sample->globals_begin + slot->globals_at,
                                        sample->globals_mid + slot->globals_at,
                                        sample->globals_end + slot->globals_at, &c->decay};
        const double cap = slot_cap(slot, s);
        charge_values(slot, s, &f, r->values[m], &sl, targets[m], cap, &t->sum[m], &t->lost[m]);
        const double init = r->bands[m] ? tribo_charging_initial_value(c, slot->model, s) : 0.0;
        if (r->bands[m] && paschen && slot->model->density_unit) {
            double *old = c->scratch + 2 * count;
            for (int i = 0; i < sl.n; i++)
                memcpy(old + sl.k0[i], r->bands[m] + sl.at[i], (size_t)sl.count[i] * sizeof *old);
            const double unit = slot->model->density_unit(s);
            charge_bands(slot, s, &f, r->bands[m], &sl, before, after, targets[m], init,
                         r->gas->limit / unit, &t->band_charge[m], &t->band_lost[m]);
            hold_grain(c, unit, r, &sl, m, t->band_charge[m] - band0[m] - init * (t->area - area0),
                       old, after, t);
        } else if (r->bands[m]) {
            charge_bands(slot, s, &f, r->bands[m], &sl, before, after, targets[m], init, cap,
                         &t->band_charge[m], &t->band_lost[m]);
        }
        updates += count;
    }
    return updates;
}

/* The instance's arrays (committed, or their output copies) as a ring. */
static ring ring_of(tribo_charging *c, tribo_charge_destination where)
{
    ring r = {.len = c->n, .wraps = 1,
              .gas = where == TRIBO_CHARGE_COMMIT ? &c->gas : &c->gas_out};
    for (int m = 0; m < c->n_models; m++) {
        const tribo_charge_slot *slot = &c->slot[m];
        if (!slot->selected)
            continue;
        r.values[m] = where == TRIBO_CHARGE_COMMIT ? slot->segments : slot->segments_out;
        r.bands[m] = where == TRIBO_CHARGE_COMMIT ? slot->bands : slot->bands_out;
    }
    r.geometry = where == TRIBO_CHARGE_COMMIT ? c->bands : c->bands_out;
    return r;
}

long tribo_charging_capped(const tribo_charge_slot *slot, const tribo_scene *s, const double *values,
                           long n)
{
    const double cap = cap_of(slot, s);
    long capped = 0;
    if (isfinite(cap))
        for (long i = 0; i < n; i++)
            capped += fabs(values[i]) >= cap; /* held values are the cap exactly */
    return capped;
}

double tribo_charging_capped_area(const tribo_charging *c, const tribo_charge_slot *slot,
                                  const tribo_scene *s, const double *bands,
                                  const tribo_band_geometry *g)
{
    double area = 0.0;
    if (c->paschen && slot->model->density_unit) {
        /* each band at the limit of the episode that last touched it (§8e) */
        const double unit = slot->model->density_unit(s);
        for (long i = 0; i < c->n; i++)
            if (fabs(bands[i]) >= g->limit[i] / unit && g->hi[i] > g->lo[i])
                area += g->width[i] * (g->hi[i] - g->lo[i]) * c->segment_length;
        return area;
    }
    const double cap = cap_of(slot, s);
    if (isfinite(cap))
        for (long i = 0; i < c->n; i++)
            if (fabs(bands[i]) >= cap && g->hi[i] > g->lo[i])
                area += g->width[i] * (g->hi[i] - g->lo[i]) * c->segment_length;
    return area;
}

static void commit_totals(tribo_charging *c, const tribo_charge_totals *t)
{
    for (int m = 0; m < c->n_models; m++) {
        if (!c->slot[m].selected)
            continue;
        tribo_compensated_add(&c->sum[m], t->sum[m]);
        if (t->lost[m] != 0.0)
            tribo_compensated_add(&c->lost[m], t->lost[m]);
        if (c->keep_bands) {
            tribo_compensated_add(&c->band_charge[m], t->band_charge[m]);
            if (t->band_lost[m] != 0.0)
                tribo_compensated_add(&c->band_lost[m], t->band_lost[m]);
        }
    }
    if (c->keep_bands && t->area != 0.0)
        tribo_compensated_add(&c->area, t->area);
}

long tribo_charging_apply(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                          tribo_charge_destination where)
{
    long first;
    const long count = segment_run(sample, &first);
    if (count <= 0)
        return 0;
    const ring r = ring_of(c, where);
    tribo_charge_totals t = {0};
    const long updates = charge_run(c, s, sample, &r, first, count, &t);
    if (where == TRIBO_CHARGE_COMMIT)
        commit_totals(c, &t);
    return updates;
}

static int copy_array(double **out, const double *in, int n)
{
    if (!in)
        return 0;
    if (!*out && !(*out = malloc((size_t)n * sizeof(double))))
        return -1;
    memcpy(*out, in, (size_t)n * sizeof(double));
    return 0;
}

int tribo_charging_copy_out(tribo_charging *c)
{
    for (int m = 0; m < c->n_models; m++) {
        tribo_charge_slot *slot = &c->slot[m];
        if (copy_array(&slot->segments_out, slot->segments, c->n) ||
            copy_array(&slot->bands_out, slot->bands, c->n))
            return -1;
    }
    if (copy_array(&c->bands_out.width, c->bands.width, c->n) ||
        copy_array(&c->bands_out.lo, c->bands.lo, c->n) ||
        copy_array(&c->bands_out.hi, c->bands.hi, c->n) ||
        copy_array(&c->bands_out.limit, c->bands.limit, c->n))
        return -1;
    c->gas_out = c->gas;
    return 0;
}

/* The pending samples' runs lie in one window of the ring (the contact moves
   continuously): the window of every array is copied once and charged in place of the
   ring. */
int tribo_charging_pending_totals(tribo_charging *c, const tribo_scene *s,
                                  const tribo_contact_sample *samples, size_t n_samples,
                                  tribo_charge_totals *totals)
{
    const long n = c->n;
    long anchor = -1, lo = 0, hi = 0; /* the window [anchor + lo, anchor + hi), unwrapped */
    /* with the Paschen limit, the episode's bands too: a sample may bring them down (§8e) */
    const int episode = c->paschen && c->gas.count > 0;
    int any_sample = 0;
    for (size_t i = 0; i < n_samples + (size_t)episode; i++) {
        long first = 0;
        const long count = i == n_samples ? (first = c->gas.first, c->gas.count)
                                          : segment_run(&samples[i], &first);
        if (!count)
            continue;
        any_sample |= i < n_samples;
        if (anchor < 0) {
            anchor = first;
            hi = count;
            continue;
        }
        long offset = (first - anchor) % n;
        if (offset < 0)
            offset += n;
        if (offset > n / 2)
            offset -= n; /* just before the anchor */
        lo = offset < lo ? offset : lo;
        hi = offset + count > hi ? offset + count : hi;
    }
    memset(totals, 0, sizeof *totals);
    if (!any_sample)
        return 0;
    const long len = hi - lo < n ? hi - lo : n;
    long start = len < n ? (anchor + lo) % n : 0;
    if (start < 0)
        start += n;
    /* the arrays of the window, side by side in one allocation */
    size_t arrays = 0;
    for (int m = 0; m < c->n_models; m++)
        arrays += (c->slot[m].segments != NULL) + (c->slot[m].bands != NULL);
    if (c->keep_bands)
        arrays += 3 + (c->paschen != 0);
    if (c->window_cap < arrays * (size_t)len) {
        double *w = realloc(c->window, arrays * (size_t)len * sizeof *w);
        if (!w)
            return -1;
        c->window = w;
        c->window_cap = arrays * (size_t)len;
    }
    tribo_gas_state gas = c->gas;
    if (episode) { /* the episode's run in the window's indices */
        gas.first = (gas.first - start) % n;
        if (gas.first < 0)
            gas.first += n;
    }
    ring r = {.len = len, .wraps = len == n, .gas = &gas};
    double *next = c->window;
    const long head = len < n - start ? len : n - start;
#define WINDOW_OF(dst, src)                                                                      \
    do {                                                                                         \
        if (src) {                                                                               \
            memcpy(next, (src) + start, (size_t)head * sizeof(double));                          \
            memcpy(next + head, (src), (size_t)(len - head) * sizeof(double));                   \
            (dst) = next;                                                                        \
            next += len;                                                                         \
        }                                                                                        \
    } while (0)
    for (int m = 0; m < c->n_models; m++) {
        WINDOW_OF(r.values[m], c->slot[m].segments);
        WINDOW_OF(r.bands[m], c->slot[m].bands);
    }
    if (c->keep_bands) {
        WINDOW_OF(r.geometry.width, c->bands.width);
        WINDOW_OF(r.geometry.lo, c->bands.lo);
        WINDOW_OF(r.geometry.hi, c->bands.hi);
        if (c->paschen)
            WINDOW_OF(r.geometry.limit, c->bands.limit);
    }
#undef WINDOW_OF
    for (size_t i = 0; i < n_samples; i++) {
        long first;
        const long count = segment_run(&samples[i], &first);
        if (!count)
            continue;
        long offset = (first - start) % n;
        if (offset < 0)
            offset += n;
        /* in a window shorter than the ring a run never wraps: it lies inside */
        charge_run(c, s, &samples[i], &r, offset, count, totals);
    }
    return 0;
}
