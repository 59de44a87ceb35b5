/* Internal: textures (Hill, chapter 8), which modulate a material's ambient
 * and diffuse colours at each hit.
 *
 * - Solid textures (texture < 0): a colour at a point of the object's own
 *   space, so the texture moves and scales with the object. Each one is a
 *   function and a row of the table in texture_solid.c; a fifth is one more
 *   of each there.
 * - Image textures (texture N > 0): pixmap N (hr_scene_set_pixmap) laid on
 *   the surface by the (u, v) its class gives (hr_shape_class.surface_uv).
 *
 * An object whose material has a texture gets an hr_texture when it is
 * added (its parameters checked and filled in with their defaults, its
 * pixmap found) and its world-to-object map at commit. Nothing else is
 * kept, so an untextured object costs shading one test of a NULL pointer. */
#ifndef HITRAY_LIB_TEXTURE_H
#define HITRAY_LIB_TEXTURE_H

#include <hitray/hitray.h>

#include "geometry/vec.h"

/* The most parameters a texture reads; a material giving more is refused. */
#define HR_TEXTURE_MAX_PARAMS 16

/* What one parameter of a texture may be. */
#define HR_TEXTURE_PARAM_ANY 0      /* finite, within [min, max] */
#define HR_TEXTURE_PARAM_POSITIVE 1 /* finite, > 0 and <= max */
#define HR_TEXTURE_PARAM_WHOLE 2    /* a whole number within [min, max] */

typedef struct hr_texture_param {
    const char *name;
    double default_value;
    int32_t kind; /* HR_TEXTURE_PARAM_* */
    double min, max;
} hr_texture_param;

/* A hit's footprint as texture.c filters it: the parallelogram of sides
 * na pa and nb pb centred on q, cut into na x nb pieces of sides pa and
 * pb, each filtered by the box +- half around its centre. */
typedef struct hri_footprint_pieces {
    hr_vec3 q, pa, pb, half;
    int na, nb;
} hri_footprint_pieces;

/* The mean of `box` (a kind's solid_box) over the pieces of f, in one
 * order (so one value, bit for bit, wherever it is inlined). */
static inline __attribute__((always_inline)) hr_color
hri_footprint_mean(hr_color (*box)(const double *, hr_vec3, hr_vec3), const double *params,
                   const hri_footprint_pieces *f)
{
    if (f->na == 1 && f->nb == 1) return box(params, f->q, f->half);
    hr_color sum = rgb(0.0, 0.0, 0.0);
    for (int i = 0; i < f->na; i++)
        for (int j = 0; j < f->nb; j++) {
            const hr_vec3 c = v3_madd(v3_madd(f->q, f->pa, i + 0.5 - 0.5 * f->na), f->pb, j + 0.5 - 0.5 * f->nb);
            sum = rgb_add(sum, box(params, c, f->half));
        }
    return rgb_scale(sum, 1.0 / (f->na * f->nb));
}

/* One kind of texture: a solid texture (`solid` set), or the image texture
 * (`solid` NULL), whose parameters say how (u, v) map onto the pixmap. */
typedef struct hr_texture_kind {
    int32_t id; /* the material's texture number; 1 stands for every N > 0 */
    const char *name;
    const hr_texture_param *params;
    int32_t param_count;
    /* The colour at object-space point p, given every parameter (the
     * material's, then defaults); reentrant, allocation-free, finite. */
    hr_color (*solid)(const double *params, hr_vec3 p);
    /* The colour averaged over the box p +- half (object space, each half
     * >= 0), for filtering by a hit's footprint; with half = 0, solid's
     * colour bit for bit. NULL: the texture has no filtered form. */
    hr_color (*solid_box)(const double *params, hr_vec3 p, hr_vec3 half);
    /* hri_footprint_mean of solid_box, the same bit for bit, for a kind
     * that runs it faster in one call; NULL: texture.c runs
     * hri_footprint_mean itself. */
    hr_color (*solid_footprint)(const double *params, const hri_footprint_pieces *f);
} hr_texture_kind;

/* The solid texture numbered `id` (< 0), NULL if there is none; the
 * public hr_solid_texture_name gives its name, and lib/util/solid_textures.h
 * the list for messages. */
const hr_texture_kind *hri_solid_texture_find(int32_t id);
/* The parameters of an image texture (texture N > 0). */
extern const hr_texture_kind hri_image_texture_kind;
#define HR_IMAGE_PARAM_UMIN 0
#define HR_IMAGE_PARAM_UMAX 1
#define HR_IMAGE_PARAM_VMIN 2
#define HR_IMAGE_PARAM_VMAX 3
#define HR_IMAGE_PARAM_NEAREST 4

/* Hill's lattice noise (texture_noise.c): a value in [0, 1) at p, smooth,
 * the same on every machine (a fixed integer hash of the lattice points, no
 * table to set up, no rand()); and his turbulence, `octaves` layers of it at
 * doubling frequency and halving weight, normalised to [0, 1). */
double hri_noise(hr_vec3 p);
double hri_turbulence(hr_vec3 p, int32_t octaves);

/* One of a scene's pixmaps (pixmap.c): linear RGB floats, rows from the top,
 * and its mip-map, built when it is made: level 0 the image, each level
 * after it half the one before in each direction (rounded up, down to
 * 1 x 1), each texel the mean of the 2 x 2 texels it covers (the box
 * filter of the level below; an odd side's last texel pairs with the
 * first, as the texture tiles). */
#define HR_PIXMAP_MAX_LEVELS 32
typedef struct hr_pixmap {
    int32_t index;
    int32_t width, height;
    float *rgb; /* level 0: levels[0] */
    int32_t level_count;
    int32_t level_width[HR_PIXMAP_MAX_LEVELS], level_height[HR_PIXMAP_MAX_LEVELS];
    float *levels[HR_PIXMAP_MAX_LEVELS];
} hr_pixmap;
/* The pixmap's colour at (s, t) in [0, 1) x [0, 1), s across from the left,
 * t up from the bottom: bilinear between the four nearest texel centres,
 * wrapping at the edges (a texture tiles), or the nearest texel. */
hr_color hri_pixmap_sample(const hr_pixmap *pm, double s, double t, int nearest);
/* Trilinear: the colour at (s, t) filtered by a footprint whose sides are
 * (ds/dx, dt/dx) = d[0], d[1] and (ds/dy, dt/dy) = d[2], d[3]: bilinear in
 * the two mip levels whose texels bracket the footprint's longer side,
 * blended by the level's fraction (the image itself where the footprint is
 * under a texel). */
hr_color hri_pixmap_sample_footprint(const hr_pixmap *pm, double s, double t, const double d[4]);
/* Bilinear in mip level `level` of pm (level 0: hri_pixmap_sample's). */
hr_color hri_pixmap_sample_level(const hr_pixmap *pm, int32_t level, double s, double t);
/* A scene's pixmaps (hr_scene.pixmaps), each on its own allocation, so
 * the textures that use one hold its address across later additions. */
typedef struct hr_pixmap_set {
    hr_pixmap **pixmaps;
    int32_t count, cap;
} hr_pixmap_set;
/* Pixmap `index` of the set, NULL if it is not made. */
const hr_pixmap *hri_pixmap_find(const hr_pixmap_set *set, int32_t index);
/* Adds pixmap `index` (>= 1, not made yet) with the pixels of `image`
 * (RGB or RGBA, each finite and within +-HR_MAX_COLOR), raising the error
 * on ctx when it cannot. */
hr_status hri_pixmap_add(hr_context *ctx, hr_pixmap_set *set, int32_t index, const hr_image *image);
/* The bytes pixmap `index` of `image` keeps (its texels as RGB floats),
 * and its name for messages, "pixmap N (W x H texels)", into `what`. */
uint64_t hri_pixmap_bytes(const hr_image *image, int32_t index, char *what, size_t what_size);
/* The bytes a w x h pixmap's mip levels above level 0 take. */
uint64_t hri_pixmap_mip_bytes(int32_t w, int32_t h);
void hri_pixmap_set_free(hr_pixmap_set *set);

/* What an object's texture needs at a hit. */
typedef struct hr_texture {
    const hr_texture_kind *kind;
    const hr_pixmap *pixmap; /* image textures */
    double params[HR_TEXTURE_MAX_PARAMS];
    double to_object[16]; /* world -> the object's own space (through every
                             composite above it) */
    double to_world[16];  /* and back, for the normal */
} hr_texture;

/* At hr_scene_add_object, after the shape is made: checks the material's
 * texture and parameters and sets *out (NULL when untextured or a
 * composite, whose hits carry its leaves' materials); refuses an image
 * texture on a class that gives no (u, v), or whose pixmap is not in
 * `pixmaps`, naming the class, the module and the number. */
hr_status hri_texture_bind(hr_context *ctx, const hr_material *m, const hr_shape_class *cls,
                          const void *shape, const char *module_path, const hr_pixmap_set *pixmaps,
                          hr_texture **out);
/* The colour that multiplies the material's ambient and diffuse colours at
 * `hit` (world space, as shade has it) of an object of class `cls` and shape
 * `shape` textured by `t`; t's maps (to_object, to_world) are set at commit
 * (lib/scene/scene_effects.c). */
hr_color hri_texture_color(const hr_texture *t, const hr_shape_class *cls, const void *shape,
                          const hr_hit *hit);
/* The same colour averaged over the hit's footprint, the pixel's extent on
 * the surface (world space: dp/dx and dp/dy, from ray differentials): a
 * solid texture over the box bounding it in the object's space (its
 * solid_box; point-sampled where it has none), an image texture by its
 * mip-map over the footprint's extent in (s, t) (point-sampled where the
 * material asks for the nearest texel). */
hr_color hri_texture_color_filtered(const hr_texture *t, const hr_shape_class *cls, const void *shape,
                                   const hr_hit *hit, hr_vec3 dpdx, hr_vec3 dpdy);

#endif
