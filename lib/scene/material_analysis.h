/* Internal: what commit works out of each material and light so that
 * shading tests one bit (scene_effects.c sets it, lib/trace/shade.c reads
 * it): the material flags, whether a light can add anything, and the Phong
 * term's cut-off. */
#ifndef HITRAY_LIB_SCENE_MATERIAL_ANALYSIS_H
#define HITRAY_LIB_SCENE_MATERIAL_ANALYSIS_H

#include <math.h>
#include <stdint.h>

#include <hitray/hitray.h>

#include "geometry/vec.h"

/* Per-material flags worked out at commit, so shade() tests one bit. */
#define HR_MAT_EMITS 1u
#define HR_MAT_AMBIENT 2u
#define HR_MAT_DIFFUSE 4u
#define HR_MAT_SPECULAR 8u
#define HR_MAT_REFLECTS 16u
#define HR_MAT_REFRACTS 32u
#define HR_MAT_INERT_LIGHT 64u /* some light cannot add to its diffuse or specular */
#define HR_MAT_COOK_TORRANCE 128u /* specularFraction > 0: Cook-Torrance, not Phong */
#define HR_MAT_TEXTURED 256u       /* it has a texture (hr_object.texture) */
/* Shading works on an adjusted copy of the material (lib/trace/shade.c). */
#define HR_MAT_ADJUSTED (HR_MAT_COOK_TORRANCE | HR_MAT_TEXTURED)

/* A light adds exactly nothing where, in every channel, its colour or
 * both of the material's lit coefficients are zero: no multiplication can
 * make that non-zero, so its shadow ray can be saved. Commit marks the
 * materials some light is inert for (HR_MAT_INERT_LIGHT); only their light
 * loops ask. Inline, as shade's light loop asks it. */
static inline int hri_light_adds_nothing(const hr_light *L, const hr_material *mat, uint32_t flags)
{
    hr_color d = flags & HR_MAT_DIFFUSE ? mat->diffuse : rgb(0, 0, 0);
    hr_color sp = flags & HR_MAT_SPECULAR ? mat->specular : rgb(0, 0, 0);
    return (L->color.r == 0.0 || (d.r == 0.0 && sp.r == 0.0)) &&
           (L->color.g == 0.0 || (d.g == 0.0 && sp.g == 0.0)) &&
           (L->color.b == 0.0 || (d.b == 0.0 && sp.b == 0.0));
}

/* The Phong term's cut-off (hr_object.specular_cutoff). Below it,
 * pow(phong, exponent) is exactly 0 in double, so shade can skip the call
 * and get the same bits: the exact power is below 2^-1100 there, 25 binades
 * under half the smallest subnormal (2^-1075), where pow's result, off from
 * the exact power by a few units in the last place at most, can only round
 * to 0. The SPD's materials use exponent 100000, where the cut-off is
 * 0.99240: most of a highlight's pow calls go. exp2's own rounding is
 * immaterial against that margin. */
static inline double hri_specular_cutoff(double exponent)
{
    /* exponent 0 (pow is 1 everywhere) and non-positive ones cut nothing. */
    return exponent > 0 ? exp2(-1100.0 / exponent) : 0.0;
}

/* The material flags of every object and the scene's effects, at commit
 * (scene_effects.c). */
void hri_scene_work_out_effects(hr_scene *s);

#endif
