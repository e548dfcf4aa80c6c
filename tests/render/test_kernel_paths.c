/* test_kernel_paths.c: the default paths (camera and restir-di shadow rays traced per tile as
 * Embree streams; AVX2 kernels where the CPU has them) and the plain ones (`--set
 * rays.streams=off`: every ray its own Embree call; `--set simd=off`: the baseline kernels) write
 * the same frames, byte for byte, for every built-in scene but night-forest and every method along
 * the scene's camera path. night-forest is left out for time: its 108,708 emitters' BVH makes each
 * of its 24 renders about 2 s longer, and its lamps take no ray or SIMD kernel path that forest
 * (alpha masks) and many-lights (many emitters) do not. Must never call the renderer directly (CLI
 * only). */
#include "cli_util.h"
#include "test_util.h"

static const char *const scenes[] = {"many-lights", "cornell", "ajar",   "foliage",
                                     "pillars",     "furnace", "forest", NULL};
static const char *const methods[] = {
    "pt", "ris-di", "restir-di", "restir-pt", "area-restir", "gpt", "grad-after-restir", "grestir-pt", NULL};

/* The plain paths, each against the default. */
static const char *const variants[] = {"rays.streams=off", "simd=off", NULL};

static int render(const char *tmp, const char *scene, const char *method, const char *set, const char *dir)
{
    char args[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof(args),
             "render --scene %s --method %s --res 40x24 --frames 3 --camera path --set %s --out '%s'", scene,
             method, set, dir);
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
    int pairs = 0;
    for (int s = 0; scenes[s]; s++) {
        for (int m = 0; methods[m]; m++) {
            char def[2 * CLI_PATH_MAX];
            snprintf(def, sizeof(def), "%s/%s-%s", tmp, scenes[s], methods[m]);
            if (render(tmp, scenes[s], methods[m], "simd=on", def) != 0) {
                EXPECT(0, "%s %s: render failed", scenes[s], methods[m]);
                continue;
            }
            for (int v = 0; variants[v]; v++) {
                char alt[2 * CLI_PATH_MAX];
                snprintf(alt, sizeof(alt), "%s/%s-%s-%d", tmp, scenes[s], methods[m], v);
                if (render(tmp, scenes[s], methods[m], variants[v], alt) != 0) {
                    EXPECT(0, "%s %s --set %s: render failed", scenes[s], methods[m], variants[v]);
                    continue;
                }
                int same = 1;
                long size = 0;
                for (int f = 0; f < 3; f++) {
                    char a[3 * CLI_PATH_MAX], b[3 * CLI_PATH_MAX];
                    snprintf(a, sizeof(a), "%s/frame_%04d.exr", def, f);
                    snprintf(b, sizeof(b), "%s/frame_%04d.exr", alt, f);
                    same &= cli_files_equal(a, b, &size) == 1 && size > 1000;
                }
                EXPECT(same, "%s %s: frames differ between the default and --set %s (or are missing)", scenes[s],
                       methods[m], variants[v]);
                pairs++;
            }
        }
    }
    printf("%d scene x method x plain-path pairs: identical frames\n", pairs);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
