/*
 * Timing driver for the reference LWPR C library (github.com/ipab-slmc/lwpr, 1.2.6), so that
 * steplearn's LWPR can be timed against it on the same machine with the same protocol as
 * `cargo run --release --example lwpr_cross`: an empty model with the C demo's settings
 * (init_D 50, init_alpha 250, w_gen 0.2, norm_in = half ranges), 100,000 noisy training
 * samples; the mean time per update over that training, then per prediction over the
 * noiseless 41^d test grid after it, then per update over 100,000 further samples (the
 * steady state that `cargo bench --bench approx -- lwpr` times). Five seeds each; prints the
 * means.
 *
 * Build (from a checkout of the reference library, with a minimal config header):
 *   printf '#define HAVE_LIBM 1\n#define LIBRARY_API\n' > include/lwpr_config.h
 *   gcc -O2 -Iinclude -o lwpr_c_timing path/to/lwpr_c_timing.c src/lwpr.c src/lwpr_aux.c \
 *       src/lwpr_math.c src/lwpr_mem.c src/lwpr_binio.c -lm
 *   ./lwpr_c_timing
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "lwpr.h"

#define N_TRAIN 100000
#define GRID 41

static double uniform(void) { return rand() / (RAND_MAX + 1.0); }

static double gaussian(void) {
    double u = uniform() + 1e-12, v = uniform();
    return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

static double cross(const double *x) {
    double a = exp(-10.0 * x[0] * x[0]), b = exp(-50.0 * x[1] * x[1]);
    double c = 1.25 * exp(-5.0 * (x[0] * x[0] + x[1] * x[1]));
    double m = a > b ? a : b;
    return m > c ? m : c;
}

static double step_offset(const double *x) {
    return 0.3 * tanh(2.0 * x[0]) + 0.05 * x[1] + 0.5 * x[2];
}

static double seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void run(const char *name, int n, const double *lo, const double *hi, double noise,
                double (*f)(const double *)) {
    double us_update = 0.0, us_predict = 0.0, us_steady = 0.0, rfs = 0.0;
    int seeds = 5;
    for (int seed = 1; seed <= seeds; seed++) {
        LWPR_Model model;
        lwpr_init_model(&model, n, 1, name);
        lwpr_set_init_D_spherical(&model, 50.0);
        lwpr_set_init_alpha(&model, 250.0);
        model.w_gen = 0.2;
        for (int i = 0; i < n; i++) model.norm_in[i] = 0.5 * (hi[i] - lo[i]);
        srand(seed);
        double *xs = malloc(sizeof(double) * n * 2 * N_TRAIN);
        double *ys = malloc(sizeof(double) * 2 * N_TRAIN);
        for (int k = 0; k < 2 * N_TRAIN; k++) {
            for (int i = 0; i < n; i++) xs[n * k + i] = lo[i] + (hi[i] - lo[i]) * uniform();
            ys[k] = f(xs + n * k) + noise * gaussian();
        }
        double yp, t0 = seconds();
        for (int k = 0; k < N_TRAIN; k++) lwpr_update(&model, xs + n * k, ys + k, &yp, NULL);
        us_update += (seconds() - t0) * 1e6 / N_TRAIN;
        int total = 1;
        for (int i = 0; i < n; i++) total *= GRID;
        double x[3];
        t0 = seconds();
        for (int k = 0; k < total; k++) {
            int j = k;
            for (int i = 0; i < n; i++) {
                x[i] = lo[i] + (hi[i] - lo[i]) * (j % GRID) / (GRID - 1.0);
                j /= GRID;
            }
            lwpr_predict(&model, x, 0.001, &yp, NULL, NULL);
        }
        us_predict += (seconds() - t0) * 1e6 / total;
        t0 = seconds();
        for (int k = N_TRAIN; k < 2 * N_TRAIN; k++)
            lwpr_update(&model, xs + n * k, ys + k, &yp, NULL);
        us_steady += (seconds() - t0) * 1e6 / N_TRAIN;
        rfs += model.sub[0].numRFS;
        lwpr_free_model(&model);
        free(xs);
        free(ys);
    }
    printf("%s: %.0f RFs, %.3f us/update, %.3f us/predict, then %.3f us/update (C reference, "
           "mean of %d seeds)\n",
           name, rfs / seeds, us_update / seeds, us_predict / seeds, us_steady / seeds, seeds);
}

int main(void) {
    double lo2[2] = {-1.0, -1.0}, hi2[2] = {1.0, 1.0};
    run("cross-2d", 2, lo2, hi2, 0.1, cross);
    double lo3[3] = {-0.5, -3.0, -0.1}, hi3[3] = {0.5, 3.0, 0.2};
    run("step-offset-3d", 3, lo3, hi3, 0.01, step_offset);
    return 0;
}
