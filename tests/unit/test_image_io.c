/* test_image_io.c: unit tests for EXR (one and several layers) and PNG (sRGB and signed false
 * colour) image files, atomic commits and the CSV/JSON writers.
 * Must never depend on render code or scenes; writes only under a fresh /tmp directory. */
#include <dirent.h>
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"
#include "io/report.h"
#include "test_util.h"

static char dir[64];

static void join(char *out, size_t n, const char *name)
{
    snprintf(out, n, "%s/%s", dir, name);
}

static long file_size(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return -1;
    return (long)st.st_size;
}

/* Number of entries in dir whose name contains ".tmp-". */
static int count_temp_files(const char *d)
{
    DIR *dp = opendir(d);
    if (!dp)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(dp)) != NULL)
        if (strstr(e->d_name, ".tmp-"))
            n++;
    closedir(dp);
    return n;
}

static void remove_all(const char *d)
{
    DIR *dp = opendir(d);
    if (!dp)
        return;
    struct dirent *e;
    char p[512];
    while ((e = readdir(dp)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(p, sizeof p, "%s/%s", d, e->d_name);
        remove(p);
    }
    closedir(dp);
    rmdir(d);
}

static float *make_image(int w, int h)
{
    float *img = xmalloc((size_t)w * (size_t)h * 3 * sizeof(float));
    for (int i = 0; i < w * h * 3; i++)
        img[i] = (float)(i % 17) * 0.37f - 0.5f + (float)(i % 5) * 1e-7f;
    int n = w * h * 3;
    img[0] = 1e4f;
    img[4 % n] = 65504.0f * 3.0f; /* beyond half range: only float channels keep it */
    img[n - 1] = 1.17549435e-38f;
    img[7 % n] = 0.0f;
    return img;
}

static void test_exr_round_trip(int w, int h)
{
    char path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "round.exr");
    float *img = make_image(w, h);
    msg[0] = '\0';
    int rc = exr_write_rgb(path, img, w, h, msg);
    EXPECT(rc == 0, "exr_write_rgb %dx%d: %s", w, h, msg);
    float *back = NULL;
    int bw = 0, bh = 0;
    rc = exr_read_rgb(path, &back, &bw, &bh, msg);
    EXPECT(rc == 0, "exr_read_rgb %dx%d: %s", w, h, msg);
    if (rc == 0) {
        EXPECT(bw == w && bh == h, "size %dx%d vs %dx%d", bw, bh, w, h);
        if (bw == w && bh == h)
            EXPECT(memcmp(back, img, (size_t)w * (size_t)h * 3 * sizeof(float)) == 0,
                   "round trip %dx%d not bit-exact", w, h);
    }
    free(back);
    free(img);
    EXPECT(count_temp_files(dir) == 0, "temporary file left after EXR write");
    remove(path);
}

static void test_exr_errors(void)
{
    char path[256], msg[RESTIR_MSG_LEN];
    float *img = NULL;
    int w = -1, h = -1;

    join(path, sizeof path, "missing.exr");
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "missing file accepted");
    EXPECT(strstr(msg, path) != NULL, "message lacks path: %s", msg);
    EXPECT(img == NULL, "buffer set on failure");

    join(path, sizeof path, "text.exr");
    FILE *f = fopen(path, "w");
    EXPECT(f != NULL, "cannot create %s", path);
    if (f) {
        fputs("this is not an image\n", f);
        fclose(f);
    }
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "text file accepted");
    EXPECT(strstr(msg, path) != NULL, "message lacks path: %s", msg);

    /* Empty file. */
    f = fopen(path, "w");
    if (f)
        fclose(f);
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "empty file accepted");
    EXPECT(strstr(msg, path) != NULL, "message lacks path: %s", msg);
    remove(path);

    /* Truncated files: half, and also just past the header-ish region. */
    join(path, sizeof path, "trunc.exr");
    int tw = 33, th = 40;
    float *src = make_image(tw, th);
    EXPECT(exr_write_rgb(path, src, tw, th, msg) == 0, "write for truncation: %s", msg);
    free(src);
    long full = file_size(path);
    EXPECT(full > 100, "EXR size %ld", full);
    long cuts[3] = {full / 2, full - 1, 40};
    for (int k = 0; k < 3; k++) {
        EXPECT(truncate(path, cuts[k]) == 0, "truncate to %ld", cuts[k]);
        msg[0] = '\0';
        img = NULL;
        int rc = exr_read_rgb(path, &img, &w, &h, msg);
        EXPECT(rc == -1, "truncated EXR (%ld of %ld bytes) accepted", cuts[k], full);
        EXPECT(strstr(msg, path) != NULL, "message lacks path: %s", msg);
        if (rc == 0)
            free(img);
        if (k == 0)
            printf("truncated EXR message: %s\n", msg);
    }
    remove(path);

    /* Write into a nonexistent directory. */
    char bad[256];
    snprintf(bad, sizeof bad, "%s/no_such_dir/out.exr", dir);
    float px[3] = {1, 2, 3};
    msg[0] = '\0';
    EXPECT(exr_write_rgb(bad, px, 1, 1, msg) == -1, "write into missing dir succeeded");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);
    EXPECT(exr_write_rgb(path, px, 0, 1, msg) == -1, "zero width accepted");
    EXPECT(count_temp_files(dir) == 0, "temporary file left");
}

/* Test-only writer for layouts exr_write_rgb never produces: the given channel names (each
 * filled with value(channel index, pixel)), pixel type, data window origin, scanline or tiled. */
static int write_custom_exr(const char *path, const char *const *names, int nch,
                            exr_pixel_type_t type, int x0, int y0, int w, int h, int tiled)
{
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    int part = 0, ok = 1;
    float *planes = xmalloc((size_t)nch * (size_t)w * (size_t)h * sizeof(float));
    for (int c = 0; c < nch; c++)
        for (int i = 0; i < w * h; i++)
            planes[(size_t)c * (size_t)(w * h) + (size_t)i] = (float)(c * 100 + i) * 0.25f;
    ok = ok && exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init) == EXR_ERR_SUCCESS;
    ok = ok && exr_add_part(ctxt, NULL, tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE,
                            &part) == EXR_ERR_SUCCESS;
    exr_attr_box2i_t box;
    box.min.x = x0;
    box.min.y = y0;
    box.max.x = x0 + w - 1;
    box.max.y = y0 + h - 1;
    exr_attr_v2f_t center;
    center.x = center.y = 0.0f;
    ok = ok && exr_initialize_required_attr(ctxt, part, &box, &box, 1.0f, &center, 1.0f,
                                            EXR_LINEORDER_INCREASING_Y,
                                            EXR_COMPRESSION_NONE) == EXR_ERR_SUCCESS;
    if (tiled)
        ok = ok && exr_set_tile_descriptor(ctxt, part, 8, 8, EXR_TILE_ONE_LEVEL,
                                           EXR_TILE_ROUND_DOWN) == EXR_ERR_SUCCESS;
    for (int c = 0; c < nch && ok; c++)
        ok = exr_add_channel(ctxt, part, names[c], type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) ==
             EXR_ERR_SUCCESS;
    ok = ok && exr_write_header(ctxt) == EXR_ERR_SUCCESS;
    int32_t lines = 1;
    if (ok && !tiled)
        ok = exr_get_scanlines_per_chunk(ctxt, part, &lines) == EXR_ERR_SUCCESS;
    int nchunks = tiled ? ((w + 7) / 8) * ((h + 7) / 8) : (h + lines - 1) / lines;
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    for (int k = 0; k < nchunks && ok; k++) {
        exr_chunk_info_t ci;
        if (tiled)
            ok = exr_write_tile_chunk_info(ctxt, part, k % ((w + 7) / 8), k / ((w + 7) / 8), 0, 0,
                                           &ci) == EXR_ERR_SUCCESS;
        else
            ok = exr_write_scanline_chunk_info(ctxt, part, y0 + k * lines, &ci) ==
                 EXR_ERR_SUCCESS;
        if (ok)
            ok = (k == 0 ? exr_encoding_initialize(ctxt, part, &ci, &enc)
                         : exr_encoding_update(ctxt, part, &ci, &enc)) == EXR_ERR_SUCCESS;
        int px = tiled ? (k % ((w + 7) / 8)) * 8 : 0;
        int py = tiled ? (k / ((w + 7) / 8)) * 8 : k * lines;
        for (int c = 0; c < enc.channel_count && ok; c++) {
            int src = 0;
            for (int j = 0; j < nch; j++)
                if (strcmp(names[j], enc.channels[c].channel_name) == 0)
                    src = j;
            enc.channels[c].user_pixel_stride = (int32_t)sizeof(float);
            enc.channels[c].user_line_stride = (int32_t)sizeof(float) * w;
            enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
            enc.channels[c].user_bytes_per_element = (int16_t)sizeof(float);
            enc.channels[c].encode_from_ptr =
                (const uint8_t *)(planes + (size_t)src * (size_t)(w * h) + (size_t)(py * w + px));
        }
        ok = ok && exr_encoding_choose_default_routines(ctxt, part, &enc) == EXR_ERR_SUCCESS;
        ok = ok && exr_encoding_run(ctxt, part, &enc) == EXR_ERR_SUCCESS;
    }
    if (nchunks > 0 && ctxt)
        exr_encoding_destroy(ctxt, &enc);
    if (ctxt && exr_finish(&ctxt) != EXR_ERR_SUCCESS)
        ok = 0;
    free(planes);
    return ok ? 0 : -1;
}

static void test_exr_foreign_layouts(void)
{
    char path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "foreign.exr");
    float *img = NULL;
    int w = 0, h = 0;

    /* HALF channels, extra alpha channel, data window starting at (-3, 10). Values are
     * multiples of 0.25 below 2048, so half stores them exactly. */
    static const char *const rgba[4] = {"A", "B", "G", "R"};
    EXPECT(write_custom_exr(path, rgba, 4, EXR_PIXEL_HALF, -3, 10, 9, 6, 0) == 0,
           "custom half write");
    msg[0] = '\0';
    int rc = exr_read_rgb(path, &img, &w, &h, msg);
    EXPECT(rc == 0, "half/offset read: %s", msg);
    if (rc == 0) {
        EXPECT(w == 9 && h == 6, "size %dx%d", w, h);
        int bad = 0;
        for (int i = 0; i < 9 * 6; i++) {
            /* channel j of names above holds (j*100 + i)/4: R=3, G=2, B=1 */
            bad += img[3 * i + 0] != (float)(300 + i) * 0.25f;
            bad += img[3 * i + 1] != (float)(200 + i) * 0.25f;
            bad += img[3 * i + 2] != (float)(100 + i) * 0.25f;
        }
        EXPECT(bad == 0, "%d wrong values after half/offset read", bad);
        free(img);
        img = NULL;
    }

    /* Float channels with a data window far from the origin. */
    static const char *const rgb[3] = {"R", "G", "B"};
    EXPECT(write_custom_exr(path, rgb, 3, EXR_PIXEL_FLOAT, 1000, -500, 5, 3, 0) == 0,
           "custom float write");
    rc = exr_read_rgb(path, &img, &w, &h, msg);
    EXPECT(rc == 0 && w == 5 && h == 3, "float/offset read: %s", msg);
    if (rc == 0) {
        EXPECT(img[0] == 0.0f && img[1] == 25.0f && img[2] == 50.0f && img[3] == 0.25f,
               "float/offset values %g %g %g %g", img[0], img[1], img[2], img[3]);
        free(img);
        img = NULL;
    }

    /* Missing blue channel. */
    static const char *const rg[2] = {"G", "R"};
    EXPECT(write_custom_exr(path, rg, 2, EXR_PIXEL_FLOAT, 0, 0, 4, 4, 0) == 0, "custom rg write");
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "EXR without B accepted");
    EXPECT(strstr(msg, path) != NULL && strstr(msg, "'B'") != NULL, "message: %s", msg);

    /* Tiled layout: a clear refusal. */
    EXPECT(write_custom_exr(path, rgb, 3, EXR_PIXEL_FLOAT, 0, 0, 11, 9, 1) == 0,
           "custom tiled write");
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "tiled EXR accepted");
    EXPECT(strstr(msg, path) != NULL && strstr(msg, "tiled") != NULL, "message: %s", msg);

    /* Absurd size: wider than any image we accept. */
    EXPECT(write_custom_exr(path, rgb, 3, EXR_PIXEL_HALF, 0, 0, 70000, 1, 0) == 0,
           "custom wide write");
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == -1, "70000-pixel-wide EXR accepted");
    EXPECT(strstr(msg, path) != NULL, "message: %s", msg);
    printf("wide EXR message: %s\n", msg);
    remove(path);
}

static void test_png(void)
{
    char path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "img.png");
    int w = 7, h = 5;
    float *img = make_image(w, h);
    img[3] = -1.0f;
    img[5] = (float)NAN;
    img[6] = (float)INFINITY;
    msg[0] = '\0';
    EXPECT(png_write_srgb(path, img, w, h, 0.5f, msg) == 0, "png write: %s", msg);
    free(img);
    unsigned char sig[8] = {0};
    FILE *f = fopen(path, "rb");
    EXPECT(f != NULL, "png missing");
    if (f) {
        EXPECT(fread(sig, 1, 8, f) == 8, "short png");
        fclose(f);
    }
    static const unsigned char want[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    EXPECT(memcmp(sig, want, 8) == 0, "PNG signature missing");
    remove(path);

    char bad[256];
    snprintf(bad, sizeof bad, "%s/no_such_dir/out.png", dir);
    float px[3] = {1, 2, 3};
    msg[0] = '\0';
    EXPECT(png_write_srgb(bad, px, 1, 1, 0.0f, msg) == -1, "png into missing dir succeeded");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);
    EXPECT(count_temp_files(dir) == 0, "temporary file left");
}

/* Fills a w x h interleaved RGB image whose values depend on seed, with negative values and
 * floats beyond half range so only a bit-exact float path reproduces it. */
static float *make_layer_image(int w, int h, float seed)
{
    float *img = make_image(w, h);
    for (int i = 0; i < w * h * 3; i++)
        img[i] = img[i] * seed - seed * 0.125f * (float)(i % 3);
    return img;
}

static int same_floats(const float *a, const float *b, int w, int h)
{
    return memcmp(a, b, (size_t)w * (size_t)h * 3 * sizeof(float)) == 0;
}

/* Reads layer (NULL = default through exr_read_rgb) and compares it bit for bit with want. */
static void expect_layer(const char *path, const char *layer, const float *want, int w, int h)
{
    char msg[RESTIR_MSG_LEN];
    float *back = NULL;
    int bw = 0, bh = 0;
    msg[0] = '\0';
    int rc = layer ? exr_read_layer(path, layer, &back, &bw, &bh, msg)
                   : exr_read_rgb(path, &back, &bw, &bh, msg);
    EXPECT(rc == 0, "read layer %s: %s", layer ? layer : "(default)", msg);
    if (rc == 0) {
        EXPECT(bw == w && bh == h, "layer %s size %dx%d vs %dx%d", layer ? layer : "(default)",
               bw, bh, w, h);
        if (bw == w && bh == h)
            EXPECT(same_floats(back, want, w, h), "layer %s not bit-exact",
                   layer ? layer : "(default)");
    }
    free(back);
}

/* Channel names of the file's only part, in file order, joined by spaces. */
static void channel_names(const char *path, char *out, size_t n)
{
    out[0] = '\0';
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    if (exr_start_read(&ctxt, path, &init) != EXR_ERR_SUCCESS) {
        if (ctxt)
            exr_finish(&ctxt);
        return;
    }
    const exr_attr_chlist_t *chl = NULL;
    if (exr_get_channels(ctxt, 0, &chl) == EXR_ERR_SUCCESS && chl) {
        size_t used = 0;
        for (int i = 0; i < chl->num_channels && used < n; i++) {
            int wrote = snprintf(out + used, n - used, "%s%s", i ? " " : "",
                                 chl->entries[i].name.str);
            if (wrote < 0)
                break;
            used += (size_t)wrote;
        }
        EXPECT(chl->entries[0].pixel_type == EXR_PIXEL_FLOAT, "channels are not 32-bit float");
    }
    exr_finish(&ctxt);
}

static void test_exr_layers(void)
{
    char path[256], msg[RESTIR_MSG_LEN], names[512];
    join(path, sizeof path, "layers.exr");
    int w = 13, h = 21;
    float *def = make_layer_image(w, h, 1.0f);
    float *primal = make_layer_image(w, h, 3.5f);
    float *dx = make_layer_image(w, h, -0.75f);
    struct exr_layer layers[3] = {{NULL, def}, {"primal", primal}, {"dx", dx}};
    msg[0] = '\0';
    EXPECT(exr_write_layers(path, layers, 3, w, h, msg) == 0, "exr_write_layers: %s", msg);
    EXPECT(count_temp_files(dir) == 0, "temporary file left after layered write");
    channel_names(path, names, sizeof names);
    EXPECT(strcmp(names, "B G R dx.B dx.G dx.R primal.B primal.G primal.R") == 0,
           "channel list: %s", names);
    expect_layer(path, NULL, def, w, h);
    expect_layer(path, "", def, w, h);
    expect_layer(path, "primal", primal, w, h);
    expect_layer(path, "dx", dx, w, h);
    float *back = NULL;
    int bw = 0, bh = 0;
    EXPECT(exr_read_layer(path, NULL, &back, &bw, &bh, msg) == 0 && same_floats(back, def, w, h),
           "exr_read_layer(NULL) differs from the default layer: %s", msg);
    free(back);
    back = NULL;

    /* A missing layer names itself and the layers the file has. */
    msg[0] = '\0';
    EXPECT(exr_read_layer(path, "dy", &back, &bw, &bh, msg) == -1, "missing layer accepted");
    EXPECT(back == NULL, "buffer set on failure");
    EXPECT(strstr(msg, path) && strstr(msg, "'dy'"), "missing-layer message: %s", msg);
    EXPECT(strstr(msg, "default") && strstr(msg, "primal") && strstr(msg, "dx"),
           "missing-layer message lacks the file's layers: %s", msg);
    printf("missing layer message: %s\n", msg);
    remove(path);

    /* Named layers sorting before and after the default channels ("A.B" < "B" < "Z.R"), the
     * default given last, and no default at all. */
    struct exr_layer order[3] = {{"Z", dx}, {"A", primal}, {"", def}};
    EXPECT(exr_write_layers(path, order, 3, w, h, msg) == 0, "write A/Z layers: %s", msg);
    channel_names(path, names, sizeof names);
    EXPECT(strcmp(names, "A.B A.G A.R B G R Z.B Z.G Z.R") == 0, "channel list: %s", names);
    expect_layer(path, NULL, def, w, h);
    expect_layer(path, "A", primal, w, h);
    expect_layer(path, "Z", dx, w, h);
    EXPECT(exr_write_layers(path, order, 2, w, h, msg) == 0, "write without default: %s", msg);
    expect_layer(path, "A", primal, w, h);
    msg[0] = '\0';
    EXPECT(exr_read_rgb(path, &back, &bw, &bh, msg) == -1, "file without R, G, B read as RGB");
    EXPECT(strstr(msg, "'R'") != NULL, "message: %s", msg);
    remove(path);

    /* A name longer than the 31-byte short-name limit of old EXR readers. */
    static const char long_name[] = "a_layer_name_of_more_than_thirty_one_bytes";
    struct exr_layer longl[2] = {{NULL, def}, {long_name, dx}};
    EXPECT(exr_write_layers(path, longl, 2, w, h, msg) == 0, "long layer name: %s", msg);
    expect_layer(path, long_name, dx, w, h);
    expect_layer(path, NULL, def, w, h);
    remove(path);

    /* exr_write_rgb is the one-layer case: its file has exactly R, G, B. */
    EXPECT(exr_write_rgb(path, def, w, h, msg) == 0, "exr_write_rgb: %s", msg);
    channel_names(path, names, sizeof names);
    EXPECT(strcmp(names, "B G R") == 0, "exr_write_rgb channels: %s", names);
    remove(path);

    /* Bad layer lists are refused before anything is created. */
    struct bad_case {
        struct exr_layer layers[3];
        int n;
        const char *needle;
    } bad[] = {
        {{{"dx.", dx}}, 1, "'dx.'"},
        {{{"a.b", dx}}, 1, "'a.b'"},
        {{{".", dx}}, 1, "'.'"},
        {{{".R", dx}}, 1, "'.R'"},
        {{{NULL, def}, {"dx", dx}, {"dx", primal}}, 3, "'dx'"},
        {{{NULL, def}, {"", dx}}, 2, "twice"},
        {{{NULL, def}, {"dx", NULL}}, 2, "'dx'"},
        {{{NULL, def}}, 0, "layers"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        msg[0] = '\0';
        EXPECT(exr_write_layers(path, bad[k].layers, bad[k].n, w, h, msg) == -1,
               "bad layer list %zu accepted", k);
        EXPECT(strstr(msg, path) && strstr(msg, bad[k].needle), "bad list %zu message: %s", k,
               msg);
        EXPECT(file_size(path) == -1, "file left behind by bad layer list %zu", k);
        EXPECT(count_temp_files(dir) == 0, "temporary file left by bad layer list %zu", k);
    }
    /* 200 bytes is the longest layer name accepted, on writing and on reading. */
    char too_long[202];
    memset(too_long, 'x', sizeof too_long - 1);
    too_long[sizeof too_long - 1] = '\0';
    struct exr_layer tl = {too_long, dx};
    EXPECT(exr_write_layers(path, &tl, 1, w, h, msg) == -1, "201-byte layer name accepted");
    EXPECT(file_size(path) == -1, "file left behind by too long a layer name");
    EXPECT(exr_read_layer(path, too_long, &back, &bw, &bh, msg) == -1 && strstr(msg, "longer"),
           "201-byte layer name read: %s", msg);
    too_long[200] = '\0';
    EXPECT(exr_write_layers(path, &tl, 1, w, h, msg) == 0, "200-byte layer name: %s", msg);
    expect_layer(path, too_long, dx, w, h);
    remove(path);
    EXPECT(exr_write_layers(path, layers, 3, 0, h, msg) == -1, "zero width accepted");
    EXPECT(count_temp_files(dir) == 0, "temporary file left");
    free(def);
    free(primal);
    free(dx);
}

/* Decodes an 8-bit RGB PNG with libpng; returns a malloc'ed w*h*3 buffer or NULL. */
static unsigned char *read_png_rgb(const char *path, int *w, int *h)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return NULL;
    img.format = PNG_FORMAT_RGB;
    unsigned char *buf = xmalloc(PNG_IMAGE_SIZE(img));
    if (!png_image_finish_read(&img, NULL, buf, 0, NULL)) {
        png_image_free(&img);
        free(buf);
        return NULL;
    }
    *w = (int)img.width;
    *h = (int)img.height;
    return buf;
}

static int red_dominant(const unsigned char *p)
{
    return p[0] > 0 && p[0] > p[1] && p[0] > p[2];
}

static int blue_dominant(const unsigned char *p)
{
    return p[2] > 0 && p[2] > p[0] && p[2] > p[1];
}

static void test_png_signed(void)
{
    char path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "grad.png");
    /* Pixels: 0, +1 (white), -1, +0.25 green, -0.5 in red only (lum < 0), -0.0, NaN, +inf. */
    enum { W = 4, H = 2 };
    float img[W * H * 3] = {
        0.0f, 0.0f, 0.0f,   1.0f, 1.0f, 1.0f,   -1.0f, -1.0f, -1.0f,   0.0f, 0.25f, 0.0f,
        -0.5f, 0.0f, 0.0f,  -0.0f, -0.0f, -0.0f, (float)NAN, 0.0f, 0.0f, (float)INFINITY, 0.0f, 0.0f,
    };
    msg[0] = '\0';
    EXPECT(png_write_signed(path, img, W, H, 1.0f, msg) == 0, "png_write_signed: %s", msg);
    EXPECT(count_temp_files(dir) == 0, "temporary file left after signed PNG");
    int w = 0, h = 0;
    unsigned char *px = read_png_rgb(path, &w, &h);
    EXPECT(px != NULL, "signed PNG does not decode");
    if (px) {
        EXPECT(w == W && h == H, "signed PNG size %dx%d", w, h);
        const unsigned char *p = px;
        EXPECT(p[0] == 0 && p[1] == 0 && p[2] == 0, "zero is %d %d %d", p[0], p[1], p[2]);
        p = px + 3;
        EXPECT(red_dominant(p) && p[0] == 255, "+1 is %d %d %d", p[0], p[1], p[2]);
        p = px + 6;
        EXPECT(blue_dominant(p) && p[2] == 255, "-1 is %d %d %d", p[0], p[1], p[2]);
        EXPECT(px[3 + 1] == px[6 + 1], "map not symmetric: %d vs %d", px[4], px[7]);
        p = px + 9;
        EXPECT(red_dominant(p) && p[0] < 255, "+0.18 is %d %d %d", p[0], p[1], p[2]);
        p = px + 12;
        EXPECT(blue_dominant(p) && p[2] < 255, "red -0.5 is %d %d %d", p[0], p[1], p[2]);
        p = px + 15;
        EXPECT(p[0] == 0 && p[1] == 0 && p[2] == 0, "-0 is %d %d %d", p[0], p[1], p[2]);
        p = px + 18;
        EXPECT(p[0] == 0 && p[1] == 0 && p[2] == 0, "NaN is %d %d %d", p[0], p[1], p[2]);
        p = px + 21;
        EXPECT(red_dominant(p) && p[0] == 255, "+inf is %d %d %d", p[0], p[1], p[2]);
        free(px);
    }

    /* Automatic scale: the 99th percentile of |lum| maps to full colour. 200 pixels: 0.01 * i
     * for i < 198 (negative at odd i), then two outliers of 1000; the nearest-rank 99th
     * percentile is the 198th value, 1.97, so pixel 197 is full blue and 99 about half. */
    enum { N = 200 };
    float *ramp = xmalloc(N * 3 * sizeof(float));
    for (int i = 0; i < N; i++) {
        float v = i < 198 ? 0.01f * (float)i * (i % 2 ? -1.0f : 1.0f) : 1000.0f;
        ramp[3 * i] = ramp[3 * i + 1] = ramp[3 * i + 2] = v;
    }
    EXPECT(png_write_signed(path, ramp, N, 1, 0.0f, msg) == 0, "auto-scale write: %s", msg);
    px = read_png_rgb(path, &w, &h);
    EXPECT(px != NULL, "auto-scale PNG does not decode");
    if (px) {
        EXPECT(px[0] == 0 && px[1] == 0 && px[2] == 0, "auto: zero not black");
        EXPECT(blue_dominant(px + 3 * 197) && px[3 * 197 + 2] == 255, "auto: 99th pct is %d",
               px[3 * 197 + 2]);
        EXPECT(blue_dominant(px + 3 * 99) && px[3 * 99 + 2] > 150 && px[3 * 99 + 2] < 240,
               "auto: half of 99th pct is %d", px[3 * 99 + 2]);
        EXPECT(red_dominant(px + 3 * 198) && px[3 * 198] == 255, "auto: outlier not saturated");
        EXPECT(red_dominant(px + 3 * 2) && px[3 * 2] < px[3 * 98], "auto: not monotone");
        free(px);
    }

    /* Sparse gradient (one nonzero pixel in 200): the percentile is 0, so the largest |lum|
     * sets the scale; an all-zero image is all black. */
    memset(ramp, 0, N * 3 * sizeof(float));
    ramp[3 * 50 + 1] = -1e-3f;
    EXPECT(png_write_signed(path, ramp, N, 1, -1.0f, msg) == 0, "sparse write: %s", msg);
    px = read_png_rgb(path, &w, &h);
    if (px) {
        EXPECT(blue_dominant(px + 150) && px[152] == 255, "sparse: spike is %d %d %d", px[150],
               px[151], px[152]);
        int nonblack = 0;
        for (int i = 0; i < N * 3; i++)
            nonblack += px[i] != 0;
        EXPECT(nonblack == 2, "sparse: %d nonzero bytes", nonblack);
        free(px);
    }
    ramp[3 * 50 + 1] = 0.0f;
    EXPECT(png_write_signed(path, ramp, N, 1, 0.0f, msg) == 0, "all-zero write: %s", msg);
    px = read_png_rgb(path, &w, &h);
    if (px) {
        int nonblack = 0;
        for (int i = 0; i < N * 3; i++)
            nonblack += px[i] != 0;
        EXPECT(nonblack == 0, "all-zero: %d nonzero bytes", nonblack);
        free(px);
    }
    free(ramp);
    remove(path);

    char bad[256];
    snprintf(bad, sizeof bad, "%s/no_such_dir/grad.png", dir);
    msg[0] = '\0';
    EXPECT(png_write_signed(bad, img, W, H, 1.0f, msg) == -1, "signed PNG into missing dir");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);
    EXPECT(png_write_signed(path, img, 0, H, 1.0f, msg) == -1, "zero width accepted");
    EXPECT(png_write_signed(path, NULL, W, H, 1.0f, msg) == -1, "NULL pixels accepted");
    EXPECT(file_size(path) == -1, "file left behind by a failed signed PNG");
    EXPECT(count_temp_files(dir) == 0, "temporary file left");
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = xcalloc(4096, 1);
    size_t n = fread(buf, 1, 4095, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void test_reports(void)
{
    char path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "table.csv");
    struct csv_writer w;
    msg[0] = '\0';
    EXPECT(csv_open(&w, path, "a,b,c", msg) == 0, "csv_open: %s", msg);
    EXPECT(file_size(path) == -1, "CSV visible before close");
    EXPECT(csv_row(&w, "%d,%s,%.3f", 1, "x", 0.5) == 0, "row 1");
    EXPECT(csv_row(&w, "%d,%s,%.3f", 2, "y", 1.25) == 0, "row 2");
    EXPECT(csv_close(&w, msg) == 0, "csv_close: %s", msg);
    char *text = slurp(path);
    EXPECT(text && strcmp(text, "a,b,c\n1,x,0.500\n2,y,1.250\n") == 0, "CSV content: %s",
           text ? text : "(none)");
    free(text);
    remove(path);

    EXPECT(csv_open(&w, path, "a", msg) == 0, "csv_open: %s", msg);
    csv_row(&w, "1");
    csv_abort(&w);
    EXPECT(file_size(path) == -1, "aborted CSV exists");
    EXPECT(count_temp_files(dir) == 0, "temporary file left after abort");
    csv_abort(&w); /* second abort is harmless */

    char bad[256];
    snprintf(bad, sizeof bad, "%s/no_such_dir/t.csv", dir);
    msg[0] = '\0';
    EXPECT(csv_open(&w, bad, "a", msg) == -1, "csv into missing dir succeeded");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);

    join(path, sizeof path, "r.json");
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "relmse", 0.25);
    cJSON_AddStringToObject(root, "name", "test");
    msg[0] = '\0';
    EXPECT(json_write_file(path, root, msg) == 0, "json_write_file: %s", msg);
    text = slurp(path);
    cJSON *back = text ? cJSON_Parse(text) : NULL;
    EXPECT(back != NULL, "JSON does not parse back");
    if (back) {
        cJSON *v = cJSON_GetObjectItemCaseSensitive(back, "relmse");
        EXPECT(cJSON_IsNumber(v) && v->valuedouble == 0.25, "relmse value");
        cJSON_Delete(back);
    }
    free(text);
    remove(path);
    snprintf(bad, sizeof bad, "%s/no_such_dir/r.json", dir);
    EXPECT(json_write_file(bad, root, msg) == -1, "json into missing dir succeeded");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);
    cJSON_Delete(root);
    EXPECT(count_temp_files(dir) == 0, "temporary file left");
}

static void test_commit(void)
{
    char tmp[256], path[256], msg[RESTIR_MSG_LEN];
    join(path, sizeof path, "c.txt");
    io_temp_path(path, tmp, sizeof tmp);
    char want[300];
    snprintf(want, sizeof want, "%s.tmp-%ld", path, (long)getpid());
    EXPECT(strcmp(tmp, want) == 0, "temp name %s", tmp);
    FILE *f = fopen(tmp, "w");
    if (f)
        fclose(f);
    char bad[256];
    snprintf(bad, sizeof bad, "%s/no_such_dir/c.txt", dir);
    msg[0] = '\0';
    EXPECT(io_commit(tmp, bad, msg) == -1, "commit into missing dir succeeded");
    EXPECT(strstr(msg, bad) != NULL, "message lacks path: %s", msg);
    EXPECT(file_size(tmp) == -1, "tmp not removed after failed commit");
}

/* Text header attributes: written with the pixels, read back exactly, absent ones reported as
 * such, bad names refused before any file exists. */
static void test_exr_attributes(void)
{
    char path[512], msg[RESTIR_MSG_LEN], value[256];
    snprintf(path, sizeof path, "%s/attrs.exr", dir);
    const float px[3 * 2] = {1, 2, 3, 4, 5, 6};
    const struct exr_layer layer = {NULL, px};
    const struct exr_attribute attrs[2] = {{"restir.samples", "1024"},
                                           {"restir.run", "scene=cornell; seed=7; \"quoted\" text"}};
    EXPECT(exr_write_layers_attrs(path, &layer, 1, attrs, 2, 2, 1, msg) == 0, "write with attributes: %s", msg);
    EXPECT(exr_read_attribute(path, "restir.samples", value, sizeof value, msg) == 0 && !strcmp(value, "1024"),
           "restir.samples read back as '%s' (%s)", value, msg);
    EXPECT(exr_read_attribute(path, "restir.run", value, sizeof value, msg) == 0 && !strcmp(value, attrs[1].value),
           "restir.run read back as '%s'", value);
    EXPECT(exr_read_attribute(path, "restir.absent", value, sizeof value, msg) == 1 && value[0] == '\0',
           "absent attribute not reported as absent");
    EXPECT(exr_read_attribute(path, "restir.run", value, 8, msg) == -1 && strstr(msg, "longer"),
           "over-long attribute accepted: %s", msg);
    EXPECT(exr_read_attribute(path, "compression", value, sizeof value, msg) == -1 && strstr(msg, "not text"),
           "non-text attribute read as text: %s", msg);
    float *img = NULL;
    int w = 0, h = 0;
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == 0 && w == 2 && h == 1 && img[5] == 6.0f,
           "pixels of a file with attributes: %s", msg);
    free(img);
    char bad[512];
    snprintf(bad, sizeof bad, "%s/bad_attrs.exr", dir);
    const struct exr_attribute unnamed = {"samples", "1"}, twice[2] = {{"restir.a", "1"}, {"restir.a", "2"}};
    EXPECT(exr_write_layers_attrs(bad, &layer, 1, &unnamed, 1, 2, 1, msg) == -1 && strstr(msg, "samples"),
           "attribute without a namespace accepted");
    EXPECT(exr_write_layers_attrs(bad, &layer, 1, twice, 2, 2, 1, msg) == -1 && strstr(msg, "twice"),
           "duplicate attribute accepted");
    struct stat st;
    EXPECT(stat(bad, &st) != 0, "a refused write left %s", bad);
    EXPECT(exr_read_attribute(bad, "restir.a", value, sizeof value, msg) == -1, "missing file has attributes");
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/restir_io_XXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_exr_round_trip(7, 5);
    test_exr_round_trip(1, 1);
    test_exr_round_trip(64, 37);
    test_exr_errors();
    test_exr_foreign_layouts();
    test_exr_layers();
    test_exr_attributes();
    test_png();
    test_png_signed();
    test_reports();
    test_commit();
    remove_all(dir);
    return test_finish();
}
