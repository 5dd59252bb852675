/*
 * The smallest C program with the leuven-rt compensator, built against the installed library
 * (scripts/c_package.sh builds it with pkg-config and with CMake):
 *
 *   cc example.c $(pkg-config --cflags --libs leuven_rt) -o example
 *   ./example [params.json]
 *
 * A 1 kHz loop: the compensator, in feedforward mode, turns a desired velocity (a triangle
 * wave, so that the example needs no libm) into the friction force to add to the command. With a parameter file (what `leuven-rt identify`
 * writes) or a versioned model file (docs/parameters.md#model-file) the compensator is made from
 * it; otherwise from a struct.
 */
#include <stdio.h>

#include "leuven_rt.h"

int main(int argc, char **argv) {
    static const double W[4] = {0.6, 0.5, 0.4, 0.3};
    static const double Delta[4] = {1e-6, 2e-6, 4e-6, 8e-6};
    leuven_rt_params p = {.Fc = 1.0, .Fs = 1.5, .Vs = 1e-3, .delta = 2.0, .n = 2.0,
                          .sigma1 = 30.0, .sigma2 = 0.4, .W = W, .Delta = Delta, .elements = 4};
    const double dt = 1e-3;
    leuven_rt_compensator *c = NULL;
    leuven_rt_error error;
    /* A model file may hold a position-dependent level; in feedforward mode it is placed from the
     * axis's start position (here 0), then along the position integrated from the desired
     * velocity. */
    leuven_rt_status status =
        argc > 1 ? leuven_rt_compensator_create_from_file_at(argv[1], dt, LEUVEN_RT_MODE_FEEDFORWARD,
                                                             0.0, &c, &error)
                 : leuven_rt_compensator_create(&p, dt, LEUVEN_RT_MODE_FEEDFORWARD, &c, &error);
    if (status != LEUVEN_RT_OK) {
        fprintf(stderr, "create: %s (field '%s'): %s\n", leuven_rt_status_message(status),
                error.field, error.message);
        return 1;
    }
    double peak = 0.0;
    for (int k = 0; k < 2000; ++k) {
        /* 1 s period, +-10 mm/s. */
        double phase = (k % 1000) / 1000.0;
        double v_desired = 0.01 * (phase < 0.5 ? 4.0 * phase - 1.0 : 3.0 - 4.0 * phase);
        double force = 0.0;
        if (leuven_rt_compensator_step(c, v_desired, &force) != LEUVEN_RT_OK) return 1;
        double size = force < 0.0 ? -force : force;
        if (size > peak) peak = size;
    }
    leuven_rt_compensator_destroy(c);
    printf("leuven_rt example: 2000 samples, peak compensation force %.3f N\n", peak);
    return peak > 1.0 ? 0 : 1;
}
