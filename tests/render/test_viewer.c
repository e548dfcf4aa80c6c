/* test_viewer.c: `restir view` under Xvfb with a script: it opens the window, moves and turns the
 * camera, switches method, saves a screenshot, the window's pixels (the script's screenshot event: the
 * frame on screen magnified to the window) and the camera path, and quits; the screenshot is a
 * rendered image of the scene, and `restir render --camera` of the recorded path reproduces the
 * screenshot's frame and the viewer's last frame byte for byte with the same seed. V cycles the
 * debug views to the last, temporal candidates per technique, whose screenshot_NNNN_view.png holds
 * only its colours: backprojection's green with temporal.reuse=backproject, splat's blue and both's
 * cyan with temporal.reuse=both. Without a display the viewer says so, exits 1 and writes nothing;
 * a bad script is refused naming its line. */
#include <png.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static void write_text(const char *path, const char *text)
{
    EXPECT(cli_write_text(path, text) == 0, "cannot write %s", path);
}

static void same_file(const char *a, const char *b)
{
    long size = 0;
    int same = cli_files_equal(a, b, &size);
    EXPECT(same == 1 && size > 1000, "%s and %s %s", a, b, same < 0 ? "are not both there" : "differ");
    printf("%s == %s: %s\n", a, b, same == 1 ? "identical" : "DIFFERENT");
}

/* The colours of the temporal-candidates view (view_debug.c) in an 8-bit RGB PNG. */
enum { TC_BLACK, TC_RECEIVED, TC_BP, TC_SPLAT, TC_BOTH, TC_OTHER, TC_COLOURS };
static const unsigned char tc_rgb[TC_OTHER][3] = {{0, 0, 0}, {128, 0, 0}, {0, 255, 0}, {0, 0, 255}, {0, 255, 255}};
static const char *const tc_names[TC_COLOURS] = {"black", "dark red", "green", "blue", "cyan", "other"};

/* path as 8-bit RGB (malloc'ed) with its size, or NULL. */
static unsigned char *read_rgb(const char *path, int *w, int *h)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path))
        return NULL;
    im.format = PNG_FORMAT_RGB;
    unsigned char *px = malloc(PNG_IMAGE_SIZE(im));
    if (!px || !png_image_finish_read(&im, NULL, px, 0, NULL)) {
        png_image_free(&im);
        free(px);
        return NULL;
    }
    *w = (int)im.width;
    *h = (int)im.height;
    return px;
}

/* Counts path's pixels per colour of the view; 0, or -1 when it cannot be read at 64x36. */
static int count_temporal_view(const char *path, long counts[TC_COLOURS])
{
    int w = 0, h = 0;
    memset(counts, 0, TC_COLOURS * sizeof(long));
    unsigned char *px = read_rgb(path, &w, &h);
    const int ok = px && w == 64 && h == 36;
    for (size_t i = 0; ok && i < (size_t)w * h; i++) {
        int c = 0;
        while (c < TC_OTHER && memcmp(px + 3 * i, tc_rgb[c], 3) != 0)
            c++;
        counts[c]++;
    }
    printf("%s:", path);
    for (int c = 0; c < TC_COLOURS; c++)
        printf(" %ld %s", counts[c], tc_names[c]);
    printf("\n");
    free(px);
    return ok ? 0 : -1;
}

/* The script's screenshot event: window (the 640x360 window of a 64x36 render, each pixel 10x10) shows
 * exactly shown, the frame on screen that K wrote. */
static void check_window_shot(const char *window, const char *shown)
{
    int ww = 0, wh = 0, w = 0, h = 0;
    unsigned char *win = read_rgb(window, &ww, &wh), *img = read_rgb(shown, &w, &h);
    EXPECT(win && img && ww == 640 && wh == 360 && w == 64 && h == 36, "%s (%dx%d) or %s (%dx%d) is missing or not "
           "of the window's and the render's size", window, ww, wh, shown, w, h);
    long differ = 0;
    for (int y = 0; win && img && ww == 10 * w && wh == 10 * h && y < h; y++)
        for (int x = 0; x < w; x++)
            differ += memcmp(win + 3 * ((size_t)(10 * y + 5) * ww + 10 * x + 5), img + 3 * ((size_t)y * w + x), 3) != 0;
    printf("%s: %dx%d, %ld of %d pixels differ from %s\n", window, ww, wh, differ, w * h, shown);
    EXPECT(differ == 0, "the window screenshot differs from what the viewer showed in %ld pixels", differ);
    free(win);
    free(img);
}

/* Runs the viewer on cornell at 64x36 (seed 5) under Xvfb with the script text and extra arguments,
 * writing into out; expects exit 0 (name labels the failure and the log, tmp/xvfb-NAME.log). */
static void viewer_session(const char *tmp, const char *name, const char *script, const char *extra, const char *out)
{
    char path[2 * CLI_PATH_MAX], full[24 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(path, sizeof path, "%s/%s.txt", tmp, name);
    write_text(path, script);
    snprintf(full, sizeof full,
             "timeout 300 xvfb-run -a '%s' view --scene cornell --res 64x36 --seed 5 %s --script '%s' --out '%s' > "
             "'%s/xvfb-%s.log' 2>&1",
             cli_bin(), extra, path, out, tmp, name);
    const int status = system(full);
    snprintf(path, sizeof path, "%s/xvfb-%s.log", tmp, name);
    cli_read_text(path, err, sizeof err);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the %s viewer exited %d:\n%s", name, WEXITSTATUS(status),
           err);
}

int main(void)
{
    char tmp[CLI_PATH_MAX], script[2 * CLI_PATH_MAX], dir[2 * CLI_PATH_MAX], replay[2 * CLI_PATH_MAX];
    char args[12 * CLI_PATH_MAX], out[4 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    snprintf(script, sizeof script, "%s/session.txt", tmp);
    /* ticks 0-5 with restir-di, then restir-pt from tick 6: its frames 0..6, screenshot before frame 6;
     * five V presses: confidence, temporal acceptance, selected neighbors, reuse cells, temporal
     * candidates per technique, the view on screen at the screenshot */
    write_text(script, "# walk, turn, switch method, screenshot, save the path\n"
                       "0 hold w 3\n1 press v\n2 press v\n3 drag 30 -10\n3 press v\n4 hold d 2\n4 press v\n"
                       "5 press v\n6 press m\n7 hold a 4\n10 drag -20 5\n"
                       "12 press k\n12 screenshot window.png\n13 press c\n13 quit\n");
    snprintf(dir, sizeof dir, "%s/view", tmp);

    /* no display: exit 1, a message, no folder */
    snprintf(args, sizeof args, "view --scene cornell --res 64x36 --script '%s' --out '%s/nodisplay'", script, tmp);
    char cmd[16 * CLI_PATH_MAX];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY '%s' %s", cli_bin(), args);
    snprintf(out, sizeof out, "%s/nodisplay.err", tmp);
    char full[24 * CLI_PATH_MAX];
    snprintf(full, sizeof full, "%s 2> '%s'", cmd, out);
    int status = system(full);
    cli_read_text(out, err, sizeof err);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 1, "without a display the viewer exited %d, want 1",
           WEXITSTATUS(status));
    EXPECT(strstr(err, "no display") != NULL, "without a display the message is: %s", err);
    snprintf(out, sizeof out, "%s/nodisplay", tmp);
    EXPECT(file_size(out) < 0, "without a display the viewer made %s", out);

    /* a bad script: exit 2 naming the line */
    snprintf(out, sizeof out, "%s/bad.txt", tmp);
    write_text(out, "0 press w\n5 jump 3\n");
    snprintf(args, sizeof args, "view --scene cornell --res 64x36 --script '%s' --out '%s/bad'", out, tmp);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 2 && strstr(err, "bad.txt:2") != NULL, "bad script: exit %d, message %s", rc, err);
    write_text(out, "0 screenshot before_any_frame.png\n"); /* the window has shown nothing yet */
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 2 && strstr(err, "bad.txt:1") != NULL, "a screenshot at frame 0: exit %d, message %s", rc, err);

    /* the scripted session under Xvfb */
    snprintf(full, sizeof full,
             "timeout 300 xvfb-run -a '%s' view --scene cornell --res 64x36 --seed 5 --script '%s' --out '%s' > "
             "'%s/xvfb.log' 2>&1",
             cli_bin(), script, dir, tmp);
    status = system(full);
    snprintf(out, sizeof out, "%s/xvfb.log", tmp);
    cli_read_text(out, err, sizeof err);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the scripted viewer under xvfb-run exited %d:\n%s",
           WEXITSTATUS(status), err);
    char shot[3 * CLI_PATH_MAX], last[3 * CLI_PATH_MAX], cams[3 * CLI_PATH_MAX], msg[512];
    snprintf(shot, sizeof shot, "%s/screenshot_0000.exr", dir);
    snprintf(last, sizeof last, "%s/last_frame.exr", dir);
    snprintf(cams, sizeof cams, "%s/camera.json", dir);
    snprintf(out, sizeof out, "%s/screenshot_0000.png", dir);
    EXPECT(file_size(out) > 100, "no screenshot PNG at %s", out);
    /* a rendered image of the scene: the Cornell box's red and green walls are both in view */
    float *img = NULL;
    int w = 0, h = 0;
    EXPECT(exr_read_rgb(shot, &img, &w, &h, msg) == 0, "%s", msg);
    if (img) {
        double red = 0.0, green = 0.0;
        for (int i = 0; i < w * h; i++) {
            red += img[3 * i] > 2.0f * img[3 * i + 1] ? 1.0 : 0.0;
            green += img[3 * i + 1] > 2.0f * img[3 * i] ? 1.0 : 0.0;
        }
        printf("screenshot %dx%d: %.0f red-wall pixels, %.0f green-wall pixels\n", w, h, red, green);
        EXPECT(w == 64 && h == 36 && red > 20 && green > 20, "the screenshot does not show the Cornell box");
        free(img);
    }
    /* the debug view on screen: restir-pt's temporal candidates, all backprojected (the default) */
    long tc[TC_COLOURS];
    snprintf(out, sizeof out, "%s/screenshot_0000_view.png", dir);
    EXPECT(count_temporal_view(out, tc) == 0, "cannot read %s at 64x36", out);
    EXPECT(tc[TC_OTHER] == 0 && tc[TC_SPLAT] == 0 && tc[TC_BOTH] == 0 && tc[TC_BP] > 64 * 36 / 4,
           "%s: the temporal-candidates view of temporal.reuse=backproject is not mostly green", out);
    char window[3 * CLI_PATH_MAX];
    snprintf(window, sizeof window, "%s/window.png", dir);
    check_window_shot(window, out);
    /* temporal.reuse=both: splatted candidates too, alone (blue) or with backprojection (cyan) */
    char both[2 * CLI_PATH_MAX];
    snprintf(both, sizeof both, "%s/both", tmp);
    viewer_session(tmp, "both",
                   "0 hold d 4\n0 press v\n0 press v\n0 press v\n0 press v\n0 press v\n5 press k\n6 quit\n",
                   "--method restir-pt --set temporal.reuse=both", both);
    snprintf(out, sizeof out, "%s/screenshot_0000_view.png", both);
    EXPECT(count_temporal_view(out, tc) == 0, "cannot read %s at 64x36", out);
    EXPECT(tc[TC_OTHER] == 0 && tc[TC_BOTH] + tc[TC_SPLAT] > 64 * 36 / 4,
           "%s: the temporal-candidates view of temporal.reuse=both shows no splatted candidates", out);

    /* O turns SVGF on: the screenshot then writes the denoised frame beside the raw one */
    char dn[2 * CLI_PATH_MAX];
    snprintf(dn, sizeof dn, "%s/denoise", tmp);
    viewer_session(tmp, "denoise", "0 press o\n4 press o\n5 press k\n6 press i\n8 press k\n9 quit\n",
                   "--method restir-di", dn);
    for (int k = 0; k < 2; k++) {
        char raw[4 * CLI_PATH_MAX];
        snprintf(raw, sizeof raw, "%s/screenshot_%04d.exr", dn, k);
        snprintf(out, sizeof out, "%s/screenshot_%04d_denoised.exr", dn, k);
        EXPECT(file_size(raw) > 0 && file_size(out) > 0, "screenshot %d: %s and its denoised frame", k, raw);
    }

    /* M from pt with a lens to the next method of the cycle, which renders no depth of field: refused by
     * the checks the command ran before the first frame, and pt keeps running */
    char refused[2 * CLI_PATH_MAX], log[2 * CLI_PATH_MAX];
    snprintf(refused, sizeof refused, "%s/refused", tmp);
    viewer_session(tmp, "refused", "0 press m\n2 press k\n3 quit\n", "--method pt --set camera.aperture=0.05", refused);
    snprintf(log, sizeof log, "%s/xvfb-refused.log", tmp);
    cli_read_text(log, err, sizeof err);
    EXPECT(strstr(err, "camera.aperture") && strstr(err, "does not render") &&
               strstr(err, "pt keeps running as it was"),
           "M to a method that cannot render the lens: not refused by name:\n%s", err);
    snprintf(out, sizeof out, "%s/screenshot_0000.exr", refused);
    EXPECT(file_size(out) > 0, "the refused switch stopped the session (no %s)", out);

    /* replay the recorded path: restir-pt (one M press from restir-di), same seed and size */
    snprintf(replay, sizeof replay, "%s/replay", tmp);
    snprintf(args, sizeof args,
             "render --scene cornell --method restir-pt --res 64x36 --seed 5 --camera '%s' --out '%s' --save all", cams,
             replay);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    snprintf(out, sizeof out, "%s/frame_0007.exr", replay);
    EXPECT(file_size(out) < 0, "the camera file should hold 7 cameras (frames 0-6)");
    snprintf(out, sizeof out, "%s/frame_0006.exr", replay);
    same_file(out, last);
    snprintf(out, sizeof out, "%s/frame_0005.exr", replay);
    same_file(out, shot);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
