/* The image formats hr_image_write knows, by name and by extension: the one
 * table that the writer's choice, the command line's --format and its
 * messages all read, so a format added here is known everywhere. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

typedef struct image_format {
    int32_t code;
    const char *name;          /* what --format takes */
    const char *extensions[2]; /* the first is the one messages suggest */
} image_format;

static const image_format formats[] = {
    {HR_FORMAT_PNG, "png", {".png", NULL}},
    {HR_FORMAT_EXR, "exr", {".exr", NULL}},
    {HR_FORMAT_PPM, "ppm", {".ppm", NULL}},
    {HR_FORMAT_PFM, "pfm", {".pfm", NULL}},
    {HR_FORMAT_JPEG, "jpeg", {".jpg", ".jpeg"}},
    {HR_FORMAT_HDR, "hdr", {".hdr", NULL}},
    {HR_FORMAT_BMP, "bmp", {".bmp", NULL}},
    {HR_FORMAT_TGA, "tga", {".tga", NULL}},
};
#define FORMAT_COUNT (int32_t)(sizeof formats / sizeof formats[0])

/* Case-insensitive "ends with", for extensions such as ".PNG". */
static int has_extension(const char *path, const char *ext)
{
    size_t np = strlen(path), ne = strlen(ext);
    if (np < ne) return 0;
    for (size_t i = 0; i < ne; i++)
        if (tolower((unsigned char)path[np - ne + i]) != ext[i]) return 0;
    return 1;
}

HR_API int32_t hr_image_format_from_path(const char *path)
{
    if (!path) return HR_FORMAT_AUTO;
    for (int32_t i = 0; i < FORMAT_COUNT; i++)
        for (int e = 0; e < 2 && formats[i].extensions[e]; e++)
            if (has_extension(path, formats[i].extensions[e])) return formats[i].code;
    return HR_FORMAT_AUTO;
}

HR_API int32_t hr_image_format_from_name(const char *name)
{
    if (!name) return HR_FORMAT_AUTO;
    for (int32_t i = 0; i < FORMAT_COUNT; i++)
        if (!strcmp(name, formats[i].name)) return formats[i].code;
    return HR_FORMAT_AUTO;
}

static const image_format *find(int32_t code)
{
    for (int32_t i = 0; i < FORMAT_COUNT; i++)
        if (formats[i].code == code) return &formats[i];
    return NULL;
}

HR_API const char *hr_image_format_name(int32_t format)
{
    const image_format *f = find(format);
    return f ? f->name : NULL;
}

HR_API const char *hr_image_format_extension(int32_t format)
{
    const image_format *f = find(format);
    return f ? f->extensions[0] : NULL;
}

HR_API void hr_image_format_list(char *buf, size_t size)
{
    if (!buf || size == 0) return;
    buf[0] = '\0';
    size_t used = 0;
    for (int32_t i = 0; i < FORMAT_COUNT && used < size; i++) {
        const char *sep = i == 0 ? "" : i + 1 == FORMAT_COUNT ? " or " : ", ";
        int n = snprintf(buf + used, size - used, "%s%s", sep, formats[i].extensions[0]);
        if (n < 0) return;
        used += (size_t)n;
    }
}
