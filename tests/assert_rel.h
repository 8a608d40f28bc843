/* Shared by the cmocka suites: a relative-tolerance comparison and an assertion that prints
 * both values and their relative difference. */
#ifndef CT_TESTS_ASSERT_REL_H
#define CT_TESTS_ASSERT_REL_H

#include <math.h>

/* |a - b| <= rel max(|a|, |b|) (two zeros are equal). */
static inline int close_rel(double a, double b, double rel)
{
    return fabs(a - b) <= rel * fmax(fabs(a), fabs(b)) + 1e-300;
}

#define assert_rel(a, b, rel)                                                                      \
    do {                                                                                           \
        double a_ = (a), b_ = (b);                                                                 \
        if (!close_rel(a_, b_, rel))                                                               \
            fail_msg("%s = %.17g vs %s = %.17g (rel %.3g > %.3g)", #a, a_, #b, b_,                 \
                     fabs(a_ - b_) / fmax(fabs(a_), fabs(b_)), (double)(rel));                     \
    } while (0)

#endif
