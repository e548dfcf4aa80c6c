/* temporal_flags.c: sums of the per-pixel temporal flags (temporal_flags.h). */
#include "render/temporal_flags.h"

#include <string.h>

void pt_temporal_counts(const unsigned char *flags, int n, struct temporal_counts *out)
{
    memset(out, 0, sizeof(*out));
    for (int i = 0; i < n; i++) {
        out->bp_received += (flags[i] & TEMPORAL_BP_RECEIVED) != 0;
        out->bp_accepted += (flags[i] & TEMPORAL_BP_ACCEPTED) != 0;
        out->splat_received += (flags[i] & TEMPORAL_SPLAT_RECEIVED) != 0;
        out->splat_accepted += (flags[i] & TEMPORAL_SPLAT_ACCEPTED) != 0;
    }
}

long long temporal_counts_any_accepted(const unsigned char *flags, int n)
{
    long long any = 0;
    for (int i = 0; i < n; i++)
        any += (flags[i] & (TEMPORAL_BP_ACCEPTED | TEMPORAL_SPLAT_ACCEPTED)) != 0;
    return any;
}
