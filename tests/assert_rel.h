/* Shared by the cmocka suites: a relative-tolerance assertion that prints both values. */
#ifndef CT_TESTS_ASSERT_REL_H
#define CT_TESTS_ASSERT_REL_H

#include <math.h>

#define assert_rel(a, b, rel)                                                                      \
    do {                                                                                           \
        double a_ = (a), b_ = (b);                                                                 \
        if (!(fabs(a_ - b_) <= (rel)*fmax(fabs(a_), fabs(b_))))                                    \
            fail_msg("%s = %.17g vs %s = %.17g", #a, a_, #b, b_);                                  \
    } while (0)

#endif
