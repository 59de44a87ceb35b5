/* hitray: the context — loads shape modules and keeps error messages.
 *
 * A context is the root of everything: scenes, images and SDL reading take
 * one. It is safe to use one context from several threads: module loading is
 * serialised inside, and the last error message is kept per thread. */
#ifndef HITRAY_CONTEXT_H
#define HITRAY_CONTEXT_H

#include "common.h"
#include "shape_module.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Make a context. Shape modules are looked for, in this order, in the
 * directories given to hr_context_add_shape_dir, in the colon-separated list
 * of the environment variable HITRAY_SHAPE_PATH, and in `hitray/shapes` next
 * to the libhitray file itself (so a build tree and an installed tree both
 * work without setup). The first module that provides a class name wins. */
HR_API hr_status hr_context_create(hr_context **out);
/* Destroy a context no other thread is using. The calling thread's error
 * message is freed here; another thread's is freed when that thread exits. */
HR_API void hr_context_destroy(hr_context *ctx);

/* The message of the calling thread's last error on this context ("" if
 * none). Valid until the next call on this context from this thread. */
HR_API const char *hr_context_last_error(const hr_context *ctx);

/* Where the last error happened, for errors in scene files. */
typedef struct hr_error_info {
    uint32_t struct_size;
    hr_status status;   /* HR_OK if there was no error */
    const char *message;
    const char *file;   /* "" if the error is not in a file */
    int32_t line;       /* 1-based; 0 if unknown */
    int32_t column;     /* 1-based; 0 if unknown */
} hr_error_info;
HR_API hr_status hr_context_last_error_info(const hr_context *ctx, hr_error_info *out);

/* Called with every error as it is raised (from the thread that raised it;
 * it may call back into the context). Set it before the context is shared
 * between threads: the setting itself is not synchronised. */
typedef void (*hr_error_fn)(void *user, hr_status status, const char *message);
HR_API void hr_context_set_error_callback(hr_context *ctx, hr_error_fn fn, void *user);

/* Raise an error on the context as the library's own calls do: `message`
 * becomes the calling thread's last error (`file`, `line` and `column`
 * those of hr_context_last_error_info: NULL or "" and 0 when it is not in a
 * file), and goes to the error callback. For code built on hitray whose
 * errors should reach the program the same way, such as a reader of
 * another scene format. Returns `status`. The message is cut to 2047 bytes,
 * the file to 511; either may be the one this thread's last error holds (an
 * error passed on with more said). A NULL ctx records nothing; a NULL
 * message is "". */
HR_API hr_status hr_context_set_error(const hr_context *ctx, hr_status status, const char *file,
                                      int32_t line, int32_t column, const char *message);

/* Warnings: input the library accepts and acts on, but that probably does
 * not do what its writer meant (a scene with nothing in it, a coefficient
 * too small to be traced). The library never prints; a program that wants
 * them shows them (the `hitray` command on stderr, Python as `warnings`).
 * The callback runs on the thread of the call that found the case, before
 * that call returns; `warning` and its strings are valid during the call
 * only. Set it before the context is shared between threads. */
#define HR_WARNING_EMPTY_SCENE 1     /* committed with no object: background only */
#define HR_WARNING_BELOW_THRESHOLD 2 /* a reflectivity (transparency) above 0 but
                                        below minReflectivity (minTransparency):
                                        it spawns no ray and adds nothing */
#define HR_WARNING_RAY_BUDGET 3      /* a render's pixels reached the ray budget
                                        (hr_render_options.ray_budget): their
                                        faintest paths were not traced */
typedef struct hr_warning {
    uint32_t struct_size;
    int32_t code;        /* HR_WARNING_* */
    const char *message; /* one line, starting with "file:line:col: " when in a file */
    const char *file;    /* "" if not in a file */
    int32_t line;        /* 1-based; 0 if unknown */
    int32_t column;      /* 1-based; 0 if unknown */
} hr_warning;
typedef void (*hr_warning_fn)(void *user, const hr_warning *warning);
HR_API void hr_context_set_warning_callback(hr_context *ctx, hr_warning_fn fn, void *user);
/* Report a warning to the context's warning callback, if one is set, as
 * the library's own calls do; the parts are those of hr_warning (`file` NULL
 * or "" when not in a file). */
HR_API void hr_context_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line,
                            int32_t column, const char *message);

/* Search `dir` for modules before the default places. */
HR_API hr_status hr_context_add_shape_dir(hr_context *ctx, const char *dir);
/* The memory budget of each scene made after this call (objects, shape
 * data such as a mesh's triangles, pixmaps' texels), in bytes; 0 restores
 * the default: environment variable HITRAY_MAX_SCENE_MEMORY, else half of
 * what the process may use (docs/limits.md). A scene refuses the object or
 * pixmap that would pass it, before allocating it. */
HR_API hr_status hr_context_set_scene_memory(hr_context *ctx, uint64_t bytes);
/* Load one module file now; its classes take precedence over modules found
 * by searching. Fails with HR_ERROR_MODULE naming `path` if the file cannot
 * be opened, has no entry point, or reports another ABI version. */
HR_API hr_status hr_context_load_module(hr_context *ctx, const char *path);
/* Register a shape class that lives in the calling process (for example one
 * written in Python through cffi). `origin` names it in messages. The class
 * table must outlive the context. */
HR_API hr_status hr_context_register_shape_class(hr_context *ctx,
                                                 const hr_shape_class *cls,
                                                 const char *origin);

/* Find a shape class by name, loading modules from the search path if it is
 * not known yet. `module_path` (may be NULL) receives the module's path. */
HR_API hr_status hr_context_find_shape_class(hr_context *ctx, const char *name,
                                             const hr_shape_class **out,
                                             const char **module_path);

/* Listing of every module found on the search path (it is scanned now),
 * including those that could not be loaded. */
typedef struct hr_module_entry {
    uint32_t struct_size;
    int32_t loaded;        /* 1: usable; 0: refused, see `error` */
    const char *path;
    const char *name;      /* "" if not loaded */
    const char *description;
    const char *error;     /* "" if loaded */
    const hr_shape_class *const *classes;
    int32_t class_count;
    /* Added within ABI 1 (read when struct_size covers them): the module's
     * hr_module_info.version, author and url; "" when it gives none (or
     * is not loaded). */
    const char *version;
    const char *author;
    const char *url;
} hr_module_entry;
HR_API int32_t hr_context_module_count(hr_context *ctx);
HR_API hr_status hr_context_module(hr_context *ctx, int32_t index, hr_module_entry *out);

/* "Did you mean": of `count` candidate words, the one nearest `word` by
 * edit distance (insertions, deletions, substitutions and swaps of two
 * neighbours, letters compared without regard to case), if it is within one
 * step per four letters of `word` (at least one); NULL if none is. The
 * first of equally near candidates wins; one equal to `word` is never
 * suggested. The returned pointer is one of `candidates`. The SDL reader and
 * the module loader use it for their messages; a program can for its own
 * words (the `hitray` command's options). */
HR_API const char *hr_suggest(const char *word, const char *const *candidates, int32_t count);

/* Short human name of a status code ("invalid argument", ...). */
HR_API const char *hr_status_name(hr_status status);

/* Version of the library actually loaded (compare with HR_VERSION_*). */
HR_API void hr_version(int32_t *major, int32_t *minor, int32_t *patch);

#ifdef __cplusplus
}
#endif
#endif
