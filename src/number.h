/* Doubles as text: byte for byte what printf("%.17g") writes (round-trip exact), faster; and
 * text as doubles and lists, by one rule for every reader. */
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

/* ---- reading: one rule for every number and list the program reads ---- */

/* What a text is as a number: CT_NUMBER_OK, or why a computation cannot use it. */
enum {
    CT_NUMBER_OK = 0,
    CT_NUMBER_NONE,       /* no number, or characters after it */
    CT_NUMBER_NOT_FINITE, /* inf or nan spelled out */
    CT_NUMBER_OVERFLOW,   /* |value| beyond the largest double */
    CT_NUMBER_UNDERFLOW   /* 0 < |value| < DBL_MIN: a subnormal or 0 */
};

/* Reads the number that the n bytes at text spell, blanks around it allowed, into *out (strtod
 * in the caller's locale: readers hold the C locale while they read). Returns CT_NUMBER_OK or
 * why the text is not a finite normal double (or 0); *out is set only when it is. */
int ct_number_parse(const char *text, size_t n, double *out);
/* The words of a status of ct_number_parse ("not a finite number", "underflows double
 * precision (0 < |value| < 2.2e-308)", ...). */
const char *ct_number_why(int status);

/* A list's fields. Fields are separated by one of the characters of seps; a blank (space or
 * tab) in seps makes any run of blanks a separator as well. Blanks around a field are not part
 * of it. An empty field is returned as one (length 0): two separators in a row, a separator at
 * the start or at the end, or an empty text; every list refuses it. */
typedef struct {
    const char *next, *seps;
    int blanks, done;
} ct_list;

/* Starts reading the fields of text. */
void ct_list_start(ct_list *l, const char *text, const char *seps);
/* The next field: 1 with *field and *len (0: an empty field), or 0 when none is left. */
int ct_list_next(ct_list *l, const char **field, size_t *len);
/* The message of an empty field: "field N is empty (...)". */
const char *ct_list_empty_why(void);

#endif
