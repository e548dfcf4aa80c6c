/* exr.c: OpenEXR reading and writing of interleaved RGB float images through the OpenEXR Core C API.
 * Must never depend on scenes, render code or anything that aborts on bad input. */
#include "io/exr.h"

#include <errno.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "io/io_msg.h"

/* Largest image side and pixel count we accept; anything beyond is a broken or hostile header. */
#define EXR_MAX_SIDE 65536
#define EXR_MAX_PIXELS ((int64_t)1 << 27)
#define EXR_PATH_MAX 4096

/* The library reports details through a callback; keep the last one for our own message. Its
 * user_data slot belongs to the default file stream, so a thread-local buffer is used instead. */
static _Thread_local char exr_last_error[256];

static void exr_error_capture(exr_const_context_t ctxt, exr_result_t code, const char *text)
{
    (void)ctxt;
    snprintf(exr_last_error, sizeof exr_last_error, "%s (%s)", text ? text : "",
             exr_get_error_code_as_string(code));
}

static exr_context_initializer_t exr_initializer(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_capture;
    init.max_image_width = EXR_MAX_SIDE;
    init.max_image_height = EXR_MAX_SIDE;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    return init;
}

/* Fills msg with "path: what: library detail". */
static void exr_fail(char *msg, const char *path, const char *what, exr_result_t rv)
{
    if (!msg)
        return;
    if (exr_last_error[0])
        io_msg(msg, "%s: %s: %s", path, what, exr_last_error);
    else
        io_msg(msg, "%s: %s: %s", path, what, exr_get_default_error_message(rv));
}

/* Longest layer name we accept and most layers per file; both far beyond any real use. The name
 * limit keeps "name.R" within the library's long-name limit (255 bytes). */
#define EXR_LAYER_NAME_MAX 200
#define EXR_MAX_LAYERS 256

/* The channel name of component c (0 = R, 1 = G, 2 = B) of a layer: "R" for the default
 * layer (NULL or ""), otherwise "layer.R". out holds EXR_LAYER_NAME_MAX + 3 bytes. */
static void exr_channel_name(char *out, size_t n, const char *layer, int c)
{
    static const char comp[3] = {'R', 'G', 'B'};
    if (!layer || !layer[0])
        snprintf(out, n, "%c", comp[c]);
    else
        snprintf(out, n, "%s.%c", layer, comp[c]);
}

static int exr_is_default_layer(const char *name)
{
    return !name || !name[0];
}

/* Checks the layer list before anything touches the disk: sources present, at most one default
 * layer, names without '.' (which would make a nested or empty layer), not too long, unique. */
static int exr_check_layers(const char *path, const struct exr_layer *layers, int n, char *msg)
{
    if (!layers || n < 1 || n > EXR_MAX_LAYERS) {
        io_msg(msg, "%s: cannot write EXR with %d layers (1 to %d allowed)", path, n,
               EXR_MAX_LAYERS);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        const char *name = layers[i].name;
        const char *shown = exr_is_default_layer(name) ? "(default)" : name;
        if (!layers[i].rgb) {
            io_msg(msg, "%s: EXR layer '%.200s' has no pixels", path, shown);
            return -1;
        }
        if (!exr_is_default_layer(name)) {
            size_t len = strlen(name);
            if (len > EXR_LAYER_NAME_MAX) {
                io_msg(msg, "%s: EXR layer name '%.40s...' is longer than %d bytes", path, name,
                       EXR_LAYER_NAME_MAX);
                return -1;
            }
            if (strchr(name, '.')) {
                io_msg(msg, "%s: EXR layer name '%s' contains '.' (layer names must be plain "
                            "words such as \"primal\" or \"dx\")",
                       path, name);
                return -1;
            }
        }
        for (int j = 0; j < i; j++) {
            const char *other = layers[j].name;
            int same = exr_is_default_layer(name) ? exr_is_default_layer(other)
                                                  : !exr_is_default_layer(other) &&
                                                        strcmp(name, other) == 0;
            if (same) {
                io_msg(msg, "%s: EXR layer '%.200s' is given twice (layers %d and %d)", path,
                       shown, j, i);
                return -1;
            }
        }
    }
    return 0;
}

/* Points the encoder's channels at the interleaved source rows of this chunk: channel
 * "layer.C" (or "C" for the default layer) reads component C of that layer's buffer. */
static int exr_bind_encode(exr_encode_pipeline_t *enc, const struct exr_layer *layers, int n,
                           int w, int start_y)
{
    char name[EXR_LAYER_NAME_MAX + 3];
    for (int c = 0; c < enc->channel_count; c++) {
        exr_coding_channel_info_t *ch = &enc->channels[c];
        const float *src = NULL;
        for (int l = 0; l < n && !src; l++)
            for (int k = 0; k < 3 && !src; k++) {
                exr_channel_name(name, sizeof name, layers[l].name, k);
                if (strcmp(ch->channel_name, name) == 0)
                    src = layers[l].rgb + ((size_t)start_y * (size_t)w * 3 + (size_t)k);
            }
        if (!src)
            return -1;
        ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
        ch->user_line_stride = 3 * (int32_t)sizeof(float) * w;
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
        ch->encode_from_ptr = (const uint8_t *)src;
    }
    return 0;
}

/* Header attributes we write: names and values must be plain, bounded text. */
#define EXR_ATTR_NAME_MAX 200
#define EXR_ATTR_VALUE_MAX 65536
#define EXR_MAX_ATTRS 64

static int exr_check_attributes(const char *path, const struct exr_attribute *attrs, int n, char *msg)
{
    if (n < 0 || n > EXR_MAX_ATTRS || (n > 0 && !attrs)) {
        io_msg(msg, "%s: cannot write EXR with %d header attributes (0 to %d allowed)", path, n, EXR_MAX_ATTRS);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        const char *name = attrs[i].name, *value = attrs[i].value;
        if (!name || !name[0] || strlen(name) > EXR_ATTR_NAME_MAX || !strchr(name, '.')) {
            io_msg(msg, "%s: EXR attribute name '%.60s' must be 1 to %d bytes with a '.' (a namespace such as "
                        "\"restir.samples\", so it never collides with the standard attributes)",
                   path, name ? name : "(null)", EXR_ATTR_NAME_MAX);
            return -1;
        }
        if (!value || strlen(value) > EXR_ATTR_VALUE_MAX) {
            io_msg(msg, "%s: EXR attribute '%s' has no value or one longer than %d bytes", path, name,
                   EXR_ATTR_VALUE_MAX);
            return -1;
        }
        for (int j = 0; j < i; j++)
            if (strcmp(attrs[j].name, name) == 0) {
                io_msg(msg, "%s: EXR attribute '%s' is given twice", path, name);
                return -1;
            }
    }
    return 0;
}

static int exr_write_body(exr_context_t ctxt, const char *path, const struct exr_layer *layers,
                          int n, const struct exr_attribute *attrs, int n_attrs, int w, int h, char *msg)
{
    int part = 0;
    exr_result_t rv = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, w, h, EXR_COMPRESSION_RLE); /* exr.h */
    /* Names past 31 bytes need the file's long-name flag (OpenEXR 1.7+ readers); set it only
     * then, so files with short names stay readable everywhere. */
    int long_names = 0;
    for (int l = 0; l < n; l++)
        long_names |= !exr_is_default_layer(layers[l].name) && strlen(layers[l].name) + 2 > 31;
    if (rv == EXR_ERR_SUCCESS && long_names)
        rv = exr_set_longname_support(ctxt, 1);
    for (int i = 0; i < n_attrs && rv == EXR_ERR_SUCCESS; i++)
        rv = exr_attr_set_string(ctxt, part, attrs[i].name, attrs[i].value);
    /* Channel order in the file is alphabetical; the library sorts the list itself. */
    char name[EXR_LAYER_NAME_MAX + 3];
    for (int l = 0; l < n && rv == EXR_ERR_SUCCESS; l++)
        for (int k = 2; k >= 0 && rv == EXR_ERR_SUCCESS; k--) {
            exr_channel_name(name, sizeof name, layers[l].name, k);
            rv = exr_add_channel(ctxt, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC,
                                 1, 1);
        }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "cannot write EXR header", rv);
        return -1;
    }

    int32_t lines = 0;
    rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    if (rv != EXR_ERR_SUCCESS || lines <= 0) {
        exr_fail(msg, path, "cannot query EXR chunk layout", rv);
        return -1;
    }

    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int have_enc = 0;
    int status = 0;
    for (int y = 0; y < h && status == 0; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS) {
            if (!have_enc) {
                rv = exr_encoding_initialize(ctxt, part, &cinfo, &enc);
                have_enc = rv == EXR_ERR_SUCCESS;
            } else {
                rv = exr_encoding_update(ctxt, part, &cinfo, &enc);
            }
        }
        if (rv == EXR_ERR_SUCCESS && exr_bind_encode(&enc, layers, n, w, cinfo.start_y) != 0) {
            io_msg(msg, "%s: unexpected channel in EXR encoder", path);
            status = -1;
            break;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &enc);
        if (rv != EXR_ERR_SUCCESS) {
            exr_fail(msg, path, "cannot encode EXR scanlines", rv);
            status = -1;
        }
    }
    if (have_enc)
        exr_encoding_destroy(ctxt, &enc);
    return status;
}

int exr_write_layers(const char *path, const struct exr_layer *layers, int n, int w, int h,
                     char *msg)
{
    return exr_write_layers_attrs(path, layers, n, NULL, 0, w, h, msg);
}

int exr_write_layers_attrs(const char *path, const struct exr_layer *layers, int n,
                           const struct exr_attribute *attrs, int n_attrs, int w, int h, char *msg)
{
    if (w <= 0 || h <= 0 || w > EXR_MAX_SIDE || h > EXR_MAX_SIDE) {
        io_msg(msg, "%s: cannot write EXR of invalid size %dx%d", path, w, h);
        return -1;
    }
    if (exr_check_layers(path, layers, n, msg) != 0 || exr_check_attributes(path, attrs, n_attrs, msg) != 0)
        return -1;
    char tmp[EXR_PATH_MAX + 32];
    if (strlen(path) >= EXR_PATH_MAX) {
        io_msg(msg, "%.200s...: output path is too long", path);
        return -1;
    }
    /* Open the temporary file ourselves first so a bad directory gets a plain errno message. */
    FILE *probe = io_open_temp(path, tmp, sizeof tmp, "wb", msg);
    if (!probe)
        return -1;
    fclose(probe);

    exr_last_error[0] = '\0';
    exr_context_initializer_t init = exr_initializer();
    exr_context_t ctxt = NULL;
    exr_result_t rv = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "cannot start EXR write", rv);
        if (ctxt)
            exr_finish(&ctxt);
        remove(tmp);
        return -1;
    }
    int status = exr_write_body(ctxt, path, layers, n, attrs, n_attrs, w, h, msg);
    rv = exr_finish(&ctxt);
    if (status == 0 && rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "cannot finish EXR file", rv);
        status = -1;
    }
    if (status != 0) {
        remove(tmp);
        return -1;
    }
    return io_commit(tmp, path, msg);
}

int exr_write_rgb(const char *path, const float *rgb, int w, int h, char *msg)
{
    if (!rgb) {
        io_msg(msg, "%s: cannot write EXR of invalid size %dx%d (no pixels)", path, w, h);
        return -1;
    }
    struct exr_layer layer = {NULL, rgb};
    return exr_write_layers(path, &layer, 1, w, h, msg);
}

/* Checks the four magic bytes so that missing and foreign files get a precise message. */
static int exr_probe_file(const char *path, char *msg)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        io_msg(msg, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    unsigned char magic[4];
    size_t got = fread(magic, 1, sizeof magic, f);
    fclose(f);
    if (got != sizeof magic || magic[0] != 0x76 || magic[1] != 0x2f || magic[2] != 0x31 ||
        magic[3] != 0x01) {
        io_msg(msg, "%s: not an OpenEXR file (bad magic number)", path);
        return -1;
    }
    return 0;
}

/* Finds a channel's index in the channel list; returns -1 where absent. */
static int exr_find_channel(const exr_attr_chlist_t *chl, const char *name)
{
    for (int i = 0; i < chl->num_channels; i++)
        if (strcmp(chl->entries[i].name.str, name) == 0)
            return i;
    return -1;
}

/* Writes the file's layers ("default" for channels without a '.', else the part before the last
 * '.') as a comma-separated list into out, each once, cut short with "..." when it does not fit. */
static void exr_list_layers(const exr_attr_chlist_t *chl, char *out, size_t n)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < chl->num_channels; i++) {
        const char *name = chl->entries[i].name.str;
        const char *dot = strrchr(name, '.');
        int len = dot ? (int)(dot - name) : 7;
        const char *shown = dot ? name : "default";
        int seen = 0;
        for (int j = 0; j < i && !seen; j++) {
            const char *prev = chl->entries[j].name.str;
            const char *pdot = strrchr(prev, '.');
            seen = dot ? pdot && pdot - prev == len && strncmp(prev, name, (size_t)len) == 0
                       : !pdot;
        }
        if (seen)
            continue;
        int wrote = snprintf(out + used, n - used, "%s%.*s", used ? ", " : "", len, shown);
        if (wrote < 0 || (size_t)wrote >= n - used) {
            if (n >= 4)
                memcpy(out + n - 4, "...", 4);
            return;
        }
        used += (size_t)wrote;
    }
}

/* Points the decoder's channels names[0..2] at this chunk's rows of the output as R, G, B;
 * skips all other channels. */
static void exr_bind_decode(exr_decode_pipeline_t *dec, char names[3][EXR_LAYER_NAME_MAX + 56],
                            float *out, int w, int row)
{
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        int off = -1;
        for (int k = 0; k < 3 && off < 0; k++)
            if (strcmp(ch->channel_name, names[k]) == 0)
                off = k;
        if (off < 0) {
            ch->decode_to_ptr = NULL;
            continue;
        }
        ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
        ch->user_line_stride = 3 * (int32_t)sizeof(float) * w;
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
        ch->decode_to_ptr = (uint8_t *)(out + ((size_t)row * (size_t)w * 3 + (size_t)off));
    }
}

/* Reads the R, G, B channels of layer (NULL or "" = the default layer's plain R, G, B). */
static int exr_read_body(exr_context_t ctxt, const char *path, const char *layer, float **rgb,
                         int *w_out, int *h_out, char *msg)
{
    int parts = 0;
    exr_result_t rv = exr_get_count(ctxt, &parts);
    if (rv != EXR_ERR_SUCCESS || parts < 1) {
        exr_fail(msg, path, "cannot read EXR parts", rv);
        return -1;
    }
    exr_storage_t storage;
    rv = exr_get_storage(ctxt, 0, &storage);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "cannot read EXR storage type", rv);
        return -1;
    }
    if (storage != EXR_STORAGE_SCANLINE) {
        io_msg(msg, "%s: unsupported EXR layout (%s); only scanline images can be read", path,
               storage == EXR_STORAGE_TILED           ? "tiled"
               : storage == EXR_STORAGE_DEEP_SCANLINE ? "deep scanline"
                                                      : "deep tiled");
        return -1;
    }

    exr_attr_box2i_t dw;
    rv = exr_get_data_window(ctxt, 0, &dw);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "cannot read EXR data window", rv);
        return -1;
    }
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    if (w <= 0 || h <= 0 || w > EXR_MAX_SIDE || h > EXR_MAX_SIDE || w * h > EXR_MAX_PIXELS) {
        io_msg(msg, "%s: unsupported EXR image size %lldx%lld", path,
                (long long)w, (long long)h);
        return -1;
    }

    const exr_attr_chlist_t *chl = NULL;
    rv = exr_get_channels(ctxt, 0, &chl);
    if (rv != EXR_ERR_SUCCESS || !chl) {
        exr_fail(msg, path, "cannot read EXR channel list", rv);
        return -1;
    }
    /* Room for a name longer than any accepted layer, so an over-long request fails as missing. */
    char names[3][EXR_LAYER_NAME_MAX + 56];
    for (int c = 0; c < 3; c++)
        exr_channel_name(names[c], sizeof names[c], layer, c);
    for (int c = 0; c < 3; c++) {
        int i = exr_find_channel(chl, names[c]);
        if (i < 0) {
            if (exr_is_default_layer(layer)) {
                io_msg(msg, "%s: EXR has no '%s' channel (R, G and B are required)", path,
                       names[c]);
            } else {
                char have[160];
                exr_list_layers(chl, have, sizeof have);
                io_msg(msg, "%s: EXR has no layer '%.200s' (channel '%s' is missing; layers "
                            "in the file: %s)",
                       path, layer, names[c], have[0] ? have : "none");
            }
            return -1;
        }
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) {
            io_msg(msg, "%s: EXR channel '%s' is not half or float", path, names[c]);
            return -1;
        }
        if (e->x_sampling != 1 || e->y_sampling != 1) {
            io_msg(msg, "%s: EXR channel '%s' is subsampled (unsupported)", path, names[c]);
            return -1;
        }
    }

    int32_t lines = 0;
    rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    if (rv != EXR_ERR_SUCCESS || lines <= 0) {
        exr_fail(msg, path, "cannot query EXR chunk layout", rv);
        return -1;
    }

    float *out = calloc((size_t)(w * h * 3), sizeof(float));
    if (!out) {
        io_msg(msg, "%s: out of memory for %lldx%lld image", path, (long long)w,
                (long long)h);
        return -1;
    }

    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int have_dec = 0;
    int status = 0;
    for (int64_t y = dw.min.y; y <= dw.max.y; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_read_scanline_chunk_info(ctxt, 0, (int)y, &cinfo);
        if (rv == EXR_ERR_SUCCESS) {
            if (!have_dec) {
                rv = exr_decoding_initialize(ctxt, 0, &cinfo, &dec);
                have_dec = rv == EXR_ERR_SUCCESS;
            } else {
                rv = exr_decoding_update(ctxt, 0, &cinfo, &dec);
            }
        }
        if (rv == EXR_ERR_SUCCESS) {
            int64_t row = (int64_t)cinfo.start_y - dw.min.y;
            if (row < 0 || row + cinfo.height > h || cinfo.width != w) {
                io_msg(msg, "%s: EXR chunk at line %lld is outside the image",
                        path, (long long)y);
                status = -1;
                break;
            }
            exr_bind_decode(&dec, names, out, (int)w, (int)row);
            rv = exr_decoding_choose_default_routines(ctxt, 0, &dec);
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_decoding_run(ctxt, 0, &dec);
        if (rv != EXR_ERR_SUCCESS) {
            char what[96];
            snprintf(what, sizeof what, "cannot decode EXR scanlines at y=%lld (truncated or corrupt?)",
                     (long long)y);
            exr_fail(msg, path, what, rv);
            status = -1;
            break;
        }
    }
    if (have_dec)
        exr_decoding_destroy(ctxt, &dec);
    if (status != 0) {
        free(out);
        return -1;
    }
    *rgb = out;
    *w_out = (int)w;
    *h_out = (int)h;
    return 0;
}

/* Checks the magic bytes and reads the header into *ctxt (to exr_finish). Returns 0, or -1 with msg. */
static int exr_open_read(const char *path, exr_context_t *ctxt, char *msg)
{
    if (exr_probe_file(path, msg) != 0)
        return -1;
    exr_last_error[0] = '\0';
    exr_context_initializer_t init = exr_initializer();
    *ctxt = NULL;
    exr_result_t rv = exr_start_read(ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(msg, path, "invalid or unreadable EXR header", rv);
        if (*ctxt)
            exr_finish(ctxt);
        return -1;
    }
    return 0;
}

int exr_read_layer(const char *path, const char *layer, float **rgb, int *w, int *h, char *msg)
{
    *rgb = NULL;
    *w = *h = 0;
    if (layer && strlen(layer) > EXR_LAYER_NAME_MAX) {
        io_msg(msg, "%s: EXR layer name '%.40s...' is longer than %d bytes", path, layer,
               EXR_LAYER_NAME_MAX);
        return -1;
    }
    exr_context_t ctxt = NULL;
    if (exr_open_read(path, &ctxt, msg) != 0)
        return -1;
    int status = exr_read_body(ctxt, path, layer, rgb, w, h, msg);
    exr_finish(&ctxt);
    return status;
}

int exr_read_rgb(const char *path, float **rgb, int *w, int *h, char *msg)
{
    return exr_read_layer(path, NULL, rgb, w, h, msg);
}

int exr_read_attribute(const char *path, const char *name, char *value, size_t len, char *msg)
{
    if (len > 0)
        value[0] = '\0';
    exr_context_t ctxt = NULL;
    if (exr_open_read(path, &ctxt, msg) != 0)
        return -1;
    int32_t n = 0;
    const char *text = NULL;
    exr_result_t rv = exr_attr_get_string(ctxt, 0, name, &n, &text);
    int status = 0;
    if (rv == EXR_ERR_NO_ATTR_BY_NAME) {
        status = 1;
    } else if (rv == EXR_ERR_ATTR_TYPE_MISMATCH) {
        io_msg(msg, "%s: EXR attribute '%.200s' is not text", path, name);
        status = -1;
    } else if (rv != EXR_ERR_SUCCESS || n < 0 || !text) {
        exr_fail(msg, path, "cannot read EXR attribute", rv);
        status = -1;
    } else if ((size_t)n >= len) {
        io_msg(msg, "%s: EXR attribute '%.200s' is longer (%d bytes) than the %zu allowed", path, name, (int)n,
               len - 1);
        status = -1;
    } else {
        memcpy(value, text, (size_t)n);
        value[n] = '\0';
    }
    exr_finish(&ctxt);
    return status;
}
