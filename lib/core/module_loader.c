/* Shape modules: found on the search path (explicit directories, then
 * HITRAY_SHAPE_PATH, then hitray/shapes next to the library file), loaded
 * with dlopen, checked (entry point, ABI version, complete vtables) and
 * copied into full-size class tables so an older, smaller hr_shape_class
 * keeps working. Every refusal names the module's path. */
#include <dirent.h>
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "util/sized_copy.h"
#include "util/errors.h"
#include "core/module_loader.h"
#include "util/strutil.h"
#include "util/suggest.h"

#define REFUSAL_SIZE 1024

/* Free the copies of the classes taken so far (class_count of them). */
static void drop_classes(hr_module *m)
{
    for (int32_t i = 0; i < m->class_count; i++) free((void *)m->classes[i].params);
    free(m->classes);
    m->classes = NULL;
    free(m->class_ptrs);
    m->class_ptrs = NULL;
    m->class_count = 0;
}

static void module_free(hr_module *m)
{
    if (!m) return;
    drop_classes(m);
    if (m->handle) dlclose(m->handle);
    free(m->path);
    free(m->error);
    free(m);
}

void hri_modules_unload_all(hr_context *ctx)
{
    for (int32_t i = 0; i < ctx->module_count; i++) module_free(ctx->modules[i]);
    free(ctx->modules);
    ctx->modules = NULL;
    ctx->module_count = 0;
    free(ctx->classes);
    ctx->classes = NULL;
    ctx->class_count = 0;
    ctx->last_found.cls = NULL;
}

static void refuse(hr_module *m, const char *fmt, ...) HR_PRINTF(2, 3);
static void refuse(hr_module *m, const char *fmt, ...)
{
    char buf[REFUSAL_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    free(m->error);
    m->error = hri_strdup(buf);
}

/* Copy a class declared with `struct_size` bytes into a zeroed full-size
 * struct, and check the fields every class must have. Returns 0 and sets
 * the module's error on a refusal. */
static int copy_class(hr_module *m, const hr_shape_class *src, hr_shape_class *dst)
{
    size_t required = offsetof(hr_shape_class, hit) + sizeof(src->hit);
    if (!src || src->struct_size < required) {
        refuse(m, "shape module '%s': a class table is too small (%u bytes)", m->path,
               src ? src->struct_size : 0u);
        return 0;
    }
    memset(dst, 0, sizeof *dst);
    HR_SIZED_COPY_IN(dst, src);
    /* The module's specs are read through their declared stride into the
     * host's own full-size copy (dst->params, freed with the class). */
    const char *given = (const char *)dst->params;
    dst->params = NULL;
    const size_t first_layout = offsetof(hr_param_spec, help) + sizeof(const char *);
    const size_t flags_layout = (offsetof(hr_param_spec, flags) + sizeof(int32_t) + 7) & ~(size_t)7;
    const size_t stride = dst->param_spec_size       ? dst->param_spec_size
                          : HR_CLASS_HAS(src, param_spec_size) ? flags_layout
                                                             : first_layout;
    dst->param_spec_size = (uint32_t)sizeof(hr_param_spec);
    const char *name = dst->name && *dst->name ? dst->name : "(unnamed)";
    if (!dst->name || !*dst->name || !dst->create || !dst->destroy || !dst->bounds || !dst->hit ||
        dst->param_count < 0 || (dst->param_count > 0 && !given)) {
        refuse(m, "shape module '%s': class '%s' lacks a name, create, destroy, bounds or hit",
               m->path, name);
        return 0;
    }
    if (stride < first_layout) {
        refuse(m, "shape module '%s': class '%s' declares parameter specs of %zu bytes, fewer "
                  "than the %zu of the first layout",
               m->path, name, stride, first_layout);
        return 0;
    }
    hr_param_spec *specs = NULL;
    if (dst->param_count > 0 && !(specs = calloc((size_t)dst->param_count, sizeof *specs))) {
        refuse(m, "shape module '%s': out of memory", m->path);
        return 0;
    }
    const int32_t known_flags = HR_PARAM_MIN_EXCLUSIVE | HR_PARAM_MAX_EXCLUSIVE;
    for (int32_t i = 0; i < dst->param_count; i++) {
        hr_param_spec *p = &specs[i];
        memcpy(p, given + (size_t)i * stride, stride < sizeof *p ? stride : sizeof *p);
        if (!p->name || !*p->name || p->type < HR_PARAM_NUMBER || p->type > HR_PARAM_NUMBERS ||
            (p->flags & ~known_flags)) {
            refuse(m, "shape module '%s': class '%s' has a malformed parameter %d", m->path,
                   name, (int)i);
            free(specs);
            return 0;
        }
    }
    dst->params = specs;
    return 1;
}

/* Take the classes of a module's info; sets m->error on a refusal. */
static int adopt_classes(hr_module *m, const hr_module_info *info)
{
    if (info->class_count < 0 || (info->class_count > 0 && !info->classes)) {
        refuse(m, "shape module '%s': malformed class list", m->path);
        return 0;
    }
    int32_t n = info->class_count;
    m->classes = calloc((size_t)(n > 0 ? n : 1), sizeof *m->classes);
    m->class_ptrs = calloc((size_t)(n > 0 ? n : 1), sizeof *m->class_ptrs);
    if (!m->classes || !m->class_ptrs) {
        refuse(m, "shape module '%s': out of memory", m->path);
        return 0;
    }
    for (int32_t i = 0; i < n; i++) {
        if (!copy_class(m, info->classes[i], &m->classes[i])) return 0;
        m->class_ptrs[i] = &m->classes[i];
        m->class_count = i + 1;
    }
    m->info = info;
    return 1;
}

/* Open one file. Always returns a module record (NULL only when out of
 * memory); a refused one has `error` set and no handle. */
static hr_module *load_file(hr_context *ctx, const char *path)
{
    hr_module *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    m->path = hri_strdup(path);
    if (!m->path) {
        free(m);
        return NULL;
    }
    dlerror();
    m->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!m->handle) {
        const char *why = dlerror();
        refuse(m, "cannot load shape module '%s': %s", path, why ? why : "unknown error");
        return m;
    }
    hr_shape_module_fn entry;
    void *sym = dlsym(m->handle, HR_SHAPE_MODULE_ENTRY_NAME);
    /* POSIX guarantees a data pointer from dlsym converts to a function. */
    memcpy(&entry, &sym, sizeof entry);
    const hr_module_info *info = NULL;
    if (!sym) {
        refuse(m, "shape module '%s' has no entry point '%s'", path, HR_SHAPE_MODULE_ENTRY_NAME);
    } else if (!(info = entry(HR_SHAPE_ABI_VERSION, &ctx->host))) {
        refuse(m, "shape module '%s' refused this host (shape ABI version %u)", path,
               HR_SHAPE_ABI_VERSION);
    } else if (info->abi_version != HR_SHAPE_ABI_VERSION) {
        refuse(m, "shape module '%s' was built for shape ABI version %u; this hitray "
                  "provides version %u",
               path, info->abi_version, HR_SHAPE_ABI_VERSION);
    } else if (info->struct_size < offsetof(hr_module_info, class_count) + sizeof(int32_t)) {
        refuse(m, "shape module '%s': its module info is too small", path);
    } else {
        adopt_classes(m, info);
    }
    if (m->error) {
        dlclose(m->handle);
        m->handle = NULL;
        drop_classes(m);
        m->info = NULL;
    }
    return m;
}

static int append_module(hr_context *ctx, hr_module *m)
{
    hr_module **mods = realloc(ctx->modules, (size_t)(ctx->module_count + 1) * sizeof *mods);
    if (!mods) return 0;
    mods[ctx->module_count++] = m;
    ctx->modules = mods;
    return 1;
}

static int known_path(const hr_context *ctx, const char *path)
{
    for (int32_t i = 0; i < ctx->module_count; i++)
        if (strcmp(ctx->modules[i]->path, path) == 0) return 1;
    return 0;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* A module found in a directory anyone may write to is not loaded: anyone
 * could have put it there, and loading it runs their code. It is listed as
 * refused (hr_context_module, `hitray shapes`), so the refusal is seen. */
static hr_module *refused_insecure(const char *path, const char *dir)
{
    hr_module *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    if (!(m->path = hri_strdup(path))) {
        free(m);
        return NULL;
    }
    refuse(m, "shape module '%s' not loaded: its directory '%s' is writable by every user (anyone "
              "could have put code there); make it writable by its owner only",
           path, dir);
    return m;
}

/* Load every *.so in dir, in name order so the result never depends on the
 * file system's listing order. A missing directory is not an error. */
static void scan_dir(hr_context *ctx, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct stat st;
    const int insecure = fstat(dirfd(d), &st) == 0 && (st.st_mode & S_IWOTH);
    char **names = NULL;
    size_t count = 0, cap = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' || !hri_str_ends_with(e->d_name, ".so")) continue;
        if (count == cap) {
            size_t ncap = cap ? cap * 2 : 16;
            char **grown = realloc(names, ncap * sizeof *grown);
            if (!grown) break;
            names = grown;
            cap = ncap;
        }
        if (!(names[count] = hri_strdup(e->d_name))) break;
        count++;
    }
    closedir(d);
    /* qsort's base must not be NULL even for no elements (a directory with
     * no module never allocated the list). */
    if (count > 1) qsort(names, count, sizeof *names, compare_names);
    for (size_t i = 0; i < count; i++) {
        char *path = hri_path_join(dir, names[i]);
        if (path && !known_path(ctx, path)) {
            hr_module *m = insecure ? refused_insecure(path, dir) : load_file(ctx, path);
            if (m && !append_module(ctx, m)) module_free(m);
        }
        free(path);
        free(names[i]);
    }
    free(names);
}

/* hitray/shapes next to the file this function lives in (libhitray). */
static char *default_shape_dir(void)
{
    Dl_info info;
    if (!dladdr((void *)&default_shape_dir, &info) || !info.dli_fname) return NULL;
    /* The loader reports the path it was given (often bin/../lib/...); the
     * canonical one reads better in messages and `hitray shapes`. */
    char *real = realpath(info.dli_fname, NULL);
    char *libdir = hri_path_dirname(real ? real : info.dli_fname);
    free(real);
    if (!libdir) return NULL;
    char *dir = hri_path_join(libdir, "hitray/shapes");
    free(libdir);
    return dir;
}

/* The search path as one list, for reading and for messages. */
static void for_each_search_dir(hr_context *ctx, void (*fn)(hr_context *, const char *, void *),
                                void *user)
{
    for (int32_t i = 0; i < ctx->dir_count; i++) fn(ctx, ctx->dirs[i], user);
    const char *env = getenv("HITRAY_SHAPE_PATH");
    if (env && *env) {
        char *copy = hri_strdup(env);
        char *save = NULL;
        for (char *tok = copy ? strtok_r(copy, ":", &save) : NULL; tok;
             tok = strtok_r(NULL, ":", &save))
            fn(ctx, tok, user);
        free(copy);
    }
    char *def = default_shape_dir();
    if (def) fn(ctx, def, user);
    free(def);
}

static void scan_one(hr_context *ctx, const char *dir, void *user)
{
    (void)user;
    scan_dir(ctx, dir);
}

static void scan_search_path(hr_context *ctx)
{
    if (ctx->scanned) return;
    for_each_search_dir(ctx, scan_one, NULL);
    ctx->scanned = 1;
}

static const hr_class_entry *find_loaded(const hr_context *ctx, const char *name,
                                         hr_class_entry *scratch)
{
    for (int32_t i = 0; i < ctx->class_count; i++)
        if (strcmp(ctx->classes[i].cls->name, name) == 0) return &ctx->classes[i];
    for (int32_t i = 0; i < ctx->module_count; i++) {
        const hr_module *m = ctx->modules[i];
        for (int32_t j = 0; j < m->class_count; j++)
            if (strcmp(m->classes[j].name, name) == 0) {
                scratch->cls = &m->classes[j];
                scratch->origin = m->path;
                return scratch;
            }
    }
    return NULL;
}

typedef struct search_listing {
    char text[2048];
    size_t len;
} search_listing;

static void list_one(hr_context *ctx, const char *dir, void *user)
{
    (void)ctx;
    search_listing *l = user;
    if (l->len >= sizeof l->text) return;
    int n = snprintf(l->text + l->len, sizeof l->text - l->len, "%s%s", l->len ? ", " : "", dir);
    if (n > 0) l->len += (size_t)n;
}

/* Errors found while holding ctx->lock are written to a buffer and raised
 * after unlocking: raising calls the context's error callback, which may call
 * back into the context (list its modules, say) and would deadlock. */
#define MESSAGE_SIZE (2 * 2048 + 256) /* not_found's two lists and more */

/* "no shape module provides 'x'" with where we looked and what was refused,
 * into msg. */
static hr_status not_found(hr_context *ctx, const char *name, char *msg, size_t size)
{
    search_listing dirs = {{0}, 0};
    for_each_search_dir(ctx, list_one, &dirs);
    char refused[2048] = "";
    size_t len = 0;
    for (int32_t i = 0; i < ctx->module_count && len < sizeof refused; i++) {
        if (!ctx->modules[i]->error) continue;
        int n = snprintf(refused + len, sizeof refused - len, "; %s", ctx->modules[i]->error);
        if (n > 0) len += (size_t)n;
    }
    hr_suggester near;
    hri_suggester_init(&near, name);
    for (int32_t i = 0; i < ctx->class_count; i++) hri_suggester_offer(&near, ctx->classes[i].cls->name);
    for (int32_t i = 0; i < ctx->module_count; i++)
        for (int32_t j = 0; j < ctx->modules[i]->class_count; j++)
            hri_suggester_offer(&near, ctx->modules[i]->classes[j].name);
    char hint[128] = "";
    if (near.best) snprintf(hint, sizeof hint, " (did you mean '%.96s'?)", near.best);
    snprintf(msg, size, "no shape module provides '%s'%s (searched: %s)%s", name, hint,
             dirs.len ? dirs.text : "nothing", refused);
    return HR_ERROR_MODULE;
}

HR_API hr_status hr_context_find_shape_class(hr_context *ctx, const char *name,
                                             const hr_shape_class **out,
                                             const char **module_path)
{
    if (!ctx || !name || !out) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "NULL argument");
    hr_class_entry scratch;
    char msg[MESSAGE_SIZE];
    pthread_mutex_lock(&ctx->lock);
    const hr_class_entry *e = NULL;
    if (ctx->last_found.cls && ctx->last_found_class_count == ctx->class_count &&
        ctx->last_found_module_count == ctx->module_count && strcmp(ctx->last_found.cls->name, name) == 0) {
        e = &ctx->last_found;
    } else {
        e = find_loaded(ctx, name, &scratch);
        if (!e) {
            scan_search_path(ctx);
            e = find_loaded(ctx, name, &scratch);
        }
        if (e) {
            ctx->last_found = *e;
            ctx->last_found_class_count = ctx->class_count;
            ctx->last_found_module_count = ctx->module_count;
        }
    }
    hr_status st = HR_OK;
    if (e) {
        *out = e->cls;
        if (module_path) *module_path = e->origin;
    } else {
        st = not_found(ctx, name, msg, sizeof msg);
    }
    pthread_mutex_unlock(&ctx->lock);
    return st ? hri_error(ctx, st, "%s", msg) : HR_OK;
}

/* Put a class in front of the searched modules. */
static hr_status add_explicit_class(hr_context *ctx, const hr_shape_class *cls, const char *origin)
{
    hr_class_entry *grown =
        realloc(ctx->classes, (size_t)(ctx->class_count + 1) * sizeof *grown);
    if (!grown) return HR_ERROR_OUT_OF_MEMORY; /* raised by the caller, unlocked */
    ctx->classes = grown;
    /* Later explicit loads win over earlier ones: insert at the front. */
    memmove(ctx->classes + 1, ctx->classes, (size_t)ctx->class_count * sizeof *grown);
    ctx->classes[0].cls = cls;
    ctx->classes[0].origin = origin;
    ctx->class_count++;
    return HR_OK;
}

HR_API hr_status hr_context_load_module(hr_context *ctx, const char *path)
{
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    if (!path || !*path) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "empty module path");
    char msg[MESSAGE_SIZE] = "out of memory";
    pthread_mutex_lock(&ctx->lock);
    hr_module *m = load_file(ctx, path);
    hr_status st = HR_OK;
    if (!m) {
        st = HR_ERROR_OUT_OF_MEMORY;
    } else if (m->error) {
        st = HR_ERROR_MODULE;
        snprintf(msg, sizeof msg, "%s", m->error);
        module_free(m);
    } else if (!append_module(ctx, m)) {
        module_free(m);
        st = HR_ERROR_OUT_OF_MEMORY;
    } else {
        for (int32_t i = m->class_count - 1; i >= 0 && st == HR_OK; i--)
            st = add_explicit_class(ctx, &m->classes[i], m->path);
    }
    pthread_mutex_unlock(&ctx->lock);
    return st ? hri_error(ctx, st, "%s", msg) : HR_OK;
}

HR_API hr_status hr_context_register_shape_class(hr_context *ctx, const hr_shape_class *cls,
                                                 const char *origin)
{
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    if (!cls) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "NULL shape class");
    char msg[MESSAGE_SIZE] = "out of memory";
    pthread_mutex_lock(&ctx->lock);
    hr_status st = HR_OK;
    hr_module *m = calloc(1, sizeof *m);
    if (!m || !(m->path = hri_strdup(origin && *origin ? origin : "(registered in process)")) ||
        !(m->classes = calloc(1, sizeof *m->classes)) ||
        !(m->class_ptrs = calloc(1, sizeof *m->class_ptrs))) {
        module_free(m);
        st = HR_ERROR_OUT_OF_MEMORY;
    } else if (!copy_class(m, cls, &m->classes[0])) {
        st = HR_ERROR_MODULE;
        snprintf(msg, sizeof msg, "%s", m->error ? m->error : "out of memory");
        module_free(m);
    } else {
        m->class_ptrs[0] = &m->classes[0];
        m->class_count = 1;
        if (!append_module(ctx, m)) {
            module_free(m);
            st = HR_ERROR_OUT_OF_MEMORY;
        } else {
            st = add_explicit_class(ctx, &m->classes[0], m->path);
        }
    }
    pthread_mutex_unlock(&ctx->lock);
    return st ? hri_error(ctx, st, "%s", msg) : HR_OK;
}

HR_API int32_t hr_context_module_count(hr_context *ctx)
{
    if (!ctx) return 0;
    pthread_mutex_lock(&ctx->lock);
    scan_search_path(ctx);
    int32_t n = ctx->module_count;
    pthread_mutex_unlock(&ctx->lock);
    return n;
}

static const char *or_empty(const char *text)
{
    return text ? text : "";
}

HR_API hr_status hr_context_module(hr_context *ctx, int32_t index, hr_module_entry *out)
{
    if (!ctx || !out || out->struct_size < sizeof(uint32_t))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "NULL argument or struct_size 0");
    pthread_mutex_lock(&ctx->lock);
    if (index < 0 || index >= ctx->module_count) {
        pthread_mutex_unlock(&ctx->lock);
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "module index %d out of range [0, %d)",
                        (int)index, (int)ctx->module_count);
    }
    const hr_module *m = ctx->modules[index];
    hr_module_entry e = {0};
    e.loaded = m->error == NULL;
    e.path = m->path;
    e.name = m->info ? or_empty(m->info->name) : "";
    e.description = m->info ? or_empty(m->info->description) : "";
    e.error = m->error ? m->error : "";
    e.classes = m->class_ptrs;
    e.class_count = m->class_count;
    /* A module built before the metadata was added has none (HR_MODULE_HAS). */
    const hr_module_info *info = m->info;
    e.version = info && HR_MODULE_HAS(info, version) ? or_empty(info->version) : "";
    e.author = info && HR_MODULE_HAS(info, author) ? or_empty(info->author) : "";
    e.url = info && HR_MODULE_HAS(info, url) ? or_empty(info->url) : "";
    HR_SIZED_COPY_OUT(out, &e);
    pthread_mutex_unlock(&ctx->lock);
    return HR_OK;
}
