/*
 * A C control loop using the compensator through include/leuven_rt.h; tests/c_control_loop.rs
 * compiles it with gcc against libgms_ffi, runs it and checks every printed number against the
 * same loop computed in Rust with gms-core.
 *
 * Two 1 kHz loops, one per mode: a mass (m = 1 kg, viscous damping c = 2 N·s/m) with friction
 * under PD control tracking x_d(t) = A·(1 − cos 2πft), plus the compensator's force. The
 * plant's friction is the library too: a third model, in observer mode with the "true"
 * parameters, fed the plant's position (applied over the next sample). The compensators start
 * from nominal parameters and at sample 1000 are swapped to the true ones (set_params); at
 * sample 1500 their input is NaN (the loop must get LEUVEN_RT_NOT_FINITE_INPUT and the last good
 * force, and leaves the compensator out for that sample). Output lines:
 *
 *   loop <k> <x_feedforward> <force_feedforward> <x_observer> <force_observer>
 *   check <name> <status> <field> <index>
 *   value <name> <number>
 *
 * Numbers are printed with %.17g, which round-trips doubles exactly.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "leuven_rt.h"

#define SAMPLES 2000
#define SWAP_AT 1000
#define NAN_AT 1500

static const double DT = 1e-3;
static const double MASS = 1.0, DAMPING = 2.0, KP = 4000.0, KD = 80.0;
static const double AMPLITUDE = 2e-4, FREQUENCY = 2.0;
static const double PI = 3.14159265358979323846;

static const double W[10] = {0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2};
static const double DELTA[10] = {1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 7e-6, 8e-6, 9e-6, 1e-5};
static const double W_NEW[10] = {0.3, 0.3, 0.25, 0.25, 0.2, 0.2, 0.15, 0.15, 0.1, 0.1};
static const double DELTA_NEW[10] = {1.5e-6, 3e-6, 4e-6, 5e-6, 6e-6, 8e-6, 9e-6, 1e-5, 1.2e-5, 1.5e-5};

static leuven_rt_params nominal(void) {
    leuven_rt_params p;
    memset(&p, 0, sizeof p);
    p.Fc = 1.0;
    p.Fs = 1.5;
    p.Vs = 1e-3;
    p.delta = 2.0;
    p.n = 2.0;
    p.sigma1 = 30.0;
    p.sigma2 = 0.4;
    p.W = W;
    p.Delta = DELTA;
    p.elements = 10;
    return p;
}

static leuven_rt_params swapped(void) {
    leuven_rt_params p = nominal();
    p.Fc = 1.1;
    p.Fs = 1.7;
    p.Vs = 1.5e-3;
    p.W = W_NEW;
    p.Delta = DELTA_NEW;
    return p;
}

static void check(const char *name, leuven_rt_status status, const leuven_rt_error *error) {
    printf("check %s %d %s %zu\n", name, (int)status,
           error && error->field && error->field[0] ? error->field : "-", error ? error->index : 0);
}

/* The message is NUL-terminated within its array, "" on success and a sentence otherwise. */
static void check_message(const char *name, leuven_rt_status status, const leuven_rt_error *error) {
    const char *nul = memchr(error->message, 0, LEUVEN_RT_ERROR_MESSAGE_SIZE);
    size_t length = nul ? (size_t)(nul - error->message) : LEUVEN_RT_ERROR_MESSAGE_SIZE;
    if (length == LEUVEN_RT_ERROR_MESSAGE_SIZE || (status == LEUVEN_RT_OK) != (length == 0)) {
        fprintf(stderr, "%s: bad error message (status %d, length %zu)\n", name, (int)status, length);
        exit(2);
    }
}

/* A plant state, its friction and its compensator. */
typedef struct {
    double x, v;
    leuven_rt_compensator *compensator;
    leuven_rt_compensator *friction;
    int mode;
} axis_t;

/* One sample of one loop; returns the compensator's force. */
static double sample(axis_t *axis, int k, double *x_out) {
    double t = k * DT;
    double x_desired = AMPLITUDE * (1.0 - cos(2.0 * PI * FREQUENCY * t));
    double v_desired = AMPLITUDE * 2.0 * PI * FREQUENCY * sin(2.0 * PI * FREQUENCY * t);
    double input = axis->mode == LEUVEN_RT_MODE_FEEDFORWARD ? v_desired : axis->x;
    if (k == NAN_AT) input = NAN;
    double force = 0.0;
    leuven_rt_status status = leuven_rt_compensator_step(axis->compensator, input, &force);
    if (k == NAN_AT) {
        double held = -1.0;
        leuven_rt_compensator_output(axis->compensator, &held);
        check(axis->mode == LEUVEN_RT_MODE_FEEDFORWARD ? "nan_feedforward" : "nan_observer",
              status, NULL);
        if (!(isfinite(force) && force == held)) {
            fprintf(stderr, "a rejected step must hold the last good force\n");
            exit(2);
        }
        force = 0.0; /* the loop leaves the compensator out for this sample */
    } else if (status != LEUVEN_RT_OK) {
        fprintf(stderr, "step %d failed: %s\n", k, leuven_rt_status_message(status));
        exit(2);
    }
    double command = KP * (x_desired - axis->x) + KD * (v_desired - axis->v) + force;
    double friction = 0.0;
    if (leuven_rt_compensator_step(axis->friction, axis->x, &friction) != LEUVEN_RT_OK) {
        fprintf(stderr, "plant friction step %d failed\n", k);
        exit(2);
    }
    /* Semi-implicit Euler of m·a = u − c·v − friction. */
    axis->v += DT * (command - DAMPING * axis->v - friction) / MASS;
    axis->x += DT * axis->v;
    *x_out = axis->x;
    return force;
}

static int control_loops(void) {
    leuven_rt_params p = nominal(), q = swapped();
    axis_t axes[2] = {{0.0, 0.0, NULL, NULL, LEUVEN_RT_MODE_FEEDFORWARD},
                      {0.0, 0.0, NULL, NULL, LEUVEN_RT_MODE_OBSERVER}};
    for (int i = 0; i < 2; ++i) {
        leuven_rt_status status =
            leuven_rt_compensator_create(&p, DT, axes[i].mode, &axes[i].compensator, NULL);
        if (status == LEUVEN_RT_OK)
            status = leuven_rt_compensator_create(&q, DT, LEUVEN_RT_MODE_OBSERVER,
                                                  &axes[i].friction, NULL);
        if (status != LEUVEN_RT_OK) {
            fprintf(stderr, "create failed: %s\n", leuven_rt_status_message(status));
            return 2;
        }
    }
    for (int k = 0; k < SAMPLES; ++k) {
        if (k == SWAP_AT) {
            for (int i = 0; i < 2; ++i) {
                leuven_rt_error error = {0};
                leuven_rt_status status =
                    leuven_rt_compensator_set_params(axes[i].compensator, &q, &error);
                if (status != LEUVEN_RT_OK) {
                    fprintf(stderr, "set_params failed: %s\n", leuven_rt_status_message(status));
                    return 2;
                }
            }
        }
        double x_feedforward, x_observer;
        double f_feedforward = sample(&axes[0], k, &x_feedforward);
        double f_observer = sample(&axes[1], k, &x_observer);
        printf("loop %d %.17g %.17g %.17g %.17g\n", k, x_feedforward, f_feedforward, x_observer,
               f_observer);
    }
    for (int i = 0; i < 2; ++i) {
        leuven_rt_compensator_destroy(axes[i].compensator);
        leuven_rt_compensator_destroy(axes[i].friction);
    }
    return 0;
}

/* Every bad argument the library can detect gets a status, never a crash. */
static void bad_input(const char *folder) {
    leuven_rt_params p = nominal();
    leuven_rt_compensator *c = NULL;
    leuven_rt_error error;
    double force = -1.0;

/* Calls with an error struct: it is filled with garbage first, so that a call that leaves it
 * unwritten shows ("unwritten", 99); every status must write all of it. */
#define EXPECT(name, call)                                 \
    do {                                                   \
        memset(&error, 0x5a, sizeof error);                \
        error.field = "unwritten";                         \
        error.index = 99;                                  \
        leuven_rt_status status_ = (call);                 \
        check(name, status_, &error);                      \
        check_message(name, status_, &error);              \
    } while (0)
/* Calls without one. */
#define STATUS(name, call)                                 \
    do {                                                   \
        leuven_rt_status status_ = (call);                 \
        check(name, status_, NULL);                        \
    } while (0)

    EXPECT("create_null_params", leuven_rt_compensator_create(NULL, DT, 0, &c, &error));
    EXPECT("create_null_out", leuven_rt_compensator_create(&p, DT, 0, NULL, &error));
    EXPECT("create_dt_zero", leuven_rt_compensator_create(&p, 0.0, 0, &c, &error));
    EXPECT("create_dt_negative", leuven_rt_compensator_create(&p, -1e-3, 0, &c, &error));
    EXPECT("create_dt_nan", leuven_rt_compensator_create(&p, NAN, 0, &c, &error));
    EXPECT("create_bad_mode", leuven_rt_compensator_create(&p, DT, 7, &c, &error));
    leuven_rt_params bad = p;
    bad.Fs = 0.5;
    EXPECT("create_fs_below_fc", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.Vs = -1.0;
    EXPECT("create_vs_negative", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.sigma2 = NAN;
    EXPECT("create_sigma2_nan", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    double w_bad[10];
    memcpy(w_bad, W, sizeof w_bad);
    w_bad[3] = -0.2;
    bad = p;
    bad.W = w_bad;
    EXPECT("create_w3_negative", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    double w_weak[10] = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1};
    bad = p;
    bad.W = w_weak;
    EXPECT("create_elements_too_weak", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.W = NULL;
    EXPECT("create_w_null", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.elements = 33;
    double many[33];
    for (int i = 0; i < 33; ++i) many[i] = 0.1;
    bad.W = many;
    bad.Delta = many;
    EXPECT("create_too_many_elements", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.sigma0 = 1e5;
    EXPECT("create_both_hysteresis", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.elements = 0;
    EXPECT("create_no_hysteresis", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    /* Misaligned pointers are refused too. */
    char buffer[sizeof(leuven_rt_params) + 1];
    memcpy(buffer + 1, &p, sizeof p);
    EXPECT("create_misaligned_params",
           leuven_rt_compensator_create((const leuven_rt_params *)(buffer + 1), DT, 0, &c, &error));
    if (c != NULL) {
        fprintf(stderr, "a failed create must leave *out as it was\n");
        exit(2);
    }

    /* Calls on a null handle. */
    STATUS("step_null_handle", leuven_rt_compensator_step(NULL, 0.0, &force));
    printf("value step_null_handle_force %.17g\n", force);
    EXPECT("set_params_null_handle", leuven_rt_compensator_set_params(NULL, &p, &error));
    STATUS("reset_null_handle", leuven_rt_compensator_reset(NULL));
    STATUS("output_null_handle", leuven_rt_compensator_output(NULL, &force));
    leuven_rt_compensator_destroy(NULL);

    /* A live observer: bad samples and bad parameter sets leave it as it was. */
    EXPECT("create_ok", leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_OBSERVER, &c, &error));
    for (int k = 0; k < 10; ++k) leuven_rt_compensator_step(c, 1e-7 * k, &force);
    double before = force;
    STATUS("step_null_force", leuven_rt_compensator_step(c, 1e-6, NULL));
    STATUS("step_inf", leuven_rt_compensator_step(c, INFINITY, &force));
    STATUS("step_nan", leuven_rt_compensator_step(c, NAN, &force));
    printf("value held_force_equal %d\n", force == before);
    /* A finite position whose jump over dt overflows the velocity. */
    STATUS("step_huge_jump", leuven_rt_compensator_step(c, 1e306, &force));
    bad = p;
    bad.Fc = -1.0;
    EXPECT("set_params_fc_negative", leuven_rt_compensator_set_params(c, &bad, &error));
    bad = p;
    bad.elements = 4;
    EXPECT("set_params_other_count", leuven_rt_compensator_set_params(c, &bad, &error));
    bad = p;
    bad.elements = 0;
    bad.sigma0 = 1e5;
    EXPECT("set_params_other_kind", leuven_rt_compensator_set_params(c, &bad, &error));
    /* After all that, the next sample is the one an untouched compensator would give. */
    leuven_rt_compensator *twin = NULL;
    leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_OBSERVER, &twin, NULL);
    double twin_force = 0.0;
    for (int k = 0; k < 10; ++k) leuven_rt_compensator_step(twin, 1e-7 * k, &twin_force);
    leuven_rt_compensator_step(c, 2e-6, &force);
    leuven_rt_compensator_step(twin, 2e-6, &twin_force);
    printf("value untouched_after_rejections %d\n", force == twin_force);
    leuven_rt_compensator_destroy(twin);
    leuven_rt_compensator_destroy(c);

    /* Parameter files: the JSON that leuven-rt identify writes. */
    static const char GOOD[] =
        "{\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0, \"sigma1\": 30.0,\n"
        " \"sigma2\": 0.4, \"W\": [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],\n"
        " \"Delta\": [1e-06, 2e-06, 3e-06, 4e-06, 5e-06, 6e-06, 7e-06, 8e-06, 9e-06, 1e-05]}\n";
    c = NULL;
    EXPECT("json_ok", leuven_rt_compensator_create_from_json(GOOD, strlen(GOOD), DT,
                                                              LEUVEN_RT_MODE_OBSERVER, &c, &error));
    twin = NULL;
    leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_OBSERVER, &twin, NULL);
    int same = c != NULL && twin != NULL;
    for (int k = 0; same && k < 50; ++k) {
        leuven_rt_compensator_step(c, 1e-7 * k, &force);
        leuven_rt_compensator_step(twin, 1e-7 * k, &twin_force);
        same = force == twin_force;
    }
    printf("value json_equals_struct %d\n", same);
    leuven_rt_compensator_destroy(c);
    c = NULL;
    static const char UNKNOWN[] =
        "{\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 1.0, \"sigma0\": 1e5,"
        " \"Fq\": 2.0}";
    EXPECT("json_unknown_key",
           leuven_rt_compensator_create_from_json(UNKNOWN, strlen(UNKNOWN), DT, 0, &c, &error));
    printf("value json_unknown_key_named %d\n", strstr(error.message, "Fq") != NULL);
    static const char MISSING[] = "{\"Fc\": 1.0, \"Fs\": 1.5, \"delta\": 2.0, \"n\": 1.0, \"sigma0\": 1e5}";
    EXPECT("json_missing_key",
           leuven_rt_compensator_create_from_json(MISSING, strlen(MISSING), DT, 0, &c, &error));
    printf("value json_missing_key_named %d\n", strstr(error.message, "Vs") != NULL);
    static const char BELOW[] = "{\"Fc\": 1.0, \"Fs\": 0.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 1.0, \"sigma0\": 1e5}";
    EXPECT("json_fs_below_fc",
           leuven_rt_compensator_create_from_json(BELOW, strlen(BELOW), DT, 0, &c, &error));
    static const char WEAK[] =
        "{\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0,"
        " \"W\": [0.5, 0.5], \"Delta\": [1e-6, 2e-6]}";
    EXPECT("json_elements_too_weak",
           leuven_rt_compensator_create_from_json(WEAK, strlen(WEAK), DT, 0, &c, &error));
    static const char HALF[] =
        "{\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0, \"W\": [1.0, 1.0]}";
    EXPECT("json_w_without_delta",
           leuven_rt_compensator_create_from_json(HALF, strlen(HALF), DT, 0, &c, &error));
    EXPECT("json_not_json", leuven_rt_compensator_create_from_json("[1, 2", 5, DT, 0, &c, &error));
    EXPECT("json_null", leuven_rt_compensator_create_from_json(NULL, 0, DT, 0, &c, &error));
    EXPECT("json_bad_mode",
           leuven_rt_compensator_create_from_json(GOOD, strlen(GOOD), DT, 9, &c, &error));

    char path[4096];
    snprintf(path, sizeof path, "%s/leuven_rt_params.json", folder);
    FILE *file = fopen(path, "w");
    if (file == NULL || fputs(GOOD, file) < 0 || fclose(file) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(2);
    }
    EXPECT("file_ok", leuven_rt_compensator_create_from_file(path, DT, 0, &c, &error));
    leuven_rt_compensator_destroy(c);
    c = NULL;
    snprintf(path, sizeof path, "%s/no_such_params.json", folder);
    EXPECT("file_missing", leuven_rt_compensator_create_from_file(path, DT, 0, &c, &error));
    printf("value file_missing_named %d\n", strstr(error.message, "no_such_params.json") != NULL);
    EXPECT("file_null", leuven_rt_compensator_create_from_file(NULL, DT, 0, &c, &error));
    /* Not a regular file: a folder, and a device that never ends (it must not be read whole). */
    EXPECT("file_folder", leuven_rt_compensator_create_from_file(folder, DT, 0, &c, &error));
    EXPECT("file_device", leuven_rt_compensator_create_from_file("/dev/zero", DT, 0, &c, &error));
    if (c != NULL) {
        fprintf(stderr, "a failed create must leave *out as it was\n");
        exit(2);
    }
}

/* argv[1]: a folder to write a parameter file in (default: the current one). */
int main(int argc, char **argv) {
    int status = control_loops();
    if (status != 0) return status;
    bad_input(argc > 1 ? argv[1] : ".");
    return 0;
}
