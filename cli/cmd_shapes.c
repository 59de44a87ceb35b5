/* hitray shapes: every shape module on the search path, what it provides and
 * what each class's parameters mean; and the modules that were refused, with
 * why, so a broken plugin is easy to diagnose. */
#include <math.h>
#include <string.h>

#include "cli.h"

static const char shapes_help[] =
    "usage: hitray shapes\n"
    "\n"
    "List the shape modules found (in HITRAY_SHAPE_PATH and in hitray/shapes\n"
    "next to libhitray), the shape classes each provides, and each class's\n"
    "parameters: name, type, default, range and meaning, and whether it gives\n"
    "(u, v) for image textures. Modules that could not be loaded are listed\n"
    "with the reason.\n"
    "\n"
    "options:\n";

const cli_option cli_shapes_options[] = {{"--help", "-h", 0, NULL, "this help"}, {NULL, NULL, 0, NULL, NULL}};

static const char *type_name(int32_t type)
{
    switch (type) {
    case HR_PARAM_NUMBER: return "number";
    case HR_PARAM_STRING: return "string";
    case HR_PARAM_OBJECT: return "object";
    case HR_PARAM_NUMBERS: return "numbers";
    default: return "?";
    }
}

static void print_param(const hr_param_spec *p)
{
    printf("      %-16s %-7s", p->name ? p->name : "?", type_name(p->type));
    if (p->required) printf(" required");
    else if (p->type == HR_PARAM_NUMBER) printf(" default %g", p->default_number);
    if (p->type == HR_PARAM_NUMBER && (isfinite(p->min) || isfinite(p->max)))
        printf(" range %c%g, %g%c", p->flags & HR_PARAM_MIN_EXCLUSIVE ? '(' : '[', p->min, p->max,
               p->flags & HR_PARAM_MAX_EXCLUSIVE ? ')' : ']');
    if (p->help && *p->help) printf("  %s", p->help);
    putchar('\n');
}

static void print_class(const hr_shape_class *cls)
{
    printf("  %s", cls->name ? cls->name : "?");
    if (cls->help && *cls->help) printf(" - %s", cls->help);
    putchar('\n');
    if (cls->param_count == 0) printf("      (no parameters)\n");
    for (int32_t i = 0; i < cls->param_count && cls->params; i++) print_param(&cls->params[i]);
    /* What hr_hit.surface (the "surface" of `hitray hits`) numbers. */
    if (HR_CLASS_HAS(cls, surface_names) && cls->surface_names && cls->surface_count > 0) {
        printf("      surfaces:");
        for (int32_t i = 0; i < cls->surface_count; i++)
            printf(" %d %s", (int)i, cls->surface_names[i] ? cls->surface_names[i] : "?");
        putchar('\n');
    }
    /* Which classes an image texture can go on (hr_shape_class.surface_uv). */
    if (cls->flags & HR_SHAPE_COMPOSITE) printf("      (u, v): its leaves'\n");
    else if (HR_CLASS_HAS(cls, surface_uv) && cls->surface_uv) printf("      (u, v): yes, for image textures\n");
    else printf("      (u, v): none (image textures refused; solid textures work)\n");
}

static void print_module(const hr_module_entry *m)
{
    printf("%s\n", m->path ? m->path : "?");
    if (!m->loaded) {
        printf("  NOT LOADED: %s\n", m->error && *m->error ? m->error : "unknown error");
        return;
    }
    printf("  module %s", m->name ? m->name : "?");
    if (m->description && *m->description) printf(": %s", m->description);
    putchar('\n');
    /* The module's metadata (hr_module_info.version, author, url), the
     * parts it gives. */
    const int has_version = m->version && *m->version, has_author = m->author && *m->author;
    if (has_version) printf("  version %s", m->version);
    if (has_author) printf("%s%s", has_version ? ", by " : "  by ", m->author);
    if (has_version || has_author) putchar('\n');
    if (m->url && *m->url) printf("  %s\n", m->url);
    for (int32_t i = 0; i < m->class_count && m->classes; i++)
        if (m->classes[i]) print_class(m->classes[i]);
}

static int list_modules(hr_context *ctx)
{
    int32_t count = hr_context_module_count(ctx);
    if (count <= 0)
        return cli_error("no shape modules found (looked in HITRAY_SHAPE_PATH and in hitray/shapes next to libhitray)");
    int refused = 0;
    for (int32_t i = 0; i < count; i++) {
        hr_module_entry m;
        memset(&m, 0, sizeof m);
        m.struct_size = sizeof m;
        hr_status st = hr_context_module(ctx, i, &m);
        if (st != HR_OK) return cli_library_error(ctx, st);
        if (i > 0) putchar('\n');
        print_module(&m);
        refused += !m.loaded;
    }
    if (refused) printf("\n%d of %d modules could not be loaded\n", refused, (int)count);
    return fflush(stdout) == 0 ? CLI_EXIT_OK : cli_error("cannot write to standard output");
}

int cmd_shapes(int argc, char **argv)
{
    cli_parser p;
    cli_parser_init(&p, argc, argv, cli_shapes_options);
    const char *name, *value;
    int kind;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_POSITIONAL) return cli_usage_error("shapes: unexpected argument '%s'", value);
        if (!strcmp(name, "--help")) {
            fputs(shapes_help, stdout);
            cli_print_options(stdout, cli_shapes_options);
            return CLI_EXIT_OK;
        }
    }
    hr_context *ctx = NULL;
    hr_status st = hr_context_create(&ctx);
    if (st != HR_OK) return cli_error("cannot start the library: %s", hr_status_name(st));
    int rc = list_modules(ctx);
    hr_context_destroy(ctx);
    return rc;
}
