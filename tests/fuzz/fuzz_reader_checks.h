/* What the scene file harnesses (fuzz_sdl.c, fuzz_nff.c) check of a
 * reader's answer: a refusal names its place, and a scene read answers
 * Hill's queries with finite, sorted, consistent hits. */
#ifndef HITRAY_FUZZ_READER_CHECKS_H
#define HITRAY_FUZZ_READER_CHECKS_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/hitray.h>

/* A refusal of the text (`length` bytes) read as `name`: no scene, and,
 * but for running out of memory, a message starting "<name>:<line>:<col>: "
 * whose error info names the file and a place within the text. `tag` starts
 * the failure messages ("sdl"). */
void fuzz_reader_check_error(hr_context *ctx, const char *tag, const char *name, hr_status st,
                            const hr_sdl_result *r, size_t length);
/* Commits the scene read and casts five rays from the camera's eye
 * through the look point and around it, each through hr_scene_first_hit,
 * hr_scene_all_hits and hr_scene_shade. */
void fuzz_reader_check_rays(hr_context *ctx, const char *tag, const hr_sdl_result *r);

/* Whether `first`, hr_scene_first_hit's answer along `ray` over the
 * interval `all` (hr_scene_all_hits's list) was made for, is the first of
 * that list: its object's first hit listed at its t with its entering
 * flag, and every hit listed before it within 1e-6 of t (relative) or a
 * mesh crossing within twice its mesh's largest t error bound along the
 * line (fuzz_reader_checks.c says why). */
int fuzz_first_hit_is_first(const hr_scene *scene, const hr_ray *ray, const hr_hit *first,
                            const hr_intersection *all);

/* A reader under test: the text (a C string) read as `name`. */
typedef hr_status (*fuzz_reader_fn)(hr_context *ctx, const char *text, const char *name,
                                       hr_sdl_result *out);
/* One input: the bytes up to the first NUL read as scene text by `read`,
 * then the checks above on its answer. */
void fuzz_reader_input(hr_context *ctx, const char *tag, const char *name,
                      fuzz_reader_fn read, const uint8_t *data, size_t size);

#endif
