/* Errors: kept per context and per thread, passed to the callback, with
 * the file position parts for scene files. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *shared;

static void *make_error(void *arg)
{
    const char *name = arg;
    const hr_shape_class *cls;
    hr_context_find_shape_class(shared, name, &cls, NULL);
    /* This thread sees its own message, whatever the other thread did. */
    return (void *)(strstr(hr_context_last_error(shared), name) != NULL ? arg : NULL);
}

static int calls;
static hr_status last_status;
static void on_error(void *user, hr_status status, const char *message)
{
    (void)message;
    (*(int *)user)++;
    last_status = status;
}

int main(void)
{
    CHECK_OK(hr_context_create(&shared));
    CHECK(strcmp(hr_context_last_error(shared), "") == 0);
    pthread_t a, b;
    pthread_create(&a, NULL, make_error, "firstMissingShape");
    pthread_create(&b, NULL, make_error, "secondMissingShape");
    void *ra, *rb;
    pthread_join(a, &ra);
    pthread_join(b, &rb);
    CHECK(ra != NULL && rb != NULL);
    /* The main thread made no error. */
    CHECK(strcmp(hr_context_last_error(shared), "") == 0);

    hr_context_set_error_callback(shared, on_error, &calls);
    hr_scene *s;
    CHECK_OK(hr_scene_create(shared, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "noSuchShape";
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_MODULE);
    CHECK(calls == 1);
    CHECK(last_status == HR_ERROR_MODULE);
    hr_error_info info = {0};
    info.struct_size = sizeof info;
    CHECK_OK(hr_context_last_error_info(shared, &info));
    CHECK(info.status == HR_ERROR_MODULE);
    CHECK(strstr(info.message, "noSuchShape") != NULL);
    CHECK(info.line == 0 && strcmp(info.file, "") == 0);

    /* Bad arguments are refused, not crashed on. */
    CHECK(hr_scene_add_object(s, NULL, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_scene_commit(NULL) == HR_ERROR_INVALID_ARGUMENT);
    hr_ray ray = {{0, 0, 0}, {0, 0, 0}};
    hr_hit h;
    int32_t found;
    CHECK(hr_scene_first_hit(s, &ray, 0, 1, &h, &found) == HR_ERROR_STATE);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_first_hit(s, &ray, 0, 1, &h, &found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(shared), "zero vector") != NULL);
    ray.dir.x = NAN;
    CHECK(hr_scene_first_hit(s, &ray, 0, 1, &h, &found) == HR_ERROR_INVALID_ARGUMENT);
    /* Any one of the six numbers infinite or NaN is refused by every
     * query, with the same message; the largest finite numbers are not. */
    const double bad[3] = {INFINITY, -INFINITY, NAN};
    for (int k = 0; k < 6; k++)
        for (int v = 0; v < 3; v++) {
            hr_ray r = {{1, 2, 3}, {0, 0, -1}};
            double *field[6] = {&r.origin.x, &r.origin.y, &r.origin.z, &r.dir.x, &r.dir.y, &r.dir.z};
            *field[k] = bad[v];
            hr_intersection all;
            hr_intersection_init(&all);
            hr_color c;
            hr_status st[3] = {hr_scene_first_hit(s, &r, 0, 1, &h, &found),
                               hr_scene_all_hits(s, &r, 0, 1, &all), hr_scene_shade(s, &r, 0, &c)};
            for (int q = 0; q < 3; q++)
                CHECK_MSG(st[q] == HR_ERROR_INVALID_ARGUMENT, "component %d = %g, query %d: status %d",
                          k, bad[v], q, (int)st[q]);
            CHECK(strcmp(hr_context_last_error(shared), "ray: origin and direction must be finite") == 0);
            hr_intersection_release(&all);
        }
    hr_ray huge = {{DBL_MAX, -DBL_MAX, DBL_MAX}, {-DBL_MAX, DBL_MAX, -0.0}};
    CHECK_OK(hr_scene_first_hit(s, &huge, 0, 1, &h, &found));
    CHECK(strcmp(hr_status_name(HR_ERROR_SDL), "scene file error") == 0);
    hr_scene_destroy(s);
    hr_context_destroy(shared);
    return hr_test_end();
}
