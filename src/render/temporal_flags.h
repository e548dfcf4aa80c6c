/* temporal_flags.h: what temporal reuse of path reservoirs proposed to each pixel and what it
 * accepted, per technique (backprojection, splatting): the bits the passes write, and their sums
 * for metrics.csv. Must never depend on reservoirs or the ray tracer. */
#ifndef RESTIR_RENDER_TEMPORAL_FLAGS_H
#define RESTIR_RENDER_TEMPORAL_FLAGS_H

/* Per-pixel temporal flags (what the debug view and metrics.csv count). */
enum {
    TEMPORAL_BP_RECEIVED = 1,    /* the backprojected previous pixel passed G-buffer validation */
    TEMPORAL_BP_ACCEPTED = 2,    /* ... and its path shifted in with a non-zero contribution */
    TEMPORAL_SPLAT_RECEIVED = 4, /* at least one previous reservoir's primary hit landed here */
    TEMPORAL_SPLAT_ACCEPTED = 8  /* ... and at least one such path shifted in with a contribution */
};

/* Pixels of one frame with each flag set (pt_temporal_counts). */
struct temporal_counts {
    long long bp_received, bp_accepted, splat_received, splat_accepted;
};

/* Sums the flags of n pixels. */
void pt_temporal_counts(const unsigned char *flags, int n, struct temporal_counts *out);
/* Pixels whose flags say a candidate of either technique shifted in. */
long long temporal_counts_any_accepted(const unsigned char *flags, int n);

#endif
