/* The EXR writer, through OpenEXRCore (OpenEXR's C library): one scanline
 * part, channels R, G, B (and A), 32-bit float or half, ZIP-compressed.
 *
 * OpenEXRCore writes through our own write function into the temporary file
 * hr_image_write opened, so the file is published the same all-or-nothing
 * way as every other format, and its error messages come to us through an
 * error handler instead of being printed. */
#include <openexr.h>

#include <errno.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include "util/errors.h"
#include "image/image_writers.h"

/* What OpenEXRCore's callbacks share with us (its context's user data). */
typedef struct exr_sink {
    int fd;
    char message[256]; /* the first error OpenEXRCore reported */
} exr_sink;

static exr_sink *sink_of(exr_const_context_t exr)
{
    void *user = NULL;
    if (!exr || exr_get_user_data(exr, &user) != EXR_ERR_SUCCESS) return NULL;
    return user;
}

static void on_exr_error(exr_const_context_t exr, exr_result_t code, const char *message)
{
    exr_sink *sink = sink_of(exr);
    /* Keep the first message: later ones are usually consequences of it. */
    if (sink && !sink->message[0])
        snprintf(sink->message, sizeof sink->message, "%s", message ? message : exr_get_default_error_message(code));
}

static int64_t write_at(exr_const_context_t exr, void *user, const void *buffer, uint64_t size,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_sink *sink = user;
    const unsigned char *p = buffer;
    uint64_t done = 0;
    while (done < size) {
        ssize_t n = pwrite(sink->fd, p + done, (size_t)(size - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error_cb(exr, EXR_ERR_WRITE_IO, "%s", n < 0 ? strerror(errno) : "nothing was written");
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)size;
}

static const char *const channel_names[4] = {"R", "G", "B", "A"};

/* Point each of the chunk's channels at its samples in the interleaved float
 * image. OpenEXRCore lists channels sorted by name (A, B, G, R), so they are
 * matched by name, not position. Samples are given as 32-bit floats; the
 * encoder converts them to half when the file's channel is half. */
static void point_channels(exr_encode_pipeline_t *enc, const hr_pixels *px, const exr_chunk_info_t *chunk)
{
    size_t pixel_bytes = (size_t)px->channels * sizeof(float);
    const float *first = px->data + (size_t)chunk->start_y * (size_t)px->width * (size_t)px->channels;
    for (int c = 0; c < enc->channel_count; c++) {
        exr_coding_channel_info_t *ch = &enc->channels[c];
        int offset = 0;
        while (offset < px->channels && strcmp(ch->channel_name, channel_names[offset]) != 0) offset++;
        ch->encode_from_ptr = (const uint8_t *)(first + offset);
        ch->user_pixel_stride = (int32_t)pixel_bytes;
        ch->user_line_stride = (int32_t)(pixel_bytes * (size_t)px->width);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
    }
}

static exr_result_t define_part(exr_context_t exr, const hr_pixels *px, int half)
{
    int part = 0;
    exr_result_t rv = exr_add_part(exr, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(exr, part, px->width, px->height, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < px->channels && rv == EXR_ERR_SUCCESS; c++) {
        /* Colour is stored as light (perceptually logarithmic for lossy
         * codecs); alpha is a linear quantity. */
        exr_perceptual_treatment_t percept = c < 3 ? EXR_PERCEPTUALLY_LOGARITHMIC : EXR_PERCEPTUALLY_LINEAR;
        rv = exr_add_channel(exr, part, channel_names[c], half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT, percept, 1, 1);
    }
    return rv;
}

static exr_result_t write_chunks(exr_context_t exr, const hr_pixels *px)
{
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(exr, 0, &lines);
    if (rv != EXR_ERR_SUCCESS) return rv;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int started = 0;
    for (int32_t y = 0; y < px->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(exr, 0, y, &chunk);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = started ? exr_encoding_update(exr, 0, &chunk, &enc) : exr_encoding_initialize(exr, 0, &chunk, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        point_channels(&enc, px, &chunk);
        if (!started) {
            started = 1;
            rv = exr_encoding_choose_default_routines(exr, 0, &enc);
            if (rv != EXR_ERR_SUCCESS) break;
        }
        rv = exr_encoding_run(exr, 0, &enc);
    }
    if (started) {
        exr_result_t drv = exr_encoding_destroy(exr, &enc);
        if (rv == EXR_ERR_SUCCESS) rv = drv;
    }
    return rv;
}

hr_status hri_write_exr(const hr_context *ctx, const hr_pixels *px,
                       const hr_image_write_options *o, hr_atomic_file *out)
{
    /* The encoder takes a row's length in bytes as an int32_t. */
    if ((size_t)px->width * (size_t)px->channels * sizeof(float) > INT32_MAX)
        return hri_error(ctx, HR_ERROR_UNSUPPORTED, "cannot write '%s': %d pixels is too wide for the EXR writer",
                        out->target, (int)px->width);
    /* OpenEXRCore writes with pwrite at offsets of its own; nothing may sit
     * in the stdio buffer in front of it. */
    if (fflush(out->fp) != 0)
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", out->target, strerror(errno));
    exr_sink sink = {fileno(out->fp), {0}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = &sink;
    init.write_fn = write_at;

    exr_context_t exr = NULL;
    exr_result_t rv = exr_start_write(&exr, out->target, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = define_part(exr, px, o->exr_half != 0);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(exr);
    if (rv == EXR_ERR_SUCCESS) rv = write_chunks(exr, px);
    /* exr_finish writes the chunk offset table, so its result matters; on
     * an earlier failure it only frees the context. */
    if (exr) {
        exr_result_t frv = exr_finish(&exr);
        if (rv == EXR_ERR_SUCCESS) rv = frv;
    }
    if (rv != EXR_ERR_SUCCESS)
        return hri_error(ctx, rv == EXR_ERR_OUT_OF_MEMORY ? HR_ERROR_OUT_OF_MEMORY : HR_ERROR_IO,
                        "cannot write '%s': OpenEXR: %s", out->target,
                        sink.message[0] ? sink.message : exr_get_default_error_message(rv));
    return HR_OK;
}
