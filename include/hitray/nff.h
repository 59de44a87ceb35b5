/* hitray: reading NFF, the Neutral File Format of Eric Haines' Standard
 * Procedural Databases (SPD), the classic ray-tracing benchmark scenes.
 *
 * One entity a line: `v` (the camera: from, at, up, angle, hither,
 * resolution), `b` (background), `l` (a light, with or without a colour),
 * `f` (the material of what follows), `c` (open cone or cylinder), `s`
 * (sphere), `p` (polygon), `pp` (polygon with a normal at each vertex) and
 * `#` comments. docs/nff.md gives each field's meaning in Hill's model; in
 * short the scene follows the SPD's testing rules: four bounces
 * (maxRecursionDepth 4), every non-zero reflectance and transmittance
 * spawning its ray, lights without a colour 1/sqrt(number of lights) each.
 *
 * The readers are separate from SDL's (NFF is a different language, with
 * no file of its own to name); both fill the same hr_sdl_result. The
 * camera is always set from `v` when the file has one (has_camera 1), its
 * width and height from `resolution`; a file without `v` gets a camera that
 * frames the scene, at 640x480.
 *
 * hr_nff_load_file reads plain or gzip-compressed files alike (zlib tells
 * them apart by their first bytes, not by the name). On error it returns
 * HR_ERROR_SDL (a scene file's error; HR_ERROR_IO when the file cannot be
 * read), makes no scene, and the context's last error names file:line:col
 * and what was expected:
 *   balls.nff:12:3: expected 4 numbers after 's', found 'x'
 * Counts are checked against the text left before anything is allocated,
 * so no file can ask for more memory than its own size implies. */
#ifndef HITRAY_NFF_H
#define HITRAY_NFF_H

#include "common.h"
#include "sdl.h"

#ifdef __cplusplus
extern "C" {
#endif

HR_API hr_status hr_nff_load_file(hr_context *ctx, const char *path, hr_sdl_result *out);
/* `name` is used in messages (NULL: "<string>"). */
HR_API hr_status hr_nff_load_string(hr_context *ctx, const char *text, const char *name,
                                    hr_sdl_result *out);

#ifdef __cplusplus
}
#endif
#endif
