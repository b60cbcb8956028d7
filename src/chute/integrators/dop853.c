/* dop853.c: the DOP853 pair and its dense output (dop853.h). */
#include "dop853.h"

#include <math.h>
#include <string.h>

/* Hairer's dop853.f: the nodes, the stages' weights (rows 12-15: the solution's weights and
   the three extra stages of the dense output), the two error estimators and the dense
   output's weights. */
static const double C[16] =
    {0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274, 0.2816496580927726,
     0.3333333333333333, 0.25, 0.3076923076923077, 0.6512820512820513, 0.6, 0.8571428571428571,
     1.0, 1.0, 0.1, 0.2, 0.7777777777777778};
static const double A[16][16] = {
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.05260015195876773, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.0197250569845379, 0.0591751709536137, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.02958758547680685, 0, 0.08876275643042054, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.2413651341592667, 0, -0.8845494793282861, 0.924834003261792, 0, 0, 0, 0, 0, 0, 0, 0, 0,
     0, 0, 0},
    {0.037037037037037035, 0, 0, 0.17082860872947386, 0.12546768756682242, 0, 0, 0, 0, 0, 0, 0,
     0, 0, 0, 0},
    {0.037109375, 0, 0, 0.17025221101954405, 0.06021653898045596, -0.017578125, 0, 0, 0, 0, 0,
     0, 0, 0, 0, 0},
    {0.03709200011850479, 0, 0, 0.17038392571223998, 0.10726203044637328,
     -0.015319437748624402, 0.008273789163814023, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.6241109587160757, 0, 0, -3.3608926294469414, -0.868219346841726, 27.59209969944671,
     20.154067550477894, -43.48988418106996, 0, 0, 0, 0, 0, 0, 0, 0},
    {0.47766253643826434, 0, 0, -2.4881146199716677, -0.590290826836843, 21.230051448181193,
     15.279233632882423, -33.28821096898486, -0.020331201708508627, 0, 0, 0, 0, 0, 0, 0},
    {-0.9371424300859873, 0, 0, 5.186372428844064, 1.0914373489967295, -8.149787010746927,
     -18.52006565999696, 22.739487099350505, 2.4936055526796523, -3.0467644718982196, 0, 0, 0,
     0, 0, 0},
    {2.273310147516538, 0, 0, -10.53449546673725, -2.0008720582248625, -17.9589318631188,
     27.94888452941996, -2.8589982771350235, -8.87285693353063, 12.360567175794303,
     0.6433927460157636, 0, 0, 0, 0, 0},
    {0.054293734116568765, 0, 0, 0, 0, 4.450312892752409, 1.8915178993145003,
     -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034,
     0.04471061572777259, 0, 0, 0, 0},
    {0.056167502283047954, 0, 0, 0, 0, 0, 0.25350021021662483, -0.2462390374708025,
     -0.12419142326381637, 0.15329179827876568, 0.00820105229563469, 0.007567897660545699,
     -0.008298, 0, 0, 0},
    {0.03183464816350214, 0, 0, 0, 0, 0.028300909672366776, 0.053541988307438566,
     -0.05492374857139099, 0, 0, -0.00010834732869724932, 0.0003825710908356584,
     -0.00034046500868740456, 0.1413124436746325, 0, 0},
    {-0.42889630158379194, 0, 0, 0, 0, -4.697621415361164, 7.683421196062599, 4.06898981839711,
     0.3567271874552811, 0, 0, 0, -0.0013990241651590145, 2.9475147891527724,
     -9.15095847217987, 0},
};
static const double B[12] =
    {0.054293734116568765, 0, 0, 0, 0, 4.450312892752409, 1.8915178993145003,
     -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034,
     0.04471061572777259};
static const double E3[13] =
    {-0.18980075407240762, 0, 0, 0, 0, 4.450312892752409, 1.8915178993145003,
     -5.801203960010585, -0.4226823213237919, -0.1521609496625161, 0.20136540080403034,
     0.02265179219836082, 0};
static const double E5[13] =
    {0.01312004499419488, 0, 0, 0, 0, -1.2251564463762044, -0.4957589496572502,
     1.6643771824549864, -0.35032884874997366, 0.3341791187130175, 0.08192320648511571,
     -0.022355307863886294, 0};
static const double D[4][16] = {
    {-8.428938276109013, 0, 0, 0, 0, 0.5667149535193777, -3.0689499459498917, 2.38466765651207,
     2.117034582445028, -0.871391583777973, 2.2404374302607883, 0.6315787787694688,
     -0.08899033645133331, 18.148505520854727, -9.194632392478356, -4.436036387594894},
    {10.427508642579134, 0, 0, 0, 0, 242.28349177525817, 165.20045171727028,
     -374.5467547226902, -22.113666853125306, 7.733432668472264, -30.674084731089398,
     -9.332130526430229, 15.697238121770845, -31.139403219565178, -9.35292435884448,
     35.81684148639408},
    {19.985053242002433, 0, 0, 0, 0, -387.0373087493518, -189.17813819516758,
     527.8081592054236, -11.57390253995963, 6.8812326946963, -1.0006050966910838,
     0.7777137798053443, -2.778205752353508, -60.19669523126412, 84.32040550667716,
     11.99229113618279},
    {-25.69393346270375, 0, 0, 0, 0, -154.18974869023643, -231.5293791760455,
     357.6391179106141, 93.40532418362432, -37.45832313645163, 104.0996495089623,
     29.8402934266605, -43.53345659001114, 96.32455395918828, -39.17726167561544,
     -149.72683625798564},
};

#define SAFETY 0.9
#define MIN_FACTOR 0.2
#define MAX_FACTOR 10.0
#define EXPONENT (-1.0 / 8.0)

static double scale_of(const tribo_dop853 *s, int i, double a, double b)
{
    return s->atol[i] + s->rtol * fmax(fabs(a), fabs(b));
}

/* The root mean square over the components of v / scale. */
static double rms(const tribo_dop853 *s, const double *v, const double *y)
{
    double sum = 0.0;
    for (int i = 0; i < s->n; i++) {
        const double r = v[i] / scale_of(s, i, y[i], y[i]);
        sum += r * r;
    }
    return sqrt(sum / s->n);
}

void tribo_dop853_start(tribo_dop853 *s, tribo_rk_rhs rhs, void *ctx, int n, double t,
                        const double *y, double rtol, const double *atol, double hmax)
{
    s->rhs = rhs;
    s->ctx = ctx;
    s->n = n;
    s->rtol = rtol;
    s->atol = atol;
    s->t = t;
    memcpy(s->y, y, (size_t)n * sizeof *y);
    rhs(ctx, t, s->y, s->f);
    /* Hairer's hinit (op. cit. §II.4): a step of 1 % of the state's scale over its rate, and
       the one whose local error the second derivative's estimate puts at 1 % */
    const double d0 = rms(s, s->y, s->y), d1 = rms(s, s->f, s->y);
    double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
    h0 = fmin(h0, hmax);
    double *y1 = s->k[1], *f1 = s->k[2];
    for (int i = 0; i < n; i++)
        y1[i] = s->y[i] + h0 * s->f[i];
    rhs(ctx, t + h0, y1, f1);
    for (int i = 0; i < n; i++)
        y1[i] = (f1[i] - s->f[i]) / h0;
    const double d2 = rms(s, y1, s->y), d = fmax(d1, d2);
    const double h1 = d <= 1e-15 ? fmax(1e-6, 1e-3 * h0) : pow(0.01 / d, 1.0 / 8.0);
    s->h = fmin(fmin(100.0 * h0, h1), hmax);
}

/* Stage st of a step of h from (t, y): its derivative, into k[st]. */
static void take_stage(tribo_dop853 *s, int st, double t, const double *y, double h)
{
    double stage[TRIBO_DOP853_MAX];
    for (int i = 0; i < s->n; i++) {
        double sum = 0.0;
        for (int j = 0; j < st; j++)
            sum += A[st][j] * s->k[j][i];
        stage[i] = y[i] + h * sum;
    }
    s->rhs(s->ctx, t + C[st] * h, stage, s->k[st]);
}

int tribo_dop853_step(tribo_dop853 *s, double hmax)
{
    const int n = s->n;
    double(*k)[TRIBO_DOP853_MAX] = s->k;
    double y_new[TRIBO_DOP853_MAX];
    const double t = s->t;
    const double min_step = 10.0 * (nextafter(t, INFINITY) - t);
    double h = fmin(s->h, hmax), factor;
    int rejected = 0;
    memcpy(k[0], s->f, (size_t)n * sizeof k[0][0]);
    for (;;) {
        if (!(h >= min_step))
            return -1;
        for (int st = 1; st < 12; st++)
            take_stage(s, st, t, s->y, h);
        for (int i = 0; i < n; i++) {
            double sum = 0.0;
            for (int j = 0; j < 12; j++)
                sum += B[j] * k[j][i];
            y_new[i] = s->y[i] + h * sum;
        }
        s->rhs(s->ctx, t + h, y_new, k[12]);
        /* the error: the fifth-order estimator, corrected by the third's (dop853.f) */
        double e5 = 0.0, e3 = 0.0;
        for (int i = 0; i < n; i++) {
            double a = 0.0, b = 0.0;
            for (int j = 0; j < 13; j++) {
                a += E5[j] * k[j][i];
                b += E3[j] * k[j][i];
            }
            const double sc = scale_of(s, i, s->y[i], y_new[i]);
            e5 += (a / sc) * (a / sc);
            e3 += (b / sc) * (b / sc);
        }
        const double err = e5 == 0.0 && e3 == 0.0 ? 0.0 : h * e5 / sqrt((e5 + 0.01 * e3) * n);
        if (err < 1.0) {
            factor = err == 0.0 ? MAX_FACTOR : fmin(MAX_FACTOR, SAFETY * pow(err, EXPONENT));
            if (rejected)
                factor = fmin(1.0, factor);
            break;
        }
        /* (a NaN error shrinks the step to the rounding of t: -1) */
        h *= fmax(MIN_FACTOR, SAFETY * pow(err, EXPONENT));
        rejected = 1;
    }
    s->t_old = t;
    s->h_old = h;
    memcpy(s->y_old, s->y, (size_t)n * sizeof s->y[0]);
    memcpy(s->y, y_new, (size_t)n * sizeof s->y[0]);
    memcpy(s->f, k[12], (size_t)n * sizeof s->f[0]);
    s->t = t + h;
    s->h = h * factor;
    /* the dense output: three more stages (dop853.f's contd8) */
    for (int st = 13; st < 16; st++)
        take_stage(s, st, t, s->y_old, h);
    for (int i = 0; i < n; i++) {
        const double dy = s->y[i] - s->y_old[i];
        s->dense[0][i] = dy;
        s->dense[1][i] = h * k[0][i] - dy;
        s->dense[2][i] = 2.0 * dy - h * (k[12][i] + k[0][i]);
        for (int r = 0; r < 4; r++) {
            double sum = 0.0;
            for (int j = 0; j < 16; j++)
                sum += D[r][j] * k[j][i];
            s->dense[3 + r][i] = h * sum;
        }
    }
    return 0;
}
