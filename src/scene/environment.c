/* environment.c: environment maps: Radiance .hdr decoding (stb_image), OpenEXR scanline decoding (the
 * OpenEXR Core C API, read here directly), texel validation, and the equirectangular mapping.
 * Must never depend on shading or render code, nor abort on bad input. */
#include "scene/environment.h"

#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <stb/stb_image.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

#define ENV_PI 3.14159265358979323846
#define ENV_TWO_PI 6.28318530717958647692
/* OpenEXR's own header limit: beyond it the library refuses before we see the size; below it our
 * ENVIRONMENT_MAX_SIDE check gives the clearer message. */
#define ENV_EXR_HEADER_MAX_SIDE 65536

static const unsigned char env_exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};

/* Formats "key name: what" into msg (RESTIR_MSG_LEN bytes). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void env_fail(char *msg, const char *key, const char *name, const char *fmt, ...)
{
    if (!msg)
        return;
    int n = snprintf(msg, RESTIR_MSG_LEN, "%s %.300s: ", key ? key : "environment", name ? name : "(unnamed)");
    if (n < 0 || n >= RESTIR_MSG_LEN)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + n, (size_t)(RESTIR_MSG_LEN - n), fmt, ap);
    va_end(ap);
}

/* ---- validation ------------------------------------------------------------------------------ */

static int check_size(long w, long h, const char *key, const char *name, char *msg)
{
    if (w < 1 || h < 1 || w > ENVIRONMENT_MAX_SIDE || h > ENVIRONMENT_MAX_SIDE || w * h > ENVIRONMENT_MAX_TEXELS) {
        env_fail(msg, key, name, "the image is %ldx%ld; environment maps may be 1 to %d texels per side and %ld "
                 "texels in all (16384 x 8192)", w, h, ENVIRONMENT_MAX_SIDE, ENVIRONMENT_MAX_TEXELS);
        return -1;
    }
    return 0;
}

static int check_scale(float intensity, float rotation, const char *key, const char *name, char *msg)
{
    if (!isfinite(intensity) || intensity < 0.0f) {
        env_fail(msg, key, name, "intensity %g must be finite and non-negative", (double)intensity);
        return -1;
    }
    if (!isfinite(rotation)) {
        env_fail(msg, key, name, "rotation %g (radians) must be finite", (double)rotation);
        return -1;
    }
    return 0;
}

static const char *bad_value_kind(const float *p)
{
    for (int c = 0; c < 3; c++)
        if (isnan(p[c]))
            return "a NaN";
    for (int c = 0; c < 3; c++)
        if (isinf(p[c]))
            return "an infinite";
    return "a negative";
}

/* Every texel finite and non-negative, and at least one above zero. The first bad texel (in row
 * order from the top-left) is named with its column x and row y. */
static int check_texels(const float *rgb, int w, int h, const char *key, const char *name, char *msg)
{
    int any = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)x);
            for (int c = 0; c < 3; c++) {
                if (!isfinite(p[c]) || p[c] < 0.0f) {
                    env_fail(msg, key, name, "texel x=%d y=%d (column, row from the top) has %s value "
                             "(R %g G %g B %g); radiance must be finite and non-negative", x, y, bad_value_kind(p),
                             (double)p[0], (double)p[1], (double)p[2]);
                    return -1;
                }
                any |= p[c] > 0.0f;
            }
        }
    if (!any) {
        env_fail(msg, key, name, "every texel is zero: this environment would emit no light");
        return -1;
    }
    return 0;
}

/* Stores the validated parameters; rotation is reduced to [0, 2 pi) so lookups keep full precision. */
static void set_scale(struct environment *env, float intensity, float rotation)
{
    double r = fmod((double)rotation, ENV_TWO_PI);
    env->intensity = intensity;
    env->rotation = (float)(r < 0.0 ? r + ENV_TWO_PI : r);
    if (env->rotation >= (float)ENV_TWO_PI)
        env->rotation = 0.0f;
}

/* ---- Radiance .hdr through stb_image ------------------------------------------------------- */

/* stb_image up to 2.27 (the system libstb is 2.27) loops forever on run-length data that ends early
 * or holds a zero-length run (CVE-2021-42715), and reads a flat file that ends early as black. So
 * the file is read into memory and its scanlines walked here first, the way stb's decoder reads
 * them, and only a complete file is handed to stb. */

static const char *stb_reason(void)
{
    const char *why = stbi_failure_reason();
    return why ? why : "unknown reason";
}

/* Reads all of path into a new buffer of *n bytes; NULL with msg when unreadable or over limit. */
static unsigned char *read_file(const char *key, const char *path, size_t limit, size_t *n, char *msg)
{
    FILE *f = fopen(path, "rb");
    long size = -1;
    if (f && fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    unsigned char *buf = NULL;
    if (f && size >= 0 && (size_t)size <= limit && fseek(f, 0, SEEK_SET) == 0) {
        buf = malloc((size_t)size + 1);
        if (buf && fread(buf, 1, (size_t)size, f) != (size_t)size) {
            free(buf);
            buf = NULL;
        }
    }
    if (f)
        fclose(f);
    if (!buf && size >= 0 && (size_t)size > limit)
        env_fail(msg, key, path, "the file (%ld bytes) is larger than its header's image size allows", size);
    else if (!buf)
        env_fail(msg, key, path, "cannot read the file: %s", strerror(errno));
    *n = (size_t)(size > 0 ? size : 0);
    return buf;
}

/* Offset of the first pixel byte: past the blank line that ends the header and the resolution
 * line after it (stbi_info has accepted both); 0 when there is none. */
static size_t hdr_data_start(const unsigned char *p, size_t n)
{
    for (size_t i = 0; i + 1 < n; i++)
        if (p[i] == '\n' && p[i + 1] == '\n') {
            const unsigned char *nl = memchr(p + i + 2, '\n', n - i - 2);
            return nl ? (size_t)(nl - p) + 1 : 0;
        }
    return 0;
}

/* One run-length encoded scanline at p[*pos]: the marker 2, 2, width (big-endian, below 32768),
 * then the four RGBE components, each as runs (a byte c > 128, then one value for c - 128 texels)
 * and dumps (a byte c in 1 ... 128, then c values) that fill exactly w texels. Returns 0, 1 when
 * the data stops early, 2 when it is malformed (stb would misread it or never finish). */
static int hdr_rle_row(const unsigned char *p, size_t n, size_t *pos, int w)
{
    size_t at = *pos;
    if (n - at < 4)
        return 1;
    if (p[at] != 2 || p[at + 1] != 2 || (p[at + 2] & 0x80) || (p[at + 2] << 8 | p[at + 3]) != w)
        return 2; /* stb would restart flat decoding at the top row */
    at += 4;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < w;) {
            if (at >= n)
                return 1;
            int count = p[at++];
            int run = count > 128;
            count -= run ? 128 : 0;
            if (count == 0 || count > w - i)
                return 2;
            size_t bytes = run ? 1u : (size_t)count;
            if (n - at < bytes)
                return 1;
            at += bytes;
            i += count;
        }
    *pos = at;
    return 0;
}

/* Checks the pixel data of a w x h file as stb reads it: flat RGBE (4 bytes a texel) for widths
 * outside 8 ... 32767 or when the first scanline is not run-length encoded, else every scanline
 * run-length encoded. Returns 0, or -1 with msg naming the first scanline that is cut or broken. */
static int hdr_check_data(const unsigned char *p, size_t n, int w, int h, const char *key, const char *path, char *msg)
{
    size_t pos = hdr_data_start(p, n);
    if (pos == 0) {
        env_fail(msg, key, path, "cannot find the end of the Radiance HDR header");
        return -1;
    }
    const int rle = w >= 8 && w < 32768 && n - pos >= 3 && p[pos] == 2 && p[pos + 1] == 2 && !(p[pos + 2] & 0x80);
    if (!rle) {
        size_t have = (n - pos) / 4, need = (size_t)w * (size_t)h;
        if (have >= need)
            return 0;
        env_fail(msg, key, path, "the pixel data stops early, in scanline %zu of %d (the file is truncated)",
                 have / (size_t)w, h);
        return -1;
    }
    for (int y = 0; y < h; y++) {
        int bad = hdr_rle_row(p, n, &pos, w);
        if (bad) {
            env_fail(msg, key, path,
                     bad == 1 ? "the pixel data stops early, in scanline %d of %d (the file is truncated)"
                              : "corrupt run-length data in scanline %d of %d",
                     y, h);
            return -1;
        }
    }
    return 0;
}

static int load_hdr(const char *key, const char *path, float **rgb, int *w, int *h, char *msg)
{
    int n = 0;
    if (!stbi_info(path, w, h, &n)) {
        env_fail(msg, key, path, "cannot read the Radiance HDR header: %s", stb_reason());
        return -1;
    }
    if (check_size(*w, *h, key, path, msg) != 0)
        return -1;
    /* Room for the worst-case run-length coding (129 bytes per 128) and a generous header. */
    size_t len = 0, limit = 5 * (size_t)*w * (size_t)*h + ((size_t)1 << 20);
    unsigned char *buf = read_file(key, path, limit, &len, msg);
    if (!buf)
        return -1;
    int status = hdr_check_data(buf, len, *w, *h, key, path, msg);
    /* Three channels asked for: stb returns w * h * 3 floats, allocated with malloc (the library's
     * default allocator, which the system libstb keeps), so environment_fini may free() them. */
    *rgb = status == 0 ? stbi_loadf_from_memory(buf, (int)len, w, h, &n, 3) : NULL;
    free(buf);
    if (status == 0 && !*rgb) {
        env_fail(msg, key, path, "cannot decode the Radiance HDR image: %s", stb_reason());
        status = -1;
    }
    return status;
}

/* ---- OpenEXR through the Core C API ---------------------------------------------------------- */

/* The library reports details through a callback; the last one is kept per thread for msg. */
static _Thread_local char env_exr_detail[256];

static void env_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *text)
{
    (void)ctxt;
    snprintf(env_exr_detail, sizeof env_exr_detail, "%.200s (%s)", text ? text : "",
             exr_get_error_code_as_string(code));
}

static void env_exr_fail(char *msg, const char *key, const char *path, const char *what, exr_result_t rv)
{
    env_fail(msg, key, path, "%s: %s", what, env_exr_detail[0] ? env_exr_detail : exr_get_default_error_message(rv));
}

/* Index of the channel called name, or -1. */
static int env_exr_channel(const exr_attr_chlist_t *chl, const char *name)
{
    for (int i = 0; i < chl->num_channels; i++)
        if (strcmp(chl->entries[i].name.str, name) == 0)
            return i;
    return -1;
}

/* The header's verdict: a scanline part 0 of acceptable size with full-resolution R, G, B. */
static int env_exr_check_header(exr_context_t ctxt, const char *key, const char *path, exr_attr_box2i_t *dw, char *msg)
{
    exr_storage_t storage;
    exr_result_t rv = exr_get_storage(ctxt, 0, &storage);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(ctxt, 0, dw);
    const exr_attr_chlist_t *chl = NULL;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_channels(ctxt, 0, &chl);
    if (rv != EXR_ERR_SUCCESS || !chl) {
        env_exr_fail(msg, key, path, "cannot read the OpenEXR header", rv);
        return -1;
    }
    if (storage != EXR_STORAGE_SCANLINE) {
        env_fail(msg, key, path, "this OpenEXR image is %s; only scanline images are supported",
                 storage == EXR_STORAGE_TILED ? "tiled" : "deep");
        return -1;
    }
    if (check_size((long)dw->max.x - dw->min.x + 1, (long)dw->max.y - dw->min.y + 1, key, path, msg) != 0)
        return -1;
    static const char *const names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; c++) {
        int i = env_exr_channel(chl, names[c]);
        if (i < 0) {
            env_fail(msg, key, path, "the OpenEXR image has no '%s' channel (R, G and B are required)", names[c]);
            return -1;
        }
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        if ((e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) || e->x_sampling != 1 ||
            e->y_sampling != 1) {
            env_fail(msg, key, path, "OpenEXR channel '%s' must be half or float, not subsampled", names[c]);
            return -1;
        }
    }
    return 0;
}

/* Points the decoder's R, G, B at image row `row` of out (interleaved floats); other channels
 * (alpha, layers) are skipped. The library converts half to float. */
static void env_exr_bind(exr_decode_pipeline_t *dec, float *out, int w, int row)
{
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        const char *n = ch->channel_name;
        int k = strcmp(n, "R") == 0 ? 0 : strcmp(n, "G") == 0 ? 1 : strcmp(n, "B") == 0 ? 2 : -1;
        if (k < 0) {
            ch->decode_to_ptr = NULL;
            continue;
        }
        ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
        ch->user_line_stride = 3 * (int32_t)sizeof(float) * w;
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
        ch->decode_to_ptr = (uint8_t *)(out + ((size_t)row * (size_t)w * 3 + (size_t)k));
    }
}

/* Decodes one chunk (a block of scanlines starting at file line y) into out. */
static exr_result_t env_exr_chunk(exr_context_t ctxt, exr_decode_pipeline_t *dec, int *have_dec, exr_attr_box2i_t dw,
                              int y, float *out)
{
    exr_chunk_info_t cinfo;
    exr_result_t rv = exr_read_scanline_chunk_info(ctxt, 0, y, &cinfo);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    if (!*have_dec) {
        rv = exr_decoding_initialize(ctxt, 0, &cinfo, dec);
        *have_dec = rv == EXR_ERR_SUCCESS;
    } else {
        rv = exr_decoding_update(ctxt, 0, &cinfo, dec);
    }
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    const int row = cinfo.start_y - dw.min.y;
    if (row < 0 || row + cinfo.height > h || cinfo.width != w)
        return EXR_ERR_CORRUPT_CHUNK;
    env_exr_bind(dec, out, w, row);
    rv = exr_decoding_choose_default_routines(ctxt, 0, dec);
    return rv == EXR_ERR_SUCCESS ? exr_decoding_run(ctxt, 0, dec) : rv;
}

static int env_exr_decode(exr_context_t ctxt, const char *key, const char *path, exr_attr_box2i_t dw, float *out,
                      char *msg)
{
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    if (rv != EXR_ERR_SUCCESS || lines <= 0) {
        env_exr_fail(msg, key, path, "cannot read the OpenEXR chunk layout", rv);
        return -1;
    }
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int have_dec = 0, status = 0;
    for (int64_t y = dw.min.y; y <= dw.max.y && status == 0; y += lines) {
        rv = env_exr_chunk(ctxt, &dec, &have_dec, dw, (int)y, out);
        if (rv != EXR_ERR_SUCCESS) {
            char what[96];
            snprintf(what, sizeof what, "cannot decode the OpenEXR scanlines at y=%lld (truncated or corrupt?)",
                     (long long)y);
            env_exr_fail(msg, key, path, what, rv);
            status = -1;
        }
    }
    if (have_dec)
        exr_decoding_destroy(ctxt, &dec);
    return status;
}

static int load_exr(const char *key, const char *path, float **rgb, int *w, int *h, char *msg)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = env_exr_error;
    init.max_image_width = ENV_EXR_HEADER_MAX_SIDE;
    init.max_image_height = ENV_EXR_HEADER_MAX_SIDE;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    env_exr_detail[0] = '\0';
    exr_context_t ctxt = NULL;
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    int status = 0;
    exr_attr_box2i_t dw;
    memset(&dw, 0, sizeof dw);
    if (rv != EXR_ERR_SUCCESS) {
        env_exr_fail(msg, key, path, "cannot read the OpenEXR header", rv);
        status = -1;
    } else {
        status = env_exr_check_header(ctxt, key, path, &dw, msg);
    }
    if (status == 0) {
        *w = dw.max.x - dw.min.x + 1;
        *h = dw.max.y - dw.min.y + 1;
        *rgb = malloc(sizeof(float) * 3 * (size_t)*w * (size_t)*h);
        if (!*rgb)
            env_fail(msg, key, path, "out of memory for a %dx%d image", *w, *h);
        status = *rgb ? env_exr_decode(ctxt, key, path, dw, *rgb, msg) : -1;
    }
    if (ctxt)
        exr_finish(&ctxt);
    if (status != 0) {
        free(*rgb);
        *rgb = NULL;
    }
    return status;
}

/* ---- loading --------------------------------------------------------------------------------- */

/* Opens path to tell the formats apart by content: 1 = OpenEXR, 0 = Radiance HDR, -1 = neither
 * (msg says why: unreadable file, or another kind of file). */
static int sniff(const char *key, const char *path, char *msg)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        env_fail(msg, key, path, "cannot open: %s", strerror(errno));
        return -1;
    }
    unsigned char head[4] = {0, 0, 0, 0};
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    if (got == sizeof head && memcmp(head, env_exr_magic, sizeof head) == 0)
        return 1;
    if (stbi_is_hdr(path))
        return 0;
    env_fail(msg, key, path, "cannot decode: not a Radiance HDR (.hdr) or OpenEXR (.exr) image");
    return -1;
}

int environment_load(const char *key, const char *path, float intensity, float rotation, struct environment *env,
                     char *msg)
{
    memset(env, 0, sizeof *env);
    if (!path || !path[0]) {
        env_fail(msg, key, "(no path)", "no image file given");
        return -1;
    }
    if (check_scale(intensity, rotation, key, path, msg) != 0)
        return -1;
    int kind = sniff(key, path, msg);
    if (kind < 0)
        return -1;
    float *rgb = NULL;
    int w = 0, h = 0;
    int status = kind == 1 ? load_exr(key, path, &rgb, &w, &h, msg) : load_hdr(key, path, &rgb, &w, &h, msg);
    if (status == 0)
        status = check_texels(rgb, w, h, key, path, msg);
    if (status != 0) {
        free(rgb);
        return -1;
    }
    env->width = w;
    env->height = h;
    env->rgb = rgb;
    set_scale(env, intensity, rotation);
    return 0;
}

int environment_from_rgb(const char *key, const char *name, const float *rgb, int width, int height, float intensity,
                         float rotation, struct environment *env, char *msg)
{
    memset(env, 0, sizeof *env);
    if (!rgb) {
        env_fail(msg, key, name, "no texels given");
        return -1;
    }
    if (check_scale(intensity, rotation, key, name, msg) != 0 || check_size(width, height, key, name, msg) != 0 ||
        check_texels(rgb, width, height, key, name, msg) != 0)
        return -1;
    size_t bytes = sizeof(float) * 3 * (size_t)width * (size_t)height;
    env->rgb = malloc(bytes);
    if (!env->rgb) {
        env_fail(msg, key, name, "out of memory for a %dx%d image", width, height);
        return -1;
    }
    memcpy(env->rgb, rgb, bytes);
    env->width = width;
    env->height = height;
    set_scale(env, intensity, rotation);
    return 0;
}

int environment_constant(const char *key, vec3 c, float intensity, struct environment *env, char *msg)
{
    memset(env, 0, sizeof *env);
    if (!v3_is_finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
        env_fail(msg, key, "colour", "(%g, %g, %g) must be finite and non-negative", (double)c.x, (double)c.y,
                 (double)c.z);
        return -1;
    }
    if (check_scale(intensity, 0.0f, key, "colour", msg) != 0)
        return -1;
    env->constant = c;
    set_scale(env, intensity, 0.0f);
    return 0;
}

void environment_fini(struct environment *env)
{
    free(env->rgb);
    memset(env, 0, sizeof *env);
}

/* ---- mapping --------------------------------------------------------------------------------- */

void environment_dir_to_uv(const struct environment *env, vec3 dir, float *u, float *v)
{
    /* atan2 of (sin, cos) rather than acos(y): accurate near the poles, and no unit length needed */
    float theta = atan2f(sqrtf(dir.x * dir.x + dir.z * dir.z), dir.y);
    float uu = (atan2f(dir.z, dir.x) - env->rotation) * (float)(1.0 / ENV_TWO_PI);
    uu -= floorf(uu);
    float vv = theta * (float)(1.0 / ENV_PI);
    *u = uu >= 0.0f && uu < 1.0f ? uu : 0.0f; /* a phi just below 0 may round to u = 1, which is 0 */
    *v = vv >= 0.0f ? (vv <= 1.0f ? vv : 1.0f) : 0.0f; /* NaN reads 0 */
}

vec3 environment_uv_to_dir(const struct environment *env, float u, float v)
{
    float phi = u * (float)ENV_TWO_PI + env->rotation, theta = v * (float)ENV_PI;
    float st = sinf(theta);
    return v3(st * cosf(phi), cosf(theta), st * sinf(phi));
}

void environment_texel_of(const struct environment *env, vec3 dir, int *x, int *y)
{
    if (!env->rgb) {
        *x = *y = 0;
        return;
    }
    float u, v;
    environment_dir_to_uv(env, dir, &u, &v);
    int ix = (int)(u * (float)env->width), iy = (int)(v * (float)env->height);
    *x = ix < env->width ? ix : env->width - 1;
    *y = iy < env->height ? iy : env->height - 1;
}

vec3 environment_texel(const struct environment *env, int x, int y)
{
    if (!env->rgb)
        return env->constant;
    const float *p = env->rgb + 3 * ((size_t)y * (size_t)env->width + (size_t)x);
    return v3(p[0], p[1], p[2]);
}

vec3 environment_radiance(const struct environment *env, vec3 dir)
{
    int x, y;
    environment_texel_of(env, dir, &x, &y);
    return v3_scale(environment_texel(env, x, y), env->intensity);
}

void environment_default_sky(struct environment *env)
{
    enum { W = 64, H = 32 };
    static float rgb[H][W][3];
    const float zenith[3] = {0.35f, 0.55f, 0.95f}, horizon[3] = {0.9f, 0.93f, 1.0f}, ground[3] = {0.3f, 0.28f, 0.25f};
    for (int y = 0; y < H; y++) {
        const float t = ((float)y + 0.5f) / (H / 2); /* 0 at the zenith, 1 at the horizon */
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                rgb[y][x][c] = y < H / 2 ? zenith[c] + (horizon[c] - zenith[c]) * t * t : ground[c];
    }
    char msg[RESTIR_MSG_LEN];
    const int rc = environment_from_rgb("default sky", "built in", &rgb[0][0][0], W, H, 1.0f, 0.0f, env, msg);
    RESTIR_CHECK(rc == 0);
}
