/* Internal: what a context holds. Only the library's own layers see this:
 * the scene file readers (lib/sdl, lib/nff) are built without lib/core on
 * their include path. */
#ifndef HITRAY_LIB_CORE_CONTEXT_INTERNAL_H
#define HITRAY_LIB_CORE_CONTEXT_INTERNAL_H

#include <pthread.h>

#include <hitray/hitray.h>

/* One module file found on the search path or loaded by path. */
typedef struct hr_module {
    char *path;
    void *handle;        /* dlopen handle; NULL if not loaded */
    char *error;         /* why it was refused; NULL if loaded */
    const hr_module_info *info;
    hr_shape_class *classes; /* full-size copies of the module's classes */
    const hr_shape_class **class_ptrs;
    int32_t class_count;
} hr_module;

/* A shape class usable by scenes, with where it came from. */
typedef struct hr_class_entry {
    const hr_shape_class *cls;
    const char *origin; /* module path, or the origin given at registration */
} hr_class_entry;

struct hr_context {
    pthread_mutex_t lock;     /* guards modules, classes and dirs */
    pthread_key_t error_key;  /* per-thread last error (hr_error_slot) */
    hr_error_fn error_fn;
    void *error_user;
    hr_warning_fn warning_fn; /* may be NULL: warnings go nowhere */
    void *warning_user;
    char **dirs;              /* extra search directories, in order */
    int32_t dir_count;
    int32_t scanned;          /* the search path has been read */
    hr_module **modules;
    int32_t module_count;
    hr_class_entry *classes;  /* explicit loads/registrations first */
    int32_t class_count;
    hr_host host;             /* the services table given to every module */
    /* The last class hr_context_find_shape_class found, and the counts of
     * classes and modules it was found among: both only grow until
     * hri_modules_unload_all (which clears this), so while they are the same
     * the first match for that name is still this one. A scene adds its
     * objects class after class, mostly of one class. */
    hr_class_entry last_found;
    int32_t last_found_class_count, last_found_module_count;
    uint64_t scene_memory; /* hr_context_set_scene_memory; 0: the default */
};

/* A context with everything but its host table (ctx->host, zeroed), or NULL
 * when out of memory. The table is made of the tracing layer's services, so
 * hr_context_create, which fills it, lives above core (trace/host_services.c). */
hr_context *hri_context_new(void);

#endif
