/* libFuzzer target for the C ABI of leuven-rt (include/leuven_rt.h).
 *
 * The whole input is first handed to create_from_json and create_from_json_at as the text of a
 * parameter or model file (in both modes). It is then decoded into a sequence of calls on up to
 * four compensators: create (with parameter structs built from a physical base and mutated with
 * random doubles, `sigma2_neg` included, random W and Delta arrays of exactly `elements` heap
 * doubles, or null pointers), step and step_trajectory with random doubles (NaN, inf, huge,
 * tiny), set_params, set_level, set_position_force, set_position, reset, output, destroy, and
 * calls with null arguments.
 * Built with -fsanitize=fuzzer,address,undefined (scripts/fuzz_c.sh); the Rust library is built
 * normally, so AddressSanitizer sees its heap through malloc/free and catches out-of-bounds
 * reads of the arrays handed across the boundary.
 *
 * Invariants checked (abort on violation):
 * - a call that does not return LEUVEN_RT_OK changes nothing: no handle is written by a refused
 *   create, and the compensator's output is the same before and after a refused step or
 *   set_params (set_level and set_position_force never change it);
 * - a refusal for a missing start position names `x`;
 * - an OK step writes a finite force, and output() then reads that force back;
 * - a refused step with a valid `force` writes the last good force (0 on a null handle);
 * - every status has a non-null message.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "leuven_rt.h"

#define SLOTS 4
#define MAX_CALLS 64

typedef struct {
    const uint8_t *data;
    size_t size;
} reader;

static uint8_t byte(reader *r) {
    if (r->size == 0) return 0;
    uint8_t b = r->data[0];
    r->data++;
    r->size--;
    return b;
}

static uint64_t raw_bits(reader *r) {
    uint64_t bits = 0;
    for (int i = 0; i < 8; i++) bits = (bits << 8) | byte(r);
    return bits;
}

static double raw_double(reader *r) {
    uint64_t bits = raw_bits(r);
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* A double: special values, physical magnitudes of either sign, or any bit pattern. */
static double number(reader *r) {
    static const double special[] = {
        0.0, -0.0, NAN, INFINITY, -INFINITY, 1e-310, 1e308, 1.7976931348623157e308,
        1e-18, 1e-160, 2.2250738585072014e-308, 1.0, -1.0, 1e-3, 1e-6, 5e-324,
    };
    uint8_t kind = byte(r);
    if (kind < 64) return special[kind % (sizeof special / sizeof special[0])];
    if (kind < 192) {
        /* m·10^e with m in [-1, 1], e in [-12, 3]. */
        double m = ((double)byte(r) - 127.5) / 127.5;
        int e = (int)(byte(r) % 16) - 12;
        return m * pow(10.0, e);
    }
    return raw_double(r);
}

static void check(int condition, const char *what) {
    if (!condition) {
        fprintf(stderr, "invariant broken: %s\n", what);
        abort();
    }
}

static double output_of(leuven_rt_compensator *c) {
    double force = NAN;
    check(leuven_rt_compensator_output(c, &force) == LEUVEN_RT_OK, "output of a live handle");
    return force;
}

/* A parameter set: a valid base, with a few fields replaced by random doubles. The arrays are
 * heap blocks of exactly `elements` doubles (or null), so that ASan catches reads past them.
 * They are freed by the caller after the call that uses them. */
static void parameters(reader *r, leuven_rt_params *p, double **w, double **delta) {
    *w = NULL;
    *delta = NULL;
    memset(p, 0, sizeof *p);
    p->Fc = 1.0;
    p->Fs = 1.5;
    p->Vs = 1e-3;
    p->delta = 2.0;
    p->n = 2.0;
    p->sigma1 = 30.0;
    p->sigma2 = 0.4;
    uint8_t shape = byte(r);
    if (shape % 8 == 0) {
        p->sigma0 = 1e5;
        p->elements = 0;
    } else {
        size_t count = (size_t)(byte(r) % 36);
        p->elements = count;
        if (shape % 16 == 3) {
            p->elements = (size_t)raw_bits(r); /* anything, with null arrays */
        } else if (count > 0) {
            *w = malloc(count * sizeof(double));
            *delta = malloc(count * sizeof(double));
            for (size_t i = 0; i < count; i++) {
                (*w)[i] = 2.0 / (double)count;
                (*delta)[i] = 1e-6 * (double)(i + 1);
            }
        }
        p->W = *w;
        p->Delta = *delta;
        if (shape % 16 == 5) p->W = NULL;
        if (shape % 16 == 7) p->Delta = NULL;
    }
    uint8_t mutations = byte(r) % 6;
    for (uint8_t m = 0; m < mutations; m++) {
        uint8_t field = byte(r) % 15;
        double value = number(r);
        switch (field) {
        case 0: p->Fc = value; break;
        case 1: p->Fs = value; break;
        case 2: p->Fc_neg = value; break;
        case 3: p->Fs_neg = value; break;
        case 4: p->Vs = value; break;
        case 5: p->delta = value; break;
        case 6: p->n = value; break;
        case 7: p->sigma1 = value; break;
        case 8: p->sigma2 = value; break;
        case 9: p->sigma0 = value; break;
        case 10: p->sigma2_neg = value; break;
        default:
            if (*w != NULL && p->elements > 0) {
                size_t i = byte(r) % p->elements;
                if (field % 2) (*w)[i] = value; else (*delta)[i] = value;
            }
        }
    }
}

/* The input as the text of a parameter file or a versioned model file, created at a start
 * position or without one. */
static void from_json(const uint8_t *data, size_t size, int32_t mode, int at) {
    leuven_rt_compensator *sentinel = (leuven_rt_compensator *)&mode; /* never a handle */
    leuven_rt_compensator *made = sentinel;
    leuven_rt_error error = {NULL, 12345};
    leuven_rt_status status =
        at ? leuven_rt_compensator_create_from_json_at((const char *)data, size, 1e-3, mode, 2e-3,
                                                       &made, &error)
           : leuven_rt_compensator_create_from_json((const char *)data, size, 1e-3, mode, &made,
                                                    &error);
    check(error.field != NULL, "create_from_json writes the error");
    if (status != LEUVEN_RT_OK) {
        check(made == sentinel, "a refused create_from_json writes no handle");
        if (status == LEUVEN_RT_NO_START_POSITION) {
            check(!at && mode == LEUVEN_RT_MODE_FEEDFORWARD && strcmp(error.field, "x") == 0,
                  "only feedforward without a start position misses it, naming x");
        }
        return;
    }
    check(made != NULL && made != sentinel, "create_from_json OK gives a handle");
    check(output_of(made) == 0.0, "a new compensator outputs 0");
    check(leuven_rt_compensator_set_position(made, 1e-3) == LEUVEN_RT_OK, "a finite position");
    for (int k = 0; k < 8; k++) {
        double force = NAN;
        if (leuven_rt_compensator_step(made, 1e-3 * sin(0.5 * k), &force) == LEUVEN_RT_OK) {
            check(isfinite(force), "an OK step from a file gives a finite force");
        }
        if (leuven_rt_compensator_step_trajectory(made, 1e-3 * cos(0.5 * k), 1e-3 * k, &force) ==
            LEUVEN_RT_OK) {
            check(isfinite(force), "an OK trajectory step from a file gives a finite force");
        }
    }
    leuven_rt_compensator_destroy(made);
}

/* A level or a position force from the input: a valid base mutated by random doubles and counts
 * (the arrays are heap blocks of exactly the counts given, so that ASan catches reads past
 * them). */
static void set_level(reader *r, leuven_rt_compensator *c, int force) {
    double *amplitudes[4] = {NULL, NULL, NULL, NULL};
    leuven_rt_ripple ripples[2];
    for (int i = 0; i < 2; i++) {
        size_t harmonics = (size_t)(byte(r) % 10);
        amplitudes[2 * i] = malloc((harmonics ? harmonics : 1) * sizeof(double));
        amplitudes[2 * i + 1] = malloc((harmonics ? harmonics : 1) * sizeof(double));
        for (size_t k = 0; k < harmonics; k++) {
            amplitudes[2 * i][k] = byte(r) < 240 ? 0.01 : number(r);
            amplitudes[2 * i + 1][k] = byte(r) < 240 ? -0.01 : number(r);
        }
        ripples[i] = (leuven_rt_ripple){byte(r) < 200 ? 0.004 : number(r), amplitudes[2 * i],
                                        amplitudes[2 * i + 1], harmonics};
    }
    leuven_rt_level level = {byte(r) < 200 ? 0.0 : number(r), byte(r) < 200 ? 0.01 : number(r),
                             {byte(r) < 200 ? 0.05 : number(r), byte(r) < 200 ? -0.02 : number(r)},
                             ripples, (size_t)(byte(r) % 3)};
    leuven_rt_error error = {NULL, 0};
    double before = c ? output_of(c) : 0.0;
    const leuven_rt_level *given = byte(r) < 250 ? &level : NULL;
    leuven_rt_status status = force ? leuven_rt_compensator_set_position_force(c, given, &error)
                                    : leuven_rt_compensator_set_level(c, given, &error);
    if (c == NULL) {
        check(status == LEUVEN_RT_INVALID_POINTER, "a null handle is refused");
    } else {
        check(output_of(c) == before, "set_level leaves the output");
        if (status == LEUVEN_RT_INVALID_PARAMETER) check(error.field[0] != 0, "a level error names a field");
        if (status == LEUVEN_RT_NO_START_POSITION) check(strcmp(error.field, "x") == 0, "names x");
    }
    for (int i = 0; i < 4; i++) free(amplitudes[i]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    from_json(data, size, 0, 0);
    from_json(data, size, 1, 0);
    from_json(data, size, 0, 1);
    reader r = {data, size};
    leuven_rt_compensator *slots[SLOTS] = {NULL};
    for (int call = 0; call < MAX_CALLS && r.size > 0; call++) {
        uint8_t op = byte(&r);
        leuven_rt_compensator **slot = &slots[(op >> 4) % SLOTS];
        switch (op % 9) {
        case 0: { /* create */
            leuven_rt_params p;
            double *w, *delta;
            parameters(&r, &p, &w, &delta);
            double dt = byte(&r) < 200 ? 1e-3 : number(&r);
            int32_t mode = (int32_t)(byte(&r) % 3);
            leuven_rt_compensator *sentinel = (leuven_rt_compensator *)&r; /* never a handle */
            leuven_rt_compensator *made = sentinel;
            leuven_rt_error error = {NULL, 12345};
            leuven_rt_status status = leuven_rt_compensator_create(&p, dt, mode, &made, &error);
            free(w);
            free(delta);
            if (status == LEUVEN_RT_OK) {
                check(made != NULL && made != sentinel, "create OK gives a handle");
                check(output_of(made) == 0.0, "a new compensator outputs 0");
                leuven_rt_compensator_destroy(*slot);
                *slot = made;
            } else {
                check(made == sentinel, "a refused create writes no handle");
                if (status == LEUVEN_RT_INVALID_PARAMETER) {
                    check(error.field != NULL, "a parameter error names a field");
                }
            }
            break;
        }
        case 1: /* destroy */
            leuven_rt_compensator_destroy(*slot);
            *slot = NULL;
            break;
        case 2: case 3: { /* step, or a trajectory step */
            double input = number(&r);
            double force = 99.0;
            leuven_rt_status status =
                op % 9 == 2 ? leuven_rt_compensator_step(*slot, input, &force)
                            : leuven_rt_compensator_step_trajectory(*slot, input, number(&r), &force);
            if (*slot == NULL) {
                check(status == LEUVEN_RT_INVALID_POINTER, "a null handle is refused");
                check(force == 0.0, "a null handle writes 0");
                break;
            }
            double after = output_of(*slot);
            if (status == LEUVEN_RT_OK) {
                check(isfinite(force), "an OK step gives a finite force");
                check(after == force, "output() reads back the last force");
            } else {
                check(status == LEUVEN_RT_NOT_FINITE_INPUT || status == LEUVEN_RT_STEP_FAILED,
                      "a step fails only for its input");
                check(force == after && isfinite(force), "a refused step gives the last good force");
            }
            break;
        }
        case 4: { /* set_params */
            leuven_rt_params p;
            double *w, *delta;
            parameters(&r, &p, &w, &delta);
            leuven_rt_error error = {NULL, 0};
            double before = *slot ? output_of(*slot) : 0.0;
            leuven_rt_status status =
                leuven_rt_compensator_set_params(*slot, byte(&r) < 250 ? &p : NULL, &error);
            free(w);
            free(delta);
            if (*slot == NULL) {
                check(status == LEUVEN_RT_INVALID_POINTER, "a null handle is refused");
            } else {
                check(output_of(*slot) == before, "set_params leaves the output");
            }
            break;
        }
        case 5: { /* reset */
            leuven_rt_status status = leuven_rt_compensator_reset(*slot);
            check((status == LEUVEN_RT_OK) == (*slot != NULL), "reset refuses only null");
            if (*slot) check(output_of(*slot) == 0.0, "reset outputs 0");
            break;
        }
        case 6: /* null arguments */
            check(leuven_rt_compensator_output(*slot, NULL) == LEUVEN_RT_INVALID_POINTER,
                  "output to null");
            check(leuven_rt_compensator_step(*slot, 0.0, NULL) == LEUVEN_RT_INVALID_POINTER,
                  "step to null");
            check(leuven_rt_compensator_create(NULL, 1e-3, 0, NULL, NULL) != LEUVEN_RT_OK,
                  "create from null");
            break;
        case 7: /* messages, levels and positions */
            check(leuven_rt_status_message((int32_t)raw_bits(&r)) != NULL, "a message");
            uint8_t which = byte(&r) % 3;
            if (which < 2) {
                set_level(&r, *slot, which);
            } else {
                double x = number(&r);
                leuven_rt_status status = leuven_rt_compensator_set_position(*slot, x);
                check(*slot == NULL ? status == LEUVEN_RT_INVALID_POINTER
                                    : (status == LEUVEN_RT_OK) == (isfinite(x) != 0),
                      "set_position refuses only null and non-finite");
            }
            break;
        default: { /* a run of steps */
            if (*slot == NULL) break;
            double v = number(&r);
            uint8_t steps = byte(&r);
            for (uint8_t k = 0; k < steps; k++) {
                double force;
                leuven_rt_status status = leuven_rt_compensator_step(*slot, v * sin(0.1 * k), &force);
                if (status == LEUVEN_RT_OK) check(isfinite(force), "finite force in a run");
            }
        }
        }
    }
    for (int i = 0; i < SLOTS; i++) leuven_rt_compensator_destroy(slots[i]);
    return 0;
}
