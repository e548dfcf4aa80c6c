/* test_report.c: `restir compare --report` writes a page whose every image exists beside it, that
 * fetches nothing from a network, and that a real browser (headless Chromium) loads with every image
 * and plot in place and no script error (the page records both on its body once loaded): the table,
 * the relMSE bars, relMSE against frame (with --ref-every), flicker against scale and the time per pass;
 * with --denoise each method's denoised row (compare.csv's errors) and image right after its own. With --self-contained
 * every image is a data: URI, and the page copied alone into an empty folder loads with none broken (the study's
 * page too).
 * The reports and the browser's screenshots stay in RESTIR_TEST_OUTPUT. */
#include <math.h>
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

/* How many times s occurs in html. */
static int count(const char *html, const char *s)
{
    int n = 0;
    for (const char *p = strstr(html, s); p; p = strstr(p + 1, s))
        n++;
    return n;
}

/* The number in the cell `col` (0: the first) of the table row whose first cell is `label`; NaN when absent. */
static double table_cell(const char *html, const char *label, int col)
{
    char key[256];
    snprintf(key, sizeof key, "<tr><td>%s</td>", label);
    const char *p = strstr(html, key);
    p = p ? p + 4 : NULL; /* the first cell's <td> */
    for (int c = 0; p && c < col; c++)
        p = strstr(p + 4, "<td>");
    return p ? strtod(p + 4, NULL) : NAN;
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
    /* the script gives each A/B view the selected image of its viewer's grid */
    EXPECT(count(dom, "alt=\"A/B\" src=\"") == count(dom, "alt=\"A/B\""), "%d of %d A/B views show no image",
           count(dom, "alt=\"A/B\"") - count(dom, "alt=\"A/B\" src=\""), count(dom, "alt=\"A/B\""));
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
 * reads its index.html into page; returns how many images the page shows (all checked present, or with
 * --self-contained in ARGS, all data: URIs). */
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
    if (!strstr(args, "--self-contained"))
        return check_sources(dir, page);
    EXPECT(count(page, "src=\"") == count(page, "src=\"data:image/"), "%s: %d of %d images are no data: URI", path,
           count(page, "src=\"") - count(page, "src=\"data:image/"), count(page, "src=\""));
    return count(page, "<img");
}

/* Copies dir/index.html alone into the cleared folder dir_alone (its path into alone). */
static void copy_alone(const char *dir, char *alone, size_t len)
{
    char cmd[16 * CLI_PATH_MAX];
    snprintf(alone, len, "%.*s_alone", 2 * CLI_PATH_MAX, dir);
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s' && cp '%.*s/index.html' '%s/'", alone, alone,
             2 * CLI_PATH_MAX, dir, alone);
    EXPECT(system(cmd) == 0, "cannot copy the page alone: %s", cmd);
}

/* --denoise: each method's denoised row (compare.csv's relmse_denoised, mape_denoised) right after its own,
 * and its image after the method's in the viewer. */
static void check_denoised_rows(const char *dir, const char *const *methods, int n)
{
    static char csv[CLI_ERR_MAX];
    char path[3 * CLI_PATH_MAX];
    snprintf(path, sizeof path, "%s/compare.csv", dir);
    cli_read_text(path, csv, sizeof csv);
    const int relmse = cli_csv_column(csv, "relmse_denoised"), mape = cli_csv_column(csv, "mape_denoised");
    const char *row = cli_next_line(csv);
    for (int k = 0; k < n; k++, row = row ? cli_next_line(row) : NULL) {
        char label[128], raw[192], next[192];
        snprintf(label, sizeof label, "%s, denoised (BIASED)", methods[k]);
        const double want[2] = {row ? cli_csv_number(row, relmse) : NAN, row ? cli_csv_number(row, mape) : NAN};
        const double got[2] = {table_cell(page, label, 4), table_cell(page, label, 5)};
        printf("%s: relMSE %.5g (compare.csv %.6g), MAPE %.5g (%.6g)\n", label, got[0], want[0], got[1], want[1]);
        for (int c = 0; c < 2; c++)
            EXPECT(isfinite(want[c]) && fabs(got[c] - want[c]) <= 1e-4 * want[c],
                   "%s: the page's %s %.6g, compare.csv's %.6g", label, c ? "MAPE" : "relMSE", got[c], want[c]);
        snprintf(raw, sizeof raw, "<figcaption>%s</figcaption>", methods[k]);
        snprintf(next, sizeof next, "<figcaption>%s</figcaption>", label);
        const char *a = strstr(page, raw), *b = strstr(page, next), *c = NULL;
        if (a && k + 1 < n) {
            snprintf(next, sizeof next, "<figcaption>%s</figcaption>", methods[k + 1]);
            c = strstr(a, next);
        }
        EXPECT(a && b && b > a && (!c || c > b), "the viewer does not show '%s' right after '%s'", label, methods[k]);
    }
}

/* --denoise --self-contained: the denoised rows, and the page alone in an empty folder loads whole. */
static void check_self_contained(const char *tmp, const char *out_root, const char *browser)
{
    char dir[2 * CLI_PATH_MAX], alone[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    int rc = cli_run(tmp, "compare --scene cornell --methods pt --res 16x16 --self-contained", err);
    EXPECT(rc == 2 && strstr(err, "--report"), "--self-contained without --report: exit %d, '%s'", rc, err);
    int images = run_report(tmp, out_root, "report_self_contained",
                            "compare --scene cornell --methods restir-di,pt --res 48x27 --frames 3 --ref-spp 16 "
                            "--denoise svgf --self-contained",
                            dir, sizeof dir);
    printf("self-contained index.html: %zu bytes, %d images\n", strlen(page), images);
    /* reference + 2 methods + 2 denoised, heat maps and FLIP maps of the 4 rows (each viewer with its A/B view),
     * 2 regions x (reference + 4 rows) crops */
    EXPECT(images == 5 + 1 + 4 + 1 + 4 + 1 + 10, "%d images on the self-contained page", images);
    static const char *const methods[2] = {"restir-di", "pt"};
    check_denoised_rows(dir, methods, 2);
    EXPECT(strstr(page, "the last frame's error only") != NULL,
           "without --ref-every the page does not say frames.csv holds the last frame's error only");
    copy_alone(dir, alone, sizeof alone);
    if (file_size(browser) > 0)
        check_in_browser(browser, alone, images, 3); /* relMSE, flicker (raw and denoised rows), passes */
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
        check_in_browser(browser, dir, images, 2);
}

/* study --report: the page shows study.csv's rows, the Pareto plot, the mask and the strip; with
 * --self-contained it does so alone in a folder. */
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
    /* --self-contained: the same page, the one file alone in a folder */
    char alone[3 * CLI_PATH_MAX];
    images = run_report(tmp, out_root, "study_report_self_contained",
                        "study --scene cornell --method restir-di --configs bitterli,fast --radii 8,16 --runs 2 "
                        "--warmup 2 --frames 4 --res 48x27 --ref-spp 16 --self-contained",
                        dir, sizeof dir);
    EXPECT(images == 5 && strstr(page, "src=\"data:image/svg+xml;base64,"), "%d images on the self-contained study "
           "page, or no embedded Pareto plot", images);
    copy_alone(dir, alone, sizeof alone);
    if (file_size(browser) > 0)
        check_in_browser(browser, alone, images, 0);
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
                            "compare --scene cornell --methods restir-di,ris-di,pt --res 64x36 --frames 3 --ref-spp 16 "
                            "--ref-every 1",
                            dir, sizeof dir);
    printf("index.html: %zu bytes, %d images\n", strlen(page), images);
    /* reference + 3 methods, their A/B view, 3 heat maps and theirs, 3 FLIP maps and theirs, 2 regions x 4 crops */
    EXPECT(images == 4 + 1 + 3 + 1 + 3 + 1 + 8, "%d images on the page", images);
    EXPECT(!strstr(page, "<script src") && !strstr(page, "<link") && !strstr(page, "href=\"http"),
           "the page loads something from outside itself");
    const char *must[] = {"restir-di", "ris-di", "<svg", "heat_2.png", "flip_2.png",
                          "crop_1_ref0.png", "restir compare --scene cornell", "Commit:", "Machine:", "relMSE",
                          "<h2>FLIP</h2>", "<h2>Error against frame</h2>", "relMSE against frame",
                          "<h2>Time per pass</h2>", "ms per frame (lower is faster)"};
    for (size_t k = 0; k < sizeof must / sizeof must[0]; k++)
        EXPECT(strstr(page, must[k]) != NULL, "the page lacks '%s'", must[k]);
    /* relMSE against frame: a point per method at each of frames 0, 1, 2 (--ref-every 1); pass times: a bar per
     * method (one segment for pt's one pass) */
    /* and flicker against scale (a static camera): a point per method at 1, 4 and 16 px */
    EXPECT(strstr(page, "<h2>Flicker against scale</h2>") != NULL, "the page lacks the flicker plot");
    EXPECT(count(page, "<circle") == 9 + 9,
           "%d points in the error-against-frame and flicker plots, want 3 methods x 3 frames + 3 methods x 3 scales",
           count(page, "<circle"));
    EXPECT(strstr(page, "<title>pt, pt: ") != NULL, "the pass-time bars lack pt's pt pass");

    /* A real browser: the page's own check of its images, plots and script errors. */
    const char *browser = getenv("CHROMIUM") ? getenv("CHROMIUM") : "/usr/bin/chromium";
    EXPECT(file_size(browser) > 0, "%s is missing (make test installs Debian's chromium)", browser);
    if (file_size(browser) > 0)
        check_in_browser(browser, dir, images, 4);
    check_self_contained(tmp, out_root, browser);
    check_study(tmp, out_root, browser);
    check_gradient(tmp, out_root, browser);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
