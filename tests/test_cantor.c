/* Cantor geometry (Eqs. 1-3, 16-18) and parameter validation. References are computed
 * here in long double from the definitions, never from the code under test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "cantact.h"

#define assert_close(a, b, rel)                                                                    \
    assert_true(fabsl((long double)(a) - (long double)(b)) <=                                      \
                (rel)*fmaxl(fabsl((long double)(a)), fabsl((long double)(b))) + 1e-300L)

static ct_params base(void)
{
    ct_params p = {
        .fx = 1.5, .fz = 1.3, .l0 = 2.0, .h0 = 0.5, .Hstar = 5.0, .E = 500.0, .sigma_y = 1.0};
    return p;
}

static void areas_sum_to_l0(void **state)
{
    (void)state;
    double fxs[] = {1.0000001, 1.2, 1.5, 3.0, 50.0};
    for (size_t f = 0; f < sizeof fxs / sizeof fxs[0]; f++) {
        ct_params p = base();
        p.fx = fxs[f];
        for (long N = 0; N <= 60; N += 3) {
            long double sum = 0.0L;
            for (long i = 0; i < N; i++)
                sum += ct_stage_area(&p, (double)i);
            sum += ct_stage_length(&p, (double)N);
            assert_close(sum, p.l0, 1e-15);
        }
    }
}

static void stage_values_against_definitions(void **state)
{
    (void)state;
    ct_params p = base();
    for (int i = 0; i < 40; i++) {
        long double l = p.l0 * powl(1.0L / p.fx, i), h = p.h0 * powl(1.0L / p.fz, i);
        assert_close(ct_stage_length(&p, i), l, 4e-15);
        assert_close(ct_stage_depth(&p, i), h, 4e-15);
        assert_close(ct_stage_area(&p, i), l - l / p.fx, 4e-15);
    }
    assert_close(ct_alpha(&p), logl(1.5L) / logl(1.3L), 1e-15);
    assert_close(ct_beta(&p), 1.0L / (1.5L * 1.3L), 1e-15);
    assert_close(ct_one_minus_beta(&p), 1.0L - 1.0L / (1.5L * 1.3L), 1e-15);
}

static void eq16_eq17_against_direct_sums(void **state)
{
    (void)state;
    ct_params p = base();
    double fzs[] = {1.01, 1.3, 1.9};
    for (size_t f = 0; f < 3; f++) {
        p.fz = fzs[f];
        for (int n1 = 0; n1 < 30; n1 += 7)
            for (int n2 = n1; n2 < 200; n2 += 13) {
                long double sa = 0.0L, sha = 0.0L;
                for (int i = n1; i <= n2; i++) {
                    long double s = p.l0 * powl(1.0L / p.fx, i) * (1.0L - 1.0L / p.fx);
                    sa += s;
                    sha += s * p.h0 * powl(1.0L / p.fz, i);
                }
                assert_close(ct_sum_area(&p, n1, n2), sa, 1e-14);
                assert_close(ct_sum_depth_area(&p, n1, n2), sha, 1e-14);
            }
        /* n2 = infinity against a long direct sum */
        long double sha = 0.0L;
        for (int i = 3; i < 20000; i++)
            sha += p.l0 * powl(1.0L / p.fx, i) * (1.0L - 1.0L / p.fx) * p.h0 * powl(1.0L / p.fz, i);
        assert_close(ct_sum_depth_area(&p, 3, INFINITY), sha, 1e-14);
    }
}

static void dimension_at_known_points(void **state)
{
    (void)state;
    ct_params p = base();
    /* D = 1 + (ln 2 - ln fz) / (ln 2 + ln fx) */
    p.fx = 2.0;
    p.fz = sqrt(2.0);
    assert_close(ct_dimension(&p), 1.25L, 1e-15);
    p.fx = 1.5;
    p.fz = 1.5;
    assert_close(ct_dimension(&p), 1.0L + logl(4.0L / 3.0L) / logl(3.0L), 1e-15);
    p.fx = 1.0 + 1e-12;
    p.fz = 1.0 + 1e-12;
    assert_close(ct_dimension(&p), 2.0L, 1e-11);
    /* D falls as fx rises (docs/model.md §8) */
    p.fz = 1.3;
    p.fx = 1.2;
    double d1 = ct_dimension(&p);
    p.fx = 1.8;
    assert_true(ct_dimension(&p) < d1);
}

static void near_one_and_deep_stages(void **state)
{
    (void)state;
    ct_params p = base();
    p.fx = 1.0 + 1e-12;
    p.fz = 1.0 + 1e-12;
    long double dfx = (long double)p.fx - 1.0L, dfz = (long double)p.fz - 1.0L;
    /* s_0 = l0 (fx - 1)/fx: a naive 1 - 1/fx would keep 4 digits here */
    assert_close(ct_stage_area(&p, 0), p.l0 * dfx / (1.0L + dfx), 1e-14);
    assert_close(ct_stage_length(&p, 1e6), p.l0 * expl(-1e6L * log1pl(dfx)), 1e-13);
    /* 1 - 1/(fx fz) = (dfx + dfz + dfx dfz) / (fx fz), free of cancellation */
    assert_close(ct_one_minus_beta(&p), (dfx + dfz + dfx * dfz) / ((1.0L + dfx) * (1.0L + dfz)),
                 1e-13);
    assert_close(ct_alpha(&p), log1pl(dfx) / log1pl(dfz), 1e-13);
    long double direct = 0.0L;
    for (int i = 0; i <= 1000; i++)
        direct +=
            p.l0 * expl(-i * log1pl(dfx)) * (dfx / (1.0L + dfx)) * p.h0 * expl(-i * log1pl(dfz));
    assert_close(ct_sum_depth_area(&p, 0, 1000), direct, 1e-12);
    /* stage indices in the millions: underflow to 0, never NaN */
    p = base();
    double deep[] = {1e6, 1e7, 3e9};
    for (int k = 0; k < 3; k++) {
        double v[] = {ct_stage_length(&p, deep[k]), ct_stage_depth(&p, deep[k]),
                      ct_stage_area(&p, deep[k]), ct_sum_area(&p, deep[k], INFINITY),
                      ct_sum_depth_area(&p, deep[k], deep[k] + 5)};
        for (int j = 0; j < 5; j++)
            assert_true(v[j] == 0.0);
    }
}

static void expect_rejected(ct_params p, const char *name)
{
    assert_int_equal(ct_params_validate(&p), CT_EINVAL);
    const char *msg = ct_error_message();
    if (!strstr(msg, name))
        fail_msg("message '%s' does not name %s", msg, name);
}

static void validation_names_the_parameter(void **state)
{
    (void)state;
    ct_params ok = base();
    assert_int_equal(ct_params_validate(&ok), CT_OK);
    double bad_values[] = {NAN, INFINITY, -INFINITY};
    struct {
        const char *name;
        size_t off;
        double out_of_range;
    } fields[] = {
        {"fx", offsetof(ct_params, fx), 1.0},           {"fz", offsetof(ct_params, fz), 2.0},
        {"l0", offsetof(ct_params, l0), 0.0},           {"h0", offsetof(ct_params, h0), -1.0},
        {"H*", offsetof(ct_params, Hstar), 0.5},        {"E", offsetof(ct_params, E), -3.0},
        {"sigma_y", offsetof(ct_params, sigma_y), 0.0},
    };
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; f++) {
        ct_params p = ok;
        *(double *)((char *)&p + fields[f].off) = fields[f].out_of_range;
        expect_rejected(p, fields[f].name);
        for (int k = 0; k < 3; k++) {
            p = ok;
            *(double *)((char *)&p + fields[f].off) = bad_values[k];
            if (!strcmp(fields[f].name, "E") && bad_values[k] == INFINITY)
                continue; /* E = inf with finite sigma_y: caught as E, see below */
            expect_rejected(p, fields[f].name);
        }
    }
    ct_params p = ok;
    p.E = INFINITY;
    expect_rejected(p, "E");
    p = ok;
    p.fz = 1.0;
    expect_rejected(p, "fz");
    p = ok;
    p.sigma_y = p.E; /* eps_y = 1 */
    expect_rejected(p, "sigma_y");
    p = ok;
    p.Hstar = p.h0; /* stage 0 rod of length 0 */
    expect_rejected(p, "H*");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(areas_sum_to_l0),
        cmocka_unit_test(stage_values_against_definitions),
        cmocka_unit_test(eq16_eq17_against_direct_sums),
        cmocka_unit_test(dimension_at_known_points),
        cmocka_unit_test(near_one_and_deep_stages),
        cmocka_unit_test(validation_names_the_parameter),
    };
    return cmocka_run_group_tests_name("cantor", tests, NULL, NULL);
}
