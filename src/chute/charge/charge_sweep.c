/* charge_sweep.c: charging along a contact seen through an integrator's dense output,
   exact in the time each segment spends in contact (docs/model.md §5). */
#include "charging.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The contact at one time; the centre is unwrapped against a neighbouring point, so that
   the edges move continuously across the start of the numbering. */
typedef struct probe_point {
    double t, lo, hi, speed;
    double depth; /* h: the patch's half-width is h Sc (model.md §8c) */
    double rates[TRIBO_CHARGE_MAX_QUADRATURES];
    double quadratures[TRIBO_CHARGE_MAX_QUADRATURES]; /* known at the ends of accepted pieces */
} probe_point;

typedef struct sweep {
    tribo_charging *c;
    const tribo_scene *s;
    const tribo_contact_probe *probe;
    double perimeter, seg; /* perimeter, segment length */
    double rtol;
    int instant;   /* instantaneous transfer (tau0 = 0, model.md §5c) */
    int reach;     /* the most segments an edge may cross within one piece */
    int emitted;   /* whether a sample has gone to the sink (saturated_piece) */
    tribo_sample_sink sink;
    void *sink_ctx;
    int status;
    double cost; /* probes and covered segments so far (tribo_charging_sweep's budget) */
    double cell_cost; /* what covering one segment adds to cost */
} sweep;

static probe_point probe_at(sweep *w, double t, const probe_point *near)
{
    double s_c, half, speed;
    tribo_contact_kinematics k;
    w->probe->at(w->probe->ctx, t, &s_c, &half, &speed, &k);
    w->cost += 1.0;
    if (near)
        s_c -= w->perimeter * floor((s_c - 0.5 * (near->lo + near->hi)) / w->perimeter + 0.5);
    probe_point pt = {t, s_c - half, s_c + half, speed, k.h, {0}, {0}};
    tribo_charging_quadrature_rates(w->c, &k, pt.rates);
    return pt;
}

static double edge_of(const probe_point *p, int hi_edge) { return hi_edge ? p->hi : p->lo; }

/* The probes of a piece: its start, quarter, middle, three-quarter and end points. */
enum { PIECE_POINTS = 5 };

/* One edge over a piece, for locating its crossings: its values e at the piece's points, and
   the weights of the inverse interpolating polynomials t(e) through all of them and through
   the start, middle and end (Lagrange form, in times from the piece's start so that the sum
   keeps the digits of a short piece at a late time). */
typedef struct edge_fit {
    int hi_edge;
    double e[PIECE_POINTS];
    int monotone; /* strictly, through all the points */
    double w_all[PIECE_POINTS], w_ends[3];
} edge_fit;

static const int ALL_POINTS[PIECE_POINTS] = {0, 1, 2, 3, 4}, END_POINTS[3] = {0, 2, 4};

/* Lagrange weights w_i = t_i / prod_{j != i} (e_i - e_j) of the points idx[0..n). */
static void lagrange_weights(const edge_fit *f, const probe_point *pts, const int *idx, int n,
                             double *w)
{
    for (int i = 0; i < n; i++) {
        double d = 1.0;
        for (int j = 0; j < n; j++)
            if (j != i)
                d *= f->e[idx[i]] - f->e[idx[j]];
        w[i] = (pts[idx[i]].t - pts[0].t) / d;
    }
}

static void fit_edge(edge_fit *f, const probe_point *pts, int hi_edge)
{
    f->hi_edge = hi_edge;
    for (int i = 0; i < PIECE_POINTS; i++)
        f->e[i] = edge_of(&pts[i], hi_edge);
    const double travel = f->e[PIECE_POINTS - 1] - f->e[0];
    f->monotone = 1;
    for (int i = 1; i < PIECE_POINTS; i++)
        f->monotone = f->monotone && (f->e[i] - f->e[i - 1]) * travel > 0.0;
    if (!f->monotone)
        return;
    lagrange_weights(f, pts, ALL_POINTS, PIECE_POINTS, f->w_all);
    lagrange_weights(f, pts, END_POINTS, 3, f->w_ends);
}

/* The inverse interpolating polynomial at x, in time from the piece's start:
   sum_i w_i prod_{j != i} (x - e_j) over the points idx[0..n). */
static double inverse_at(const edge_fit *f, const int *idx, int n, const double *w, double x)
{
    double d[PIECE_POINTS], before[PIECE_POINTS], after = 1.0, sum = 0.0;
    before[0] = 1.0;
    for (int i = 0; i < n; i++) {
        d[i] = x - f->e[idx[i]];
        if (i + 1 < n)
            before[i + 1] = before[i] * d[i];
    }
    for (int i = n - 1; i >= 0; i--) {
        sum += w[i] * before[i] * after;
        after *= d[i];
    }
    return sum;
}

/* When an edge, moving monotonically through the piece's points, crosses the boundary at x,
   to rtol of the piece's duration. The five points give it without a further probe where the
   edge is smooth: the inverse quartic through them, taken where it agrees with the inverse
   quadratic through the start, middle and end (an estimate of the quadratic's error, the
   quartic's being far smaller) to within that tolerance. Otherwise the quartic's estimate is
   checked on the probe, and then, if needed, the Illinois variant of regula falsi from the
   tightest bracket. */
static double crossing(sweep *w, const probe_point *pts, const edge_fit *f, double x)
{
    const probe_point *first = &pts[0], *last = &pts[PIECE_POINTS - 1];
    const double tol = w->rtol * (last->t - first->t) + 1e-15 * fabs(last->t);
    const double travel = f->e[PIECE_POINTS - 1] - f->e[0];
    /* the bracket: the neighbouring points between which a monotone edge passes x, else
       the piece */
    int k = 0, l = PIECE_POINTS - 1;
    if (f->monotone) {
        while (k < PIECE_POINTS - 2 && (f->e[k + 1] - x) * travel < 0.0)
            k++;
        l = k + 1;
    }
    probe_point a = pts[k], b = pts[l];
    double fa = f->e[k] - x, fb = f->e[l] - x;
    if (f->monotone) {
        const double quartic = first->t + inverse_at(f, ALL_POINTS, PIECE_POINTS, f->w_all, x);
        const double quadratic = first->t + inverse_at(f, END_POINTS, 3, f->w_ends, x);
        if (quartic > a.t && quartic < b.t) {
            if (fabs(quartic - quadratic) <= tol)
                return quartic;
            const probe_point p = probe_at(w, quartic, &a);
            const double fp = edge_of(&p, f->hi_edge) - x;
            if (fabs(fp) <= fabs(travel) / (last->t - first->t) * tol)
                return quartic;
            if ((fp > 0) == (fb > 0)) {
                b = p;
                fb = fp;
            } else {
                a = p;
                fa = fp;
            }
        }
    }
    int side = 0;
    for (int it = 0; it < 100 && b.t - a.t > tol; it++) {
        double tm = (a.t * fb - b.t * fa) / (fb - fa);
        if (!(tm > a.t && tm < b.t))
            tm = 0.5 * (a.t + b.t);
        const probe_point p = probe_at(w, tm, &a);
        const double fp = edge_of(&p, f->hi_edge) - x;
        if ((fp > 0) == (fb > 0)) {
            b = p;
            fb = fp;
            if (side == -1)
                fa *= 0.5;
            side = -1;
        } else {
            a = p;
            fa = fp;
            if (side == +1)
                fb *= 0.5;
            side = +1;
        }
    }
    return 0.5 * (a.t + b.t);
}

/* How many segment boundaries an edge may cross within one piece: each crossing is
   located on its own, so a piece may span several; fewer pieces, fewer probes. With
   instantaneous transfer (model.md §5c) a piece whose globals hold still is charged whole,
   without locating its crossings, and may span more. */
#define SEGMENTS_PER_PIECE 8
#define SEGMENTS_PER_INSTANT_PIECE 64
/* A piece left as it is (saturated_piece) needs no crossings: it may span a CVODE step's
   travel of a rolling grain (0.2 rad of spin, 64 of the default 2000 segments) and more. */
#define SEGMENTS_PER_SATURATED_PIECE 256
#define MAX_CUTS (2 * SEGMENTS_PER_INSTANT_PIECE + 2)

/* A boundary crossing inside a piece: when, and which edge's segment index moves how. */
typedef struct cut {
    double t;
    int hi_edge, step;
} cut;

/* The cuts in time order. Each edge's come in order already (in order of the boundaries it
   crosses, reversed where it moves down), so an insertion sort costs what interleaving the
   two edges' lists takes. */
static void sort_cuts(cut *cuts, int n)
{
    for (int i = 1; i < n; i++) {
        const cut c = cuts[i];
        int j = i;
        for (; j > 0 && cuts[j - 1].t > c.t; j--)
            cuts[j] = cuts[j - 1];
        cuts[j] = c;
    }
}

static int inside(double e0, double em, double e1)
{
    const double slack = 1e-12 * (fabs(e0) + fabs(e1) + 1.0);
    return em >= tribo_min(e0, e1) - slack && em <= tribo_max(e0, e1) + slack;
}

/* The patch (model.md §8c) within a piece, for the grain's bands: the edges and the depth
   at any time, interpolated through the piece's points (barycentric, equispaced nodes) and
   held within their range over the points. */
typedef struct patch_fit {
    const probe_point *pts;
    double lo_range[2], hi_range[2], depth_range[2];
} patch_fit;

static void fit_patch(patch_fit *f, const probe_point *pts)
{
    f->pts = pts;
    f->lo_range[0] = f->hi_range[0] = f->depth_range[0] = INFINITY;
    f->lo_range[1] = f->hi_range[1] = f->depth_range[1] = -INFINITY;
    for (int i = 0; i < PIECE_POINTS; i++) {
        f->lo_range[0] = tribo_min(f->lo_range[0], pts[i].lo);
        f->lo_range[1] = tribo_max(f->lo_range[1], pts[i].lo);
        f->hi_range[0] = tribo_min(f->hi_range[0], pts[i].hi);
        f->hi_range[1] = tribo_max(f->hi_range[1], pts[i].hi);
        f->depth_range[0] = tribo_min(f->depth_range[0], pts[i].depth);
        f->depth_range[1] = tribo_max(f->depth_range[1], pts[i].depth);
    }
}

/* The edges and depth at time t: out[0] lo, out[1] hi, out[2] depth. */
static void patch_at(const patch_fit *f, double t, double *out)
{
    /* barycentric weights of five equispaced nodes: (-1)^i C(4, i) */
    static const double W[PIECE_POINTS] = {1.0, -4.0, 6.0, -4.0, 1.0};
    const probe_point *p = f->pts;
    double num[3] = {0.0, 0.0, 0.0}, den = 0.0;
    for (int i = 0; i < PIECE_POINTS; i++) {
        if (t == p[i].t) {
            out[0] = p[i].lo;
            out[1] = p[i].hi;
            out[2] = p[i].depth;
            return;
        }
        const double c = W[i] / (t - p[i].t);
        num[0] += c * p[i].lo;
        num[1] += c * p[i].hi;
        num[2] += c * p[i].depth;
        den += c;
    }
    out[0] = tribo_min(tribo_max(num[0] / den, f->lo_range[0]), f->lo_range[1]);
    out[1] = tribo_min(tribo_max(num[1] / den, f->hi_range[0]), f->hi_range[1]);
    out[2] = tribo_min(tribo_max(num[2] / den, f->depth_range[0]), f->depth_range[1]);
}

/* A patch point from edges and depth, in segments from the segment `origin`. */
static tribo_patch_point patch_point(const sweep *w, const double *e, double origin)
{
    const double lo = e[0] / w->seg, hi = e[1] / w->seg;
    return (tribo_patch_point){0.5 * (lo + hi) - origin, 0.5 * (hi - lo), e[2]};
}

/* Whether the globals hold still over a piece (each the same at its start, middle and end). */
static int still(int n, const double *S0, const double *S1, const double *S2)
{
    for (int g = 0; g < n; g++)
        if (!(S0[g] == S1[g] && S1[g] == S2[g]))
            return 0;
    return 1;
}

/* An edge's extreme over a piece (the upper edge's highest, the lower's lowest), where it
   turns between the piece's points: the vertex of the parabola through the extreme point and
   its neighbours, probed there. The points alone can miss the far end of a contact's reach by
   the edge's curvature times the square of their spacing, and with it a segment the contact
   covers. Without such a turn, the extreme point's own value. */
static double edge_extreme(sweep *w, const probe_point *pts, int hi_edge)
{
    const double sign = hi_edge ? 1.0 : -1.0;
    int k = 0;
    for (int i = 1; i < PIECE_POINTS; i++)
        if (sign * edge_of(&pts[i], hi_edge) > sign * edge_of(&pts[k], hi_edge))
            k = i;
    const int c = k == 0 ? 1 : k == PIECE_POINTS - 1 ? PIECE_POINTS - 2 : k;
    const double e0 = edge_of(&pts[c - 1], hi_edge), e1 = edge_of(&pts[c], hi_edge),
                 e2 = edge_of(&pts[c + 1], hi_edge), best = edge_of(&pts[k], hi_edge);
    const double curvature = e0 - 2.0 * e1 + e2;
    if (!(sign * curvature < 0.0))
        return best;
    /* the vertex, in spacings of the points from the middle one */
    const double u = 0.5 * (e0 - e2) / curvature;
    if (!(fabs(u) < 1.0) || (k != c && (k < c) != (u < 0.0)))
        return best;
    const double t = pts[c].t + u * (pts[c + 1].t - pts[c].t);
    const probe_point p = probe_at(w, t, &pts[c]);
    const double e = edge_of(&p, hi_edge);
    return sign * e > sign * best ? e : best;
}

/* Instantaneous transfer over a piece (model.md §5c): every segment the contact covers
   within it is at its saturation at once, whenever it was covered, and keeps the
   saturation of the time it left, so the piece is one sample over the union of the
   contact's positions (the edges' extremes over its points; a piece's edges move
   monotonically), with the patch at its five points, from which the charging finds when
   each segment left (leave_by_edges) where the globals move. S0, S1, S2: the globals at the
   piece's start, middle and end. */
static void charge_whole_piece(sweep *w, const probe_point *pts, const double *S0, const double *S1,
                               const double *S2)
{
    const probe_point *a = &pts[0], *b = &pts[PIECE_POINTS - 1];
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < PIECE_POINTS; i++) {
        lo = tribo_min(lo, pts[i].lo);
        hi = tribo_max(hi, pts[i].hi);
    }
    lo = tribo_min(lo, edge_extreme(w, pts, 0));
    hi = tribo_max(hi, edge_extreme(w, pts, 1));
    tribo_contact_sample s;
    s.duration = b->t - a->t;
    const double first = floor(lo / w->seg);
    tribo_charging_run(w->c, first, floor(hi / w->seg), &s);
    const int n_globals = w->c->n_globals;
    s.leave_by_edges = !still(n_globals, S0, S1, S2);
    s.n_patch = 0;
    if (w->c->keep_bands || s.leave_by_edges) {
        s.n_patch = PIECE_POINTS;
        for (int i = 0; i < PIECE_POINTS; i++) {
            const double e[3] = {pts[i].lo, pts[i].hi, pts[i].depth};
            s.patch[i] = patch_point(w, e, first);
        }
    }
    memcpy(s.globals_begin, S0, (size_t)n_globals * sizeof *S0);
    memcpy(s.globals_mid, S1, (size_t)n_globals * sizeof *S1);
    memcpy(s.globals_end, S2, (size_t)n_globals * sizeof *S2);
    w->status = w->sink(w->sink_ctx, &s);
    w->cost += w->cell_cost * tribo_min((double)s.count, w->c->n);
}

/* The boundary crossings of both edges within a piece, in time order: each crossing moves
   one edge by one segment (step +1 or -1). Returns how many (at most MAX_CUTS). */
static int locate_cuts(sweep *w, const probe_point *pts, cut *cuts)
{
    const probe_point *a = &pts[0], *b = &pts[PIECE_POINTS - 1];
    int n = 0;
    for (int edge = 0; edge < 2; edge++) {
        const double e0 = edge_of(a, edge), e1 = edge_of(b, edge);
        const int step = e1 > e0 ? 1 : -1;
        const double lo = tribo_min(e0, e1), hi = tribo_max(e0, e1);
        edge_fit fit;
        fit_edge(&fit, pts, edge);
        const int from = n;
        for (double k = floor(lo / w->seg) + 1; k * w->seg < hi && n < MAX_CUTS; k++) {
            const cut c = {crossing(w, pts, &fit, k * w->seg), edge, step};
            cuts[n++] = c;
        }
        for (int i = from, j = n - 1; step < 0 && i < j; i++, j--) {
            const cut swap = cuts[i];
            cuts[i] = cuts[j];
            cuts[j] = swap;
        }
    }
    sort_cuts(cuts, n);
    return n;
}

/* Each global within a piece as the quadratic S0 + u (c1 + u c2), u in [0, 1], through its
   start, middle and end; one that holds still (as Sigma_s without work) exactly still:
   its coefficients would be rounding. */
static void globals_quadratic(int n_globals, const double *S0, const double *S1,
                              const double *S2, double *c1, double *c2)
{
    for (int g = 0; g < n_globals; g++) {
        const int flat = S0[g] == S1[g] && S1[g] == S2[g];
        c1[g] = flat ? 0.0 : -3.0 * S0[g] + 4.0 * S1[g] - S2[g];
        c2[g] = flat ? 0.0 : 2.0 * (S0[g] - 2.0 * S1[g] + S2[g]);
    }
}

/* How close to its saturation a segment must be for a piece to leave it as it is
   (saturated_piece): 16 units of rounding of the saturation. */
#define SATURATED_ULPS 16.0

/* Whether every selected model's committed value of the segments lo_segment ... hi_segment
   (numbers that wrap around the ring) is within SATURATED_ULPS of its saturation at the
   globals g, the breakdown limit holding none of them back. Returns how many segments that
   is (0: not all of them are). */
static long run_saturated(const sweep *w, double lo_segment, double hi_segment, const double *g)
{
    const tribo_charging *c = w->c;
    tribo_contact_sample run;
    tribo_charging_run(c, lo_segment, hi_segment, &run);
    const long head = tribo_min(run.count, c->n - run.first);
    for (int m = 0; m < c->n_models; m++) {
        const tribo_charge_slot *slot = &c->slot[m];
        if (!slot->selected)
            continue;
        const double target = slot->model->saturation(w->s, g + slot->globals_at);
        const double cap = slot->model->density_unit
                               ? w->s->Sigma_bd / slot->model->density_unit(w->s)
                               : INFINITY;
        if (!(fabs(target) < cap))
            return 0;
        const double tol = SATURATED_ULPS * DBL_EPSILON * fabs(target);
        for (long i = 0; i < run.count; i++) {
            const double v = slot->segments[i < head ? run.first + i : i - head];
            if (!(fabs(v - target) <= tol))
                return 0;
        }
    }
    return run.count;
}

/* Whether a piece may leave every segment it covers as it is: the rate law (§5a, §5b, tau0 >
   0) moves a segment only towards its saturation, which the globals fix, so where they hold
   still over the piece and each segment under the contact is within SATURATED_ULPS of it,
   charging the piece would change no segment by more than that (a rolling grain's boundary,
   charged turn after turn, sits there: its segments are held a unit or two of rounding off
   the saturation, where each sample's update rounds back to the value it had). Only for a
   contact that moves on, farther than its width and a segment over the piece (what is saved
   is locating the crossings and charging the samples between them; a grain at rest keeps
   its samples). Not for the grain's bands (their area grows), not where the breakdown limit
   holds the saturation back, and only before the sweep has given its sink a sample: the
   committed values read here are then those the sweep's samples apply to, whether the sink
   applies them at once or keeps them pending. */
static int saturated_piece(sweep *w, const probe_point *pts, const double *S0, const double *S1,
                           const double *S2)
{
    const tribo_charging *c = w->c;
    const probe_point *a = &pts[0], *b = &pts[PIECE_POINTS - 1];
    if (w->instant || w->emitted || c->keep_bands || !still(c->n_globals, S0, S1, S2) ||
        !(fabs(b->lo - a->lo) >= tribo_max(a->hi - a->lo, b->hi - b->lo) + w->seg))
        return 0;
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < PIECE_POINTS; i++) {
        lo = tribo_min(lo, pts[i].lo);
        hi = tribo_max(hi, pts[i].hi);
    }
    const long count = run_saturated(w, floor(lo / w->seg), floor(hi / w->seg), S0);
    w->cost += w->cell_cost * (double)count;
    return count > 0;
}

/* Whether the sweep's first trial piece may be a saturated piece's: the segments under the
   contact at the start are saturated (saturated_piece) at the globals there. */
static int saturated_here(const sweep *w, const probe_point *at, const double *globals)
{
    if (w->instant || w->c->keep_bands)
        return 0;
    return run_saturated(w, floor(at->lo / w->seg), floor(at->hi / w->seg), globals) > 0;
}

/* A piece in which each edge moves monotonically by at most w->reach segments and the
   globals are quadratic to the tolerances: locate the boundary crossings, and charge the
   parts between them, each with its fixed set of segments (§5a, §5b). pts: the piece's
   points (PIECE_POINTS); S0, S1, S2: the globals at its start, middle and end. */
static void charge_piece(sweep *w, const probe_point *pts, const double *S0, const double *S1,
                         const double *S2)
{
    const int n_globals = w->c->n_globals;
    if (w->instant) {
        charge_whole_piece(w, pts, S0, S1, S2);
        return;
    }
    w->emitted = 1;
    const probe_point *a = &pts[0], *b = &pts[PIECE_POINTS - 1];
    cut cuts[MAX_CUTS];
    const int n = locate_cuts(w, pts, cuts);
    double cell[2] = {floor(a->lo / w->seg), floor(a->hi / w->seg)};
    double c1[TRIBO_CHARGE_MAX_GLOBALS], c2[TRIBO_CHARGE_MAX_GLOBALS];
    globals_quadratic(n_globals, S0, S1, S2, c1, c2);
    /* The segments from the lower edge's to the upper edge's, as the cuts so far have
       moved them: the run is located once (a division and a floor), then each cut steps it
       around the ring in integers; a contact as wide as the ring, or one far off the
       numbering, is located afresh for each sample. */
    const long ring = w->c->n;
    tribo_contact_sample s;
    s.leave_by_edges = 0;
    tribo_charging_run(w->c, cell[0], cell[1], &s);
    const int stepped = s.count < ring && fabs(cell[0]) < 0x1p52;
    long first = s.first, span = s.count;
    /* the patch at each sample's ends, for the grain's bands */
    const int bands = w->c->keep_bands;
    patch_fit patch = {0};
    double at_start[3] = {a->lo, a->hi, a->depth}, at_end[3];
    if (bands)
        fit_patch(&patch, pts);
    s.n_patch = bands ? 2 : 0;

    const double T = b->t - a->t;
    double t0 = a->t;
    for (int i = 0; i <= n && !w->status; i++) {
        const double t1 = i < n ? cuts[i].t : b->t;
        if (t1 > t0) {
            const double u0 = (t0 - a->t) / T, u1 = (t1 - a->t) / T;
            const double um = 0.5 * (u0 + u1);
            s.duration = t1 - t0;
            if (!stepped) {
                tribo_charging_run(w->c, cell[0], cell[1], &s);
            } else if (span < ring) {
                s.first = first;
                s.count = span;
            } else {
                s.first = 0;
                s.count = ring;
            }
            for (int g = 0; g < n_globals; g++) {
                s.globals_begin[g] = S0[g] + u0 * (c1[g] + u0 * c2[g]);
                s.globals_mid[g] = S0[g] + um * (c1[g] + um * c2[g]);
                s.globals_end[g] = S0[g] + u1 * (c1[g] + u1 * c2[g]);
            }
            if (bands) {
                patch_at(&patch, t1, at_end);
                s.patch[0] = patch_point(w, at_start, cell[0]);
                s.patch[1] = patch_point(w, at_end, cell[0]);
                memcpy(at_start, at_end, sizeof at_end);
            }
            w->status = w->sink(w->sink_ctx, &s);
            w->cost += w->cell_cost * tribo_min(cell[1] - cell[0] + 1.0, w->c->n);
            t0 = t1;
        }
        if (i < n) {
            const int step = cuts[i].step;
            cell[cuts[i].hi_edge] += step;
            if (cuts[i].hi_edge) {
                span += step;
            } else {
                span -= step;
                first += step;
                first += first < 0 ? ring : first >= ring ? -ring : 0;
            }
        }
    }
}

/* Whether any selected model integrates or carries something along the contact. */
static int has_states(const tribo_charging *c)
{
    for (int i = 0; i < c->n_models; i++)
        if (c->slot[i].selected && (c->slot[i].model->n_quadratures || c->slot[i].model->n_globals))
            return 1;
    return 0;
}

/* The quadratures over a piece by Simpson on the halves against Simpson on the whole, to
   the tolerances CVODE holds the motion to: rtol of the piece's increment, atol per unit
   time (a rate can be ~0 and noisy, as the work rate in stick, and can go as
   sqrt(delta_y) at the ends of a contact). Fills q_mid and q_end from cur's; returns
   whether all are accurate. Then the globals follow (each model's piece_globals). */
static int advance_states(sweep *w, const probe_point *pts, double h, double rtol, double atol,
                          double *q_end, const double *g0, double *g_mid, double *g_end)
{
    const tribo_charging *c = w->c;
    const probe_point *cur = &pts[0], *m = &pts[2], *next = &pts[4];
    const probe_point q1 = pts[1], q3 = pts[3];
    double rates[TRIBO_CHARGE_MAX_QUADRATURES][5];
    double q_mid[TRIBO_CHARGE_MAX_QUADRATURES];
    int ok = 1;
    for (int k = 0; k < c->n_quadratures; k++) {
        const double whole = h / 6.0 * (cur->rates[k] + 4.0 * m->rates[k] + next->rates[k]);
        const double left = h / 12.0 * (cur->rates[k] + 4.0 * q1.rates[k] + m->rates[k]);
        const double right = h / 12.0 * (m->rates[k] + 4.0 * q3.rates[k] + next->rates[k]);
        const double halves = left + right;
        ok = ok && fabs(halves - whole) <= 15.0 * (rtol * fabs(halves) + atol * h);
        q_mid[k] = cur->quadratures[k] + left;
        q_end[k] = cur->quadratures[k] + halves + (halves - whole) / 15.0;
        const double r[5] = {cur->rates[k], q1.rates[k], m->rates[k], q3.rates[k], next->rates[k]};
        memcpy(rates[k], r, sizeof r);
    }
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        if (!slot->selected || !slot->model->n_globals)
            continue;
        const int qa = slot->quadratures_at, ga = slot->globals_at;
        ok = ok && slot->model->piece_globals(slot->cache, w->s, h, (const double(*)[5])rates + qa,
                                              cur->quadratures + qa, q_mid + qa, q_end + qa,
                                              g0 + ga, g_mid + ga, g_end + ga, rtol, atol);
    }
    return ok;
}

int tribo_charging_sweep(tribo_charging *c, const tribo_scene *s, const tribo_contact_probe *probe,
                         double a, double b, double rtol, double atol, double *quadratures,
                         double *globals, tribo_sample_sink sink, void *sink_ctx, double budget,
                         double cell_cost, double *reached)
{
    if (reached)
        *reached = b;
    if (!(b > a))
        return 0;
    const int instant = s->tau0 == 0.0;
    sweep w = {c,        s,
               probe,    c->arc.perimeter,
               c->arc.perimeter / c->n, rtol,
               instant,  SEGMENTS_PER_PIECE,
               0,
               sink,     sink_ctx,
               0,        0.0,
               cell_cost};
    const size_t q_bytes = (size_t)c->n_quadratures * sizeof(double);
    const size_t g_bytes = (size_t)c->n_globals * sizeof(double);
    const int with_states = has_states(c);
    /* Left to right in pieces; a trial piece is at most the time the centre takes, at its
       speed at the start, to travel one segment less than a piece may span (so that a contact
       that speeds up stays within it), halved until the piece is regular, and grown after
       each accepted one. */
    probe_point cur = probe_at(&w, a, NULL);
    memcpy(cur.quadratures, quadratures, q_bytes);
    const double min_piece = 1e-13 * (1.0 + fabs(b));
    double trial = b - a;
    /* Where the boundary under the contact is saturated, a trial piece may be as long as a
       saturated piece (saturated_piece). One that turns out not to be is dropped, its probes'
       cost with it, and tried again as long as a piece that is charged: at the sweep's start
       the sweep starts again as it would have without the hope, piece for piece. */
    int hopeful = saturated_here(&w, &cur, globals);
    const double cost_at_start = w.cost;
    while (cur.t < b && !w.status) {
        w.reach = hopeful ? SEGMENTS_PER_SATURATED_PIECE
                          : instant ? SEGMENTS_PER_INSTANT_PIECE : SEGMENTS_PER_PIECE;
        if (cur.speed > 0.0)
            trial = tribo_min(trial, (w.reach - 1) * w.seg / cur.speed);
        /* within min_piece of b, go to b: the piece then is at most trial + min_piece */
        const double t1 = cur.t + trial >= b - min_piece ? b : cur.t + trial;
        const double h = t1 - cur.t;
        probe_point pts[PIECE_POINTS];
        pts[0] = cur;
        pts[2] = probe_at(&w, cur.t + 0.5 * h, &cur);
        pts[4] = probe_at(&w, t1, &pts[2]);
        const probe_point *m = &pts[2], *next = &pts[4];
        const double reach = w.reach * w.seg;
        int ok = fabs(next->lo - cur.lo) <= reach && fabs(next->hi - cur.hi) <= reach &&
                 inside(cur.lo, m->lo, next->lo) && inside(cur.hi, m->hi, next->hi);
        double q_end[TRIBO_CHARGE_MAX_QUADRATURES], g_mid[TRIBO_CHARGE_MAX_GLOBALS],
            g_end[TRIBO_CHARGE_MAX_GLOBALS];
        memcpy(q_end, cur.quadratures, q_bytes);
        memcpy(g_mid, globals, g_bytes);
        memcpy(g_end, globals, g_bytes);
        /* a trial piece below min_piece is taken whatever the tests say: trial only halves,
           so every piece advances by at least min_piece / 2 */
        const int forced = trial <= min_piece;
        if (ok || forced) {
            pts[1] = probe_at(&w, cur.t + 0.25 * h, &cur);
            pts[3] = probe_at(&w, cur.t + 0.75 * h, &cur);
        }
        if (ok && with_states)
            ok = advance_states(&w, pts, h, rtol, atol, q_end, globals, g_mid, g_end);
        const int saturated = ok && saturated_piece(&w, pts, globals, g_mid, g_end);
        if (hopeful && !saturated) {
            hopeful = 0;
            if (cur.t == a) {
                w.cost = cost_at_start;
                trial = b - a;
            }
            continue;
        }
        if (ok || forced) {
            memcpy(pts[4].quadratures, q_end, q_bytes);
            if (!saturated)
                charge_piece(&w, pts, globals, g_mid, g_end);
            hopeful = saturated;
            memcpy(globals, g_end, g_bytes);
            cur = pts[4];
            trial = 2.0 * h;
            if (w.cost >= budget && cur.t < b) {
                if (reached)
                    *reached = cur.t;
                break;
            }
        } else {
            trial *= 0.5;
        }
    }
    memcpy(quadratures, cur.quadratures, q_bytes);
    return w.status;
}
