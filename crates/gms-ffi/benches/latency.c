/*
 * Step latency of the compensator through the C ABI: the same measurement as
 * examples/latency.rs (10^6 steps per mode, N = 10, each step timed on its own with
 * clock_gettime(CLOCK_MONOTONIC), input 1 kHz samples of v = 10 mm/s·sin(2π·5 Hz·t), its
 * integral for the observer). benches/latency.py compiles it against libgms_ffi.a and runs it;
 * it prints one JSON object per mode.
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "leuven_rt.h"

#define STEPS 1000000
#define WARMUP 10000
#define ELEMENTS 10
#define BATCH 100

static const double DT = 1e-3;
static const double PI = 3.14159265358979323846;

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static int ascending(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(const double *sorted, size_t count, double q) {
    return sorted[(size_t)llround((double)(count - 1) * q)];
}

int main(void) {
    double w[ELEMENTS], delta[ELEMENTS];
    for (int i = 0; i < ELEMENTS; ++i) {
        w[i] = 0.2;
        delta[i] = 1e-6 * (i + 1);
    }
    leuven_rt_params p;
    memset(&p, 0, sizeof p);
    p.Fc = 1.0;
    p.Fs = 1.5;
    p.Vs = 1e-3;
    p.delta = 2.0;
    p.n = 2.0;
    p.sigma1 = 30.0;
    p.sigma2 = 0.4;
    p.W = w;
    p.Delta = delta;
    p.elements = ELEMENTS;

    double *inputs = malloc(STEPS * sizeof *inputs);
    double *times = malloc(STEPS * sizeof *times);
    if (!inputs || !times) return 1;

    /* The clock's own cost: median of empty intervals. */
    for (int i = 0; i < STEPS / 10; ++i) {
        double start = now_ns();
        times[i] = now_ns() - start;
    }
    qsort(times, STEPS / 10, sizeof *times, ascending);
    double overhead = quantile(times, STEPS / 10, 0.5);

    const char *names[2] = {"feedforward", "observer"};
    for (int mode = 0; mode < 2; ++mode) {
        double x = 0.0;
        for (int k = 0; k < STEPS; ++k) {
            double v = 0.01 * sin(2.0 * PI * 5.0 * k * DT);
            x += v * DT;
            inputs[k] = mode == LEUVEN_RT_MODE_FEEDFORWARD ? v : x;
        }
        leuven_rt_compensator *c = NULL;
        if (leuven_rt_compensator_create(&p, DT, mode, &c, NULL) != LEUVEN_RT_OK) return 1;
        volatile double sink = 0.0;
        double force = 0.0;
        for (int k = 0; k < WARMUP; ++k) {
            leuven_rt_compensator_step(c, inputs[k], &force);
            sink += force;
        }
        leuven_rt_compensator_reset(c);
        for (int k = 0; k < STEPS; ++k) {
            double start = now_ns();
            leuven_rt_status status = leuven_rt_compensator_step(c, inputs[k], &force);
            times[k] = now_ns() - start;
            if (status != LEUVEN_RT_OK) return 1;
            sink += force;
        }
        /* Batches of 100 consecutive steps: finer than the clock's granularity. */
        leuven_rt_compensator_reset(c);
        double averages[STEPS / BATCH];
        for (int b = 0; b < STEPS / BATCH; ++b) {
            double start = now_ns();
            for (int k = b * BATCH; k < (b + 1) * BATCH; ++k) {
                leuven_rt_compensator_step(c, inputs[k], &force);
                sink += force;
            }
            averages[b] = (now_ns() - start) / BATCH;
        }
        qsort(averages, STEPS / BATCH, sizeof *averages, ascending);
        (void)sink;
        leuven_rt_compensator_destroy(c);
        qsort(times, STEPS, sizeof *times, ascending);
        printf("{\"language\": \"c\", \"mode\": \"%s\", \"steps\": %d, \"elements\": %d, "
               "\"median_ns\": %.1f, \"p999_ns\": %.1f, \"max_ns\": %.1f, "
               "\"batched_median_ns\": %.2f, \"clock_overhead_ns\": %.1f}\n",
               names[mode], STEPS, ELEMENTS, quantile(times, STEPS, 0.5),
               quantile(times, STEPS, 0.999), times[STEPS - 1],
               quantile(averages, STEPS / BATCH, 0.5), overhead);
    }
    free(inputs);
    free(times);
    return 0;
}
