/* test_registry.c: the method registry refuses, naming both owners, what would make two settings, two
 * methods or two random streams indistinguishable, and outputs the frame writers cannot name or write
 * (methods/settings.h settings_registry_check); and the
 * real registry passes the same check, with every key of every row read by at least one method. */
#include <string.h>

#include "core/check.h"
#include "methods/method.h"
#include "methods/settings.h"
#include "render/params.h"
#include "render/tiles.h"
#include "scene/scene.h"
#include "test_util.h"

struct toy_settings {
    int count;
};

static const struct param_def toy_rows[] = {
    {"toy.count", P_INT, 0, 1, 64, "4", NULL, "a toy method's count", NULL},
};
static struct param_block toy_block = {"toy", toy_rows, 1, 0, sizeof(struct toy_settings), 4, 0, NULL, NULL};

/* A method block declaring a key the toolkit's spp block owns. */
static const struct param_def thief_rows[] = {
    {"spp", P_INT, 0, 1, 64, "4", NULL, "a second spp", NULL},
};
static struct param_block thief_block = {"thief", thief_rows, 1, 0, sizeof(struct toy_settings), 4, 0, NULL, NULL};

/* A method block too large for the method storage. */
static struct param_block huge_block = {"huge", toy_rows + 0, 0, 0, RENDER_PARAMS_METHOD_BYTES + 4, 4, 0, NULL, NULL};

static const struct param_block *const toy_blocks[] = {&toy_block, NULL};
static const struct param_block *const thief_blocks[] = {&thief_block, NULL};
static const struct param_block *const huge_blocks[] = {&huge_block, NULL};
static const char *const streams_a[] = {"toy.candidates", "toy.shade", NULL};
static const char *const streams_b[] = {"toy.shade", NULL};

static const struct method toy_a = {.name = "toy-a", .description = "", .blocks = toy_blocks, .streams = streams_a};
static const struct method toy_b = {.name = "toy-b", .description = "", .blocks = toy_blocks, .streams = NULL};
static const struct method toy_a_again = {.name = "toy-a", .description = "", .blocks = NULL};
static const struct method thief = {.name = "thief", .description = "", .blocks = thief_blocks};
static const struct method huge = {.name = "huge", .description = "", .blocks = huge_blocks};
static const struct method shade_twice = {.name = "toy-c", .description = "", .streams = streams_b};
static float *toy_output(const struct renderer *r, void *state, int k)
{
    (void)r, (void)state, (void)k;
    return NULL;
}
static const struct method_output outputs_twice[] = {
    {"dx", 3, METHOD_OUTPUT_SIGNED}, {"dx", 3, METHOD_OUTPUT_SIGNED}, {NULL, 0, METHOD_OUTPUT_RADIANCE}};
static const struct method_output outputs_gray[] = {{"albedo", 1, METHOD_OUTPUT_DEBUG}, {NULL, 0, METHOD_OUTPUT_RADIANCE}};
static const struct method_output outputs_path[] = {{"../x", 3, METHOD_OUTPUT_DEBUG}, {NULL, 0, METHOD_OUTPUT_RADIANCE}};
static const struct method output_twice = {.name = "toy-d", .outputs = outputs_twice, .output = toy_output};
static const struct method output_gray = {.name = "toy-e", .outputs = outputs_gray, .output = toy_output};
static const struct method output_path = {.name = "toy-f", .outputs = outputs_path, .output = toy_output};
static const struct method output_none = {.name = "toy-g", .outputs = outputs_gray};

/* Expects settings_registry_check to refuse methods[0..n) with a message holding each of the words. */
static void expect_refused(const struct method *const *methods, int n, const char *what, const char *w1,
                           const char *w2)
{
    char msg[RESTIR_MSG_LEN] = "";
    EXPECT(settings_registry_check(methods, n, msg) != 0, "%s: accepted", what);
    EXPECT(strstr(msg, w1) && strstr(msg, w2), "%s: message '%s' does not name '%s' and '%s'", what, msg, w1, w2);
}

int main(void)
{
    char msg[RESTIR_MSG_LEN];
    const struct method *ok[] = {&toy_a, &toy_b};
    EXPECT(settings_registry_check(ok, 2, msg) == 0, "two methods sharing one block: %s", msg);

    const struct method *names[] = {&toy_a, &toy_b, &toy_a_again};
    expect_refused(names, 3, "two methods of one name", "toy-a", "two registered methods");
    const struct method *keys[] = {&toy_a, &thief};
    expect_refused(keys, 2, "a key the toolkit owns", "'spp'", "thief");
    const struct method *bytes[] = {&huge};
    expect_refused(bytes, 1, "blocks beyond the method storage", "RENDER_PARAMS_METHOD_BYTES", "bytes");
    const struct method *streams[] = {&toy_a, &shade_twice};
    expect_refused(streams, 2, "one stream name in two methods", "toy.shade", "toy-c");

    const struct method *outputs[][1] = {{&output_twice}, {&output_gray}, {&output_path}, {&output_none}};
    expect_refused(outputs[0], 1, "one output name twice", "toy-d", "'dx' twice");
    expect_refused(outputs[1], 1, "a one-channel output", "toy-e", "1 channels");
    expect_refused(outputs[2], 1, "an output named as a path", "toy-f", "'../x'");
    expect_refused(outputs[3], 1, "outputs without an output function", "toy-g", "no output function");

    /* A method that does not say it renders animated emitters is refused on a scene that has them, by
     * name, with the methods that do (method_check_settings). */
    struct emission_animation anim = {0};
    struct scene lit = {0};
    strcpy(lit.name, "lit");
    lit.emission_anim = &anim;
    struct render_params p;
    render_params_defaults(&p);
    EXPECT(method_check_settings(&toy_b, &p, &lit, msg) != 0 && strstr(msg, "animated emitters") &&
               strstr(msg, "toy-b") && strstr(msg, "restir-pt"),
           "a method without METHOD_ANIMATED_EMITTERS on an animated scene: %s", msg);

    /* Named streams never take a toolkit pass id, and differ by name. */
    EXPECT(rng_stream_id("toy.shade") >= RNG_PASS_COUNT, "a named stream below the toolkit's ids");
    EXPECT(rng_stream_id("toy.shade") != rng_stream_id("toy.shadf"), "one id for two names");

    /* The real registry: consistent, and every block is read by some method (a block no method lists is
     * a setting that could never be given). */
    const struct method *all[64];
    for (int k = 0; k < method_count(); k++)
        all[k] = method_at(k);
    EXPECT(settings_registry_check(all, method_count(), msg) == 0, "the registry: %s", msg);
    for (size_t b = 0; b < settings_block_count(); b++) {
        int readers = 0;
        for (int k = 0; k < method_count(); k++)
            readers += method_reads_block(method_at(k), settings_block_at(b));
        EXPECT(readers > 0, "block '%s' is read by no method", settings_block_at(b)->name);
        for (size_t i = 0; i < settings_block_at(b)->count; i++)
            EXPECT(settings_block_of(settings_block_at(b)->rows[i].key) == settings_block_at(b), "key %s",
                   settings_block_at(b)->rows[i].key);
    }
    /* A key is taken by a method exactly when one of its blocks declares it. */
    EXPECT(method_uses_setting(method_named("restir-di"), "di.visibility_mis"), "restir-di reads di.visibility_mis");
    EXPECT(!method_uses_setting(method_named("ris-di"), "di.visibility_mis"), "ris-di does not reuse");
    EXPECT(!method_uses_setting(method_named("pt"), "spatial.radius"), "pt does not reuse");
    EXPECT(method_uses_setting(method_named("pt"), "denoise.svgf.alpha"), "the denoiser is every method's");
    return test_finish();
}
