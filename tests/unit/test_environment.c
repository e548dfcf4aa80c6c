/* test_environment.c: environment maps (scene/environment.h): .hdr and .exr (float and half) files
 * written under a fresh /tmp directory and loaded back texel for texel, the direction <-> texel
 * mapping at hand-computed directions (with and without rotation), and every refusal (missing
 * file, not an image, NaN / infinite / negative texels, all zero, too large, truncated, no RGB,
 * bad intensity or rotation, bad constant colour), each with a message naming the key and file. */
#include <math.h>
#include <openexr.h>
#include <stb/stb_image_write.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/check.h"
#include "io/exr.h"
#include "scene/environment.h"
#include "test_util.h"

#define KEY "--env"
#define MW 8 /* the test map: 8 x 4 texels of 45 degrees */
#define MH 4

static char dir[64];

static const char *path_of(const char *name)
{
    static char buf[8][256];
    static int next;
    char *p = buf[next++ % 8];
    snprintf(p, 256, "%s/%s", dir, name);
    return p;
}

/* R = x + 1, G = y + 1, B = 0.5: all exact in RGBE (each component a multiple of the shared
 * exponent's 8-bit step), half and float. */
static void make_map(float *rgb)
{
    for (int y = 0; y < MH; y++)
        for (int x = 0; x < MW; x++) {
            float *p = rgb + 3 * (y * MW + x);
            p[0] = (float)(x + 1);
            p[1] = (float)(y + 1);
            p[2] = 0.5f;
        }
}

static int texel_is(const struct environment *env, int x, int y, float r, float g, float b)
{
    vec3 c = environment_texel(env, x, y);
    return c.x == r && c.y == g && c.z == b;
}

/* A refusal: load must fail with a message naming the key, the file and containing `what`. */
static void expect_refused(const char *path, float intensity, float rotation, const char *what, const char *label)
{
    struct environment env;
    char msg[RESTIR_MSG_LEN] = "";
    int rc = environment_load(KEY, path, intensity, rotation, &env, msg);
    EXPECT(rc == -1 && env.rgb == NULL, "%s: load succeeded", label);
    EXPECT(strstr(msg, KEY) && strstr(msg, path) && strstr(msg, what), "%s: message '%s' lacks '%s'", label, msg,
           what);
    printf("  refused (%s): %s\n", label, msg);
}

static void write_text(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(text, 1, n, f);
        fclose(f);
    }
}

/* Half-float bits of a value that half represents exactly (normal, or zero). */
static uint16_t to_half(float v)
{
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    uint32_t sign = (b >> 16) & 0x8000u, mag = b & 0x7fffffffu;
    if (mag == 0)
        return (uint16_t)sign;
    uint32_t exp = (mag >> 23) - 127 + 15, mant = (mag >> 13) & 0x3ffu;
    return (uint16_t)(sign | (exp << 10) | mant);
}

/* Points the encoder's channels at this chunk's rows of the half planes (R, G, B, A). */
static void bind_half(exr_encode_pipeline_t *enc, uint16_t *planes[4], int w, int row)
{
    static const char *const names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < enc->channel_count; c++)
        for (int k = 0; k < 4; k++)
            if (strcmp(enc->channels[c].channel_name, names[k]) == 0) {
                exr_coding_channel_info_t *ch = &enc->channels[c];
                ch->user_pixel_stride = (int32_t)sizeof(uint16_t);
                ch->user_line_stride = (int32_t)sizeof(uint16_t) * w;
                ch->user_data_type = EXR_PIXEL_HALF;
                ch->user_bytes_per_element = (int16_t)sizeof(uint16_t);
                ch->encode_from_ptr = (const uint8_t *)(planes[k] + (size_t)row * (size_t)w);
            }
}

/* Writes an RGBA half-float scanline EXR (A = 0.25 everywhere) with the Core C API. */
static int write_half_exr(const char *path, const float *rgb, int w, int h)
{
    uint16_t *planes[4];
    for (int k = 0; k < 4; k++) {
        planes[k] = xmalloc(sizeof(uint16_t) * (size_t)(w * h));
        for (int i = 0; i < w * h; i++)
            planes[k][i] = to_half(k < 3 ? rgb[3 * i + k] : 0.25f);
    }
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, w, h, EXR_COMPRESSION_ZIP);
    static const char *const names[4] = {"R", "G", "B", "A"};
    for (int k = 0; k < 4 && rv == EXR_ERR_SUCCESS; k++)
        rv = exr_add_channel(ctxt, part, names[k], EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);
    int32_t lines = 0;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int have = 0;
    for (int y = 0; y < h && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS) {
            rv = have ? exr_encoding_update(ctxt, part, &cinfo, &enc)
                      : exr_encoding_initialize(ctxt, part, &cinfo, &enc);
            have = 1;
        }
        if (rv == EXR_ERR_SUCCESS) {
            bind_half(&enc, planes, w, cinfo.start_y);
            rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &enc);
    }
    if (have)
        exr_encoding_destroy(ctxt, &enc);
    if (ctxt && exr_finish(&ctxt) != EXR_ERR_SUCCESS)
        rv = EXR_ERR_UNKNOWN;
    for (int k = 0; k < 4; k++)
        free(planes[k]);
    return rv == EXR_ERR_SUCCESS ? 0 : -1;
}

/* Every texel of env equals make_map's. */
static void expect_map(const struct environment *env, const char *label)
{
    EXPECT(env->width == MW && env->height == MH, "%s: %dx%d", label, env->width, env->height);
    if (!env->rgb || env->width != MW || env->height != MH)
        return;
    int bad = 0;
    for (int y = 0; y < MH; y++)
        for (int x = 0; x < MW; x++)
            bad += !texel_is(env, x, y, (float)(x + 1), (float)(y + 1), 0.5f);
    EXPECT(bad == 0, "%s: %d texels differ from what was written", label, bad);
}

static void test_load_formats(void)
{
    float rgb[MW * MH * 3];
    make_map(rgb);
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    const char *hdr = path_of("map.hdr"), *exr = path_of("map.exr"), *half = path_of("half.exr");
    EXPECT(stbi_write_hdr(hdr, MW, MH, 3, rgb) != 0, "writing %s", hdr);
    EXPECT(environment_load(KEY, hdr, 2.0f, 0.25f, &env, msg) == 0, "%s", msg);
    expect_map(&env, "hdr");
    EXPECT(env.intensity == 2.0f && env.rotation == 0.25f, "intensity %g rotation %g", env.intensity, env.rotation);
    environment_fini(&env);
    EXPECT(env.rgb == NULL && env.width == 0, "fini clears");

    EXPECT(exr_write_rgb(exr, rgb, MW, MH, msg) == 0, "%s", msg);
    EXPECT(environment_load(KEY, exr, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    expect_map(&env, "float exr");
    environment_fini(&env);

    EXPECT(write_half_exr(half, rgb, MW, MH) == 0, "writing %s", half);
    EXPECT(environment_load(KEY, half, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    expect_map(&env, "half exr (alpha ignored)");
    environment_fini(&env);

    /* Content decides, not the name: an EXR called .hdr loads. */
    const char *misnamed = path_of("really-exr.hdr");
    EXPECT(exr_write_rgb(misnamed, rgb, MW, MH, msg) == 0, "%s", msg);
    EXPECT(environment_load(KEY, misnamed, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    expect_map(&env, "misnamed exr");
    environment_fini(&env);

    /* A rotation beyond 2 pi is kept modulo 2 pi. */
    EXPECT(environment_load(KEY, hdr, 1.0f, -0.5f, &env, msg) == 0, "%s", msg);
    EXPECT(fabsf(env.rotation - (float)(2.0 * 3.14159265358979 - 0.5)) < 1e-6f, "rotation -0.5 -> %g", env.rotation);
    environment_fini(&env);
}

/* Texel of a direction and its radiance (intensity 2) equal the expected texel. */
static void expect_dir(const struct environment *env, vec3 d, int x, int y)
{
    int tx, ty;
    environment_texel_of(env, d, &tx, &ty);
    EXPECT(tx == x && ty == y, "direction (%g, %g, %g) reads texel (%d, %d), want (%d, %d)", d.x, d.y, d.z, tx, ty, x,
           y);
    vec3 l = environment_radiance(env, d);
    EXPECT(l.x == 2.0f * (float)(x + 1) && l.y == 2.0f * (float)(y + 1) && l.z == 1.0f,
           "radiance along (%g, %g, %g): %g %g %g", d.x, d.y, d.z, l.x, l.y, l.z);
}

static void test_mapping(void)
{
    float rgb[MW * MH * 3];
    make_map(rgb);
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    EXPECT(environment_load(KEY, path_of("map.hdr"), 2.0f, 0.0f, &env, msg) == 0, "%s", msg);
    if (!env.rgb)
        return;
    /* Texel (1, 1) is centred at theta = 1.5 * 45 = 67.5 deg, phi = 67.5 deg:
     * (sin 67.5 cos 67.5, cos 67.5, sin 67.5 sin 67.5) = (0.353553, 0.382683, 0.853553). */
    expect_dir(&env, v3(0.35355339f, 0.38268343f, 0.85355339f), 1, 1);
    /* Texel (6, 2): theta = 112.5 deg, phi = 292.5 deg: (0.353553, -0.382683, -0.853553). */
    expect_dir(&env, v3(0.35355339f, -0.38268343f, -0.85355339f), 6, 2);
    expect_dir(&env, v3(0, 1, 0), 0, 0);                 /* +y: theta 0, the top row */
    expect_dir(&env, v3(0, -1, 0), 0, MH - 1);           /* -y: the bottom row */
    expect_dir(&env, v3(1, 0.1f, 0.01f), 0, 1);          /* just past phi = 0 (+x): column 0 */
    expect_dir(&env, v3(1, 0.1f, -0.01f), MW - 1, 1);    /* just before it: wraps to the last column */
    expect_dir(&env, v3(-1, -0.5f, 0.001f), 3, 2);       /* phi just below pi: column 3; theta 116.6 deg */
    expect_dir(&env, v3(-1, -0.5f, -0.001f), 4, 2);      /* just above pi: column 4 */
    expect_dir(&env, v3(0.7f, 0.38268343f * 4, 1.7f), 1, 1); /* length does not matter */
    float u, v;
    environment_dir_to_uv(&env, v3(0.35355339f, 0.38268343f, 0.85355339f), &u, &v);
    EXPECT(fabsf(u - 1.5f / MW) < 1e-6f && fabsf(v - 1.5f / MH) < 1e-6f, "uv of texel (1, 1)'s centre: %g %g", u, v);
    vec3 d = environment_uv_to_dir(&env, 1.5f / MW, 1.5f / MH);
    EXPECT(fabsf(d.x - 0.35355339f) < 1e-6f && fabsf(d.y - 0.38268343f) < 1e-6f && fabsf(d.z - 0.85355339f) < 1e-6f,
           "direction of texel (1, 1)'s centre: %g %g %g", d.x, d.y, d.z);
    environment_dir_to_uv(&env, v3(NAN, 0, 1), &u, &v);
    EXPECT(u == 0.0f && v == 0.0f, "a NaN direction reads (0, 0): %g %g", u, v);
    environment_fini(&env);

    /* Rotation pi / 2 turns the map from +x toward +z: texel (1, 1) moves to phi = 157.5 deg,
     * (sin 67.5 cos 157.5, cos 67.5, sin 67.5 sin 157.5) = (-0.853553, 0.382683, 0.353553). */
    EXPECT(environment_load(KEY, path_of("map.hdr"), 2.0f, 1.57079633f, &env, msg) == 0, "%s", msg);
    if (!env.rgb)
        return;
    expect_dir(&env, v3(-0.85355339f, 0.38268343f, 0.35355339f), 1, 1);
    expect_dir(&env, v3(-0.01f, 0.1f, 1), 0, 1);      /* world phi 90.6 deg = image 0.6 deg */
    expect_dir(&env, v3(0.01f, 0.1f, 1), MW - 1, 1);  /* world phi 89.4 deg = image -0.6 deg */
    d = environment_uv_to_dir(&env, 1.5f / MW, 1.5f / MH);
    EXPECT(fabsf(d.x + 0.85355339f) < 1e-6f && fabsf(d.z - 0.35355339f) < 1e-6f, "rotated centre %g %g %g", d.x, d.y,
           d.z);
    environment_fini(&env);
}

static void test_constant(void)
{
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    EXPECT(environment_constant(KEY, v3(0.5f, 1.0f, 0.25f), 4.0f, &env, msg) == 0, "%s", msg);
    vec3 l = environment_radiance(&env, v3(0.2f, -0.9f, 0.1f));
    EXPECT(env.rgb == NULL && l.x == 2.0f && l.y == 4.0f && l.z == 1.0f, "constant radiance %g %g %g", l.x, l.y, l.z);
    environment_fini(&env);
    EXPECT(environment_constant(KEY, v3(0, 0, 0), 1.0f, &env, msg) == 0, "a black constant is allowed: %s", msg);
    EXPECT(environment_constant(KEY, v3(NAN, 1, 1), 1.0f, &env, msg) == -1 && strstr(msg, KEY), "NaN colour: %s",
           msg);
    EXPECT(environment_constant(KEY, v3(1, -0.1f, 1), 1.0f, &env, msg) == -1 && strstr(msg, "non-negative"),
           "negative colour: %s", msg);
    EXPECT(environment_constant(KEY, v3(1, INFINITY, 1), 1.0f, &env, msg) == -1, "infinite colour: %s", msg);
    EXPECT(environment_constant(KEY, v3(1, 1, 1), -1.0f, &env, msg) == -1 && strstr(msg, "intensity"),
           "negative intensity: %s", msg);
    printf("  refused (constant): %s\n", msg);
}

/* An EXR of the test map with texel (5, 2) channel c set to v. */
static const char *exr_with(const char *name, int c, float v)
{
    float rgb[MW * MH * 3];
    make_map(rgb);
    rgb[3 * (2 * MW + 5) + c] = v;
    char msg[RESTIR_MSG_LEN];
    const char *p = path_of(name);
    EXPECT(exr_write_rgb(p, rgb, MW, MH, msg) == 0, "%s", msg);
    return p;
}

/* Refusals decided from the header, before any texel is decoded: sizes past the limits. */
static void test_too_large(void)
{
    const char *wide = path_of("wide.hdr"), *many = path_of("many.hdr"), *wide_exr = path_of("wide.exr");
    const char head_wide[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 16385\n";
    const char head_many[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8193 +X 16384\n";
    write_text(wide, head_wide, sizeof head_wide - 1);
    write_text(many, head_many, sizeof head_many - 1);
    expect_refused(wide, 1.0f, 0.0f, "16385x1", "hdr wider than 16384 (header only)");
    expect_refused(many, 1.0f, 0.0f, "16384x8193", "hdr of more than 2^27 texels (header only)");
    float *row = xcalloc(16385 * 3, sizeof(float));
    row[0] = 1.0f;
    char msg[RESTIR_MSG_LEN];
    EXPECT(exr_write_rgb(wide_exr, row, 16385, 1, msg) == 0, "%s", msg);
    free(row);
    expect_refused(wide_exr, 1.0f, 0.0f, "16385x1", "exr wider than 16384");
}

/* A copy of src without its last `drop` bytes. */
static const char *truncated(const char *src, const char *name, size_t drop)
{
    const char *dst = path_of(name);
    char buf[4096];
    FILE *f = fopen(src, "rb");
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f)
        fclose(f);
    write_text(dst, buf, n > drop ? n - drop : 0);
    return dst;
}

static void test_refusals(void)
{
    float rgb[MW * MH * 3] = {0};
    char msg[RESTIR_MSG_LEN];
    expect_refused(path_of("no-such.hdr"), 1.0f, 0.0f, "cannot open", "missing file");
    const char *text = path_of("notes.hdr");
    const char words[] = "just some text, not an image\n", junk[] = "\x76\x2f\x31\x01garbage after the magic number";
    write_text(text, words, sizeof words - 1);
    expect_refused(text, 1.0f, 0.0f, "not a Radiance HDR", "not an image");
    const char *fake = path_of("fake.exr");
    write_text(fake, junk, sizeof junk - 1);
    expect_refused(fake, 1.0f, 0.0f, "OpenEXR header", "EXR magic then garbage");

    expect_refused(exr_with("nan.exr", 1, NAN), 1.0f, 0.0f, "texel x=5 y=2", "NaN texel");
    expect_refused(exr_with("inf.exr", 0, INFINITY), 1.0f, 0.0f, "infinite", "infinite texel");
    expect_refused(exr_with("neg.exr", 2, -0.5f), 1.0f, 0.0f, "texel x=5 y=2 (column, row from the top) has a negative",
                   "negative texel");

    const char *zero_hdr = path_of("zero.hdr"), *zero_exr = path_of("zero.exr");
    EXPECT(stbi_write_hdr(zero_hdr, MW, MH, 3, rgb) != 0, "writing %s", zero_hdr);
    EXPECT(exr_write_rgb(zero_exr, rgb, MW, MH, msg) == 0, "%s", msg);
    expect_refused(zero_hdr, 1.0f, 0.0f, "every texel is zero", "all-zero hdr");
    expect_refused(zero_exr, 1.0f, 0.0f, "every texel is zero", "all-zero exr");

    /* An EXR whose only channels are a layer's (other.R, ...): no plain R, G, B. */
    make_map(rgb);
    const char *layer = path_of("layer.exr");
    struct exr_layer only = {"other", rgb};
    EXPECT(exr_write_layers(layer, &only, 1, MW, MH, msg) == 0, "%s", msg);
    expect_refused(layer, 1.0f, 0.0f, "no 'R' channel", "no RGB channels");
    expect_refused(truncated(path_of("map.exr"), "cut.exr", 16), 1.0f, 0.0f, "OpenEXR", "truncated exr");

    expect_refused(path_of("map.hdr"), NAN, 0.0f, "intensity", "NaN intensity");
    expect_refused(path_of("map.hdr"), -2.0f, 0.0f, "intensity", "negative intensity");
    expect_refused(path_of("map.hdr"), 1.0f, INFINITY, "rotation", "infinite rotation");

    struct environment env;
    EXPECT(environment_load(NULL, path_of("no-such.exr"), 1.0f, 0.0f, &env, msg) == -1 &&
               strstr(msg, "environment ") == msg,
           "key NULL reads 'environment': %s", msg);
    /* The first bad texel in row order is named: (7, 0) before (2, 1). */
    rgb[3 * (1 * MW + 2) + 0] = -1.0f;
    rgb[3 * (0 * MW + 7) + 1] = NAN;
    EXPECT(environment_from_rgb(KEY, "generated", rgb, MW, MH, 1.0f, 0.0f, &env, msg) == -1 &&
               strstr(msg, "generated") && strstr(msg, "x=7 y=0") && strstr(msg, "NaN"),
           "in-memory bad texels: %s", msg);
}

/* Damaged Radiance files: stb_image 2.27 never returns on run-length data that ends early or has
 * a zero-length run (CVE-2021-42715), so environment_load must refuse these before stb sees them
 * (main's alarm turns a hang into a failure). A flat file (width below 8) loads, and cut short is
 * refused rather than read as black. */
static void test_damaged_hdr(void)
{
    enum { RW = 16, RH = 4 };
    float rgb[RW * RH * 3];
    for (int i = 0; i < RW * RH * 3; i++)
        rgb[i] = (float)(i % 7) + 0.5f;
    const char *rle = path_of("rle.hdr"), *flat = path_of("flat.hdr");
    EXPECT(stbi_write_hdr(rle, RW, RH, 3, rgb) != 0, "writing %s", rle);
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    EXPECT(environment_load(KEY, rle, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    EXPECT(env.rgb && texel_is(&env, 3, 2, rgb[3 * 35], rgb[3 * 35 + 1], rgb[3 * 35 + 2]), "run-length texel (3, 2)");
    environment_fini(&env);
    expect_refused(truncated(rle, "rle-cut.hdr", 10), 1.0f, 0.0f, "stops early, in scanline 3 of 4", "truncated hdr");
    expect_refused(truncated(rle, "rle-cut2.hdr", 150), 1.0f, 0.0f, "stops early", "hdr cut in the middle");

    /* The first scanline's first run count (after the 4-byte marker) set to 0. */
    FILE *f = fopen(rle, "rb");
    unsigned char buf[4096];
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f)
        fclose(f);
    size_t data = 0;
    for (size_t i = 0; i + 1 < n && !data; i++)
        if (buf[i] == '\n' && buf[i + 1] == '\n')
            data = (size_t)((unsigned char *)memchr(buf + i + 2, '\n', n - i - 2) - buf) + 1;
    EXPECT(data > 0 && data + 4 < n && buf[data] == 2 && buf[data + 1] == 2, "run-length marker at %zu", data);
    buf[data + 4] = 0;
    const char *zero_run = path_of("zero-run.hdr");
    write_text(zero_run, (const char *)buf, n);
    expect_refused(zero_run, 1.0f, 0.0f, "corrupt run-length data in scanline 0", "zero-length run");

    EXPECT(stbi_write_hdr(flat, 4, 2, 3, rgb) != 0, "writing %s", flat);
    EXPECT(environment_load(KEY, flat, 1.0f, 0.0f, &env, msg) == 0, "flat hdr: %s", msg);
    EXPECT(env.width == 4 && env.height == 2 && texel_is(&env, 1, 1, rgb[15], rgb[16], rgb[17]), "flat texel (1, 1)");
    environment_fini(&env);
    expect_refused(truncated(flat, "flat-cut.hdr", 4), 1.0f, 0.0f, "stops early, in scanline 1 of 2",
                   "truncated flat hdr");
}

/* Removes the files the test wrote and the directory. */
static void cleanup(void)
{
    static const char *const names[] = {"map.hdr", "map.exr", "half.exr", "really-exr.hdr", "wide.hdr", "many.hdr",
                                        "wide.exr", "notes.hdr", "fake.exr", "nan.exr", "inf.exr",
                                        "neg.exr", "zero.hdr", "zero.exr", "layer.exr", "cut.exr", "rle.hdr",
                                        "flat.hdr", "rle-cut.hdr", "rle-cut2.hdr", "zero-run.hdr", "flat-cut.hdr"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        remove(path_of(names[i]));
    rmdir(dir);
}

int main(void)
{
    alarm(120); /* a decoder that never returns fails the test instead of holding ctest for 15 min */
    snprintf(dir, sizeof dir, "/tmp/restir-env-XXXXXX");
    if (!mkdtemp(dir)) {
        EXPECT(0, "mkdtemp failed");
        return test_finish();
    }
    test_load_formats();
    test_mapping();
    test_constant();
    test_too_large();
    test_refusals();
    test_damaged_hdr();
    cleanup();
    return test_finish();
}
