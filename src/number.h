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

/* A line of a table being written: its fields formatted into b and written to f in one call
 * when it ends (or fills), instead of a stream call for every field and comma. The bytes are
 * the same. Start one with ct_line_start (b is not cleared: it is written before it is read). */
typedef struct {
    FILE *f;
    size_t n;
    char b[2048];
} ct_line;

static inline void ct_line_start(ct_line *l, FILE *f)
{
    l->f = f;
    l->n = 0;
}

/* Writes what l holds to its stream. */
void ct_line_flush(ct_line *l);
/* Room for `need` more bytes in l (need <= sizeof l->b): flushed first when short of it. */
static inline char *ct_line_room(ct_line *l, size_t need)
{
    if (l->n + need > sizeof l->b)
        ct_line_flush(l);
    return l->b + l->n;
}
static inline void ct_line_char(ct_line *l, char c)
{
    *ct_line_room(l, 1) = c;
    l->n++;
}
/* x as "%.17g", as "%.3g", v as "%ld", s as it is */
static inline void ct_line_double(ct_line *l, double x)
{
    l->n += ct_format_double(ct_line_room(l, CT_NUMBER_MAX), x);
}
static inline void ct_line_g3(ct_line *l, double x)
{
    l->n += ct_format_g3(ct_line_room(l, CT_NUMBER_MAX), x);
}
void ct_line_long(ct_line *l, long v);
void ct_line_str(ct_line *l, const char *s);

#endif
