/* hitray hits: Hill's getFirstHit (or the whole Intersection) of one ray,
 * as JSON lines — a way to check a scene, or a shape, by hand. */
#include <math.h>
#include <string.h>

#include "cli.h"

static const char hits_help[] =
    "usage: hitray hits SCENE --origin X,Y,Z --dir X,Y,Z [--all]\n"
    "\n"
    "Shoot the ray origin + t * dir (t > 0) into the scene SCENE (SDL, or NFF\n"
    "if it ends in .nff or .nff.gz) and print the first hit, or with --all\n"
    "every hit sorted by t, one JSON object per line:\n"
    "  {\"t\": ..., \"point\": [x, y, z], \"normal\": [x, y, z], \"entering\": true,\n"
    "   \"surface\": 0, \"object\": 0, \"shape\": \"sphere\"}\n"
    "Numbers are printed with 17 significant digits, so they read back exactly.\n"
    "No output means no hit. `object` is the object's index in file order.\n"
    "\n"
    "options:\n";

const cli_option cli_hits_options[] = {
    {"--origin", NULL, 1, "X,Y,Z", "where the ray starts (world coordinates)"},
    {"--dir", NULL, 1, "X,Y,Z", "its direction (any non-zero length; t is measured in units of this vector)"},
    {"--all", NULL, 0, NULL, "every hit, not just the first"},
    {"--help", "-h", 0, NULL, "this help"},
    {NULL, NULL, 0, NULL, NULL},
};

typedef struct hits_request {
    const char *scene_path;
    hr_ray ray;
    int has_origin, has_dir, all;
} hits_request;

/* Go on, stop after the help, or stop with CLI_EXIT_USAGE (reported). */
#define PARSE_OK 0
#define PARSE_HELP (-1)

static int parse_request(int argc, char **argv, hits_request *r)
{
    memset(r, 0, sizeof *r);
    cli_parser p;
    cli_parser_init(&p, argc, argv, cli_hits_options);
    const char *name, *value;
    int kind;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_POSITIONAL) {
            if (r->scene_path) return cli_usage_error("hits: one scene file only ('%s' is extra)", value);
            r->scene_path = value;
            continue;
        }
        double v[3];
        if (!strcmp(name, "--help")) {
            fputs(hits_help, stdout);
            cli_print_options(stdout, cli_hits_options);
            return PARSE_HELP;
        } else if (!strcmp(name, "--all")) {
            r->all = 1;
        } else if (!strcmp(name, "--origin")) {
            if (!cli_parse_doubles(name, value, 3, v)) return CLI_EXIT_USAGE;
            r->ray.origin = (hr_vec3){v[0], v[1], v[2]};
            r->has_origin = 1;
        } else if (!strcmp(name, "--dir")) {
            if (!cli_parse_doubles(name, value, 3, v)) return CLI_EXIT_USAGE;
            r->ray.dir = (hr_vec3){v[0], v[1], v[2]};
            r->has_dir = 1;
        }
    }
    if (!r->scene_path) return cli_usage_error("hits: no scene file given (see 'hitray hits --help')");
    if (!r->has_origin) return cli_usage_error("hits: --origin X,Y,Z is required");
    if (!r->has_dir) return cli_usage_error("hits: --dir X,Y,Z is required");
    if (r->ray.dir.x == 0 && r->ray.dir.y == 0 && r->ray.dir.z == 0)
        return cli_usage_error("hits: --dir must not be the zero vector");
    return PARSE_OK;
}

static void print_hit(const hr_scene *scene, const hr_hit *h)
{
    hr_object_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    const char *shape = hr_scene_object_info(scene, h->object, &info) == HR_OK && info.shape ? info.shape : "";
    fputs("{\"t\": ", stdout);
    json_number(stdout, h->t);
    fputs(", \"point\": ", stdout);
    json_vec3(stdout, h->point);
    fputs(", \"normal\": ", stdout);
    json_vec3(stdout, h->normal);
    printf(", \"entering\": %s, \"surface\": %d, \"object\": %lld, \"shape\": ", h->entering ? "true" : "false",
           (int)h->surface, (long long)h->object);
    json_string(stdout, shape);
    fputs("}\n", stdout);
}

static int trace(const hits_request *r, cli_scene *s)
{
    hr_status st;
    if (r->all) {
        hr_intersection list;
        hr_intersection_init(&list);
        st = hr_scene_all_hits(s->sdl.scene, &r->ray, 0.0, INFINITY, &list);
        if (st == HR_OK)
            for (int32_t i = 0; i < list.count; i++) print_hit(s->sdl.scene, &list.hits[i]);
        hr_intersection_release(&list);
    } else {
        hr_hit hit;
        int32_t found = 0;
        st = hr_scene_first_hit(s->sdl.scene, &r->ray, 0.0, INFINITY, &hit, &found);
        if (st == HR_OK && found) print_hit(s->sdl.scene, &hit);
    }
    if (st != HR_OK) return cli_library_error(s->ctx, st);
    return fflush(stdout) == 0 ? CLI_EXIT_OK : cli_error("cannot write the hits to standard output");
}

int cmd_hits(int argc, char **argv)
{
    hits_request r;
    int parsed = parse_request(argc, argv, &r);
    if (parsed != PARSE_OK) return parsed == PARSE_HELP ? CLI_EXIT_OK : parsed;
    cli_scene s;
    if (cli_scene_load(&s, r.scene_path)) return CLI_EXIT_ERROR;
    int rc = cli_scene_commit(&s) ? CLI_EXIT_ERROR : trace(&r, &s);
    cli_scene_free(&s);
    return rc;
}
