/* check.h: the internal-invariant macro and the status type that input-reading code returns.
 * Must never be used to reject user input: bad input gets a status and a message, not an abort. */
#ifndef RESTIR_CORE_CHECK_H
#define RESTIR_CORE_CHECK_H

#include <stdio.h>
#include <stdlib.h>

#define RESTIR_CHECK(cond)                                                                      \
    do {                                                                                        \
        if (!(cond)) {                                                                          \
            fprintf(stderr, "internal error: %s:%d: check failed: %s\n", __FILE__, __LINE__,    \
                    #cond);                                                                     \
            abort();                                                                            \
        }                                                                                       \
    } while (0)

/* Size of the message buffer every fallible API fills on failure. */
#define RESTIR_MSG_LEN 512

/* Allocation that dies loudly: running out of memory is not an input error we can recover. */
void *xmalloc(size_t n);
/* realloc that dies loudly the same way (p may be NULL); the new tail is not initialized. */
void *xrealloc(void *p, size_t n);
/* Zeroed; blocks of 64 KiB or more come with their pages already backed (check.c says why). */
void *xcalloc(size_t count, size_t size);

#endif
