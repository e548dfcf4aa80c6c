/* test_report.c: `restir compare --report` writes a self-contained page: every image it shows
 * exists beside it, nothing is fetched from a network, and a real browser (headless Chromium)
 * loads it with every image and plot in place and no script error (the page records both on its
 * body once loaded). The report and the browser's screenshot stay in RESTIR_TEST_OUTPUT/report. */
#include <string.h>
#include <sys/stat.h>

#include "cli_util.h"
#include "test_util.h"

static char page[1 << 20], dom[1 << 20];

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Every src="..." of the page names a non-empty file in dir; returns how many. */
static int check_sources(const char *dir, const char *html)
{
    int n = 0;
    for (const char *p = strstr(html, "src=\""); p; p = strstr(p + 5, "src=\"")) {
        const char *b = p + 5, *e = strchr(b, '"');
        if (!e)
            break;
        char rel[512], path[3 * CLI_PATH_MAX];
        snprintf(rel, sizeof rel, "%.*s", (int)(e - b) < 500 ? (int)(e - b) : 500, b);
        snprintf(path, sizeof path, "%.*s/%s", CLI_PATH_MAX, dir, rel);
        EXPECT(strncmp(rel, "http", 4) != 0 && strncmp(rel, "//", 2) != 0, "the page fetches %s", rel);
        EXPECT(file_size(path) > 0, "the page shows %s, which is missing or empty", rel);
        n++;
    }
    return n;
}

/* The value of data-NAME="..." on the dumped body, or -1. */
static int body_attribute(const char *html, const char *name)
{
    const char *body = strstr(html, "<body");
    char key[64];
    snprintf(key, sizeof key, "data-%s=\"", name);
    const char *p = body ? strstr(body, key) : NULL;
    const char *end = body ? strchr(body, '>') : NULL;
    return p && end && p < end ? atoi(p + strlen(key)) : -1;
}

/* Loads dir/index.html in headless Chromium: the page's body must report `images` images, none
 * broken, `plots` inline plots and no script error; keeps dir/screenshot.png. */
static void check_in_browser(const char *browser, const char *dir, int images, int plots)
{
    char cmd[16 * CLI_PATH_MAX], dom_path[3 * CLI_PATH_MAX], shot[3 * CLI_PATH_MAX];
    const char *flags = "--headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=5000 "
                        "--enable-logging=stderr --v=0";
    snprintf(dom_path, sizeof dom_path, "%s/dom.html", dir);
    snprintf(cmd, sizeof cmd, "timeout 120 '%s' %s --dump-dom 'file://%s/index.html' > '%s' 2> '%s/browser.log'",
             browser, flags, dir, dom_path, dir);
    EXPECT(system(cmd) == 0, "headless chromium failed: %s (see %s/browser.log)", cmd, dir);
    cli_read_text(dom_path, dom, sizeof dom);
    int loaded = body_attribute(dom, "images"), broken = body_attribute(dom, "broken");
    int errors = body_attribute(dom, "errors"), seen_plots = body_attribute(dom, "plots");
    printf("chromium, %s: %d images (%d broken), %d inline plots, %d script errors\n", dir, loaded, broken,
           seen_plots, errors);
    EXPECT(loaded == images, "the browser saw %d images, the page has %d", loaded, images);
    EXPECT(broken == 0, "%d images did not load in the browser", broken);
    EXPECT(seen_plots == plots, "the browser saw %d inline plots, want %d", seen_plots, plots);
    EXPECT(errors == 0, "%d script errors in the browser", errors);
    /* the browser's log shows every console message as INFO:CONSOLE:LINE; the page writes none */
    char log_path[3 * CLI_PATH_MAX];
    snprintf(log_path, sizeof log_path, "%s/browser.log", dir);
    cli_read_text(log_path, dom, sizeof dom);
    EXPECT(strstr(dom, ":CONSOLE") == NULL, "the browser console has messages (see %s)", log_path);
    snprintf(shot, sizeof shot, "%s/screenshot.png", dir);
    snprintf(cmd, sizeof cmd,
             "timeout 120 '%s' %s --window-size=1300,2600 --screenshot='%s' 'file://%s/index.html' 2>> '%s/browser.log'",
             browser, flags, shot, dir, dir);
    EXPECT(system(cmd) == 0 && file_size(shot) > 10000, "no screenshot at %s", shot);
    printf("screenshot: %s\n", shot);
}

/* Runs `restir ARGS --report --out OUT_ROOT/sub` into a cleared folder (its path into dir) and
 * reads its index.html into page; returns how many images the page shows (all checked present). */
static int run_report(const char *tmp, const char *out_root, const char *sub, const char *args, char *dir,
                      size_t dir_len)
{
    char cmd[6 * CLI_PATH_MAX], err[CLI_ERR_MAX], path[3 * CLI_PATH_MAX];
    snprintf(dir, dir_len, "%s/%s", out_root, sub);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    EXPECT(system(cmd) == 0, "cannot clear %s", dir);
    snprintf(cmd, sizeof cmd, "%s --report --out '%s'", args, dir);
    int rc = cli_run(tmp, cmd, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", cmd, rc, err);
    snprintf(path, sizeof path, "%s/index.html", dir);
    cli_read_text(path, page, sizeof page);
    EXPECT(strlen(page) > 1000, "%s is missing or nearly empty", path);
    return check_sources(dir, page);
}

/* Gradient methods: the page adds their primal and gradient layers. */
static void check_gradient(const char *tmp, const char *out_root, const char *browser)
{
    char dir[2 * CLI_PATH_MAX];
    int images = run_report(tmp, out_root, "gradient_report",
                            "compare --scene cornell --methods restir-pt,gpt --res 48x27 --frames 2 --ref-spp 16", dir,
                            sizeof dir);
    const char *must[] = {"Gradient layers", "gpt/frame_0001_primal.png", "gpt/frame_0001_dx.png",
                          "gpt/frame_0001_dy.png"};
    for (size_t k = 0; k < sizeof must / sizeof must[0]; k++)
        EXPECT(strstr(page, must[k]) != NULL, "the gradient page lacks '%s'", must[k]);
    if (file_size(browser) > 0)
        check_in_browser(browser, dir, images, 1);
}

/* study --report: the page shows study.csv's rows, the Pareto plot, the mask and the strip. */
static void check_study(const char *tmp, const char *out_root, const char *browser)
{
    char dir[2 * CLI_PATH_MAX];
    int images = run_report(tmp, out_root, "study_report",
                            "study --scene cornell --method restir-di --configs bitterli,fast --radii 8,16 --runs 2 "
                            "--warmup 2 --frames 4 --res 48x27 --ref-spp 16",
                            dir, sizeof dir);
    /* pareto.svg, reference and mask, their A/B view, the strip */
    EXPECT(images == 5, "%d images on the study page", images);
    const char *must[] = {"pareto.svg", "hard_pixels.png", "strip.png", "<td>fast</td>", "<td>compat@16</td>",
                          "smape_hard", "Commit:"};
    for (size_t k = 0; k < sizeof must / sizeof must[0]; k++)
        EXPECT(strstr(page, must[k]) != NULL, "the study page lacks '%s'", must[k]);
    if (file_size(browser) > 0)
        check_in_browser(browser, dir, images, 0);
}

int main(void)
{
    char tmp[CLI_PATH_MAX], dir[2 * CLI_PATH_MAX];
    const char *out_root = getenv("RESTIR_TEST_OUTPUT");
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0 || !out_root) {
        EXPECT(0, "cannot set up (RESTIR_BIN, RESTIR_TEST_OUTPUT or a temporary folder)");
        return test_finish();
    }
    int images = run_report(tmp, out_root, "report",
                            "compare --scene cornell --methods restir-di,ris-di,pt --res 64x36 --frames 3 --ref-spp 16",
                            dir, sizeof dir);
    printf("index.html: %zu bytes, %d images\n", strlen(page), images);
    /* reference + 3 methods, their A/B view, 3 heat maps and theirs, 3 FLIP maps and theirs, 2 regions x 4 crops */
    EXPECT(images == 4 + 1 + 3 + 1 + 3 + 1 + 8, "%d images on the page", images);
    EXPECT(!strstr(page, "<script src") && !strstr(page, "<link") && !strstr(page, "href=\"http"),
           "the page loads something from outside itself");
    const char *must[] = {"restir-di", "ris-di", "<svg", "heat_2.png", "flip_2.png",
                          "crop_1_ref0.png", "restir compare --scene cornell", "Commit:", "Machine:", "relMSE",
                          "<h2>FLIP</h2>"};
    for (size_t k = 0; k < sizeof must / sizeof must[0]; k++)
        EXPECT(strstr(page, must[k]) != NULL, "the page lacks '%s'", must[k]);

    /* A real browser: the page's own check of its images, plots and script errors. */
    const char *browser = getenv("CHROMIUM") ? getenv("CHROMIUM") : "/usr/bin/chromium";
    EXPECT(file_size(browser) > 0, "%s is missing (make test installs Debian's chromium)", browser);
    if (file_size(browser) > 0)
        check_in_browser(browser, dir, images, 1);
    check_study(tmp, out_root, browser);
    check_gradient(tmp, out_root, browser);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
