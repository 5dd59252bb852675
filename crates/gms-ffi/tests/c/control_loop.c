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
 * A third part gives compensators a position-dependent level, from the versioned model file and
 * from the struct, steps them over a fixed trajectory, and refuses bad levels and bad files. A
 * fourth gives them a viscous coefficient of their own for v < 0, a position force and trajectory
 * steps (velocity and position together), and refuses feedforward terms without a start position.
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

/* Every bad argument the library can detect gets a status, never a crash. */
static void bad_input(const char *folder) {
    leuven_rt_params p = nominal();
    leuven_rt_compensator *c = NULL;
    leuven_rt_error error;
    double force = -1.0;

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
    bad = p;
    bad.sigma2_neg = -0.5;
    EXPECT("create_sigma2_neg_negative", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
    bad = p;
    bad.sigma2_neg = NAN;
    EXPECT("create_sigma2_neg_nan", leuven_rt_compensator_create(&bad, DT, 0, &c, &error));
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

#define LEVEL_SAMPLES 300

/* The trajectory of the level part: a swing of a few ripple periods with a slow drift. */
static double level_position(int k) { return 0.003 * sin(0.01 * k) + 1e-5 * k; }
static double level_velocity(int k) { return 8e-3 * cos(0.01 * k); }

/* A trend and two ripples; the model file MODEL below holds the same. */
static const double COS0[3] = {0.03, 0.01, 0.005}, SIN0[3] = {0.0, 0.02, -0.004};
static const double COS1[2] = {0.01, -0.006}, SIN1[2] = {0.012, 0.003};

static const char MODEL[] =
    "{\"format\": \"leuven-rt model\", \"version\": 1, \"units\": \"linear\",\n"
    " \"friction\": {\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0,\n"
    "   \"sigma1\": 30.0, \"sigma2\": 0.4, \"W\": [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],\n"
    "   \"Delta\": [1e-06, 2e-06, 3e-06, 4e-06, 5e-06, 6e-06, 7e-06, 8e-06, 9e-06, 1e-05]},\n"
    " \"level\": {\"middle\": 0.002, \"half_stroke\": 0.01, \"trend\": [0.05, -0.02],\n"
    "   \"ripples\": [{\"period\": 0.004, \"cos\": [0.03, 0.01, 0.005], \"sin\": [0.0, 0.02, -0.004]},\n"
    "                 {\"period\": 0.0013, \"cos\": [0.01, -0.006], \"sin\": [0.012, 0.003]}]},\n"
    " \"measurement\": {\"offset\": 0.1, \"inertia\": 0.0},\n"
    " \"report\": {\"rms\": 0.02, \"notes\": [\"anything\", {\"goes\": null}]}}\n";

/* A model file without a level, its measurement and report ignored. */
static const char MODEL_NO_LEVEL[] =
    "{\"format\": \"leuven-rt model\", \"version\": 1, \"units\": \"rotary\",\n"
    " \"friction\": {\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0,\n"
    "   \"sigma1\": 30.0, \"sigma2\": 0.4, \"W\": [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],\n"
    "   \"Delta\": [1e-06, 2e-06, 3e-06, 4e-06, 5e-06, 6e-06, 7e-06, 8e-06, 9e-06, 1e-05]},\n"
    " \"level\": null, \"measurement\": {\"offset\": -3.5, \"inertia\": 0.25}}";

/* `MODEL` with `from` (the first occurrence) replaced by `to`, in `out`. */
static const char *edited(char *out, size_t size, const char *from, const char *to) {
    const char *at = strstr(MODEL, from);
    if (at == NULL) {
        fprintf(stderr, "no %s in the model file\n", from);
        exit(2);
    }
    snprintf(out, size, "%.*s%s%s", (int)(at - MODEL), MODEL, to, at + strlen(from));
    return out;
}

static void levels(const char *folder) {
    leuven_rt_params p = nominal();
    leuven_rt_error error;
    leuven_rt_compensator *file = NULL, *made = NULL, *plain = NULL, *c = NULL;
    double force = 0.0, other = 0.0;
    EXPECT("model_ok", leuven_rt_compensator_create_from_json(MODEL, strlen(MODEL), DT,
                                                               LEUVEN_RT_MODE_OBSERVER, &file, &error));
    EXPECT("model_struct_create", leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_OBSERVER, &made, &error));
    leuven_rt_ripple ripples[3] = {{0.004, COS0, SIN0, 3}, {0.0013, COS1, SIN1, 2}, {0.5, NULL, NULL, 0}};
    leuven_rt_level level = {0.002, 0.01, {0.05, -0.02}, ripples, 2};
    EXPECT("set_level_ok", leuven_rt_compensator_set_level(made, &level, &error));
    int same = file != NULL && made != NULL;
    for (int k = 0; same && k < LEVEL_SAMPLES; ++k) {
        same = leuven_rt_compensator_step(file, level_position(k), &force) == LEUVEN_RT_OK &&
               leuven_rt_compensator_step(made, level_position(k), &other) == LEUVEN_RT_OK &&
               force == other;
        printf("value level_observer_%d %.17g\n", k, force);
    }
    printf("value level_struct_equals_file %d\n", same);

    /* Bad levels: each named, and none changes the compensator. */
    leuven_rt_level bad = level;
    bad.half_stroke = 0.0;
    EXPECT("level_half_stroke_zero", leuven_rt_compensator_set_level(made, &bad, &error));
    bad = level;
    bad.middle = INFINITY;
    EXPECT("level_middle_inf", leuven_rt_compensator_set_level(made, &bad, &error));
    bad = level;
    bad.trend[1] = NAN;
    EXPECT("level_trend1_nan", leuven_rt_compensator_set_level(made, &bad, &error));
    bad = level;
    bad.ripple_count = 3;
    EXPECT("level_three_ripples", leuven_rt_compensator_set_level(made, &bad, &error));
    leuven_rt_ripple bad_ripples[2] = {ripples[0], ripples[1]};
    bad = level;
    bad.ripples = bad_ripples;
    bad_ripples[1].period = -1.0;
    EXPECT("level_period_negative", leuven_rt_compensator_set_level(made, &bad, &error));
    static const double NINE[9] = {0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01};
    bad_ripples[1] = (leuven_rt_ripple){0.01, NINE, NINE, 9};
    EXPECT("level_nine_harmonics", leuven_rt_compensator_set_level(made, &bad, &error));
    const double cos_nan[2] = {0.01, NAN};
    bad_ripples[1] = (leuven_rt_ripple){0.01, cos_nan, SIN1, 2};
    EXPECT("level_cos_nan", leuven_rt_compensator_set_level(made, &bad, &error));
    printf("value level_cos_nan_named %d\n", strstr(error.message, "ripples[1].cos[1]") != NULL);
    const double deep[2] = {0.5, 0.4};
    bad_ripples[1] = (leuven_rt_ripple){0.01, deep, SIN1, 2};
    EXPECT("level_too_deep", leuven_rt_compensator_set_level(made, &bad, &error));
    bad_ripples[1] = (leuven_rt_ripple){0.01, NULL, SIN1, 2};
    EXPECT("level_null_cos", leuven_rt_compensator_set_level(made, &bad, &error));
    bad = level;
    bad.ripples = NULL;
    EXPECT("level_null_ripples", leuven_rt_compensator_set_level(made, &bad, &error));
    EXPECT("level_null", leuven_rt_compensator_set_level(made, NULL, &error));
    EXPECT("level_null_handle", leuven_rt_compensator_set_level(NULL, &level, &error));
    leuven_rt_compensator_step(file, level_position(LEVEL_SAMPLES), &force);
    leuven_rt_compensator_step(made, level_position(LEVEL_SAMPLES), &other);
    printf("value level_untouched_after_rejections %d\n", force == other);
    leuven_rt_compensator_destroy(made);
    made = NULL;

    /* Feedforward: a level needs the start position, and the position is integrated from it. */
    EXPECT("model_feedforward", leuven_rt_compensator_create_from_json(
                                    MODEL, strlen(MODEL), DT, LEUVEN_RT_MODE_FEEDFORWARD, &c, &error));
    printf("value model_feedforward_named %d\n", strstr(error.message, "`x`") == error.message);
    EXPECT("model_feedforward_at_nan",
           leuven_rt_compensator_create_from_json_at(MODEL, strlen(MODEL), DT,
                                                     LEUVEN_RT_MODE_FEEDFORWARD, NAN, &c, &error));
    if (c != NULL) {
        fprintf(stderr, "a refused create must leave *out as it was\n");
        exit(2);
    }
    EXPECT("model_feedforward_at",
           leuven_rt_compensator_create_from_json_at(MODEL, strlen(MODEL), DT,
                                                     LEUVEN_RT_MODE_FEEDFORWARD, 0.5, &c, &error));
    STATUS("set_position_nan", leuven_rt_compensator_set_position(c, NAN));
    STATUS("set_position_null", leuven_rt_compensator_set_position(NULL, 0.0));
    STATUS("set_position_ok", leuven_rt_compensator_set_position(c, -0.0042));
    for (int k = 0; k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step(c, level_velocity(k), &force);
        printf("value level_feedforward_%d %.17g\n", k, force);
    }
    leuven_rt_compensator_destroy(c);
    c = NULL;

    /* A model file without a level is the plain parameter set. */
    EXPECT("model_no_level", leuven_rt_compensator_create_from_json(
                                 MODEL_NO_LEVEL, strlen(MODEL_NO_LEVEL), DT, LEUVEN_RT_MODE_OBSERVER, &c, &error));
    leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_OBSERVER, &plain, NULL);
    same = c != NULL && plain != NULL;
    for (int k = 0; same && k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step(c, level_position(k), &force);
        leuven_rt_compensator_step(plain, level_position(k), &other);
        same = force == other;
    }
    printf("value model_no_level_equals_plain %d\n", same);
    leuven_rt_compensator_destroy(c);
    leuven_rt_compensator_destroy(plain);
    c = NULL;

    /* Bad model files. */
    char text[4096];
#define MODEL_EXPECT(name, from, to)                                                         \
    do {                                                                                     \
        const char *json_ = edited(text, sizeof text, from, to);                             \
        EXPECT(name, leuven_rt_compensator_create_from_json(json_, strlen(json_), DT, 0, &c, &error)); \
    } while (0)
    MODEL_EXPECT("model_version_4", "\"version\": 1", "\"version\": 4");
    printf("value model_version_named %d\n", strstr(error.message, "`version` is 4") != NULL &&
                                                 strstr(error.message, "upgrade leuven-rt") != NULL);
    MODEL_EXPECT("model_version_missing", "\"version\": 1,", "");
    MODEL_EXPECT("model_format_other", "leuven-rt model", "leuven-rt params");
    printf("value model_format_named %d\n", strstr(error.message, "`format` must be") != NULL);
    MODEL_EXPECT("model_unknown_key", "\"units\"", "\"extra\": 1, \"units\"");
    printf("value model_unknown_key_named %d\n", strstr(error.message, "extra") != NULL);
    MODEL_EXPECT("model_units_other", "\"linear\"", "\"furlongs\"");
    MODEL_EXPECT("model_units_missing", "\"units\": \"linear\",", "");
    MODEL_EXPECT("model_measurement_string", "\"offset\": 0.1", "\"offset\": \"0.1\"");
    MODEL_EXPECT("model_measurement_unknown", "\"inertia\": 0.0", "\"inertia\": 0.0, \"mass\": 1");
    MODEL_EXPECT("model_friction_unknown", "\"sigma2\": 0.4", "\"sigma2\": 0.4, \"Fq\": 1");
    MODEL_EXPECT("model_friction_missing", "\"Vs\": 0.001, ", "");
    MODEL_EXPECT("model_friction_fs_below_fc", "\"Fs\": 1.5", "\"Fs\": 0.5");
    MODEL_EXPECT("model_level_half_stroke", "\"half_stroke\": 0.01", "\"half_stroke\": -0.01");
    MODEL_EXPECT("model_level_trend_length", "[0.05, -0.02]", "[0.05, -0.02, 0.1]");
    MODEL_EXPECT("model_level_sin_length", "\"sin\": [0.012, 0.003]", "\"sin\": [0.012]");
    MODEL_EXPECT("model_level_too_deep", "\"trend\": [0.05, -0.02]", "\"trend\": [0.5, -0.4]");
    MODEL_EXPECT("model_level_unknown", "\"middle\"", "\"centre\": 0, \"middle\"");
    if (c != NULL) {
        fprintf(stderr, "a refused model file must leave *out as it was\n");
        exit(2);
    }

    char path[4096];
    snprintf(path, sizeof path, "%s/leuven_rt_model.json", folder);
    FILE *out = fopen(path, "w");
    if (out == NULL || fputs(MODEL, out) < 0 || fclose(out) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(2);
    }
    EXPECT("model_file_ok", leuven_rt_compensator_create_from_file(path, DT, LEUVEN_RT_MODE_OBSERVER, &c, &error));
    leuven_rt_compensator_step(c, level_position(0), &force);
    leuven_rt_compensator_step(c, level_position(1), &force);
    leuven_rt_compensator_destroy(file);
    file = NULL;
    leuven_rt_compensator_create_from_json(MODEL, strlen(MODEL), DT, LEUVEN_RT_MODE_OBSERVER, &file, NULL);
    leuven_rt_compensator_step(file, level_position(0), &other);
    leuven_rt_compensator_step(file, level_position(1), &other);
    printf("value model_file_equals_text %d\n", force == other);
    leuven_rt_compensator_destroy(c);
    c = NULL;
    EXPECT("model_file_at", leuven_rt_compensator_create_from_file_at(
                                path, DT, LEUVEN_RT_MODE_FEEDFORWARD, -0.0042, &c, &error));
    leuven_rt_compensator_destroy(file);
    file = NULL;
    leuven_rt_compensator_create_from_json_at(MODEL, strlen(MODEL), DT, LEUVEN_RT_MODE_FEEDFORWARD,
                                              -0.0042, &file, NULL);
    same = c != NULL && file != NULL;
    for (int k = 0; same && k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step(c, level_velocity(k), &force);
        leuven_rt_compensator_step(file, level_velocity(k), &other);
        same = force == other;
    }
    printf("value model_file_at_equals_text %d\n", same);
    leuven_rt_compensator_destroy(c);
    leuven_rt_compensator_destroy(file);
}

/* A cogging force [N]: a gravity-like trend and one ripple; the Rust side holds the same. */
static const double COG_COS[2] = {0.4, 0.1}, COG_SIN[2] = {-0.3, 0.05};

/* Viscous asymmetry, a position force and trajectory steps. */
static void terms(void) {
    leuven_rt_params p = nominal();
    p.sigma2_neg = 0.9;
    leuven_rt_error error;
    leuven_rt_compensator *c = NULL, *t = NULL;
    double force = 0.0;
    leuven_rt_ripple ripples[2] = {{0.004, COS0, SIN0, 3}, {0.0013, COS1, SIN1, 2}};
    leuven_rt_level level = {0.002, 0.01, {0.05, -0.02}, ripples, 2};
    leuven_rt_ripple cog_ripple = {0.0025, COG_COS, COG_SIN, 2};
    leuven_rt_position_force cogging = {0.001, 0.02, {0.8, -0.3}, &cog_ripple, 1};

    /* Feedforward without a start position refuses the terms, naming x; then takes them. */
    EXPECT("terms_create", leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_FEEDFORWARD, &c, &error));
    EXPECT("level_without_start", leuven_rt_compensator_set_level(c, &level, &error));
    EXPECT("force_without_start", leuven_rt_compensator_set_position_force(c, &cogging, &error));
    STATUS("terms_start", leuven_rt_compensator_set_position(c, -0.0042));
    EXPECT("level_with_start", leuven_rt_compensator_set_level(c, &level, &error));
    EXPECT("force_with_start", leuven_rt_compensator_set_position_force(c, &cogging, &error));
    for (int k = 0; k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step(c, level_velocity(k), &force);
        printf("value terms_feedforward_%d %.17g\n", k, force);
    }
    /* Trajectory steps: the velocity drives the model, the position places the terms. */
    EXPECT("trajectory_create", leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_FEEDFORWARD, &t, &error));
    leuven_rt_compensator_set_position(t, level_position(0));
    leuven_rt_compensator_set_level(t, &level, NULL);
    leuven_rt_compensator_set_position_force(t, &cogging, NULL);
    for (int k = 0; k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step_trajectory(t, 1.1 * level_velocity(k), level_position(k), &force);
        printf("value terms_trajectory_%d %.17g\n", k, force);
    }
    double held = 0.0;
    leuven_rt_compensator_output(t, &held);
    force = -1.0;
    STATUS("trajectory_nan_x", leuven_rt_compensator_step_trajectory(t, 1e-3, NAN, &force));
    printf("value trajectory_held %d\n", force == held);
    STATUS("trajectory_inf_v", leuven_rt_compensator_step_trajectory(t, INFINITY, 0.0, &force));
    STATUS("trajectory_null_handle", leuven_rt_compensator_step_trajectory(NULL, 0.0, 0.0, &force));
    printf("value trajectory_null_handle_force %.17g\n", force);
    STATUS("trajectory_null_force", leuven_rt_compensator_step_trajectory(t, 0.0, 0.0, NULL));

    /* Positions and levels whose phase cannot be resolved, and bad position forces. */
    leuven_rt_ripple fine = {1e-12, COG_COS, COG_SIN, 2};
    leuven_rt_position_force bad = cogging;
    bad.ripples = &fine;
    EXPECT("force_period_unresolved", leuven_rt_compensator_set_position_force(c, &bad, &error));
    printf("value force_period_named %d\n", strstr(error.message, "`ripples[0].period` must be at least 2^20 ulps") != NULL);
    fine.period = 1e-300;
    leuven_rt_level bad_level = level;
    bad_level.ripples = &fine;
    bad_level.ripple_count = 1;
    EXPECT("level_period_1e-300", leuven_rt_compensator_set_level(c, &bad_level, &error));
    bad_level = level;
    bad_level.half_stroke = 1e-300;
    EXPECT("level_half_stroke_1e-300", leuven_rt_compensator_set_level(c, &bad_level, &error));
    bad_level = level;
    bad_level.middle = 1e308;
    EXPECT("level_middle_1e308", leuven_rt_compensator_set_level(c, &bad_level, &error));
    bad = cogging;
    bad.trend[0] = NAN;
    EXPECT("force_trend_nan", leuven_rt_compensator_set_position_force(c, &bad, &error));
    EXPECT("force_null", leuven_rt_compensator_set_position_force(c, NULL, &error));
    EXPECT("force_null_handle", leuven_rt_compensator_set_position_force(NULL, &cogging, &error));
    /* None of them changed the compensator: its next sample is its twin's. */
    double other = 0.0;
    leuven_rt_compensator *twin = NULL;
    leuven_rt_compensator_create(&p, DT, LEUVEN_RT_MODE_FEEDFORWARD, &twin, NULL);
    leuven_rt_compensator_set_position(twin, -0.0042);
    leuven_rt_compensator_set_level(twin, &level, NULL);
    leuven_rt_compensator_set_position_force(twin, &cogging, NULL);
    for (int k = 0; k < LEVEL_SAMPLES; ++k) leuven_rt_compensator_step(twin, level_velocity(k), &other);
    leuven_rt_compensator_step(c, 1e-3, &force);
    leuven_rt_compensator_step(twin, 1e-3, &other);
    printf("value terms_untouched_after_rejections %d\n", force == other);
    leuven_rt_compensator_destroy(twin);
    leuven_rt_compensator_destroy(t);
    leuven_rt_compensator_destroy(c);

    /* A parameter file can give sigma2_neg = 0 beside sigma2 = 0.4. */
    static const char ZERO_NEG[] =
        "{\"Fc\": 1.0, \"Fs\": 1.5, \"Vs\": 0.001, \"delta\": 2.0, \"n\": 2.0, \"sigma1\": 30.0,\n"
        " \"sigma2\": 0.4, \"sigma2_neg\": 0.0, \"W\": [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],\n"
        " \"Delta\": [1e-06, 2e-06, 3e-06, 4e-06, 5e-06, 6e-06, 7e-06, 8e-06, 9e-06, 1e-05]}\n";
    c = NULL;
    EXPECT("json_sigma2_neg_zero", leuven_rt_compensator_create_from_json(ZERO_NEG, strlen(ZERO_NEG), DT,
                                                                          LEUVEN_RT_MODE_FEEDFORWARD, &c, &error));
    for (int k = 0; k < LEVEL_SAMPLES; ++k) {
        leuven_rt_compensator_step(c, level_velocity(k), &force);
        printf("value sigma2_neg_zero_%d %.17g\n", k, force);
    }
    leuven_rt_compensator_destroy(c);
}

/* argv[1]: a folder to write a parameter file in (default: the current one). */
int main(int argc, char **argv) {
    int status = control_loops();
    if (status != 0) return status;
    bad_input(argc > 1 ? argv[1] : ".");
    levels(argc > 1 ? argv[1] : ".");
    terms();
    return 0;
}
