/* Doubles as text: byte for byte what printf("%.17g") writes (round-trip exact), faster. */
#ifndef CT_NUMBER_H
#define CT_NUMBER_H

#include <stddef.h>
#include <stdio.h>

#define CT_NUMBER_MAX 32

/* Writes x as "%.17g" would into buf (CT_NUMBER_MAX bytes); returns its length. */
size_t ct_format_double(char *buf, double x);
/* Writes x as "%.17g" would to f. */
void ct_put_double(FILE *f, double x);
/* Writes x as "%.3g" would into buf (CT_NUMBER_MAX bytes); returns its length. */
size_t ct_format_g3(char *buf, double x);
/* Writes x as "%.3g" would to f. */
void ct_put_g3(FILE *f, double x);
/* Writes v as "%ld" would to f. */
void ct_put_long(FILE *f, long v);

#endif
