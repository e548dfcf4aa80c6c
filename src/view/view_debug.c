/* view_debug.c: the viewer's debug views (view_debug.h), drawn from what the method exposes of its
 * last frame (renderer_inspect). */
#include "view/view_debug.h"

#include "io/png.h"
#include "render/temporal_flags.h"
#include "render/reuse_cells.h"

const char *const view_mode_names[VIEW_MODES] = {"image", "confidence", "temporal acceptance", "selected neighbors",
                                                 "reuse cells", "temporal candidates per technique"};

/* VIEW_TEMPORAL_CANDIDATES: one pixel's TEMPORAL_* flags, black without a candidate, dark red
 * where candidates came but none shifted in, else green (backprojection) plus blue (splat) for each
 * technique that did (both: cyan). */
static const unsigned char temporal_none[3] = {0, 0, 0}, temporal_rejected[3] = {128, 0, 0},
                           temporal_bp[3] = {0, 255, 0}, temporal_splat[3] = {0, 0, 255};

static void temporal_color(unsigned char flags, unsigned char *out)
{
    const int bp = (flags & TEMPORAL_BP_ACCEPTED) != 0, splat = (flags & TEMPORAL_SPLAT_ACCEPTED) != 0;
    const int received = (flags & (TEMPORAL_BP_RECEIVED | TEMPORAL_SPLAT_RECEIVED)) != 0;
    for (int k = 0; k < 3; k++)
        out[k] = bp || splat ? (unsigned char)(bp * temporal_bp[k] + splat * temporal_splat[k])
                 : received  ? temporal_rejected[k]
                             : temporal_none[k];
}

/* Distinct colours for cell ids (an integer hash to a hue-ish RGB). */
static void cell_color(int id, unsigned char *out)
{
    unsigned h = (unsigned)id * 2654435761u;
    out[0] = (unsigned char)(64 + (h >> 24) % 192);
    out[1] = (unsigned char)(64 + (h >> 16) % 192);
    out[2] = (unsigned char)(64 + (h >> 8) % 192);
}

int view_count(const struct renderer *r) { return VIEW_MODES + method_output_count(r->method); }

const char *view_name(const struct renderer *r, int mode)
{
    if (mode >= VIEW_MODES && mode < view_count(r))
        return r->method->outputs[mode - VIEW_MODES].name;
    return mode >= 0 && mode < VIEW_MODES ? view_mode_names[mode] : view_mode_names[VIEW_IMAGE];
}

/* View VIEW_MODES + k: the method's output k as 8-bit RGB. Returns 1, or 0 without it this frame. */
static int output_rgb8(const struct renderer *r, int k, unsigned char *rgb8)
{
    const float *px = renderer_output(r, k);
    const size_t n = (size_t)r->p.width * (size_t)r->p.height;
    if (!px || r->method->outputs[k].channels != 3)
        return 0;
    if (r->method->outputs[k].kind == METHOD_OUTPUT_SIGNED)
        return encode_signed8(px, n, 0.0f, rgb8) == 0;
    encode_srgb8(px, 3 * n, 0.0f, rgb8);
    return 1;
}

int view_debug_rgb8(const struct renderer *r, int mode, unsigned char *rgb8)
{
    if (mode >= VIEW_MODES && mode < view_count(r) && output_rgb8(r, mode - VIEW_MODES, rgb8))
        return 1;
    struct renderer_inspect in;
    renderer_inspect(r, &in);
    const int n = r->p.width * r->p.height, m = in.neighbors_per_pixel;
    const int ok = mode == VIEW_CONFIDENCE            ? in.reservoirs != NULL && in.confidence != NULL
                   : mode == VIEW_ACCEPTANCE          ? in.age != NULL
                   : mode == VIEW_NEIGHBORS           ? in.neighbors != NULL && r->p.reuse.spatial &&
                                                  r->p.reuse.spatial_reuse == REUSE_STANDARD && m > 0
                   : mode == VIEW_CELLS               ? in.spmis != NULL && r->p.reuse.spatial_reuse == REUSE_SPMIS
                   : mode == VIEW_TEMPORAL_CANDIDATES ? in.temporal_flags != NULL
                                                      : 0;
    if (!ok) {
        encode_srgb8(r->image, 3 * (size_t)n, 0.0f, rgb8);
        return 0;
    }
    const float cap = r->p.reuse.confidence_cap > 0.0f ? r->p.reuse.confidence_cap : 1.0f;
    for (int i = 0; i < n; i++) {
        unsigned char *o = rgb8 + 3 * (size_t)i;
        if (mode == VIEW_CONFIDENCE) {
            heat_color(in.confidence(in.reservoirs, i) / cap, o);
        } else if (mode == VIEW_ACCEPTANCE) {
            heat_color((float)in.age[i] / 20.0f, o);
        } else if (mode == VIEW_NEIGHBORS) {
            int count = 0;
            for (int k = 0; k < m; k++)
                count += in.neighbors[(size_t)i * m + k] >= 0;
            heat_color((float)count / (float)m, o);
        } else if (mode == VIEW_TEMPORAL_CANDIDATES) {
            /* a single buffer, not ping-pong: always the last frame's */
            temporal_color(in.temporal_flags[i], o);
        } else {
            /* the cell a pixel belongs to (tile, object, quantized normal: 004 Algorithm 1) */
            if (in.spmis->cell[i] < 0)
                o[0] = o[1] = o[2] = 0;
            else
                cell_color((int)in.spmis->key[i], o);
        }
    }
    return 1;
}
