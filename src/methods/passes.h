/* passes.h: the pass timers. A method names the passes it times (struct method.passes); the harness
 * reads them here as ids into struct frame_stats.ms, each with its name, in the order of the columns
 * of metrics.csv, passes.csv, the report's pass bars and the viewer's title. Must never depend on the
 * passes or the ray tracer. */
#ifndef RESTIR_METHODS_PASSES_H
#define RESTIR_METHODS_PASSES_H

/* The ids of the passes timed before methods named their own, in today's column order (renderer.c
 * keeps their names). PASS_CELLS .. PASS_SPMIS_REUSE are spatial.reuse=spmis's passes, split as 004
 * Table 2: create reuse cells (Algorithm 1), cell search (Algorithm 2 line 2, Sec. 5.1), the canonical
 * weight (lines 6-12) and stochastic neighbor reuse (lines 13-20). A name a method lists that is none
 * of these gets the next id after them (pass_find), in registry order. */
enum pass_id {
    PASS_GBUFFER,
    PASS_INITIAL,
    PASS_TEMPORAL,
    PASS_SELECT,
    PASS_SPATIAL,
    PASS_CELLS,
    PASS_CELL_SEARCH,
    PASS_SPMIS_CANONICAL,
    PASS_SPMIS_REUSE,
    PASS_SHADE,
    PASS_PT,
    PASS_GPT,
    PASS_GRAD_INITIAL,
    PASS_GRAD_TEMPORAL,
    PASS_GRAD_SELECT,
    PASS_GRAD_SPATIAL,
    PASS_GRAD_SHADE,
    PASS_RECON_L2,
    PASS_RECON_L1,
    PASS_DENOISE, /* denoise=svgf|atrous: the renderer's, after any method */
    PASS_COUNT
};
/* The timers a struct frame_stats holds: the ids above and the methods' own names. */
#define PASS_MAX 48

/* The number of pass ids (PASS_COUNT and the methods' own names): ids 0 .. pass_count() - 1, which
 * is also the columns' order. Built from the registry on first use; thread-safe. */
int pass_count(void);
/* The name of pass id (metrics.csv's column ms_<name>), or NULL out of range. */
const char *pass_name(int id);
/* The id of the pass called name, or -1 when no method times one of that name (or name is NULL). */
int pass_find(const char *name);

/* The names of the PASS_COUNT ids above, in order. */
extern const char *const pass_toolkit_names[PASS_COUNT];

#endif
