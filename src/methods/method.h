/* method.h: the method registry. A method is one row, `struct method`: its name, what it estimates,
 * what it can do (capability bits that the commands, the viewer and the harness read instead of
 * naming methods) and the functions that create, run and destroy its own state. The rows live in
 * the methods' own files; method_table.c lists them, and is the one place that names every
 * method. docs/ADDING_A_METHOD.md walks through adding one.
 * Must never depend on the passes or the ray tracer. */
#ifndef RESTIR_METHODS_METHOD_H
#define RESTIR_METHODS_METHOD_H

#include "render/params.h"
#include "scene/scene_types.h"

struct renderer;
struct frame_stats;
struct camera_view;
struct renderer_inspect;

/* Capability bits of struct method.caps (a new bit gets its name for restir list --json in method_json.c). */
enum method_caps {
    /* estimates direct lighting only: its reference is pt with max_bounces = 1 */
    METHOD_DIRECT_ONLY = 1u << 0,
    /* renders a primal and forward-difference gradients and reconstructs them (002) */
    METHOD_GRADIENT = 1u << 1,
    /* keeps a G-buffer and temporal history: it has disoccluded pixels (004 Sec. 6.2), a
     * temporal acceptance rate and debug views of its reuse */
    METHOD_HISTORY = 1u << 2,
    /* its samples carry the primary ray's shutter time and lens point: renders camera.shutter
     * (motion blur) and camera.aperture (depth of field) */
    METHOD_CAMERA_EFFECTS = 1u << 3,
    /* keeps path reservoirs with primary hits: temporal.reuse=splat|both apply, and spatial
     * reuse defaults to 3 neighbors (render_params_spatial_neighbors) */
    METHOD_PATH_RESERVOIRS = 1u << 4,
    /* stateless between frames: reaches an equal-time budget by paths per pixel (spp) rather
     * than by averaging independent instances */
    METHOD_BUDGET_BY_SPP = 1u << 5,
    /* 000's study (restir study) runs it: spatial reuse from the neighbor selection pass */
    METHOD_SELECTION_STUDY = 1u << 6,
    /* renders scenes with animated emitters (scene/scene_animation.h) without bias: it reuses no earlier
     * frame, measures each reused sample's domain under that domain's frame's lights (restir-di), or
     * drops its temporal reuse on a frame whose lights changed (renderer_history_reusable) */
    METHOD_ANIMATED_EMITTERS = 1u << 7,
    /* hands the denoiser a temporal gradient (renderer_inspect.temporal_gradient): takes
     * denoise.svgf.temporal_gradient=on */
    METHOD_TEMPORAL_GRADIENT = 1u << 8,
};

/* What the harness does with an output a method declares (struct method_output). */
enum method_output_kind {
    /* an estimate of radiance: averaged over a compare row's instances, written as the EXR layer and
     * as frame_NNNN_<name>.png (sRGB) */
    METHOD_OUTPUT_RADIANCE,
    /* a signed estimate: averaged as radiance is, written as the EXR layer and as frame_NNNN_<name>.png
     * (png_write_signed: red positive, blue negative). A pair named "dx" and "dy" is read as forward
     * differences dx[a] = F(a + x) - F(a), dy[a] = F(a + y) - F(a): compare's gradient_relmse columns
     * and worst pairs measure it (002 Fig. 7) */
    METHOD_OUTPUT_SIGNED,
    /* derived from the others or diagnostic: an EXR layer and a viewer view only, never averaged (a
     * method with a reconstruct recomputes what it derives after the averaging) */
    METHOD_OUTPUT_DEBUG,
};

/* One image a method renders beside its frame (r->image), e.g. the gradient methods' primal and
 * differences. Frame writers, compare's averaging and measures and the viewer's views iterate over
 * a method's list and name no method. */
struct method_output {
    const char *name; /* the EXR layer's name and the PNG's suffix: letters, digits and '_' */
    int channels;     /* floats per pixel; 3 (RGB) is what the writers take today (the registry checks it) */
    enum method_output_kind kind;
};

struct method {
    const char *name;        /* what --method and method specs spell */
    const char *description; /* one line for `restir list` */
    unsigned caps;           /* enum method_caps bits */
    int viewer_order;        /* position in the viewer's M cycle (1, 2, ...); 0: not offered there */
    /* The settings blocks it reads beyond the common ones (render/settings_block.h), NULL-terminated:
     * the toolkit's (render/params.h: &params_block_lights, ...) and its own, declared in its folder.
     * Which keys it takes follows from them; a setting given to a method that reads none of its
     * blocks is refused by name. */
    const struct param_block *const *blocks;
    /* The names of its own random streams (rng_stream_id, render/tiles.h), NULL-terminated (NULL:
     * it seeds only through the toolkit's pass ids). The registry refuses two of one id. */
    const char *const *streams;
    /* Settings that exercise its own code paths beyond its defaults, space-separated, each "key=value" or
     * "key=value:key=value" (NULL: none). restir list --json lists them; scripts/render_hashes.sh and
     * scripts/tsan.sh render each one, so a new method's variants are covered without editing a script. */
    const char *variants;
    /* What scripts pick it for, space-separated (NULL: nothing): "reference", the method whose paths every
     * reference integrates (methods/pt/reference.c); "demo", the method scripts/demo.sh shows against it. */
    const char *roles;
    /* The passes it times into struct frame_stats.ms, by name, NULL-terminated (NULL: none): every pass
     * its render_frame and reconstruct time, toolkit passes included (the renderer's own "denoise"
     * is every method's and not listed). A test renders each method and refuses a pass timed but not
     * listed. A new pass needs no edit of passes.h: list a name no method uses, look its id up once
     * with pass_find (it gets the next id after enum pass_id's, in registry order) and time with
     * RENDERER_TIMED(st, id, ...); metrics.csv and passes.csv then get its column after today's, so
     * existing columns keep their names and order. */
    const char *const *passes;
    /* The method's own defaults on top of p (NULL: none). renderer_init applies them; reports
     * call method_params to say what ran. */
    void (*defaults)(struct render_params *p);
    /* Checks what depends on the method beyond the capability bits (s may be NULL). Returns 0,
     * or -1 with msg (RESTIR_MSG_LEN bytes) naming the key or the scene. NULL: nothing more. */
    int (*check)(const struct render_params *p, const struct scene *s, char *msg);
    /* Allocates the method's state for r (r->scene, r->p with the defaults applied, r->image
     * allocated). Never fails: allocation failure aborts (core/check.h). */
    void *(*create)(const struct renderer *r);
    void (*destroy)(void *state);
    /* Renders frame r->frame seen through view into r->image; adds rays and per-pass times to st.
     * r->prev_view is the previous frame's view (valid after the first frame). */
    void (*render_frame)(struct renderer *r, void *state, const struct camera_view *view, struct frame_stats *st);
    /* Gradient methods: reconstructs the image from the state's primal and gradients (NULL for
     * the others). */
    void (*reconstruct)(struct renderer *r, void *state, struct frame_stats *st);
    /* What the last frame left for debug views and metrics (NULL: nothing; renderer_inspect
     * zeroes the record first). */
    void (*inspect)(const void *state, struct renderer_inspect *out);
    /* The images it renders beside r->image, terminated by a row with a NULL name (NULL: none), in
     * the order the EXR layers are written after R, G, B. */
    const struct method_output *outputs;
    /* Output k of outputs for the last frame: width x height x channels floats owned by the state,
     * valid until the next frame or destroy; writable, so that a caller averaging instances writes
     * the mean into the first one's and reconstructs from it. NULL where these settings leave the
     * output out (e.g. the L1 layer with recon=l2). Required when outputs is not NULL. */
    float *(*output)(const struct renderer *r, void *state, int k);
};

/* The registered methods, in `restir list` order: method_at(0 .. method_count() - 1). */
int method_count(void);
const struct method *method_at(int k);
/* The method of that name, or NULL for an unknown name (or NULL). */
const struct method *method_find(const char *name);
/* As method_find, for names the caller spells itself (tests, benchmarks): aborts naming the
 * name when it is not registered. */
const struct method *method_named(const char *name);
static inline int method_has(const struct method *m, unsigned caps) { return (m->caps & caps) == caps; }
/* The number of outputs m declares (struct method.outputs). */
int method_output_count(const struct method *m);
/* The index in m->outputs of the output called name with that kind, or -1 when m has none. */
int method_output_find(const struct method *m, const char *name, enum method_output_kind kind);

/* Writes the names of the methods with all of caps, ", "-separated, into out (n bytes): for
 * messages that say which methods would accept a setting. */
void method_names_with(unsigned caps, char *out, size_t n);
/* The same for the methods for which keep(m, ctx) is nonzero. */
void method_names_where(int (*keep)(const struct method *m, const void *ctx), const void *ctx, char *out, size_t n);

/* Checks what depends on the method (and the scene, when s is not NULL): temporal.reuse=splat|both
 * needs METHOD_PATH_RESERVOIRS; motion blur and depth of field need METHOD_CAMERA_EFFECTS; then
 * the method's own check. Returns 0, or -1 with msg naming the key. */
int method_check_settings(const struct method *m, const struct render_params *p, const struct scene *s, char *msg);

/* The method's own defaults on top of p (ris-di: no reuse; area-restir and the primal of
 * grad-after-restir and grestir-pt: 2 spatial neighbors unless spatial.neighbors is set). */
void method_params(const struct method *m, struct render_params *p);
/* The parameters a method's reference integrates with: pt with max_bounces = 1 for
 * METHOD_DIRECT_ONLY methods, p unchanged otherwise. */
void method_reference_params(const struct method *m, struct render_params *p);

#endif
