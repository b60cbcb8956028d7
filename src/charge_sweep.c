/* charge_sweep.c: charging along a contact seen through an integrator's dense output,
   exact in the time each segment spends in contact (docs/model.md §5). */
#include "charging.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The contact at one time; the centre is unwrapped against a neighbouring point, so that
   the edges move continuously across the start of the numbering. */
typedef struct probe_point {
    double t, lo, hi, speed;
    double rates[TRIBO_CHARGE_MAX_QUADRATURES];
    double quadratures[TRIBO_CHARGE_MAX_QUADRATURES]; /* known at the ends of accepted pieces */
} probe_point;

typedef struct sweep {
    tribo_charging *c;
    const tribo_scene *s;
    const tribo_contact_probe *probe;
    double perimeter, seg; /* perimeter, segment length */
    double rtol;
    tribo_sample_sink sink;
    void *sink_ctx;
    int status;
} sweep;

static probe_point probe_at(sweep *w, double t, const probe_point *near)
{
    double s_c, half, speed;
    tribo_contact_kinematics k;
    w->probe->at(w->probe->ctx, t, &s_c, &half, &speed, &k);
    if (near)
        s_c -= w->perimeter * floor((s_c - 0.5 * (near->lo + near->hi)) / w->perimeter + 0.5);
    probe_point pt = {t, s_c - half, s_c + half, speed, {0}, {0}};
    tribo_charging_quadrature_rates(w->c, &k, pt.rates);
    return pt;
}

static double edge_of(const probe_point *p, int hi_edge) { return hi_edge ? p->hi : p->lo; }

/* When an edge (lo or hi), moving monotonically through a, m, b, crosses the boundary at
   x: first the inverse quadratic through the three points, checked on the probe; then, if
   needed, the Illinois variant of regula falsi from the tighter bracket. Located to
   rtol of the piece's duration. */
static double crossing(sweep *w, probe_point a, const probe_point *m, probe_point b, int hi_edge,
                       double x)
{
    const double tol = w->rtol * (b.t - a.t) + 1e-15 * fabs(b.t);
    const double ea = edge_of(&a, hi_edge), em = edge_of(m, hi_edge), eb = edge_of(&b, hi_edge);
    double fa = ea - x, fb = eb - x;
    if (ea != em && em != eb && ea != eb) {
        /* Lagrange interpolation of t as a function of the edge */
        const double t = a.t * (x - em) * (x - eb) / ((ea - em) * (ea - eb)) +
                         m->t * (x - ea) * (x - eb) / ((em - ea) * (em - eb)) +
                         b.t * (x - ea) * (x - em) / ((eb - ea) * (eb - em));
        if (t > a.t && t < b.t) {
            const probe_point p = probe_at(w, t, m);
            const double fp = edge_of(&p, hi_edge) - x;
            const double speed = fabs(eb - ea) / (b.t - a.t);
            if (fabs(fp) <= speed * tol)
                return t;
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
        double t = (a.t * fb - b.t * fa) / (fb - fa);
        if (!(t > a.t && t < b.t))
            t = 0.5 * (a.t + b.t);
        const probe_point p = probe_at(w, t, &a);
        const double fp = edge_of(&p, hi_edge) - x;
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
   located on its own, so a piece may span several; fewer pieces, fewer probes. */
#define SEGMENTS_PER_PIECE 8

/* A boundary crossing inside a piece: when, and which edge's segment index moves how. */
typedef struct cut {
    double t;
    int hi_edge, step;
} cut;

static int cmp_cut(const void *x, const void *y)
{
    const double a = ((const cut *)x)->t, b = ((const cut *)y)->t;
    return (a > b) - (a < b);
}

static int inside(double e0, double em, double e1)
{
    const double slack = 1e-12 * (fabs(e0) + fabs(e1) + 1.0);
    return em >= fmin(e0, e1) - slack && em <= fmax(e0, e1) + slack;
}

/* A piece in which each edge moves monotonically by at most SEGMENTS_PER_PIECE segments
   and the globals are quadratic to the tolerances: locate the boundary crossings, and
   charge the parts between them, each with its fixed set of segments (§5a, §5b). S0, S1,
   S2: the globals at the piece's start, middle and end. */
static void charge_piece(sweep *w, const probe_point *a, const probe_point *m,
                         const probe_point *b, const double *S0, const double *S1,
                         const double *S2)
{
    cut cuts[2 * SEGMENTS_PER_PIECE + 2];
    int n = 0;
    double cell[2] = {floor(a->lo / w->seg), floor(a->hi / w->seg)};
    for (int edge = 0; edge < 2; edge++) {
        const double e0 = edge_of(a, edge), e1 = edge_of(b, edge);
        const int step = e1 > e0 ? 1 : -1;
        const double lo = fmin(e0, e1), hi = fmax(e0, e1);
        for (double k = floor(lo / w->seg) + 1; k * w->seg < hi && n < 2 * SEGMENTS_PER_PIECE + 2; k++) {
            const cut c = {crossing(w, *a, m, *b, edge, k * w->seg), edge, step};
            cuts[n++] = c;
        }
    }
    qsort(cuts, (size_t)n, sizeof cuts[0], cmp_cut);

    /* each global within the piece: the quadratic through its start, middle and end */
    const int n_globals = w->c->n_globals;
    double c1[TRIBO_CHARGE_MAX_GLOBALS], c2[TRIBO_CHARGE_MAX_GLOBALS];
    for (int g = 0; g < n_globals; g++) {
        c1[g] = -3.0 * S0[g] + 4.0 * S1[g] - S2[g];
        c2[g] = 2.0 * (S0[g] - 2.0 * S1[g] + S2[g]);
    }
    const double T = b->t - a->t;
    double t0 = a->t;
    for (int i = 0; i <= n && !w->status; i++) {
        const double t1 = i < n ? cuts[i].t : b->t;
        if (t1 > t0) {
            /* the segments from the lower edge's to the upper edge's, as the crossings so
               far have moved them: a contact whose edges sit mid-segment covers exactly those */
            const double u0 = (t0 - a->t) / T, u1 = (t1 - a->t) / T;
            const double um = 0.5 * (u0 + u1);
            tribo_contact_sample s;
            s.duration = t1 - t0;
            s.in_contact = 1;
            s.s_centre = 0.5 * (cell[0] + cell[1] + 1.0) * w->seg;
            s.half_width = 0.5 * (cell[1] - cell[0]) * w->seg;
            for (int g = 0; g < n_globals; g++) {
                s.globals_begin[g] = S0[g] + u0 * (c1[g] + u0 * c2[g]);
                s.globals_mid[g] = S0[g] + um * (c1[g] + um * c2[g]);
                s.globals_end[g] = S0[g] + u1 * (c1[g] + u1 * c2[g]);
            }
            w->status = w->sink(w->sink_ctx, &s);
            t0 = t1;
        }
        if (i < n)
            cell[cuts[i].hi_edge] += cuts[i].step;
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
static int advance_states(sweep *w, const probe_point *cur, const probe_point *m,
                          const probe_point *next, double h, double rtol, double atol,
                          double *q_end, const double *g0, double *g_mid, double *g_end)
{
    const tribo_charging *c = w->c;
    const probe_point q1 = probe_at(w, cur->t + 0.25 * h, cur);
    const probe_point q3 = probe_at(w, cur->t + 0.75 * h, cur);
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
                         double *globals, tribo_sample_sink sink, void *sink_ctx)
{
    if (!(b > a))
        return 0;
    sweep w = {c, s, probe, c->arc.perimeter, c->arc.perimeter / c->n, rtol, sink, sink_ctx, 0};
    const size_t q_bytes = (size_t)c->n_quadratures * sizeof(double);
    const size_t g_bytes = (size_t)c->n_globals * sizeof(double);
    const int with_states = has_states(c);
    /* Left to right in pieces; a trial piece is at most a segment's travel of the centre,
       halved until the piece is regular, and grown after each accepted one. */
    probe_point cur = probe_at(&w, a, NULL);
    memcpy(cur.quadratures, quadratures, q_bytes);
    const double min_piece = 1e-13 * (1.0 + fabs(b));
    double trial = b - a;
    while (cur.t < b && !w.status) {
        if (cur.speed > 0.0)
            trial = fmin(trial, SEGMENTS_PER_PIECE * w.seg / cur.speed);
        /* within min_piece of b, go to b: the piece then is at most trial + min_piece */
        const double t1 = cur.t + trial >= b - min_piece ? b : cur.t + trial;
        const double h = t1 - cur.t;
        const probe_point m = probe_at(&w, cur.t + 0.5 * h, &cur);
        probe_point next = probe_at(&w, t1, &m);
        const double reach = SEGMENTS_PER_PIECE * w.seg;
        int ok = fabs(next.lo - cur.lo) <= reach && fabs(next.hi - cur.hi) <= reach &&
                 inside(cur.lo, m.lo, next.lo) && inside(cur.hi, m.hi, next.hi);
        double q_end[TRIBO_CHARGE_MAX_QUADRATURES], g_mid[TRIBO_CHARGE_MAX_GLOBALS],
            g_end[TRIBO_CHARGE_MAX_GLOBALS];
        memcpy(q_end, cur.quadratures, q_bytes);
        memcpy(g_mid, globals, g_bytes);
        memcpy(g_end, globals, g_bytes);
        if (ok && with_states)
            ok = advance_states(&w, &cur, &m, &next, h, rtol, atol, q_end, globals, g_mid, g_end);
        /* a trial piece below min_piece is taken whatever the tests say: trial only halves,
           so every piece advances by at least min_piece / 2 */
        if (ok || trial <= min_piece) {
            memcpy(next.quadratures, q_end, q_bytes);
            charge_piece(&w, &cur, &m, &next, globals, g_mid, g_end);
            memcpy(globals, g_end, g_bytes);
            cur = next;
            trial = 2.0 * h;
        } else {
            trial *= 0.5;
        }
    }
    memcpy(quadratures, cur.quadratures, q_bytes);
    return w.status;
}
