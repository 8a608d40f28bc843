/* cantact/status.h: status codes and error messages. Part of the library's API: include
 * <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_STATUS_H
#define CANTACT_PART_STATUS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- status ---------------------------------------------------------------------- */

enum {
    CT_OK = 0,
    CT_EINVAL = 1,   /* a parameter or input is outside its valid range */
    CT_ENOMEM = 2,   /* allocation failed, or the request would not fit in memory */
    CT_ERANGE = 3,   /* the physics leaves the model (e.g. crushed layer, u_max >= H*) */
    CT_ENOCONV = 4,  /* a solve did not meet its tolerance */
    CT_EIO = 5,      /* a file could not be read or written */
    CT_ESKIPPED = 6, /* not run: an earlier impact of the same speed failed */
    CT_EINTR = 7,    /* stopped: the caller's interrupt flag was set (the spec's interrupt) */
};

/* Returns a static, generic description of a status code. */
const char *ct_strerror(int status);

/* Returns the detailed message of the last error raised in this thread ("" if none). */
const char *ct_error_message(void);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
