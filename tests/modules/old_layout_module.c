/* A test module built against an older, shorter hr_shape_class: it declares
 * only the fields up to `hit` (no first_hit, any_hit). The host must read
 * only those bytes and fall back to `hit` for the fast paths. The bytes after
 * the declared size hold garbage on purpose. */
#include <stddef.h>

#include <hitray/shape_module.h>

typedef struct old_class {
    hr_shape_class head;    /* only the first `struct_size` bytes are real */
} old_class;

static char token;

static hr_status create(const hr_create_args *a, void **out)
{
    (void)a;
    *out = &token; /* no per-object state: a unit slab |z| <= 1 */
    return HR_OK;
}
static void destroy(void *shape) { (void)shape; }
static void bounds(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo.x = b->lo.y = b->lo.z = -1;
    b->hi.x = b->hi.y = b->hi.z = 1;
}
/* The cube [-1,1]^3 hit only on its z faces, enough for a plumbing test. */
static hr_status hit(const hr_hit_args *a)
{
    double oz = a->ray.origin.z, dz = a->ray.dir.z;
    if (dz == 0) return HR_OK;
    double t0 = (-1 - oz) / dz, t1 = (1 - oz) / dz;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    double ts[2] = {t0, t1};
    for (int i = 0; i < 2; i++) {
        double x = a->ray.origin.x + ts[i] * a->ray.dir.x, y = a->ray.origin.y + ts[i] * a->ray.dir.y;
        if (!(ts[i] > a->tmin && ts[i] < a->tmax) || x < -1 || x > 1 || y < -1 || y > 1) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        h->t = ts[i];
        h->point.x = x, h->point.y = y, h->point.z = a->ray.origin.z + ts[i] * dz;
        h->normal.x = 0, h->normal.y = 0, h->normal.z = h->point.z > 0 ? 1 : -1;
        h->error = 1e-12;
        h->entering = i == 0;
    }
    return HR_OK;
}

static hr_shape_class make_class(void);
static hr_shape_class the_class;
static const hr_shape_class *classes[1];
static hr_module_info info;

static hr_shape_class make_class(void)
{
    hr_shape_class c = {0};
    c.struct_size = (uint32_t)(offsetof(hr_shape_class, hit) + sizeof(hr_hit_fn));
    c.flags = HR_SHAPE_CLOSED;
    c.name = "oldSlab";
    c.help = "a class table from an older ABI minor revision";
    c.create = create;
    c.destroy = destroy;
    c.bounds = bounds;
    c.hit = hit;
    /* Past the declared size: must be ignored by the host. */
    c.first_hit = (hr_hit_fn)(uintptr_t)0x1;
    c.any_hit = (hr_hit_fn)(uintptr_t)0x1;
    return c;
}

HR_DEFINE_SHAPE_MODULE(host_version, host)
{
    (void)host_version;
    (void)host;
    the_class = make_class();
    classes[0] = &the_class;
    /* An info from before the metadata fields; what lies past its size
     * must not be read. */
    info.struct_size = (uint32_t)offsetof(hr_module_info, version);
    info.version = "past the declared size";
    info.abi_version = HR_SHAPE_ABI_VERSION;
    info.name = "old_abi_layout";
    info.description = "test: short class table";
    info.classes = classes;
    info.class_count = 1;
    return &info;
}
