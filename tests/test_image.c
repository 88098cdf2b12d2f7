/* Tests of src/image: the float image, sRGB, PNG/EXR/PFM files (round trips, files written
 * independently with libpng and the OpenEXR C API, malformed and truncated input, atomic writes),
 * tonemapping, differences, heat maps and the RMS metrics.
 * Expected values come from the formulas quoted beside them, evaluated by hand or in double here. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <openexr.h> /* the C core API, to build test files independently of Lucent */
#include <png.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "lucent/image.h"
#include "test.h"

/* ---- helpers ---- */

/* The sRGB curve (IEC 61966-2-1) in double, written out independently of the library. */
static double srgb_enc(double x)
{
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

static double srgb_dec(double e) { return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4); }

/* An image whose values sweep [lo, hi] deterministically (a simple LCG, no RNG dependency). */
static lucent_image *make_image(int w, int h, int ch, float lo, float hi)
{
    lucent_image *img;
    if (lucent_image_create(w, h, ch, &img) != LUCENT_OK) return NULL;
    uint32_t state = 12345u;
    size_t n = lucent_image_value_count(img);
    for (size_t i = 0; i < n; i++) {
        state = state * 1664525u + 1013904223u;
        img->data[i] = lo + (hi - lo) * (float)(state >> 8) / 16777216.0f;
    }
    return img;
}

/* Number of entries of directory dir whose name starts with prefix. */
static int count_entries(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0) n++;
    closedir(d);
    return n;
}

static void write_bytes(const char *path, const void *data, size_t size)
{
    FILE *fp = fopen(path, "wb");
    if (!fp) return;
    if (size) fwrite(data, 1, size, fp);
    fclose(fp);
}

/* ---- the image ---- */

TEST(create_access_and_limits)
{
    lucent_image *img;
    CHECK_OK(lucent_image_create(3, 2, 3, &img));
    CHECK(img->width == 3 && img->height == 2 && img->channels == 3);
    for (size_t i = 0; i < 18; i++) CHECK(img->data[i] == 0.0f);
    lucent_image_set(img, 2, 1, 1, 0.25f);
    CHECK(img->data[(1 * 3 + 2) * 3 + 1] == 0.25f); /* row-major, top row first, interleaved */
    CHECK(lucent_image_get(img, 2, 1, 1) == 0.25f);
    CHECK(lucent_image_pixel(img, 1, 1) == img->data + 12);
    lucent_image_fill(img, 2, 7.0f);
    CHECK(lucent_image_get(img, 0, 0, 2) == 7.0f && lucent_image_get(img, 0, 0, 1) == 0.0f);
    lucent_image *copy;
    CHECK_OK(lucent_image_clone(img, &copy));
    CHECK(memcmp(copy->data, img->data, 18 * sizeof(float)) == 0 && copy->data != img->data);
    lucent_image_destroy(copy);
    lucent_image_destroy(img);
    lucent_image_destroy(NULL);

    CHECK_ERR(lucent_image_create(0, 5, 3, &img), LUCENT_ERR_INVALID_ARGUMENT, "empty");
    CHECK(img == NULL);
    CHECK_ERR(lucent_image_create(4, 4, 2, &img), LUCENT_ERR_INVALID_ARGUMENT, "2 channels");
    CHECK_ERR(lucent_image_create(-3, 4, 3, &img), LUCENT_ERR_INVALID_ARGUMENT, "empty");
    /* 2^20 x 2^20 x 4 floats overflows 32 bits many times and exceeds the pixel limit */
    CHECK_ERR(lucent_image_create(1 << 20, 1 << 20, 4, &img), LUCENT_ERR_INVALID_ARGUMENT, "too large");
    CHECK_ERR(lucent_image_create(2147483647, 2, 1, &img), LUCENT_ERR_INVALID_ARGUMENT, "too large");
}

TEST(convert_channels)
{
    lucent_image *rgb, *out;
    CHECK_OK(lucent_image_create(1, 1, 3, &rgb));
    float px[3] = {1.0f, 0.5f, 0.25f};
    memcpy(rgb->data, px, sizeof px);
    CHECK_OK(lucent_image_convert_channels(rgb, 1, &out));
    /* Rec. 709 luminance: 0.2126 * 1 + 0.7152 * 0.5 + 0.0722 * 0.25 = 0.58825 */
    CHECK_NEAR(out->data[0], 0.58825, 1e-6);
    lucent_image_destroy(out);
    CHECK_OK(lucent_image_convert_channels(rgb, 4, &out));
    CHECK(out->data[0] == 1.0f && out->data[2] == 0.25f && out->data[3] == 1.0f);
    lucent_image *back;
    CHECK_OK(lucent_image_convert_channels(out, 3, &back));
    CHECK(memcmp(back->data, px, sizeof px) == 0);
    lucent_image_destroy(back);
    lucent_image_destroy(out);
    lucent_image_destroy(rgb);
}

/* ---- sRGB and tonemapping ---- */

TEST(srgb_curve_known_values)
{
    /* 1.055 * 0.5^(1/2.4) - 0.055 = 0.7353570 */
    CHECK_NEAR(lucent_srgb_encode(0.5f), 0.735357, 1e-6);
    CHECK_NEAR(lucent_srgb_encode(0.18f), 0.4613561, 1e-6);
    CHECK_NEAR(lucent_srgb_encode(1.0f), 1.0, 1e-6);
    CHECK(lucent_srgb_encode(0.0f) == 0.0f && lucent_srgb_encode(-1.0f) == 0.0f);
    CHECK(lucent_srgb_encode(NAN) == 0.0f);
    CHECK_NEAR(lucent_srgb_encode(0.001f), 0.01292, 1e-7); /* linear segment, 12.92 x */
    /* continuity at the breakpoint: both pieces give 0.0404499 at 0.0031308 */
    CHECK_NEAR(lucent_srgb_encode(0.0031308f), 0.040449936, 1e-7);
    CHECK_NEAR(lucent_srgb_encode(0.0031309f), 0.0404500, 2e-6);
    CHECK_NEAR(lucent_srgb_decode(0.5f), 0.2140411, 1e-6);
    CHECK_NEAR(lucent_srgb_decode(0.04045f), 0.0031308, 1e-7);
    for (int i = 0; i <= 100; i++) {
        float x = (float)i / 100.0f;
        CHECK_NEAR(lucent_srgb_decode(lucent_srgb_encode(x)), x, 2e-6);
        CHECK_NEAR(lucent_srgb_encode(x), srgb_enc(x), 1e-6);
    }
}

TEST(tonemap_operators)
{
    CHECK_NEAR(lucent_tonemap_value(LUCENT_TONEMAP_REINHARD, 1.0f), 0.5, 1e-7); /* 1 / (1 + 1) */
    CHECK_NEAR(lucent_tonemap_value(LUCENT_TONEMAP_REINHARD, 3.0f), 0.75, 1e-7);
    /* Narkowicz: (2.51 + 0.03) / (2.43 + 0.59 + 0.14) = 2.54 / 3.16 at x = 1 */
    CHECK_NEAR(lucent_tonemap_value(LUCENT_TONEMAP_FILMIC, 1.0f), 2.54 / 3.16, 1e-6);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_FILMIC, 1e30f) == 1.0f);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_FILMIC, INFINITY) == 1.0f);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_FILMIC, 0.0f) == 0.0f);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_CLAMP, 2.0f) == 1.0f);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_CLAMP, NAN) == 0.0f);
    CHECK(lucent_tonemap_value(LUCENT_TONEMAP_NONE, 2.0f) == 2.0f);
    lucent_tonemap_op op;
    CHECK(lucent_tonemap_op_parse("filmic", &op) == LUCENT_OK && op == LUCENT_TONEMAP_FILMIC);
    CHECK_ERR(lucent_tonemap_op_parse("aces", &op), LUCENT_ERR_INVALID_ARGUMENT, "aces", "reinhard");
    for (int i = 0; i < 4; i++) /* the names the sidecar writes read back */
        CHECK(lucent_tonemap_op_parse(lucent_tonemap_op_name((lucent_tonemap_op)i), &op) == LUCENT_OK &&
              op == (lucent_tonemap_op)i);
    CHECK(!strcmp(lucent_tonemap_op_name((lucent_tonemap_op)7), "unknown"));

    lucent_image *img;
    CHECK_OK(lucent_image_create(1, 1, 4, &img));
    float px[4] = {0.25f, 0.5f, 1.0f, 0.5f};
    memcpy(img->data, px, sizeof px);
    lucent_image_tonemap(img, &(lucent_tonemap_desc){.op = LUCENT_TONEMAP_REINHARD, .exposure = 1});
    CHECK_NEAR(img->data[0], 0.5 / 1.5, 1e-7); /* exposure +1 stop doubles: 0.25 -> 0.5 */
    CHECK_NEAR(img->data[1], 0.5, 1e-7);
    CHECK_NEAR(img->data[2], 2.0 / 3.0, 1e-7);
    CHECK(img->data[3] == 0.5f); /* alpha untouched */
    lucent_image_destroy(img);
}

/* ---- PNG ---- */

/* Round trip through a PNG: the encoded values differ by at most half a code (plus float noise). */
static void check_png_roundtrip(int ch, int bits, bool linear)
{
    lucent_image *img = make_image(13, 7, ch, -0.1f, 1.2f), *back = NULL;
    img->data[0] = 0.0f, img->data[1] = 1.0f, img->data[2] = 0.002f;
    const char *path = test_path(bits == 8 ? "rt8.png" : "rt16.png");
    lucent_image_write_desc d = {.png_bits = bits, .png_linear = linear};
    CHECK_OK(lucent_image_write(path, img, &d));
    CHECK_OK(lucent_image_load(path, &back));
    if (!back) return lucent_image_destroy(img);
    CHECK(back->width == 13 && back->height == 7 && back->channels == ch);
    double step = bits == 8 ? 1.0 / 255 : 1.0 / 65535, worst = 0;
    for (size_t i = 0; i < lucent_image_value_count(img); i++) {
        bool alpha = ch == 4 && i % 4 == 3;
        double v = fmin(fmax(img->data[i], 0.0), 1.0), r = back->data[i];
        double err = alpha || linear ? fabs(r - v) : fabs(srgb_enc(r) - srgb_enc(v));
        worst = fmax(worst, err);
    }
    CHECK_MSG(worst <= 0.5 * step + 2e-7, "%d-bit %d-channel PNG: worst encoded error %.3g > %.3g", bits, ch, worst,
              0.5 * step);
    lucent_image_destroy(back);
    lucent_image_destroy(img);
}

TEST(png_roundtrips)
{
    for (int ch = 1; ch <= 4; ch++) {
        if (ch == 2) continue;
        check_png_roundtrip(ch, 8, false);
        check_png_roundtrip(ch, 16, false);
    }
    check_png_roundtrip(3, 16, true);
    check_png_roundtrip(4, 8, true);
    lucent_image *img = make_image(2, 2, 3, 0, 1);
    CHECK_ERR(lucent_image_write_png(test_path("x.png"), img, &(lucent_image_write_desc){.png_bits = 12}),
              LUCENT_ERR_INVALID_ARGUMENT, "x.png", "bit depth 12");
    lucent_image_destroy(img);
}

/* Writes a PNG with libpng directly (independently of the library's writer). */
static bool write_raw_png(const char *path, int w, int h, int bits, int type, const png_byte *data,
                          void (*extra)(png_structp, png_infop))
{
    FILE *fp = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (!fp || !png || !info || setjmp(png_jmpbuf(png))) {
        if (fp) fclose(fp);
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, fp);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, bits, type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (extra) extra(png, info);
    png_write_info(png, info);
    size_t rowbytes = png_get_rowbytes(png, info);
    for (int y = 0; y < h; y++) png_write_row(png, data + (size_t)y * rowbytes);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    fclose(fp);
    return true;
}

static void palette_chunks(png_structp png, png_infop info)
{
    png_color pal[4] = {{0, 0, 0}, {255, 0, 0}, {0, 128, 255}, {255, 255, 255}};
    png_byte trans[3] = {255, 64, 0}; /* entry 0 opaque, 1 a quarter, 2 transparent, 3 opaque */
    png_set_PLTE(png, info, pal, 4);
    png_set_tRNS(png, info, trans, 3, NULL);
}

TEST(png_palette_written_by_libpng)
{
    /* 4 pixels, 2 bits each, in one byte per row: indices 0 1 / 2 3 */
    const png_byte rows[2] = {0x10, 0xB0}; /* 00 01 0000, 10 11 0000 */
    const char *path = test_path("palette.png");
    CHECK(write_raw_png(path, 2, 2, 2, PNG_COLOR_TYPE_PALETTE, rows, palette_chunks));
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load(path, &img));
    if (!img) return;
    CHECK(img->channels == 4 && img->width == 2 && img->height == 2);
    CHECK_NEAR(lucent_image_get(img, 1, 0, 0), 1.0, 1e-6);        /* red */
    CHECK_NEAR(lucent_image_get(img, 1, 0, 3), 64.0 / 255, 1e-6); /* alpha is linear */
    CHECK_NEAR(lucent_image_get(img, 0, 1, 2), 1.0, 1e-6);
    CHECK_NEAR(lucent_image_get(img, 0, 1, 1), srgb_dec(128.0 / 255), 1e-6); /* 0.2158605 */
    CHECK(lucent_image_get(img, 0, 1, 3) == 0.0f);
    CHECK(lucent_image_get(img, 1, 1, 3) == 1.0f && lucent_image_get(img, 0, 0, 3) == 1.0f);
    lucent_image_destroy(img);
}

static void linear_gamma_chunk(png_structp png, png_infop info)
{
    png_set_gAMA_fixed(png, info, 100000); /* gAMA 1.0: samples are linear */
}

static void grey_trns_chunk(png_structp png, png_infop info)
{
    png_color_16 key = {.gray = 0};
    png_set_tRNS(png, info, NULL, 0, &key);
}

TEST(png_grey_formats_written_by_libpng)
{
    /* 16-bit grey+alpha, big endian: (grey 0x8000, alpha 0xFFFF), (grey 0xFFFF, alpha 0x4000) */
    const png_byte ga[8] = {0x80, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0x40, 0x00};
    const char *path = test_path("ga16.png");
    CHECK(write_raw_png(path, 2, 1, 16, PNG_COLOR_TYPE_GRAY_ALPHA, ga, linear_gamma_chunk));
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load_png(path, &img));
    if (img) {
        CHECK(img->channels == 4);
        CHECK_NEAR(img->data[0], 32768.0 / 65535, 1e-7); /* linear, by the gAMA chunk */
        CHECK(img->data[0] == img->data[1] && img->data[1] == img->data[2]);
        CHECK_NEAR(img->data[7], 16384.0 / 65535, 1e-7);
        lucent_image_destroy(img);
    }
    /* 1-bit grey with a tRNS key on black: 0 1 0 1 -> RGBA with alpha 0 on the black pixels */
    const png_byte bits1[1] = {0x50};
    path = test_path("grey1.png");
    CHECK(write_raw_png(path, 4, 1, 1, PNG_COLOR_TYPE_GRAY, bits1, grey_trns_chunk));
    CHECK_OK(lucent_image_load_png(path, &img));
    if (img) {
        CHECK(img->channels == 4 && img->width == 4);
        CHECK(img->data[3] == 0.0f && img->data[4] == 1.0f && img->data[7] == 1.0f);
        lucent_image_destroy(img);
    }
    /* 8-bit grey, no chunks: sRGB assumed */
    const png_byte g8[2] = {0, 188};
    path = test_path("grey8.png");
    CHECK(write_raw_png(path, 2, 1, 8, PNG_COLOR_TYPE_GRAY, g8, NULL));
    CHECK_OK(lucent_image_load_png(path, &img));
    if (img) {
        CHECK(img->channels == 1);
        CHECK_NEAR(img->data[1], srgb_dec(188.0 / 255), 1e-6);
        lucent_image_destroy(img);
    }
}

/* Every prefix of a valid file must fail with a message naming the file, never crash. */
static void check_truncations(const char *name, const char *substring, int step)
{
    char *data;
    size_t size;
    char full[600];
    snprintf(full, sizeof full, "%s", test_path(name));
    CHECK_OK(lucent_read_file(full, &data, &size));
    if (!data) return;
    char cut_name[64];
    snprintf(cut_name, sizeof cut_name, "cut-%s", name);
    const char *cut = test_path(cut_name);
    int checked = 0;
    for (size_t len = 0; len < size; len += (len < 64 ? 1 : (size_t)step)) {
        write_bytes(cut, data, len);
        lucent_image *img = NULL;
        lucent_status s = lucent_image_load(cut, &img);
        CHECK_MSG(s != LUCENT_OK && img == NULL, "%s cut to %zu of %zu bytes was accepted", name, len, size);
        CHECK_MSG((strstr(lucent_last_error(), cut_name) && strstr(lucent_last_error(), substring)) || len == 0,
                  "%s cut to %zu bytes: message \"%s\"", name, len, lucent_last_error());
        lucent_image_destroy(img);
        checked++;
    }
    CHECK(checked > 64);
    free(data);
}

TEST(png_malformed)
{
    lucent_image *img = make_image(40, 30, 3, 0, 1), *out = NULL;
    CHECK_OK(lucent_image_write(test_path("ok.png"), img, NULL));
    lucent_image_destroy(img);
    check_truncations("ok.png", "PNG", 37);

    const char *text = test_path("text.png");
    write_bytes(text, "hello, I am not a picture\n", 26);
    CHECK_ERR(lucent_image_load(text, &out), LUCENT_ERR_PARSE, "text.png: not a PNG file (bad signature)");
    write_bytes(text, "", 0);
    CHECK_ERR(lucent_image_load(text, &out), LUCENT_ERR_PARSE, "text.png: not a PNG file");
    CHECK_ERR(lucent_image_load(test_path("absent.png"), &out), LUCENT_ERR_IO, "absent.png", "No such file");
    CHECK_ERR(lucent_image_load(test_tmpdir(), &out), LUCENT_ERR_UNSUPPORTED, "unknown image format");

    /* a corrupted byte inside IDAT (CRC mismatch) */
    char *data;
    size_t size;
    CHECK_OK(lucent_read_file(test_path("ok.png"), &data, &size));
    if (data) {
        data[size / 2] ^= 0x55;
        write_bytes(test_path("crc.png"), data, size);
        CHECK_ERR(lucent_image_load(test_path("crc.png"), &out), LUCENT_ERR_PARSE, "crc.png", "corrupt PNG data");
        free(data);
    }
    CHECK(out == NULL);
}

/* ---- OpenEXR ---- */

TEST(exr_float_and_half_roundtrips)
{
    lucent_image *img = make_image(37, 21, 4, 1e-3f, 6e4f), *back = NULL;
    img->data[0] = 0.0f, img->data[1] = -2.5f, img->data[2] = 1.0f;
    const lucent_exr_compression comps[] = {LUCENT_EXR_COMPRESSION_DEFAULT, LUCENT_EXR_COMPRESSION_NONE,
                                            LUCENT_EXR_COMPRESSION_RLE, LUCENT_EXR_COMPRESSION_ZIPS,
                                            LUCENT_EXR_COMPRESSION_PIZ};
    for (int k = 0; k < 5; k++) { /* float: exact, whatever the (lossless) compression */
        lucent_image_write_desc d = {.exr_compression = comps[k]};
        CHECK_OK(lucent_image_write(test_path("f.exr"), img, &d));
        CHECK_OK(lucent_image_load(test_path("f.exr"), &back));
        if (!back) continue;
        CHECK(back->channels == 4 && back->width == 37 && back->height == 21);
        CHECK_MSG(memcmp(back->data, img->data, lucent_image_value_count(img) * 4) == 0,
                  "float EXR (compression %d) not exact", k);
        lucent_image_destroy(back);
    }
    /* half: 11 significant bits, round to nearest: relative error <= 2^-11 for normal values */
    CHECK_OK(
        lucent_image_write(test_path("h.exr"), img, &(lucent_image_write_desc){.exr_pixel = LUCENT_EXR_PIXEL_HALF}));
    CHECK_OK(lucent_image_load(test_path("h.exr"), &back));
    if (back) {
        double worst = 0;
        for (size_t i = 0; i < lucent_image_value_count(img); i++)
            if (img->data[i] != 0) worst = fmax(worst, fabs(back->data[i] - img->data[i]) / fabs(img->data[i]));
        CHECK_MSG(worst <= ldexp(1, -11), "half EXR: relative error %.3g > 2^-11", worst);
        CHECK(back->data[0] == 0.0f && back->data[1] == -2.5f && back->data[2] == 1.0f);
        lucent_image_destroy(back);
    }
    lucent_image_destroy(img);
}

TEST(exr_grey_and_rgb)
{
    for (int ch = 1; ch <= 3; ch += 2) {
        lucent_image *img = make_image(5, 300, ch, -1, 1), *back = NULL; /* many zip chunks */
        CHECK_OK(lucent_image_write_exr(test_path("g.exr"), img, NULL));
        CHECK_OK(lucent_image_load_exr(test_path("g.exr"), &back));
        if (back) {
            CHECK(back->channels == ch);
            CHECK(memcmp(back->data, img->data, lucent_image_value_count(img) * 4) == 0);
        }
        lucent_image_destroy(back);
        lucent_image_destroy(img);
    }
}

static void quiet_exr(exr_const_context_t c, exr_result_t code, const char *msg) { (void)c, (void)code, (void)msg; }

/* Writes a tiled EXR with the OpenEXR C API directly: channels Y (half) and A (float), 4x4 tiles,
 * data window (10, 20) - (10 + w - 1, 20 + h - 1). Y = x + 100 y, A = 0.5. */
static bool write_tiled_exr(const char *path, int w, int h)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet_exr;
    exr_context_t ctx;
    int part;
    if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init)) return false;
    exr_attr_box2i_t dw;
    dw.min.x = 10, dw.min.y = 20, dw.max.x = 10 + w - 1, dw.max.y = 20 + h - 1;
    bool ok = !exr_add_part(ctx, NULL, EXR_STORAGE_TILED, &part) &&
              !exr_initialize_required_attr_simple(ctx, part, w, h, EXR_COMPRESSION_ZIP) &&
              !exr_set_data_window(ctx, part, &dw) && !exr_set_display_window(ctx, part, &dw) &&
              !exr_set_tile_descriptor(ctx, part, 4, 4, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN) &&
              !exr_add_channel(ctx, part, "Y", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) &&
              !exr_add_channel(ctx, part, "A", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1) &&
              !exr_write_header(ctx);
    float *src = malloc((size_t)w * h * 2 * sizeof(float));
    for (int y = 0; src && y < h; y++)
        for (int x = 0; x < w; x++) src[2 * (y * w + x)] = (float)(x + 100 * y), src[2 * (y * w + x) + 1] = 0.5f;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool first = true;
    for (int ty = 0; ok && src && ty < (h + 3) / 4; ty++) {
        for (int tx = 0; ok && tx < (w + 3) / 4; tx++, first = false) {
            exr_chunk_info_t ci;
            ok = !exr_write_tile_chunk_info(ctx, part, tx, ty, 0, 0, &ci) &&
                 !(first ? exr_encoding_initialize(ctx, part, &ci, &enc) : exr_encoding_update(ctx, part, &ci, &enc));
            for (int i = 0; ok && i < enc.channel_count; i++) {
                exr_coding_channel_info_t *c = &enc.channels[i];
                c->encode_from_ptr =
                    (const uint8_t *)(src + 2 * (ty * 4 * w + tx * 4) + (strcmp(c->channel_name, "A") == 0));
                c->user_pixel_stride = 8, c->user_line_stride = 8 * w;
                c->user_data_type = EXR_PIXEL_FLOAT, c->user_bytes_per_element = 4;
            }
            ok = ok && !(first && exr_encoding_choose_default_routines(ctx, part, &enc)) &&
                 !exr_encoding_run(ctx, part, &enc);
        }
    }
    if (!first) exr_encoding_destroy(ctx, &enc);
    free(src);
    return !exr_finish(&ctx) && ok;
}

TEST(exr_tiled_written_by_openexr)
{
    const char *path = test_path("tiled.exr");
    CHECK(write_tiled_exr(path, 10, 7)); /* partial tiles on the right and the bottom */
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load(path, &img));
    if (!img) return;
    CHECK(img->width == 10 && img->height == 7 && img->channels == 4);
    int bad = 0;
    for (int y = 0; y < 7; y++)
        for (int x = 0; x < 10; x++) {
            const float *p = lucent_image_pixel(img, x, y);
            /* x + 100 y <= 609 is exact in half (integers up to 2048) */
            bad += p[0] != (float)(x + 100 * y) || p[1] != p[0] || p[2] != p[0] || p[3] != 0.5f;
        }
    CHECK_MSG(bad == 0, "%d wrong pixels in the tiled EXR", bad);
    lucent_image_destroy(img);
}

/* Writes a 3x1 scanline EXR with one UINT channel "Y" with the OpenEXR C API directly. */
static bool write_uint_exr(const char *path, const uint32_t v[3])
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet_exr;
    exr_context_t ctx;
    int part;
    if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init)) return false;
    exr_chunk_info_t ci;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool ok = !exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part) &&
              !exr_initialize_required_attr_simple(ctx, part, 3, 1, EXR_COMPRESSION_NONE) &&
              !exr_add_channel(ctx, part, "Y", EXR_PIXEL_UINT, EXR_PERCEPTUALLY_LINEAR, 1, 1) &&
              !exr_write_header(ctx) && !exr_write_scanline_chunk_info(ctx, part, 0, &ci) &&
              !exr_encoding_initialize(ctx, part, &ci, &enc);
    if (ok) {
        exr_coding_channel_info_t *c = &enc.channels[0];
        c->encode_from_ptr = (const uint8_t *)v;
        c->user_pixel_stride = 4, c->user_line_stride = 12;
        c->user_data_type = EXR_PIXEL_UINT, c->user_bytes_per_element = 4;
        ok = !exr_encoding_choose_default_routines(ctx, part, &enc) && !exr_encoding_run(ctx, part, &enc);
        exr_encoding_destroy(ctx, &enc);
    }
    return !exr_finish(&ctx) && ok;
}

TEST(exr_uint_channel_written_by_openexr)
{
    const uint32_t v[3] = {7, 100000, 4000000000u}; /* 4e9 = 15625000 * 2^8: exact in float */
    CHECK(write_uint_exr(test_path("uint.exr"), v));
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load(test_path("uint.exr"), &img));
    if (!img) return;
    CHECK(img->channels == 1 && img->width == 3);
    CHECK(img->data[0] == 7.0f && img->data[1] == 100000.0f && img->data[2] == 4e9f);
    lucent_image_destroy(img);
}

TEST(exr_malformed)
{
    lucent_image *img = make_image(24, 40, 3, 0, 4), *out = NULL;
    CHECK_OK(lucent_image_write(test_path("ok.exr"), img, NULL));
    CHECK_OK(lucent_image_write(test_path("none.exr"), img,
                                &(lucent_image_write_desc){.exr_compression = LUCENT_EXR_COMPRESSION_NONE}));
    lucent_image_destroy(img);
    check_truncations("ok.exr", "OpenEXR", 97);
    check_truncations("none.exr", "OpenEXR", 211);
    write_bytes(test_path("text.exr"), "not an exr, clearly", 19);
    CHECK_ERR(lucent_image_load(test_path("text.exr"), &out), LUCENT_ERR_PARSE, "text.exr",
              "not an OpenEXR file (bad magic number)");
    CHECK_ERR(lucent_image_load(test_path("absent.exr"), &out), LUCENT_ERR_IO, "absent.exr", "No such file");
    CHECK(out == NULL);
}

/* ---- Image bombs (issue 17) ---- */

static void put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* A 57-byte PNG whose IHDR declares 12000 x 12000 RGB pixels (137 Mpixels; 2.3 GB as float RGBA): refused
 * by the read limit from the header, before a byte of it is decoded; a lowered limit refuses a small one. */
TEST(png_bomb_refused_from_the_header)
{
    unsigned char f[57] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    put_be32(f + 8, 13);
    memcpy(f + 12, "IHDR", 4);
    put_be32(f + 16, 12000), put_be32(f + 20, 12000);
    f[24] = 8, f[25] = 2, f[26] = 0, f[27] = 0, f[28] = 0; /* 8-bit RGB, deflate, no filter, no interlace */
    put_be32(f + 29, (uint32_t)crc32(0, f + 12, 17));
    put_be32(f + 33, 0);
    memcpy(f + 37, "IDAT", 4);
    put_be32(f + 41, (uint32_t)crc32(0, f + 37, 4));
    put_be32(f + 45, 0);
    memcpy(f + 49, "IEND", 4);
    put_be32(f + 53, (uint32_t)crc32(0, f + 49, 4));
    write_bytes(test_path("bomb.png"), f, sizeof f);
    lucent_image *out = NULL;
    CHECK(lucent_image_read_limit() == LUCENT_IMAGE_DEFAULT_READ_PIXELS || getenv("LUCENT_IMAGE_MAX_PIXELS"));
    CHECK_ERR(lucent_image_load(test_path("bomb.png"), &out), LUCENT_ERR_PARSE, "bomb.png",
              "declares 12000x12000 pixels", "above the read limit of 64 Mpixels");
    CHECK(out == NULL);
    lucent_image *img = make_image(24, 40, 3, 0, 4);
    CHECK_OK(lucent_image_write(test_path("small.png"), img, NULL));
    CHECK_OK(lucent_image_write(test_path("small.exr"), img, NULL));
    lucent_image_destroy(img);
    lucent_image_set_read_limit(24 * 40 - 1);
    CHECK_ERR(lucent_image_load(test_path("small.png"), &out), LUCENT_ERR_PARSE, "small.png", "24x40");
    CHECK_ERR(lucent_image_load(test_path("small.exr"), &out), LUCENT_ERR_PARSE, "small.exr", "24x40");
    lucent_image_set_read_limit(0);
    CHECK_OK(lucent_image_load(test_path("small.png"), &out));
    lucent_image_destroy(out);
}

/* An EXR whose data window is enlarged in place to 8000 x 8000 (64 Mpixels, under the read limit) while the
 * file keeps its 24 x 40 chunk table: the table cannot fit the file, refused before the 1 GB image is
 * allocated. */
TEST(exr_chunk_table_checked_before_allocating)
{
    lucent_image *img = make_image(24, 40, 3, 0, 4), *out = NULL;
    CHECK_OK(lucent_image_write(test_path("win.exr"), img, NULL));
    lucent_image_destroy(img);
    char *data;
    size_t n;
    CHECK_OK(lucent_read_file(test_path("win.exr"), &data, &n));
    if (!data) return;
    char *at = memmem(data, n, "dataWindow\0box2i\0", 17);
    CHECK(at != NULL);
    if (at) {
        int32_t win[4] = {0, 0, 7999, 7999};
        memcpy(at + 17 + 4, win, sizeof win); /* after the 4-byte attribute size; little endian as the file */
        write_bytes(test_path("win.exr"), data, n);
        CHECK_ERR(lucent_image_load(test_path("win.exr"), &out), LUCENT_ERR_PARSE, "win.exr", "chunk table");
        CHECK(out == NULL);
    }
    free(data);
}

/* Issue 32 items 4, 5: chunks shorter than their lines are refused, scanline or tile, so that no undecoded
 * (uninitialised) scratch byte becomes a pixel; tiles get the chunk-table checks of scanlines. The fixtures:
 * tests/fixtures/images/make_tiled_exr.py (written from the file format's specification, not with OpenEXR)
 * and the reproducers of ../shared/repro-3 (tests/fixtures/bad-images). */
#define BAD_IMAGE(name) LUCENT_SOURCE_DIR "/tests/fixtures/bad-images/" name
#define GOOD_IMAGE(name) LUCENT_SOURCE_DIR "/tests/fixtures/images/" name

TEST(exr_short_chunks_refused)
{
    lucent_image *out = NULL;
    CHECK_ERR(lucent_image_load(BAD_IMAGE("uninit-exr-short-scanline-chunk.exr"), &out), LUCENT_ERR_PARSE,
              "uninit-exr-short-scanline-chunk.exr: truncated or corrupt OpenEXR data",
              "chunk at line 0 holds 5 bytes, its 4 x 1 pixels need 24");
    CHECK_ERR(lucent_image_load(BAD_IMAGE("uninit-exr-short-tile.exr"), &out), LUCENT_ERR_PARSE,
              "uninit-exr-short-tile.exr: truncated or corrupt OpenEXR data", "tile 0, 0 holds 10 bytes");
    CHECK_ERR(lucent_image_load(BAD_IMAGE("hand-exr-short-zip-tile.exr"), &out), LUCENT_ERR_PARSE,
              "hand-exr-short-zip-tile.exr: truncated or corrupt OpenEXR data");
    /* Lucent's own uncompressed file with its first chunk's size field lowered by 4: the bytes are there, the
     * chunk says it holds fewer than its line needs. */
    lucent_image *img = make_image(24, 40, 3, 0, 4);
    CHECK_OK(lucent_image_write(test_path("short.exr"), img,
                                &(lucent_image_write_desc){.exr_compression = LUCENT_EXR_COMPRESSION_NONE}));
    lucent_image_destroy(img);
    char *data;
    size_t n;
    CHECK_OK(lucent_read_file(test_path("short.exr"), &data, &n));
    if (!data) return;
    /* The offset table follows the header (attributes "name\0type\0" size value, ended by an empty name); its
     * first entry is the first chunk's offset. */
    uint64_t first;
    size_t header_end = 8;
    while (header_end < n && data[header_end] != 0) {
        header_end += strlen(data + header_end) + 1;
        header_end += strlen(data + header_end) + 1;
        int32_t size;
        memcpy(&size, data + header_end, 4);
        header_end += 4 + (size_t)size;
    }
    header_end++;
    memcpy(&first, data + header_end, 8);
    CHECK(first + 8 < n);
    if (first + 8 < n) {
        int32_t y, bytes;
        memcpy(&y, data + first, 4), memcpy(&bytes, data + first + 4, 4);
        CHECK(y == 0 && bytes == 24 * 3 * 4); /* one line of 24 float RGB pixels (the writer's default) */
        bytes -= 4;
        memcpy(data + first + 4, &bytes, 4);
        write_bytes(test_path("short.exr"), data, n);
        CHECK_ERR(lucent_image_load(test_path("short.exr"), &out), LUCENT_ERR_PARSE,
                  "short.exr: truncated or corrupt OpenEXR data", "holds 284 bytes, its 24 x 1 pixels need 288");
    }
    free(data);
    CHECK(out == NULL);
}

/* A 379-byte tiled file declaring 8000 x 8000 half RGB in one tile of 10 bytes: refused from its chunk table
 * before the 1 GB image is allocated (it read 1.5 GB and returned zeros). */
TEST(exr_tiled_bomb_refused_from_the_chunk_table)
{
    lucent_image *out = NULL;
    CHECK_ERR(lucent_image_load(BAD_IMAGE("bomb-exr-tiled-379-bytes.exr"), &out), LUCENT_ERR_PARSE,
              "bomb-exr-tiled-379-bytes.exr: corrupt OpenEXR chunk table",
              "tile 0, 0 claims 10 bytes at offset 369, 384000000 unpacked, in a 379-byte file");
    CHECK(out == NULL);
}

/* The specification-built tiled files read with their known values, and every truncation of them is refused. */
TEST(exr_tiled_fixtures_read_and_truncations_refused)
{
    static const char *const names[] = {"tiled-none.exr", "tiled-zip.exr"};
    for (int f = 0; f < 2; f++) {
        char path[600];
        snprintf(path, sizeof path, "%s/tests/fixtures/images/%s", LUCENT_SOURCE_DIR, names[f]);
        lucent_image *img = NULL;
        CHECK_OK(lucent_image_load(path, &img));
        if (!img) continue;
        CHECK(img->width == 37 && img->height == 21 && img->channels == 3);
        int bad = 0;
        for (int y = 0; y < 21; y++)
            for (int x = 0; x < 37; x++) {
                const float *p = lucent_image_pixel(img, x, y);
                bad += p[0] != x / 64.0f || p[1] != y / 32.0f || p[2] != (x + y) / 128.0f;
            }
        CHECK_MSG(bad == 0, "%s: %d wrong pixels", names[f], bad);
        lucent_image_destroy(img);
        char *data;
        size_t n;
        CHECK_OK(lucent_read_file(path, &data, &n));
        if (data) write_bytes(test_path(names[f]), data, n);
        free(data);
        check_truncations(names[f], "OpenEXR", 13);
    }
}

/* ---- PFM ---- */

TEST(pfm_roundtrip_exact)
{
    for (int ch = 1; ch <= 3; ch += 2) {
        lucent_image *img = make_image(6, 4, ch, -1e6f, 1e6f), *back = NULL;
        img->data[0] = INFINITY;
        CHECK_OK(lucent_image_write(test_path("rt.pfm"), img, NULL));
        CHECK_OK(lucent_image_load(test_path("rt.pfm"), &back));
        if (back) {
            CHECK(back->channels == ch && back->width == 6 && back->height == 4);
            CHECK(memcmp(back->data, img->data, lucent_image_value_count(img) * 4) == 0);
        }
        lucent_image_destroy(back);
        lucent_image_destroy(img);
    }
    lucent_image *rgba = make_image(2, 2, 4, 0, 1);
    CHECK_ERR(lucent_image_write(test_path("a.pfm"), rgba, NULL), LUCENT_ERR_UNSUPPORTED, "a.pfm", "4");
    CHECK(count_entries(test_tmpdir(), "a.pfm") == 0);
    lucent_image_destroy(rgba);
}

TEST(pfm_big_endian_bottom_up)
{
    /* "Pf", 1 x 2, scale +1 (big endian); the file's first row is the image's bottom row.
     * 1.0f = 3F800000, 2.0f = 40000000. */
    const unsigned char file[] = {'P',  'f',  '\n', '1',  ' ',  '2',  '\n', '1',  '.', '0',
                                  '\n', 0x3F, 0x80, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00};
    write_bytes(test_path("be.pfm"), file, sizeof file);
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load(test_path("be.pfm"), &img));
    if (!img) return;
    CHECK(img->channels == 1 && img->width == 1 && img->height == 2);
    CHECK(img->data[0] == 2.0f && img->data[1] == 1.0f); /* top row first in memory */
    lucent_image_destroy(img);
}

TEST(pfm_malformed)
{
    struct {
        const char *text, *message;
    } cases[] = {
        {"P6\n2 2\n255\n", "not a PFM file"},
        {"PF\n2 x\n-1.0\n", "bad width or height"},
        {"PF\n-2 2\n-1.0\n", "bad width or height"},
        {"PF\n2 2\n0\n", "bad scale"},
        {"PF\n2 2\nnan\n", "bad scale"},
        {"PF\n0 2\n-1\n", "empty image"},
        {"PF\n100000 100000\n-1.0\n", "too large"},
        {"Pf\n99999999999999999999999 1\n-1\n", "bad width or height"},
        {"PF\n2 2\n-1.0\n0123456789", "truncated PFM data"},
        {"PF\n2", "bad width or height"},
        {"", "not a PFM file"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_bytes(test_path("bad.pfm"), cases[i].text, strlen(cases[i].text));
        lucent_image *img = NULL;
        CHECK_ERR(lucent_image_load(test_path("bad.pfm"), &img), LUCENT_ERR_PARSE, "bad.pfm", cases[i].message);
        CHECK(img == NULL);
    }
    lucent_image *img = make_image(9, 5, 3, 0, 1);
    CHECK_OK(lucent_image_write(test_path("ok.pfm"), img, NULL));
    lucent_image_destroy(img);
    check_truncations("ok.pfm", "PFM", 13);
}

/* ---- atomic writes ---- */

TEST(write_into_missing_directory)
{
    lucent_image *img = make_image(3, 3, 3, 0, 1);
    const char *exts[] = {"png", "exr", "pfm"};
    for (int i = 0; i < 3; i++) {
        char name[64];
        snprintf(name, sizeof name, "missing/x.%s", exts[i]);
        CHECK_ERR(lucent_image_write(test_path(name), img, NULL), LUCENT_ERR_IO, name, "No such file or directory");
    }
    CHECK(count_entries(test_tmpdir(), "missing") == 0);
    lucent_image_destroy(img);
}

TEST(write_into_read_only_directory)
{
    char dir[600];
    snprintf(dir, sizeof dir, "%s", test_path("ro"));
    CHECK(mkdir(dir, 0755) == 0);
    CHECK(chmod(dir, 0555) == 0);
    if (access(dir, W_OK) == 0) { /* root ignores the permission bits */
        printf("  note: running as root, the read-only directory is writable; check skipped\n");
        chmod(dir, 0755);
        return;
    }
    lucent_image *img = make_image(3, 3, 4, 0, 1);
    const char *exts[] = {"png", "exr"};
    for (int i = 0; i < 2; i++) {
        char name[64];
        snprintf(name, sizeof name, "ro/x.%s", exts[i]);
        CHECK_ERR(lucent_image_write(test_path(name), img, NULL), LUCENT_ERR_IO, name, "Permission denied");
    }
    CHECK(count_entries(dir, "") == 2); /* "." and ".." only: no file, no temporary */
    chmod(dir, 0755);
    lucent_image_destroy(img);
}

TEST(write_replaces_only_when_complete)
{
    lucent_image *a = make_image(4, 4, 3, 0, 1), *b = NULL;
    CHECK_OK(lucent_image_write(test_path("keep.png"), a, NULL));
    lucent_image_write_desc bad = {.png_bits = 7};
    CHECK(lucent_image_write(test_path("keep.png"), a, &bad) != LUCENT_OK);
    CHECK_OK(lucent_image_load(test_path("keep.png"), &b)); /* the old file is intact */
    CHECK(count_entries(test_tmpdir(), "keep.png") == 1);
    CHECK_ERR(lucent_image_write(test_path("x.tiff"), a, NULL), LUCENT_ERR_UNSUPPORTED, "x.tiff");
    lucent_image_destroy(b);
    lucent_image_destroy(a);
}

/* ---- metrics and differences ---- */

TEST(rms_hand_computed)
{
    /* a, b: 2x1 RGB. Differences per channel: R (1, -1), G (0, 2), B (0, 0).
     * rms_R = sqrt((1 + 1) / 2) = 1; rms_G = sqrt((0 + 4) / 2) = sqrt 2; rms_B = 0.
     * b_R = (1, 3): sqrt((1 + 9) / 2) = sqrt 5 -> rel_R = 1 / sqrt 5 = 0.4472136.
     * b_G = (2, 2): sqrt 4 = 2 -> rel_G = sqrt 2 / 2 = 0.7071068. b_B = 0 and no error -> 0.
     * pooled: sum d^2 = 6 over 6 values -> 1; sum b^2 = 10 + 8 + 0 = 18 -> rel = sqrt(6 / 18). */
    lucent_image *a, *b;
    CHECK_OK(lucent_image_create(2, 1, 3, &a));
    CHECK_OK(lucent_image_create(2, 1, 3, &b));
    const float av[6] = {2, 2, 0, 2, 4, 0}, bv[6] = {1, 2, 0, 3, 2, 0};
    memcpy(a->data, av, sizeof av);
    memcpy(b->data, bv, sizeof bv);
    lucent_image_error_stats e;
    CHECK_OK(lucent_image_compare(a, b, NULL, &e));
    CHECK(e.pixel_count == 2 && e.channels == 3);
    CHECK_NEAR(e.rms[0], 1.0, 1e-12);
    CHECK_NEAR(e.rms[1], sqrt(2.0), 1e-12);
    CHECK(e.rms[2] == 0.0 && e.rel_rms[2] == 0.0);
    CHECK_NEAR(e.rel_rms[0], 1 / sqrt(5.0), 1e-12);
    CHECK_NEAR(e.rel_rms[1], sqrt(2.0) / 2, 1e-12);
    CHECK_NEAR(e.max_abs[1], 2.0, 0);
    CHECK_NEAR(e.rms_all, 1.0, 1e-12);
    CHECK_NEAR(e.rel_rms_all, sqrt(6.0 / 18.0), 1e-12);

    /* under a mask selecting pixel 1 only: R diff -1, b_R 3 -> rms 1, rel 1/3 */
    const float mask[2] = {0.2f, 1.0f};
    CHECK_OK(lucent_image_compare(a, b, mask, &e));
    CHECK(e.pixel_count == 1);
    CHECK_NEAR(e.rms[0], 1.0, 1e-12);
    CHECK_NEAR(e.rel_rms[0], 1.0 / 3.0, 1e-12);
    CHECK_NEAR(e.rms[1], 2.0, 1e-12);
    lucent_image *m;
    CHECK_OK(lucent_image_create(2, 1, 1, &m));
    memcpy(m->data, mask, sizeof mask);
    lucent_image_error_stats e2;
    CHECK_OK(lucent_image_compare_masked(a, b, m, &e2));
    CHECK(e2.pixel_count == 1 && e2.rms[1] == e.rms[1]);
    lucent_image_fill(m, 0, 0.5f); /* 0.5 is not > 0.5 */
    CHECK_ERR(lucent_image_compare_masked(a, b, m, &e2), LUCENT_ERR_INVALID_ARGUMENT, "no pixel");
    lucent_image_destroy(m);

    /* only the reference has zero energy: relative error is infinite */
    lucent_image_fill(b, 2, 0.0f);
    lucent_image_fill(a, 2, 1.0f);
    CHECK_OK(lucent_image_compare(a, b, NULL, &e));
    CHECK(isinf(e.rel_rms[2]));
    lucent_image_destroy(a);
    lucent_image_destroy(b);
}

TEST(compare_size_mismatch)
{
    lucent_image *a, *b, *m;
    CHECK_OK(lucent_image_create(64, 32, 3, &a));
    CHECK_OK(lucent_image_create(64, 48, 3, &b));
    lucent_image_error_stats e;
    CHECK_ERR(lucent_image_compare(a, b, NULL, &e), LUCENT_ERR_INVALID_ARGUMENT, "64x32", "64x48");
    CHECK_OK(lucent_image_create(32, 32, 1, &m));
    CHECK_ERR(lucent_image_compare_masked(a, a, m, &e), LUCENT_ERR_INVALID_ARGUMENT, "mask is 32x32", "64x32");
    lucent_image *d;
    CHECK_ERR(lucent_image_difference(a, b, LUCENT_DIFF_SIGNED, &d), LUCENT_ERR_INVALID_ARGUMENT, "64x48");
    CHECK(d == NULL);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
    lucent_image_destroy(m);
}

TEST(difference_error_map_heatmap)
{
    lucent_image *a, *b, *d, *map, *heat;
    CHECK_OK(lucent_image_create(2, 1, 4, &a));
    CHECK_OK(lucent_image_create(2, 1, 4, &b));
    const float av[8] = {1, 0, 3, 1, 0.5f, 0.5f, 0.5f, 1}, bv[8] = {2, 0, 1, 0, 0.5f, 0.5f, 0.5f, 1};
    memcpy(a->data, av, sizeof av);
    memcpy(b->data, bv, sizeof bv);
    CHECK_OK(lucent_image_difference(a, b, LUCENT_DIFF_SIGNED, &d));
    CHECK(d->data[0] == -1 && d->data[2] == 2 && d->data[3] == 1);
    lucent_image_destroy(d);
    CHECK_OK(lucent_image_difference(a, b, LUCENT_DIFF_ABSOLUTE, &d));
    CHECK(d->data[0] == 1 && d->data[2] == 2);
    lucent_image_destroy(d);
    /* pixel 0: |a-b| over RGB = (1, 0, 2) -> mean 1; relative (eps 0.01): (1/2.01 + 0 + 2/1.01) / 3 */
    CHECK_OK(lucent_image_error_map(a, b, false, 0, &map));
    CHECK(map->channels == 1);
    CHECK_NEAR(map->data[0], 1.0, 1e-7);
    CHECK(map->data[1] == 0.0f);
    lucent_image_destroy(map);
    CHECK_OK(lucent_image_error_map(a, b, true, 0, &map));
    CHECK_NEAR(map->data[0], (1 / 2.01 + 2 / 1.01) / 3, 1e-6);
    lucent_image_destroy(map);

    /* heat map: 0 -> black, >= scale -> white (the ends of the ramp) */
    CHECK_OK(lucent_image_create(3, 1, 1, &map));
    map->data[1] = 2.0f, map->data[2] = 9.0f;
    CHECK_OK(lucent_image_heatmap(map, 2.0f, &heat));
    CHECK(heat->channels == 3);
    CHECK(heat->data[0] == 0 && heat->data[1] == 0 && heat->data[2] == 0);
    for (int c = 3; c < 9; c++) CHECK_NEAR(heat->data[c], 1.0, 1e-6);
    lucent_image_destroy(heat);
    float p;
    CHECK_OK(lucent_image_percentile(map, 0, 50, &p)); /* nearest rank: ceil(0.5 * 3) = 2nd of 0 2 9 */
    CHECK(p == 2.0f);
    CHECK_OK(lucent_image_percentile(map, 0, 100, &p));
    CHECK(p == 9.0f);
    CHECK_ERR(lucent_image_heatmap(a, 1, &heat), LUCENT_ERR_INVALID_ARGUMENT, "4-channel");
    lucent_image_destroy(map);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
}

TEST(image_stats)
{
    lucent_image *img;
    CHECK_OK(lucent_image_create(3, 1, 1, &img));
    img->data[0] = -1, img->data[1] = 4, img->data[2] = NAN;
    lucent_image_stats st;
    lucent_image_stats_compute(img, &st);
    CHECK(st.min[0] == -1 && st.max[0] == 4 && st.mean[0] == 1.5 && st.nonfinite[0] == 1);
    lucent_image_destroy(img);
}

/* Labels: a minus sign is the middle row of its 5 x 7 cell (row 3), scaled by whole pixels; text is
 * clipped at the image's edges; widths are 6 pixels a glyph less the last gap. */
TEST(draw_text)
{
    lucent_image *img;
    CHECK_OK(lucent_image_create(20, 20, 3, &img));
    static const float white[3] = {1, 1, 1};
    lucent_image_draw_text(img, 1, 1, 2, white, "-");
    int set = 0, inside = 0;
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 20; x++)
            if (lucent_image_get(img, x, y, 1) == 1) set++, inside += x >= 1 && x < 11 && y >= 7 && y < 9;
    CHECK(set == 20 && inside == 20);
    lucent_image_draw_text(img, -7, 15, 3, white, "Skin1 mm^-1"); /* runs off both edges: clipped */
    CHECK(lucent_image_text_width("ab", 2) == 22 && lucent_image_text_width("", 3) == 0);
    lucent_image_destroy(img);
}

/* ---- FLIP (Andersson et al. 2020) ---- */

static lucent_image *uniform_image(int w, int h, float r, float g, float b)
{
    lucent_image *im = NULL;
    CHECK_OK(lucent_image_create(w, h, 3, &im));
    for (int i = 0; im && i < w * h; i++) im->data[3 * i] = r, im->data[3 * i + 1] = g, im->data[3 * i + 2] = b;
    return im;
}

/* Uniform fields, where the contrast sensitivity filters (normalised) change nothing and no edge or
 * point exists, so FLIP is the colour error of the two colours' HyAB distance, worked by hand from
 * the paper's equations (section 4.1; sRGB primaries, white D65, CIELAB with a and b times L / 100):
 *   the largest distance, green (L 87.74, a -86.18, b 83.18 -> Hunt -75.61, 72.98) against blue
 *   (L 32.30, a 79.19, b -107.86 -> Hunt 25.58, -34.84): 55.44 + hypot(101.19, 107.82) = 203.30
 *   (203.2973 with Lindbloom's sRGB matrix, which Lucent uses; 203.3017, evaluated in double, with
 *   the rational-form matrix of the reference implementation, NVlabs/flip src/cpp/FLIP.h at commit
 *   1eb247c, computeMaxDistance and LinearRGBToXYZ, lines 367-386 and 482-489);
 *   black against white: |0 - 100| = 100;
 *   the colour error e = d^0.7 against cmax^0.7 = 41.28: below p_c cmax^0.7 = 16.51 it is
 *   0.95 e / 16.51, above 0.95 + 0.05 (e - 16.51) / (41.28 - 16.51); 100^0.7 = 25.12 -> 0.96738.
 * And the paper's two anchors: the largest distance maps to 1, p_c of it (after the power) to p_t. */
TEST(flip_of_uniform_fields_follows_the_papers_colour_pipeline)
{
    const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1}, black[3] = {0, 0, 0}, white[3] = {1, 1, 1};
    double cmax = lucent_flip_hyab(green, blue);
    CHECK_NEAR(cmax, 203.30, 0.01);
    CHECK_NEAR(lucent_flip_hyab(black, white), 100, 1e-9);
    CHECK_NEAR(lucent_flip_color_error(cmax), 1, 1e-12);
    CHECK_NEAR(lucent_flip_color_error(cmax * pow(0.4, 1 / 0.7)), 0.95, 1e-12);
    CHECK(lucent_flip_color_error(0) == 0);
    lucent_image *a = uniform_image(24, 20, 0, 0, 0), *b = uniform_image(24, 20, 1, 1, 1);
    lucent_image *g = uniform_image(24, 20, 0, 1, 0), *u = uniform_image(24, 20, 0, 0, 1), *map = NULL;
    double mean;
    CHECK_OK(lucent_image_flip(a, b, LUCENT_FLIP_PPD, NULL, &map, &mean));
    CHECK_NEAR(mean, 0.96738, 2e-5);
    CHECK(map && map->channels == 1 && fabsf(map->data[0] - map->data[24 * 20 - 1]) < 1e-6f);
    lucent_image_destroy(map);
    CHECK_OK(lucent_image_flip(g, u, LUCENT_FLIP_PPD, NULL, NULL, &mean));
    CHECK_NEAR(mean, 1, 1e-6);
    CHECK_OK(lucent_image_flip(g, g, LUCENT_FLIP_PPD, NULL, NULL, &mean));
    CHECK(mean == 0);
    float mask[24 * 20] = {0};
    CHECK_OK(lucent_image_flip(a, b, LUCENT_FLIP_PPD, mask, NULL, &mean));
    CHECK(isnan(mean)); /* an empty mask: no mean */
    CHECK_ERR(lucent_image_flip(a, b, 0, NULL, NULL, &mean), LUCENT_ERR_INVALID_ARGUMENT, "pixels per degree");
    lucent_image *small = uniform_image(4, 4, 0, 0, 0);
    CHECK_ERR(lucent_image_flip(a, small, 67, NULL, NULL, &mean), LUCENT_ERR_INVALID_ARGUMENT, "flip");
    lucent_image_destroy(small);
    lucent_image_destroy(a), lucent_image_destroy(b), lucent_image_destroy(g), lucent_image_destroy(u);
}

/* The contrast sensitivity functions: a black and white checkerboard of 2-pixel period against its
 * mean grey (the grey whose luminance is the checkerboard's mean, linear 0.5). Seen from 67 pixels per
 * degree its frequency is 33.5 cycles per degree along both axes, where the achromatic CSF is
 * exp(-0.0047 (33.5^2 + 33.5^2)) = 3e-5 of its peak: the two look alike, FLIP near 0; from 2 pixels
 * per degree (1 cycle per degree, CSF 0.99) they differ as black and white differ from grey. */
TEST(flip_sees_fine_patterns_only_from_near)
{
    lucent_image *c = uniform_image(64, 64, 0, 0, 0), *grey = uniform_image(64, 64, 0.5f, 0.5f, 0.5f);
    for (int y = 0; c && y < 64; y++)
        for (int x = 0; x < 64; x++)
            for (int k = 0; k < 3; k++) c->data[3 * (y * 64 + x) + k] = (float)((x + y) % 2);
    double far, near;
    CHECK_OK(lucent_image_flip(grey, c, LUCENT_FLIP_PPD, NULL, NULL, &far));
    CHECK_OK(lucent_image_flip(grey, c, 2, NULL, NULL, &near));
    CHECK_MSG(far < 0.05, "FLIP at 67 ppd: %g", far); /* measured 0.004 and 0.998 */
    CHECK_MSG(near > 0.5, "FLIP at 2 ppd: %g", near);
    lucent_image_destroy(c), lucent_image_destroy(grey);
}

/* The heat map's colour bar: the ramp from black (0) to white (the scale) under the map, the map's
 * pixels as lucent_image_heatmap draws them; with a fixed scale one error has one colour in every map
 * (with the 99th percentile it depends on the rest of the map). */
TEST(heatmap_with_a_bar_and_a_fixed_scale)
{
    lucent_image *v1, *v2, *h1 = NULL, *h2 = NULL, *plain = NULL;
    CHECK_OK(lucent_image_create(10, 4, 1, &v1));
    CHECK_OK(lucent_image_create(10, 4, 1, &v2));
    for (int i = 0; i < 40; i++) v1->data[i] = i == 0 ? 0.1f : 10.0f, v2->data[i] = i == 0 ? 0.1f : 0.2f;
    float used;
    CHECK_OK(lucent_image_heatmap_with_bar(v1, 1.0f, "A-B", &h1, &used));
    CHECK(used == 1.0f && h1 && h1->width == 200 && h1->height > 4 + 12 && h1->channels == 3);
    CHECK_OK(lucent_image_heatmap(v1, 1.0f, &plain));
    for (int c = 0; c < 3 && h1 && plain; c++) CHECK(lucent_image_get(h1, 0, 0, c) == lucent_image_get(plain, 0, 0, c));
    /* the bar: 6 pixels under the map, from x = 8 (black) to x = 191 (white, the ramp's last stop) */
    for (int c = 0; c < 3 && h1; c++) {
        CHECK(lucent_image_get(h1, 8, 4 + 6 + 5, c) == 0.0f);
        CHECK_NEAR(lucent_image_get(h1, 191, 4 + 6 + 5, c), 1.0f, 1e-6);
    }
    CHECK_OK(lucent_image_heatmap_with_bar(v2, 1.0f, NULL, &h2, &used));
    for (int c = 0; c < 3 && h1 && h2; c++) CHECK(lucent_image_get(h1, 0, 0, c) == lucent_image_get(h2, 0, 0, c));
    lucent_image_destroy(h2);
    CHECK_OK(lucent_image_heatmap_with_bar(v2, 0, NULL, &h2, &used)); /* the 99th percentile: 0.2 */
    CHECK(used == 0.2f);
    for (int c = 0, differs = 0; c < 3 && h1 && h2; c++) {
        differs |= lucent_image_get(h1, 0, 0, c) != lucent_image_get(h2, 0, 0, c);
        if (c == 2) CHECK(differs);
    }
    lucent_image_destroy(v1), lucent_image_destroy(v2), lucent_image_destroy(h1), lucent_image_destroy(h2);
    lucent_image_destroy(plain);
}

/* ---- FLIP against the reference implementation (NVlabs/flip) ----
 * The reference's published test compares its mean over its own image pair (0.159691 for LDR-FLIP,
 * src/tests/test.py at commit 1eb247cabcf2862c2c8207ab15314304394132b9); that pair cannot be committed
 * or fetched here, so the expected values below are the reference's output on synthetic pairs built by
 * flip_pair() (the same formulas in float): its C++ FLIP::evaluate (src/cpp/FLIP.h at that commit, LDR,
 * its own float32 arithmetic, unchanged), called on linear RGB from a throwaway driver on 2026-12-07;
 * they are not published numbers. Each row: the pixels per degree, the pair, the reference's mean (its
 * float32 sum) and its map at the pixels (0, 0), (15, 16), (16, 16), (20, 5) and (17, 18), printed to 6
 * decimals. Tolerance 2e-4: the same reference code rebuilt in double moves its map by up to 1.3e-4 on
 * these pairs (float32 rounding, largest where the feature term sqrt(f) is near 0) and its means by up
 * to 6e-5; Lucent (double) differs from that double build by at most 3.3e-5 per pixel (the last digits
 * of the sRGB matrix: Lindbloom's against the reference's rational form); the printing adds 5e-7.
 * Before the blue-yellow filter's weights were corrected to the paper's a sqrt(pi / b) (flip.c), pairs
 * 3 and 4 differed by 6.7e-4 and 5.7e-4 at (15, 16), so the test separates them. */
#define FLIP_W 32
#define FLIP_H 32

/* The pairs (linear RGB): 0 black / white; 1 a black|white step edge / grey 0.5; 2 black / one white
 * pixel at (16, 16); 3 yellow|blue stripes 4 pixels wide / grey 0.5; 4 a smooth colour pattern / the
 * same with red compressed and blue raised in a box; 5 red/green stripes 3 pixels high / (0.5, 0.5, 0);
 * 7 (0.2, 0.4, 0.6) / grey 0.3; 8 red / green; 9 grey 0.5 / grey 0.25. */
static void flip_pair(int k, int test, float *im)
{
    for (int y = 0; y < FLIP_H; y++)
        for (int x = 0; x < FLIP_W; x++) {
            float r = 0, g = 0, b = 0;
            switch (k) {
            case 0: r = g = b = test ? 1.f : 0.f; break;
            case 1: r = g = b = test ? 0.5f : x < FLIP_W / 2 ? 0.f : 1.f; break;
            case 2: r = g = b = (test && x == 16 && y == 16) ? 1.f : 0.f; break;
            case 3:
                if (test)
                    r = g = b = 0.5f;
                else
                    r = g = (x / 4) % 2 == 0 ? 1.f : 0.f, b = 1.f - r;
                break;
            case 4:
                r = 0.5f + 0.4f * sinf(0.7f * (float)x + 0.3f * (float)y);
                g = 0.5f + 0.4f * sinf(0.2f * (float)x - 0.5f * (float)y + 1.f);
                b = 0.5f + 0.4f * cosf(0.4f * (float)x + 0.45f * (float)y);
                if (test) {
                    r = r * 0.8f + 0.1f;
                    if (x > 10 && x < 20 && y > 8 && y < 24) b = fminf(b + 0.15f, 1.f);
                }
                break;
            case 5:
                if (test)
                    r = g = 0.5f;
                else
                    r = (y / 3) % 2 == 0 ? 1.f : 0.f, g = 1.f - r;
                break;
            case 7:
                if (test)
                    r = g = b = 0.3f;
                else
                    r = 0.2f, g = 0.4f, b = 0.6f;
                break;
            case 8:
                if (test)
                    g = 1.f;
                else
                    r = 1.f;
                break;
            case 9: r = g = b = test ? 0.25f : 0.5f; break;
            }
            float *p = im + 3 * (y * FLIP_W + x);
            p[0] = r, p[1] = g, p[2] = b;
        }
}

TEST(flip_matches_the_reference_implementation_on_synthetic_pairs)
{
    /* The paper's observer: 0.7 m from a 0.7 m wide screen of 3840 pixels, ppd = d (N / w) pi / 180
     * (NVlabs/flip src/cpp/FLIP.h lines 110-118: calculatePPD(0.7, 3840, 0.7)); the paper rounds it to
     * 67 (LUCENT_FLIP_PPD). */
    const double ppd_paper = 0.7 * (3840 / 0.7) * M_PI / 180;
    CHECK_NEAR(ppd_paper, 67.0206, 1e-4);
    CHECK_NEAR(LUCENT_FLIP_PPD, ppd_paper, 0.05);
    static const struct {
        double ppd;
        int pair;
        double mean, px[5];
    } rows[] = {
        {0, 0, 0.967395, {0.967388, 0.967388, 0.967388, 0.967388, 0.967388}},
        {0, 1, 0.797866, {0.958551, 0.850504, 0.825644, 0.727782, 0.858716}},
        {0, 2, 0.013974, {0.000000, 0.763491, 0.864906, 0.000000, 0.390681}},
        {0, 3, 0.832804, {0.980888, 0.668102, 0.623844, 0.668102, 0.873061}},
        {0, 4, 0.138352, {0.084965, 0.248746, 0.280241, 0.059226, 0.340384}},
        {0, 5, 0.796084, {0.977045, 0.962478, 0.962478, 0.724996, 0.672590}},
        {0, 7, 0.490507, {0.490503, 0.490503, 0.490503, 0.490503, 0.490503}},
        {0, 8, 0.986679, {0.986665, 0.986665, 0.986665, 0.986665, 0.986665}},
        {0, 9, 0.451902, {0.451898, 0.451898, 0.451898, 0.451898, 0.451898}},
        {20, 1, 0.764690, {0.958553, 0.992985, 0.903390, 0.531256, 0.699689}},
        {20, 2, 0.002839, {0.000000, 0.433408, 0.989930, 0.000000, 0.000000}},
        {20, 3, 0.982641, {0.972666, 0.990522, 0.988799, 0.990522, 0.981403}},
        {20, 4, 0.168962, {0.027442, 0.281063, 0.318945, 0.069854, 0.426657}},
        {20, 5, 0.979892, {0.962657, 0.976625, 0.976625, 0.982427, 0.983401}},
    };
    static const int px[5][2] = {{0, 0}, {15, 16}, {16, 16}, {20, 5}, {17, 18}};
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        lucent_image *a = NULL, *b = NULL, *map = NULL;
        CHECK_OK(lucent_image_create(FLIP_W, FLIP_H, 3, &a));
        CHECK_OK(lucent_image_create(FLIP_W, FLIP_H, 3, &b));
        if (!a || !b) break;
        flip_pair(rows[r].pair, 0, a->data), flip_pair(rows[r].pair, 1, b->data);
        double ppd = rows[r].ppd > 0 ? rows[r].ppd : ppd_paper, mean = NAN;
        CHECK_OK(lucent_image_flip(a, b, ppd, NULL, &map, &mean));
        CHECK_MSG(fabs(mean - rows[r].mean) < 2e-4, "ppd %g pair %d: mean %.6f, reference %.6f", ppd, rows[r].pair,
                  mean, rows[r].mean);
        for (int i = 0; map && i < 5; i++) {
            double v = map->data[px[i][1] * FLIP_W + px[i][0]];
            CHECK_MSG(fabs(v - rows[r].px[i]) < 2e-4, "ppd %g pair %d at (%d, %d): %.6f, reference %.6f", ppd,
                      rows[r].pair, px[i][0], px[i][1], v, rows[r].px[i]);
        }
        /* Uniform pairs: no edge, no point, filters that change nothing, so the map is the colour error
         * of the two colours' HyAB distance (the public stages). */
        if (rows[r].pair == 0 || rows[r].pair >= 7) {
            float ca[3] = {a->data[0], a->data[1], a->data[2]}, cb[3] = {b->data[0], b->data[1], b->data[2]};
            double c = lucent_flip_color_error(lucent_flip_hyab(ca, cb));
            CHECK_MSG(fabs(c - rows[r].px[0]) < 2e-4, "pair %d: colour error %.6f, reference %.6f", rows[r].pair, c,
                      rows[r].px[0]);
        }
        lucent_image_destroy(map), lucent_image_destroy(a), lucent_image_destroy(b);
    }
}

/* The reach of the contrast sensitivity filters: the reference's radius, ceil(3 sqrt(b_max / (2 pi^2)) ppd)
 * pixels with b_max = 0.04 the widest Gaussian's (NVlabs/flip src/cpp/FLIP.h at commit 1eb247c, lines
 * 612-620): 10 at the paper's 67.02 ppd (3 x 0.04502 x 67.02 = 9.05), 3 at 20 ppd (2.70). One blue
 * pixel on black: the colour error, and so FLIP (0^x = 0), is non-zero exactly within that reach of it
 * along its row (the blue-yellow filter's tap at 10 pixels is exp(-pi^2 (10 / 67.02)^2 / 0.04) = 0.004
 * of its centre, far above rounding). */
TEST(flip_filters_reach_as_far_as_the_reference_radius)
{
    const double ppds[2] = {0.7 * (3840 / 0.7) * M_PI / 180, 20};
    const int reach[2] = {10, 3};
    for (int k = 0; k < 2; k++) {
        lucent_image *a = NULL, *b = NULL, *map = NULL;
        CHECK_OK(lucent_image_create(48, 5, 3, &a));
        CHECK_OK(lucent_image_create(48, 5, 3, &b));
        if (!a || !b) break;
        b->data[3 * (2 * 48 + 24) + 2] = 1; /* blue at (24, 2) */
        double mean;
        CHECK_OK(lucent_image_flip(a, b, ppds[k], NULL, &map, &mean));
        for (int x = 0; map && x < 48; x++) {
            int inside = abs(x - 24) <= reach[k];
            CHECK_MSG((map->data[2 * 48 + x] > 0) == inside, "ppd %g: FLIP %g at %d pixels from the point", ppds[k],
                      map->data[2 * 48 + x], x - 24);
        }
        lucent_image_destroy(map), lucent_image_destroy(a), lucent_image_destroy(b);
    }
}

TEST_MAIN(TEST_ENTRY(draw_text), TEST_ENTRY(flip_of_uniform_fields_follows_the_papers_colour_pipeline),
          TEST_ENTRY(flip_sees_fine_patterns_only_from_near),
          TEST_ENTRY(flip_matches_the_reference_implementation_on_synthetic_pairs),
          TEST_ENTRY(flip_filters_reach_as_far_as_the_reference_radius),
          TEST_ENTRY(heatmap_with_a_bar_and_a_fixed_scale), TEST_ENTRY(png_bomb_refused_from_the_header),
          TEST_ENTRY(exr_short_chunks_refused), TEST_ENTRY(exr_tiled_bomb_refused_from_the_chunk_table),
          TEST_ENTRY(exr_tiled_fixtures_read_and_truncations_refused),
          TEST_ENTRY(exr_chunk_table_checked_before_allocating), TEST_ENTRY(create_access_and_limits),
          TEST_ENTRY(convert_channels), TEST_ENTRY(srgb_curve_known_values), TEST_ENTRY(tonemap_operators),
          TEST_ENTRY(png_roundtrips), TEST_ENTRY(png_palette_written_by_libpng),
          TEST_ENTRY(png_grey_formats_written_by_libpng), TEST_ENTRY(png_malformed),
          TEST_ENTRY(exr_float_and_half_roundtrips), TEST_ENTRY(exr_grey_and_rgb),
          TEST_ENTRY(exr_tiled_written_by_openexr), TEST_ENTRY(exr_uint_channel_written_by_openexr),
          TEST_ENTRY(exr_malformed), TEST_ENTRY(pfm_roundtrip_exact), TEST_ENTRY(pfm_big_endian_bottom_up),
          TEST_ENTRY(pfm_malformed), TEST_ENTRY(write_into_missing_directory),
          TEST_ENTRY(write_into_read_only_directory), TEST_ENTRY(write_replaces_only_when_complete),
          TEST_ENTRY(rms_hand_computed), TEST_ENTRY(compare_size_mismatch), TEST_ENTRY(difference_error_map_heatmap),
          TEST_ENTRY(image_stats), TEST_ENTRY(draw_text))
