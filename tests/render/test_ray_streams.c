/* test_ray_streams.c: `--set rays.streams=off` (every ray its own Embree call) and the default
 * (camera and restir-di shadow rays traced per tile as Embree streams) write the same frames, byte
 * for byte, for every built-in scene and every method along the scene's camera path. Must never
 * call the renderer directly (CLI only). */
#include "cli_util.h"
#include "test_util.h"

static const char *const scenes[] = {"many-lights", "cornell", "ajar",   "foliage",
                                     "pillars",     "furnace", "forest", NULL};
static const char *const methods[] = {
    "pt", "ris-di", "restir-di", "restir-pt", "area-restir", "gpt", "grad-after-restir", "grestir-pt", NULL};

static int render(const char *tmp, const char *scene, const char *method, const char *streams, const char *dir)
{
    char args[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof(args),
             "render --scene %s --method %s --res 40x24 --frames 3 --camera path --set rays.streams=%s --out '%s'",
             scene, method, streams, dir);
    int rc = cli_run(tmp, args, err);
    if (rc != 0)
        printf("restir %s exited %d:\n%s", args, rc, err);
    return rc;
}

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    for (int s = 0; scenes[s]; s++) {
        for (int m = 0; methods[m]; m++) {
            char on[2 * CLI_PATH_MAX], off[2 * CLI_PATH_MAX];
            snprintf(on, sizeof(on), "%s/%s-%s-on", tmp, scenes[s], methods[m]);
            snprintf(off, sizeof(off), "%s/%s-%s-off", tmp, scenes[s], methods[m]);
            if (render(tmp, scenes[s], methods[m], "on", on) != 0 ||
                render(tmp, scenes[s], methods[m], "off", off) != 0) {
                EXPECT(0, "%s %s: render failed", scenes[s], methods[m]);
                continue;
            }
            int same = 1;
            long size = 0;
            for (int f = 0; f < 3; f++) {
                char a[3 * CLI_PATH_MAX], b[3 * CLI_PATH_MAX];
                snprintf(a, sizeof(a), "%s/frame_%04d.exr", on, f);
                snprintf(b, sizeof(b), "%s/frame_%04d.exr", off, f);
                same &= cli_files_equal(a, b, &size) == 1 && size > 1000;
            }
            EXPECT(same, "%s %s: frames differ between rays.streams=on and off (or are missing)", scenes[s],
                   methods[m]);
        }
    }
    printf("%d scenes x %d methods: identical frames with and without ray streams\n", 7, 8);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
