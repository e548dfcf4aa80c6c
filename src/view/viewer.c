/* viewer.c: the interactive viewer (viewer.h). Everything that changes the image is a function of
 * the frame's inputs, never of wall time: a held movement key moves the camera by a fixed step per
 * frame, so a scripted session, and the camera file it records, replay exactly. A screenshot taken
 * in a debug view also writes that view (screenshot_NNNN_view.png); a script's screenshot event writes
 * the window itself. */
#include "view/viewer.h"
#include "methods/settings.h"

#include <math.h>
#include <SDL2/SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"
#include "io/scene_export.h"
#include "view/view_debug.h"
#include "view/view_script.h"

const struct method *view_method_after(const struct method *m)
{
    /* the cycle member of the smallest order above m's, else of the smallest order overall */
    const int from = m ? m->viewer_order : 0;
    const struct method *next = NULL, *first = NULL;
    for (int k = 0; k < method_count(); k++) {
        const struct method *c = method_at(k);
        if (c->viewer_order <= 0)
            continue;
        if (!first || c->viewer_order < first->viewer_order)
            first = c;
        if (from > 0 && c->viewer_order > from && (!next || c->viewer_order < next->viewer_order))
            next = c;
    }
    return next ? next : first;
}

void view_method_cycle_names(char *out, size_t n)
{
    size_t len = 0;
    out[0] = '\0';
    const struct method *first = view_method_after(NULL);
    for (const struct method *m = first; m && len < n; m = view_method_after(m)) {
        int w = snprintf(out + len, n - len, "%s%s", len ? ", " : "", m->name);
        len += w > 0 ? (size_t)w : 0;
        if (view_method_after(m) == first)
            break;
    }
}

struct view {
    const struct view_options *o;
    struct render_params p;
    const struct method *method;
    struct renderer r;
    vec3 position;
    float yaw, pitch, vfov, step;
    int frame; /* since the renderer was (re)started */
    int held[256];     /* frames a key stays held (script), or -1 while held on the keyboard */
    struct camera *path; /* cameras of frames 0 .. frame-1 */
    int path_cap;
    int quit;
    int shots;
    int mode; /* what the window shows (V cycles; view_debug.h); screenshots are always the image */
    int show_denoised;   /* O: the denoised frame instead of the raw one (denoise=svgf|atrous) */
    SDL_Renderer *ren;   /* the window's, and the texture it shows the frame from (window_shot) */
    SDL_Texture *tex;
};

static struct camera current_camera(const struct view *v)
{
    vec3 dir = v3(cosf(v->pitch) * sinf(v->yaw), sinf(v->pitch), -cosf(v->pitch) * cosf(v->yaw));
    return (struct camera){v->position, v3_add(v->position, dir), v3(0, 1, 0), v->vfov, 0.0f, 0.0f};
}

/* The spec the camera file names: method[:key=value]... of what differs from the defaults. */
static void spec(const struct view *v, char *out, size_t len)
{
    char select[64];
    render_params_get(&v->p, "spatial.select", select, sizeof select);
    snprintf(out, len, "%s%s%s%s%s%s%s%s", v->method->name, v->p.reuse.temporal ? "" : ":temporal=off",
             v->p.reuse.spatial ? "" : ":spatial=off",
             v->p.reuse.spatial_select == SELECT_BITTERLI ? "" : ":spatial.select=",
             v->p.reuse.spatial_select == SELECT_BITTERLI ? "" : select,
             v->p.reuse.spatial_reuse == REUSE_SPMIS ? ":spatial.reuse=spmis" : "",
             v->p.denoise.method > 0 ? ":denoise=" : "",
             v->p.denoise.method > 0 ? denoise_names[v->p.denoise.method] : "");
}

static void restart(struct view *v, int first)
{
    if (!first)
        renderer_fini(&v->r);
    renderer_init(&v->r, v->o->scene, v->method, &v->p);
    v->frame = 0;
    if (v->mode >= view_count(&v->r)) /* an output of the method before */
        v->mode = VIEW_IMAGE;
}

/* Restarts with method m and parameters q when the command's checks accept them (the same checks as
 * before the first frame: settings against the method and the scene, memory); otherwise says why on
 * stderr and keeps what runs. Returns 1 when it switched. */
static int switch_to(struct view *v, const struct method *m, const struct render_params *q)
{
    char msg[RESTIR_MSG_LEN];
    if (v->o->check && v->o->check(v->o->check_ctx, m, q, msg) != 0) {
        fprintf(stderr, "restir: view: %s; %s keeps running as it was\n", msg, v->method->name);
        return 0;
    }
    v->method = m;
    v->p = *q;
    restart(v, 0);
    return 1;
}

static void press(struct view *v, char key)
{
    struct render_params q = v->p;
    switch (key) {
    case 'm': switch_to(v, view_method_after(v->method), &q); break;
    case 't': q.reuse.temporal = !q.reuse.temporal; switch_to(v, v->method, &q); break;
    case 'y': q.reuse.spatial = !q.reuse.spatial; switch_to(v, v->method, &q); break;
    case 'n':
        q.reuse.spatial_select = (enum spatial_select_mode)((q.reuse.spatial_select + 1) % 3);
        switch_to(v, v->method, &q);
        break;
    case 'p':
        q.reuse.spatial_reuse = q.reuse.spatial_reuse == REUSE_SPMIS ? REUSE_STANDARD : REUSE_SPMIS;
        switch_to(v, v->method, &q);
        break;
    case 'v': v->mode = (v->mode + 1) % view_count(&v->r); break;
    case 'o': /* raw / denoised; the first time turns SVGF on */
        if (v->p.denoise.method == DENOISE_OFF) {
            q.denoise.method = 1;
            if (switch_to(v, v->method, &q))
                v->show_denoised = 1;
        } else {
            v->show_denoised = !v->show_denoised;
        }
        break;
    case 'i': /* the next denoiser (denoise_names after "off") */
        if (v->p.denoise.method > 0) {
            q.denoise.method = denoise_names[q.denoise.method + 1] ? q.denoise.method + 1 : 1;
            switch_to(v, v->method, &q);
        }
        break;
    case 27: v->quit = 1; break;
    default:
        if (v->held[(unsigned char)key] == 0)
            v->held[(unsigned char)key] = 1; /* a movement key pressed once moves one step */
    }
}

/* Moves by the held keys (one fixed step per frame each) and counts scripted holds down. */
static void move(struct view *v)
{
    struct camera c = current_camera(v);
    vec3 fwd = v3_normalize(v3_sub(c.target, c.position)), right = v3_normalize(v3_cross(fwd, v3(0, 1, 0)));
    const char keys[6] = {'w', 's', 'a', 'd', 'q', 'e'};
    const vec3 dirs[6] = {fwd, v3_neg(fwd), v3_neg(right), right, v3(0, -1, 0), v3(0, 1, 0)};
    for (int k = 0; k < 6; k++) {
        int *h = &v->held[(unsigned char)keys[k]];
        if (*h != 0)
            v->position = v3_madd(v->position, dirs[k], v->step);
        if (*h > 0)
            (*h)--;
    }
}

static void drag(struct view *v, int dx, int dy)
{
    v->yaw += 0.005f * (float)dx;
    v->pitch = fminf(fmaxf(v->pitch - 0.005f * (float)dy, -1.5f), 1.5f);
}

static void save_outputs(struct view *v, const char *stem, char *msg, int *rc)
{
    char path[4300];
    const int w = v->p.width, h = v->p.height;
    snprintf(path, sizeof path, "%s/%s.exr", v->o->out_dir, stem);
    if (*rc == 0 && exr_write_rgb(path, v->r.image, w, h, msg) != 0)
        *rc = 1;
    snprintf(path, sizeof path, "%s/%s.png", v->o->out_dir, stem);
    if (*rc == 0 && png_write_srgb(path, v->r.image, w, h, 0.0f, msg) != 0)
        *rc = 1;
    if (!v->r.denoised) /* and the denoised frame, whichever is on screen */
        return;
    snprintf(path, sizeof path, "%s/%s_denoised.exr", v->o->out_dir, stem);
    if (*rc == 0 && exr_write_rgb(path, v->r.denoised, w, h, msg) != 0)
        *rc = 1;
    snprintf(path, sizeof path, "%s/%s_denoised.png", v->o->out_dir, stem);
    if (*rc == 0 && png_write_srgb(path, v->r.denoised, w, h, 0.0f, msg) != 0)
        *rc = 1;
}

static void save_path(struct view *v, char *msg, int *rc)
{
    char path[4300], method[256];
    snprintf(path, sizeof path, "%s/camera.json", v->o->out_dir);
    spec(v, method, sizeof method);
    if (*rc == 0 && cameras_write_json(path, v->path, v->frame, v->o->scene->name, method, v->p.width, v->p.height,
                                       (unsigned long long)v->p.seed, msg) != 0)
        *rc = 1;
}

static void key_event(struct view *v, SDL_Keycode k, int down, char *msg, int *rc)
{
    char key = k == SDLK_ESCAPE ? 27 : (k >= 'a' && k <= 'z') ? (char)k : 0;
    if (!key)
        return;
    const int movement = strchr("wasdqe", key) != NULL;
    if (movement) {
        v->held[(unsigned char)key] = down ? -1 : 0;
        return;
    }
    if (!down)
        return;
    if (key == 'k') {
        char stem[64];
        snprintf(stem, sizeof stem, "screenshot_%04d", v->shots++);
        save_outputs(v, stem, msg, rc);
        if (*rc == 0 && v->mode != VIEW_IMAGE) { /* and the debug view on screen */
            const int w = v->p.width, h = v->p.height;
            unsigned char *view = xmalloc(3 * (size_t)w * (size_t)h);
            char path[4300];
            view_debug_rgb8(&v->r, v->mode, view);
            snprintf(path, sizeof path, "%s/%s_view.png", v->o->out_dir, stem);
            if (png_write_rgb8(path, view, w, h, msg) != 0)
                *rc = 1;
            free(view);
        }
    } else if (key == 'c') {
        save_path(v, msg, rc);
    } else {
        press(v, key);
    }
}

/* The script's screenshot: the window as it shows now (the texture of the last frame shown, drawn again at the
 * window's size without presenting it) to file, under the output folder unless absolute, as an 8-bit PNG. */
static void window_shot(struct view *v, const char *file, char *msg, int *rc)
{
    char path[8400];
    if (file[0] == '/')
        snprintf(path, sizeof path, "%s", file);
    else
        snprintf(path, sizeof path, "%s/%s", v->o->out_dir, file);
    int w = 0, h = 0;
    if (SDL_GetRendererOutputSize(v->ren, &w, &h) != 0 || w < 1 || h < 1) {
        snprintf(msg, RESTIR_MSG_LEN, "screenshot %.200s: no window size (SDL: %.200s)", file, SDL_GetError());
        *rc = 1;
        return;
    }
    unsigned char *px = xmalloc(3 * (size_t)w * (size_t)h);
    SDL_RenderClear(v->ren);
    SDL_RenderCopy(v->ren, v->tex, NULL, NULL);
    if (SDL_RenderReadPixels(v->ren, NULL, SDL_PIXELFORMAT_RGB24, px, 3 * w) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "screenshot %.200s: cannot read the window (SDL: %.200s)", file,
                 SDL_GetError());
        *rc = 1;
    } else if (png_write_rgb8(path, px, w, h, msg) != 0) {
        *rc = 1;
    }
    free(px);
}

static void scripted(struct view *v, const struct view_script *s, int *next, int tick, char *msg, int *rc)
{
    for (; *next < s->count && s->events[*next].frame <= tick; (*next)++) {
        const struct view_event *e = &s->events[*next];
        switch (e->kind) {
        case VIEW_QUIT: v->quit = 1; break;
        case VIEW_DRAG: drag(v, e->dx, e->dy); break;
        case VIEW_HOLD: v->held[(unsigned char)e->key] = e->frames; break;
        case VIEW_SHOT:
            if (*rc == 0)
                window_shot(v, e->file, msg, rc);
            break;
        case VIEW_PRESS:
            if (e->key == 'k' || e->key == 'c')
                key_event(v, e->key, 1, msg, rc);
            else
                press(v, e->key);
            break;
        }
    }
}

static void show(struct view *v, SDL_Window *win, SDL_Renderer *ren, SDL_Texture *tex, unsigned char *rgb8,
                 const struct frame_stats *st)
{
    const int w = v->p.width, h = v->p.height;
    int shown = v->mode != VIEW_IMAGE && view_debug_rgb8(&v->r, v->mode, rgb8);
    const int denoised = v->show_denoised && v->r.denoised;
    if (v->mode == VIEW_IMAGE)
        encode_srgb8(denoised ? v->r.denoised : v->r.image, 3 * (size_t)w * (size_t)h, 0.0f, rgb8);
    SDL_UpdateTexture(tex, NULL, rgb8, 3 * w);
    SDL_RenderClear(ren);
    SDL_RenderCopy(ren, tex, NULL, NULL);
    SDL_RenderPresent(ren);
    char title[1024], method[256];
    spec(v, method, sizeof method);
    int n = snprintf(title, sizeof title, "restir view: %s, %s%s%s, frame %d, %.1f ms:", method,
                     view_name(&v->r, v->mode), v->mode != VIEW_IMAGE && !shown ? " (none for this method)" : "",
                     v->mode == VIEW_IMAGE && denoised ? " denoised (BIASED)" : "", v->frame, st->ms_total);
    for (int q = 0; q < pass_count() && n > 0 && n < (int)sizeof title; q++)
        if (st->ms[q] > 0.0)
            n += snprintf(title + n, sizeof title - (size_t)n, " %s %.1f", pass_name(q), st->ms[q]);
    SDL_SetWindowTitle(win, title);
}

int view_run(const struct view_options *o, char *msg)
{
    struct view_script script = {0, NULL};
    if (o->script && view_script_load(o->script, &script, msg) != 0)
        return 2;
    /* SDL falls back to windowless drivers (KMSDRM, offscreen): without a display server named in
     * the environment, or on such a driver not asked for by SDL_VIDEODRIVER, there is no window. */
    const int forced = getenv("SDL_VIDEODRIVER") != NULL;
    if (!forced && !getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        snprintf(msg, RESTIR_MSG_LEN, "no display to open a window on (DISPLAY and WAYLAND_DISPLAY are unset)");
        view_script_fini(&script);
        return 1;
    }
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "no display to open a window on (SDL: %s)", SDL_GetError());
        view_script_fini(&script);
        return 1;
    }
    const char *driver = SDL_GetCurrentVideoDriver();
    if (!forced && driver && (strcmp(driver, "x11") && strcmp(driver, "wayland"))) {
        snprintf(msg, RESTIR_MSG_LEN, "no display to open a window on (SDL found only the '%s' video driver)", driver);
        SDL_Quit();
        view_script_fini(&script);
        return 1;
    }
    const int w = o->params.width, h = o->params.height, zoom = w < 640 ? (640 + w - 1) / w : 1;
    SDL_Window *win = SDL_CreateWindow("restir view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, zoom * w,
                                       zoom * h, 0);
    SDL_Renderer *ren = win ? SDL_CreateRenderer(win, -1, 0) : NULL;
    if (win && !ren)
        ren = SDL_CreateRenderer(win, -1, SDL_RENDERER_SOFTWARE);
    SDL_Texture *tex = ren ? SDL_CreateTexture(ren, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, w, h) : NULL;
    if (!tex) {
        snprintf(msg, RESTIR_MSG_LEN, "cannot open a %dx%d window (SDL: %s)", zoom * w, zoom * h, SDL_GetError());
        if (ren)
            SDL_DestroyRenderer(ren);
        if (win)
            SDL_DestroyWindow(win);
        SDL_Quit();
        view_script_fini(&script);
        return 1;
    }
    if (io_make_dirs(o->out_dir, msg) != 0) { /* only once a window is open: no display, no folder */
        SDL_DestroyTexture(tex);
        SDL_DestroyRenderer(ren);
        SDL_DestroyWindow(win);
        SDL_Quit();
        view_script_fini(&script);
        return 1;
    }
    struct view v;
    memset(&v, 0, sizeof v);
    v.o = o;
    v.p = o->params;
    v.method = o->method;
    v.show_denoised = v.p.denoise.method > 0; /* --denoise: start on the denoised frame */
    v.ren = ren;
    v.tex = tex;
    const struct camera *c0 = &o->scene->camera;
    vec3 d = v3_normalize(v3_sub(c0->target, c0->position));
    v.position = c0->position;
    v.yaw = atan2f(d.x, -d.z);
    v.pitch = asinf(fminf(fmaxf(d.y, -1.0f), 1.0f));
    v.vfov = c0->vfov_deg;
    v.step = 0.005f * scene_diagonal(o->scene);
    restart(&v, 1);
    unsigned char *rgb8 = xmalloc(3 * (size_t)w * (size_t)h);
    int rc = 0, next = 0, mouse_down = 0;
    for (int tick = 0; !v.quit && rc == 0; tick++) {
        scripted(&v, &script, &next, tick, msg, &rc);
        SDL_Event e;
        while (SDL_PollEvent(&e)) {
            if (e.type == SDL_QUIT)
                v.quit = 1;
            else if (e.type == SDL_KEYDOWN && !e.key.repeat)
                key_event(&v, e.key.keysym.sym, 1, msg, &rc);
            else if (e.type == SDL_KEYUP)
                key_event(&v, e.key.keysym.sym, 0, msg, &rc);
            else if (e.type == SDL_MOUSEBUTTONDOWN || e.type == SDL_MOUSEBUTTONUP)
                mouse_down = e.type == SDL_MOUSEBUTTONDOWN;
            else if (e.type == SDL_MOUSEMOTION && mouse_down)
                drag(&v, e.motion.xrel, e.motion.yrel);
        }
        if (v.quit || rc != 0)
            break;
        move(&v);
        struct camera cam = current_camera(&v);
        if (v.frame == v.path_cap) {
            v.path_cap = v.path_cap ? 2 * v.path_cap : 64;
            v.path = realloc(v.path, sizeof(*v.path) * (size_t)v.path_cap);
            RESTIR_CHECK(v.path != NULL);
        }
        v.path[v.frame] = cam;
        struct frame_stats st;
        renderer_render(&v.r, v.frame, &cam, &st);
        v.frame++;
        show(&v, win, ren, tex, rgb8, &st);
    }
    if (rc == 0 && v.frame > 0)
        save_outputs(&v, "last_frame", msg, &rc);
    free(rgb8);
    free(v.path);
    renderer_fini(&v.r);
    SDL_DestroyTexture(tex);
    SDL_DestroyRenderer(ren);
    SDL_DestroyWindow(win);
    SDL_Quit();
    view_script_fini(&script);
    return rc;
}
