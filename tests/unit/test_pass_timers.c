/* test_pass_timers.c: the pass timers methods name (struct method.passes, methods/passes.h). Each
 * registered method renders a few frames of a tiny cornell (and with spatial.reuse=spmis where it
 * reads that setting), and every pass it timed must be one it lists (or the renderer's denoise); today's
 * ids keep their names and order (so metrics.csv and passes.csv keep their columns), each listed by a
 * method, and the names methods add come after them; the registry refuses malformed names. */
#include <string.h>

#include "core/check.h"
#include "methods/method.h"
#include "methods/passes.h"
#include "methods/renderer.h"
#include "methods/settings.h"
#include "scene/scene_file.h"
#include "test_util.h"

static const char *const upper[] = {"Shade", NULL}, *const pt_twice[] = {"pt", "pt", NULL},
                         *const renderer_own[] = {"denoise", NULL};
static const struct method bad_name = {.name = "toy-p", .passes = upper};
static const struct method twice = {.name = "toy-q", .passes = pt_twice};
static const struct method denoise_too = {.name = "toy-r", .passes = renderer_own};

static int lists(const struct method *m, int id)
{
    for (const char *const *p = m->passes; p && *p; p++)
        if (pass_find(*p) == id)
            return 1;
    return 0;
}

/* Renders 3 frames of m (with assignment, NULL: none) and checks its timers against its list. */
static void check_timed(const struct scene *s, const struct method *m, const char *assignment)
{
    struct render_params p;
    char msg[RESTIR_MSG_LEN];
    render_params_defaults(&p);
    p.width = 16;
    p.height = 12;
    if (assignment && render_params_set(&p, assignment, msg) != 0) {
        EXPECT(0, "%s: %s", m->name, msg);
        return;
    }
    struct renderer r;
    renderer_init(&r, s, m, &p);
    for (int f = 0; f < 3; f++) {
        struct frame_stats st;
        struct camera cam = scene_camera_at(s, 1, (float)f);
        renderer_render(&r, f, &cam, &st);
        for (int q = 0; q < PASS_MAX; q++)
            EXPECT(st.ms[q] == 0.0 || q == PASS_DENOISE || lists(m, q), "%s%s%s times pass %s (id %d) but does not "
                   "list it in .passes", m->name, assignment ? " " : "", assignment ? assignment : "",
                   pass_name(q) ? pass_name(q) : "(none)", q);
    }
    renderer_fini(&r);
}

int main(void)
{
    /* today's ids, names and order: the columns metrics.csv readers know */
    for (int q = PASS_COUNT; q < pass_count(); q++) { /* the methods' own names, after today's */
        int listed = 0;
        for (int k = 0; k < method_count() && !listed; k++)
            listed = lists(method_at(k), q);
        EXPECT(listed, "pass id %d (%s) is listed by no method", q, pass_name(q));
    }
    for (int q = 0; q < PASS_COUNT; q++)
        EXPECT(pass_find(pass_toolkit_names[q]) == q && !strcmp(pass_name(q), pass_toolkit_names[q]), "pass %d: %s",
               q, pass_toolkit_names[q]);
    EXPECT(pass_name(-1) == NULL && pass_name(pass_count()) == NULL && pass_find("no_such_pass") == -1 &&
               pass_find(NULL) == -1,
           "out of range");
    for (int q = 0; q < PASS_COUNT; q++) { /* no column no method times (denoise is the renderer's) */
        int listed = q == PASS_DENOISE;
        for (int k = 0; k < method_count() && !listed; k++)
            listed = lists(method_at(k), q);
        EXPECT(listed, "pass %s is listed by no method", pass_toolkit_names[q]);
    }

    /* names the registry refuses */
    const struct method *one[3][1] = {{&bad_name}, {&twice}, {&denoise_too}};
    const char *want[3][2] = {{"toy-p", "'Shade'"}, {"toy-q", "'pt' twice"}, {"toy-r", "'denoise'"}};
    char msg[RESTIR_MSG_LEN];
    for (int k = 0; k < 3; k++) {
        msg[0] = '\0';
        EXPECT(settings_registry_check(one[k], 1, msg) != 0, "%s: accepted", want[k][0]);
        EXPECT(strstr(msg, want[k][0]) && strstr(msg, want[k][1]), "message '%s' names neither '%s' nor '%s'", msg,
               want[k][0], want[k][1]);
    }

    struct scene s;
    if (scene_load("cornell", &s, msg) != 0) {
        EXPECT(0, "cornell: %s", msg);
        return test_finish();
    }
    for (int k = 0; k < method_count(); k++) {
        check_timed(&s, method_at(k), NULL);
        if (method_uses_setting(method_at(k), "spatial.reuse"))
            check_timed(&s, method_at(k), "spatial.reuse=spmis");
    }
    scene_destroy(&s);
    return test_finish();
}
