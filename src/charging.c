/* charging.c: static (capacitive) and sliding (frictional-work) charge models (MODEL §5). */
#include "charging.h"

#include <stdlib.h>
#include <string.h>

int tribo_charging_init(tribo_charging *c, double eps, int n, int with_static, int with_sliding)
{
    memset(c, 0, sizeof *c);
    c->with_static = with_static;
    c->with_sliding = with_sliding;
    c->n = n;
    if (tribo_arclength_init(&c->arc, eps) != 0)
        return -1;
    c->segments_per_length = (double)n / c->arc.perimeter;
    if (with_static && !(c->q = malloc((size_t)n * sizeof *c->q)))
        goto fail;
    if (with_sliding && !(c->sigma = malloc((size_t)n * sizeof *c->sigma)))
        goto fail;
    tribo_charging_reset(c);
    return 0;
fail:
    tribo_charging_free(c);
    return -1;
}

void tribo_charging_free(tribo_charging *c)
{
    tribo_arclength_free(&c->arc);
    free(c->q);
    free(c->sigma);
    c->q = c->sigma = NULL;
}

void tribo_charging_reset(tribo_charging *c)
{
    if (c->q)
        memset(c->q, 0, (size_t)c->n * sizeof *c->q);
    if (c->sigma)
        memset(c->sigma, 0, (size_t)c->n * sizeof *c->sigma);
    c->charge_cache.duration = c->relax_cache.duration = -1.0;
}

void tribo_charging_sample(const tribo_charging *c, const tribo_pose *pose, double delta_y,
                           double duration, double work_begin, double work_end,
                           tribo_contact_sample *sample)
{
    sample->duration = duration;
    sample->work_begin = work_begin;
    sample->work_end = work_end;
    sample->in_contact = delta_y > 0.0;
    if (!sample->in_contact) {
        sample->s_centre = sample->half_width = 0.0;
        return;
    }
    const double eps = c->arc.eps;
    const double rho_c = tribo_contact_curvature_radius(eps * eps, pose->h);
    sample->half_width = sqrt(rho_c * delta_y); /* MODEL §5 (paper eq. 4) */
    sample->s_centre = tribo_arclength_at(&c->arc, tribo_contact_parameter(eps, pose));
}

/* F_k(z) = int_0^1 v^k e^{-z v} dv, k = 1, 2: by its series where the closed form
   cancels (small z), else closed. */
static double moment(int k, double z)
{
    if (z < 0.5) {
        double term = 1.0, sum = 0.0;
        for (int n = 0; n < 30; n++) {
            sum += term / (double)(n + k + 1);
            term *= -z / (double)(n + 1);
        }
        return sum;
    }
    const double e = exp(-z);
    return k == 1 ? (1.0 - e * (1.0 + z)) / (z * z) : (2.0 - e * (z * z + 2.0 * z + 2.0)) / (z * z * z);
}

/* exp(-duration / tau), phi1(z) = (1 - e^-z) / z and z F_k(z), z = duration / tau,
   recomputed only when the duration or tau changed. */
static const tribo_decay_cache *decay(tribo_decay_cache *k, double duration, double tau)
{
    if (k->duration != duration || k->tau != tau) {
        const double z = duration / tau;
        k->duration = duration;
        k->tau = tau;
        k->one_minus_decay = -expm1(-z);
        k->decay = 1.0 - k->one_minus_decay;
        k->phi1 = z > 1e-8 ? k->one_minus_decay / z : 1.0 - 0.5 * z;
        k->zf1 = z * moment(1, z);
        k->zf2 = z * moment(2, z);
    }
    return k;
}

void tribo_charging_saturation(tribo_charging *c, const tribo_charge_params *p, double *Sigma_s,
                               tribo_contact_sample *sample)
{
    const double s0 = *Sigma_s;
    double s1 = s0;
    if (sample->in_contact && sample->duration > 0.0) {
        /* MODEL §5b: dSigma_s = eta domega / sqrt(Sigma0^2 + 2 eta omega) + (Sigma0 - Sigma_s) / tau_r.
           The work term is the exact increment of sqrt(Sigma0^2 + 2 eta omega); with the
           relaxation solved exactly for a constant work rate over the sample, the update
           is stable for any tau_r (a stiff tau_r just pins Sigma_s to Sigma0). */
        const double g0 = sqrt(p->Sigma0 * p->Sigma0 + 2.0 * p->eta * sample->work_begin);
        const double g1 = sqrt(p->Sigma0 * p->Sigma0 + 2.0 * p->eta * sample->work_end);
        const tribo_decay_cache *k = decay(&c->relax_cache, sample->duration, p->tau_r);
        s1 = p->Sigma0 + (s0 - p->Sigma0) * k->decay + (g1 - g0) * k->phi1;
    }
    /* in flight the back-flow stops (c = 0 in MODEL §5b) and no work is done */
    sample->Sigma_s_begin = s0;
    sample->Sigma_s_mid = 0.5 * (s0 + s1);
    sample->Sigma_s_end = s1;
    *Sigma_s = s1;
}

void tribo_charging_segments(tribo_charging *c, const tribo_charge_params *p,
                             const tribo_contact_sample *sample, double *q, double *sigma)
{
    if (!sample->in_contact || sample->duration <= 0.0 || (!q && !sigma))
        return;
    /* Segments whose arc [i L, (i+1) L) overlaps [s_c - Sc, s_c + Sc], periodic (MODEL §5). */
    const double lo = (sample->s_centre - sample->half_width) * c->segments_per_length;
    const double hi = (sample->s_centre + sample->half_width) * c->segments_per_length;
    const long first = (long)floor(lo);
    long count = (long)floor(hi) - first + 1;
    if (count > c->n)
        count = c->n;
    long i = first % c->n;
    if (i < 0)
        i += c->n;

    /* Exact over the sample: the static model has constant coefficients (MODEL §5a); the
       sliding one, dSigma_i = (Sigma_s - Sigma_i) / tau0 with Sigma_s = A + B u + C u^2
       over u in [0, 1] (MODEL §5b), is Sigma_i <- e^{-z} Sigma_i + K with
       K = (A + B + C)(1 - e^{-z}) - (B + 2C) z F_1(z) + C z F_2(z), z = duration / tau0. */
    const tribo_decay_cache *k = decay(&c->charge_cache, sample->duration, p->tau0);
    const double d = k->decay, one_minus_d = k->one_minus_decay;
    const double A = sample->Sigma_s_begin;
    const double C = 2.0 * (A - 2.0 * sample->Sigma_s_mid + sample->Sigma_s_end);
    const double B = sample->Sigma_s_end - A - C;
    const double K = (A + B + C) * one_minus_d - (B + 2.0 * C) * k->zf1 + C * k->zf2;
    for (long j = 0; j < count; j++) {
        if (q)
            q[i] += (1.0 - q[i]) * one_minus_d; /* MODEL §5a */
        if (sigma)
            sigma[i] = d * sigma[i] + K; /* MODEL §5b */
        if (++i == c->n)
            i = 0;
    }
}

double tribo_charging_mean(const double *v, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        sum += v[i];
    return sum / (double)n;
}

/* ---- sweeping a contact along an interval ------------------------------------------------ */

/* The contact at one time; the centre is unwrapped against a neighbouring point, so that
   the edges move continuously across the start of the numbering. */
typedef struct probe_point {
    double t, lo, hi, rate, speed;
    double work; /* omega, known at the ends of accepted pieces */
} probe_point;

typedef struct sweep {
    tribo_charging *c;
    const tribo_charge_params *p;
    const tribo_contact_probe *probe;
    double perimeter, seg; /* perimeter, segment length */
    double rtol;
    double *Sigma_s;
    tribo_sample_sink sink;
    void *sink_ctx;
    int status;
} sweep;

static probe_point probe_at(sweep *w, double t, const probe_point *near)
{
    double s_c, half, rate, speed;
    w->probe->at(w->probe->ctx, t, &s_c, &half, &rate, &speed);
    if (near)
        s_c -= w->perimeter * floor((s_c - 0.5 * (near->lo + near->hi)) / w->perimeter + 0.5);
    const probe_point pt = {t, s_c - half, s_c + half, rate, speed, 0.0};
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
   located on its own, so a piece may span several; fewer pieces, fewer probes (measured:
   8 halves the cost of a rolling disc against 1, with Q equal to 1e-10). */
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

/* Sigma_s over a piece of the contact from work w0 to w1 (MODEL §5b). */
static double saturation_after(sweep *w, double S, double duration, double w0, double w1)
{
    tribo_contact_sample piece = {duration, 1, 0, 0, w0, w1, 0, 0, 0};
    tribo_charging_saturation(w->c, w->p, &S, &piece);
    return S;
}

/* Sigma_s at the middle and the end of a piece, from S[0] at its start (MODEL §5b):
   dSigma_s/dtau = g - (Sigma_s - Sigma0) / tau_r with g = eta (d omega/dtau) / sqrt(Sigma0^2
   + 2 eta omega). The relaxation is linear, so Sigma_s - Sigma0 is the start value decayed
   plus the integral of e^{-(h - s)/tau_r} g(s); where tau_r is not stiff over the piece,
   that integral is taken by Simpson on the five points omega already used, and is as
   accurate as omega. Where it is stiff, the exact update for a constant work rate is taken
   over the halves and the whole and must agree. Returns whether the piece is accepted. */
static int saturation_piece(sweep *w, const probe_point *const pts[5], double h, double work0,
                            double work_left, double work1, double S[3], double rtol, double atol)
{
    const tribo_charge_params *p = w->p;
    const double z = h / p->tau_r;
    const double work_mid = work0 + work_left;
    if (z <= 1.0) {
        /* omega at the quarter points only feeds sqrt(Sigma0^2 + 2 eta omega): trapezoids */
        const double quarter = 0.25 * h;
        const double works[5] = {work0, work0 + 0.5 * quarter * (pts[0]->rate + pts[1]->rate), work_mid,
                                 work_mid + 0.5 * quarter * (pts[2]->rate + pts[3]->rate), work1};
        double g[5];
        for (int j = 0; j < 5; j++)
            g[j] = p->eta * pts[j]->rate / sqrt(p->Sigma0 * p->Sigma0 + 2.0 * p->eta * works[j]);
        const double d = exp(-0.25 * z); /* e^{-(quarter of the piece) / tau_r} */
        const double d2 = d * d, d3 = d2 * d, d4 = d2 * d2;
        S[1] = p->Sigma0 + (S[0] - p->Sigma0) * d2 + h / 12.0 * (d2 * g[0] + 4.0 * d * g[1] + g[2]);
        S[2] = p->Sigma0 + (S[0] - p->Sigma0) * d4 +
               h / 12.0 * (d4 * g[0] + 4.0 * d3 * g[1] + 2.0 * d2 * g[2] + 4.0 * d * g[3] + g[4]);
        return 1;
    }
    S[1] = saturation_after(w, S[0], 0.5 * h, work0, work_mid);
    S[2] = saturation_after(w, S[1], 0.5 * h, work_mid, work1);
    const double S_whole = saturation_after(w, S[0], h, work0, work1);
    return fabs(S[2] - S_whole) <= rtol * fabs(S[2]) + atol;
}

/* A piece in which each edge moves monotonically by at most a segment and Sigma_s (with
   the sliding model) is quadratic to the tolerances: locate the boundary crossings, and
   charge the parts between them, each with its fixed set of segments (MODEL §5a, §5b). */
static void charge_piece(sweep *w, const probe_point *a, const probe_point *m,
                         const probe_point *b, const double S[3])
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

    /* Sigma_s within the piece: the quadratic through its start, middle and end */
    const double T = b->t - a->t;
    const double c1 = -3.0 * S[0] + 4.0 * S[1] - S[2], c2 = 2.0 * (S[0] - 2.0 * S[1] + S[2]);
    double t0 = a->t;
    for (int i = 0; i <= n && !w->status; i++) {
        const double t1 = i < n ? cuts[i].t : b->t;
        if (t1 > t0) {
            /* the segments from the lower edge's to the upper edge's, as the crossings so
               far have moved them: a contact whose edges sit mid-segment covers exactly those */
            const double u0 = (t0 - a->t) / T, u1 = (t1 - a->t) / T;
            tribo_contact_sample s;
            s.duration = t1 - t0;
            s.in_contact = 1;
            s.s_centre = 0.5 * (cell[0] + cell[1] + 1.0) * w->seg;
            s.half_width = 0.5 * (cell[1] - cell[0]) * w->seg;
            s.work_begin = s.work_end = 0.0; /* Sigma_s is given */
            const double um = 0.5 * (u0 + u1);
            s.Sigma_s_begin = S[0] + u0 * (c1 + u0 * c2);
            s.Sigma_s_mid = S[0] + um * (c1 + um * c2);
            s.Sigma_s_end = S[0] + u1 * (c1 + u1 * c2);
            w->status = w->sink(w->sink_ctx, &s);
            t0 = t1;
        }
        if (i < n)
            cell[cuts[i].hi_edge] += cuts[i].step;
    }
}

int tribo_charging_sweep(tribo_charging *c, const tribo_charge_params *p,
                         const tribo_contact_probe *probe, double a, double b, double rtol,
                         double atol, double *work, double *Sigma_s, tribo_sample_sink sink,
                         void *sink_ctx)
{
    if (!(b > a))
        return 0;
    sweep w = {c, p, probe, c->arc.perimeter, c->arc.perimeter / c->n, rtol, Sigma_s,
               sink, sink_ctx, 0};
    /* Left to right in pieces; a trial piece is at most a segment's travel of the centre,
       halved until the piece is regular, and grown after each accepted one. */
    probe_point cur = probe_at(&w, a, NULL);
    cur.work = *work;
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
        double work_end = cur.work, S[3] = {*Sigma_s, *Sigma_s, *Sigma_s};
        if (ok && c->with_sliding) {
            /* omega by Simpson on the halves against Simpson on the whole (MODEL §5b), to
               the tolerances CVODE holds the motion to: rtol of the piece's work, atol per
               unit time (the rate is ~0 and noisy in stick, and goes as sqrt(delta_y) at
               the ends of a contact) */
            const probe_point q1 = probe_at(&w, cur.t + 0.25 * h, &cur);
            const probe_point q3 = probe_at(&w, cur.t + 0.75 * h, &cur);
            const double whole = h / 6.0 * (cur.rate + 4.0 * m.rate + next.rate);
            const double left = h / 12.0 * (cur.rate + 4.0 * q1.rate + m.rate);
            const double right = h / 12.0 * (m.rate + 4.0 * q3.rate + next.rate);
            const double halves = left + right;
            ok = fabs(halves - whole) <= 15.0 * (rtol * fabs(halves) + atol * h);
            work_end = cur.work + halves + (halves - whole) / 15.0;
            const probe_point *pts[5] = {&cur, &q1, &m, &q3, &next};
            ok = ok && saturation_piece(&w, pts, h, cur.work, left, work_end, S, rtol, atol);
        }
        /* a trial piece below min_piece is taken whatever the tests say: trial only halves,
           so every piece advances by at least min_piece / 2 */
        if (ok || trial <= min_piece) {
            next.work = work_end;
            charge_piece(&w, &cur, &m, &next, S);
            *Sigma_s = S[2];
            cur = next;
            trial = 2.0 * h;
        } else {
            trial *= 0.5;
        }
    }
    *work = cur.work;
    return w.status;
}
