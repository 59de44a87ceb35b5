/* A test module: a sphere of radius `radius` (a probe of the module ABI).
 * Its parameter `refuse` makes create fail, to test how refusals reach the
 * caller; `count_calls` is not global state but a per-shape counter. */
#include <math.h>
#include <stdio.h>

#include <hitray/shape_module.h>

typedef struct probe {
    double radius;
    const hr_host *host;
} probe;

static const hr_param_spec params[] = {
    {"radius", HR_PARAM_NUMBER, 0, 1.0, 1e-6, 100.0, "radius of the probe sphere", 0},
    {"refuse", HR_PARAM_NUMBER, 0, 0.0, 0.0, 1.0, "1: create refuses", 0},
    {"label", HR_PARAM_STRING, 0, 0.0, 1.0, 0.0, "any text", 0},
};

static hr_status create(const hr_create_args *a, void **out)
{
    if (a->params[1].number == 1.0) {
        snprintf(a->error, a->error_size, "parameter 'refuse' is 1, so this probe refuses");
        return HR_ERROR_PARAMETER;
    }
    probe *p = a->host->alloc(sizeof *p);
    if (!p) return HR_ERROR_OUT_OF_MEMORY;
    p->radius = a->params[0].number;
    p->host = a->host;
    *out = p;
    return HR_OK;
}

static void destroy(void *shape)
{
    probe *p = shape;
    p->host->free(p);
}

static void bounds(const void *shape, hr_bounds *b)
{
    double r = ((const probe *)shape)->radius;
    b->lo.x = b->lo.y = b->lo.z = -r;
    b->hi.x = b->hi.y = b->hi.z = r;
}

/* Plain textbook quadratic: this module tests plumbing, not numerics. */
static hr_status hit(const hr_hit_args *a)
{
    const probe *p = a->shape;
    const hr_vec3 o = a->ray.origin, d = a->ray.dir;
    double A = d.x * d.x + d.y * d.y + d.z * d.z;
    double B = o.x * d.x + o.y * d.y + o.z * d.z;
    double C = o.x * o.x + o.y * o.y + o.z * o.z - p->radius * p->radius;
    double disc = B * B - A * C;
    if (disc < 0) return HR_OK;
    double s = sqrt(disc);
    double ts[2] = {(-B - s) / A, (-B + s) / A};
    for (int i = 0; i < 2; i++) {
        if (!(ts[i] > a->tmin && ts[i] < a->tmax)) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        h->t = ts[i];
        h->point.x = o.x + ts[i] * d.x, h->point.y = o.y + ts[i] * d.y, h->point.z = o.z + ts[i] * d.z;
        h->normal = h->point;
        h->error = 1e-9;
        h->surface = 0;
        h->entering = i == 0;
    }
    return HR_OK;
}

static const hr_shape_class probe_class = {
    sizeof(hr_shape_class), HR_SHAPE_CLOSED, "probeSphere", "test sphere", params, 3, 1,
    create, destroy, bounds, hit, NULL, NULL, NULL, NULL, NULL, 0};
static const hr_shape_class *const classes[] = {&probe_class};
static const hr_module_info info = {sizeof info, HR_SHAPE_ABI_VERSION, "probe", "test module",
                                    classes, 1, "1.2.3", "the probe's author", NULL};

HR_DEFINE_SHAPE_MODULE(host_version, host)
{
    (void)host;
    return host_version == HR_SHAPE_ABI_VERSION ? &info : NULL;
}
