/* test_nonfinite.c: no pass of any method discards a NaN or infinite value on any built-in scene
 * (metrics.csv's nonfinite column is 0 on every frame; the renderer's guard, nonfinite.h, counts
 * what it discards), along the camera path so that temporal reuse runs too. */
#include <string.h>

#include "cli_util.h"
#include "methods/renderer.h"
#include "scene/scene.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

static char text[1 << 16];

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    int runs = 0;
    for (int sc = 0; scene_builtins[sc].name; sc++) {
        for (int k = 0; k < method_count(); k++) {
            const struct method *m = method_at(k);
            char dir[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX], err[CLI_ERR_MAX], path[3 * CLI_PATH_MAX];
            snprintf(dir, sizeof dir, "%s/%s-%s", tmp, scene_builtins[sc].name, m->name);
            snprintf(args, sizeof args, "render --scene %s --method %s --res 24x16 --frames 3 --camera path --out '%s'",
                     scene_builtins[sc].name, m->name, dir);
            int rc = cli_run(tmp, args, err);
            EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
            snprintf(path, sizeof path, "%s/metrics.csv", dir);
            cli_read_text(path, text, sizeof text);
            const char *header_end = strchr(text, '\n');
            const char *last_col = NULL;
            for (const char *c = text; header_end && c < header_end; c++)
                if (*c == ',')
                    last_col = c;
            EXPECT(last_col && !strncmp(last_col, ",nonfinite\n", 11), "%s: metrics.csv's last column is not nonfinite",
                   dir);
            int rows = 0;
            for (const char *line = header_end ? header_end + 1 : NULL; line && *line; rows++) {
                const char *end = strchr(line, '\n');
                const char *comma = line;
                for (const char *c = line; *c && c != end; c++)
                    if (*c == ',')
                        comma = c;
                long long n = atoll(comma + 1);
                EXPECT(n == 0, "%s %s frame %d: %lld non-finite values discarded", scene_builtins[sc].name,
                       m->name, rows, n);
                line = end ? end + 1 : NULL;
            }
            EXPECT(rows == 3, "%s: %d frames in metrics.csv", dir, rows);
            runs++;
        }
    }
    printf("%d scene x method renders, every frame without a non-finite value\n", runs);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
