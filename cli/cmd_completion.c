/* hitray completion bash|zsh: the shell completion script, written from the
 * verbs' table (verbs.c) and each verb's option table, the ones its parser
 * and its --help read, so the completion offers what the command takes. */
#include <string.h>

#include "cli.h"
#include "render_flags.h"

static const char completion_help[] =
    "usage: hitray completion bash|zsh\n"
    "\n"
    "Print the completion script of hitray for bash or zsh: the commands, each\n"
    "command's options, file names where a file is expected and the choices of\n"
    "an option that has some. Load it in the running shell with\n"
    "  source <(hitray completion bash)\n"
    "or install it: bash's as /usr/share/bash-completion/completions/hitray,\n"
    "zsh's as _hitray in a directory of $fpath.\n"
    "\n"
    "options:\n";

const cli_option cli_completion_options[] = {
    {"--help", "-h", 0, NULL, "this help"},
    {NULL, NULL, 0, NULL, NULL},
};

/* A verb's whole table: its own options and the render flags it takes. */
static int verb_table(const cli_verb *v, cli_option out[CLI_TABLE_CAPACITY])
{
    return cli_render_flags_table(v->options, v->render_flags, out, CLI_TABLE_CAPACITY);
}

static int is_file(const char *value)
{
    size_t n = value ? strlen(value) : 0;
    return n >= 4 && !strcmp(value + n - 4, "FILE");
}

static int has_choices(const char *value) { return value && strchr(value, '|'); }

/* The choices "a|b|c" as "a b c". */
static void put_choices(FILE *f, const char *value)
{
    for (const char *c = value; *c; c++) fputc(*c == '|' ? ' ' : *c, f);
}

/* --- bash --- */

/* The names (and aliases) of the options in `table` that `pick` picks. */
static void bash_names(FILE *f, const cli_option *table, int (*pick)(const cli_option *))
{
    for (const cli_option *o = table; o->name; o++) {
        if (pick && !pick(o)) continue;
        if (o->alias) fprintf(f, " %s", o->alias);
        fprintf(f, " %s", o->name);
    }
}

static int takes_file(const cli_option *o) { return o->takes_value && is_file(o->value); }
static int takes_other(const cli_option *o) { return o->takes_value && !is_file(o->value); }

static void write_bash(FILE *f)
{
    fputs("# bash completion for hitray, written by `hitray completion bash` from the\n"
          "# command's own option tables. Load it with: source <(hitray completion bash)\n"
          "_hitray()\n"
          "{\n"
          "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
          "    if [ \"$COMP_CWORD\" -eq 1 ]; then\n"
          "        COMPREPLY=($(compgen -W \"",
          f);
    for (int32_t i = 0; i < cli_verb_count; i++) fprintf(f, "%s ", cli_verbs[i].name);
    bash_names(f, cli_top_options, NULL);
    fputs("\" -- \"$cur\"))\n"
          "        return\n"
          "    fi\n"
          "    local options files values operand\n"
          "    case ${COMP_WORDS[1]} in\n",
          f);
    for (int32_t i = 0; i < cli_verb_count; i++) {
        const cli_verb *v = &cli_verbs[i];
        cli_option table[CLI_TABLE_CAPACITY];
        if (verb_table(v, table) < 0) continue; /* the tests see a verb missing */
        fprintf(f, "    %s)\n        options=\"", v->name);
        bash_names(f, table, NULL);
        fputs("\"\n        files=\" ", f);
        bash_names(f, table, takes_file);
        fputs(" \"\n        values=\" ", f);
        bash_names(f, table, takes_other);
        fputs(" \"\n", f);
        for (const cli_option *o = table; o->name; o++) {
            if (!has_choices(o->value)) continue;
            fprintf(f, "        case $prev in %s%s%s) COMPREPLY=($(compgen -W \"", o->alias ? o->alias : "",
                    o->alias ? "|" : "", o->name);
            put_choices(f, o->value);
            fputs("\" -- \"$cur\")); return ;; esac\n", f);
        }
        fputs("        operand=\"", f);
        if (v->operand) put_choices(f, v->operand);
        fputs("\" ;;\n", f);
    }
    fputs("    *) return ;;\n"
          "    esac\n"
          "    case $files in *\" $prev \"*) COMPREPLY=($(compgen -f -- \"$cur\")); return ;; esac\n"
          "    case $values in *\" $prev \"*) COMPREPLY=(); return ;; esac\n"
          "    if [[ $cur == -* || -z $operand ]]; then\n"
          "        COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
          "    elif [ \"$operand\" = FILE ]; then\n"
          "        COMPREPLY=($(compgen -f -- \"$cur\"))\n"
          "    else\n"
          "        COMPREPLY=($(compgen -W \"$operand\" -- \"$cur\"))\n"
          "    fi\n"
          "}\n"
          "complete -o filenames -F _hitray hitray\n",
          f);
}

/* --- zsh --- */

/* A help text's first clause (to its first '(', ';' or ':'), as text inside
 * a single-quoted zsh word and inside _arguments' brackets. */
static void zsh_description(FILE *f, const char *help)
{
    size_t n = strcspn(help, "(;:\n");
    while (n > 0 && help[n - 1] == ' ') n--;
    for (size_t i = 0; i < n; i++) {
        char c = help[i];
        if (c == '\n') fputc(' ', f);
        else if (c == '\'') fputs("'\\''", f);
        else if (c == '[' || c == ']' || c == '\\') fprintf(f, "\\%c", c);
        else fputc(c, f);
    }
}

/* One _arguments spec: '(-o --output)'{-o,--output}'[text]:VALUE:action'. */
static void zsh_spec(FILE *f, const cli_option *o)
{
    fputs("        ", f);
    if (o->alias) fprintf(f, "'(%s %s)'{%s,%s}'", o->alias, o->name, o->alias, o->name);
    else fprintf(f, "'%s", o->name);
    fputc('[', f);
    zsh_description(f, o->help ? o->help : "");
    fputc(']', f);
    if (o->takes_value) {
        fputc(':', f);
        for (const char *c = o->value; *c; c++) fputc(*c == ':' ? '.' : *c, f);
        if (is_file(o->value)) fputs(":_files", f);
        else if (has_choices(o->value)) fputs(":(", f), put_choices(f, o->value), fputc(')', f);
        else fputs(": ", f);
    }
    fputs("' \\\n", f);
}

static void write_zsh(FILE *f)
{
    fputs("#compdef hitray\n"
          "# zsh completion for hitray, written by `hitray completion zsh` from the\n"
          "# command's own option tables. Install it as _hitray in a directory of\n"
          "# $fpath, or load it with: source <(hitray completion zsh)\n"
          "_hitray() {\n"
          "    local -a verbs\n"
          "    verbs=(\n",
          f);
    for (int32_t i = 0; i < cli_verb_count; i++) {
        fprintf(f, "        '%s:", cli_verbs[i].name);
        zsh_description(f, cli_verbs[i].summary);
        fputs("'\n", f);
    }
    fputs("    )\n"
          "    if (( CURRENT == 2 )); then\n"
          "        _describe -t commands 'hitray command' verbs\n"
          "        compadd --",
          f);
    bash_names(f, cli_top_options, NULL);
    fputs("\n"
          "        return\n"
          "    fi\n"
          "    local verb=$words[2]\n"
          "    shift words\n"
          "    (( CURRENT-- ))\n"
          "    case $verb in\n",
          f);
    for (int32_t i = 0; i < cli_verb_count; i++) {
        const cli_verb *v = &cli_verbs[i];
        cli_option table[CLI_TABLE_CAPACITY];
        if (verb_table(v, table) < 0) continue;
        fprintf(f, "    %s)\n        _arguments -s \\\n", v->name);
        for (const cli_option *o = table; o->name; o++) zsh_spec(f, o);
        if (v->operand && is_file(v->operand)) fputs("        '1:file:_files'\n", f);
        else if (v->operand) fputs("        '1:shell:(", f), put_choices(f, v->operand), fputs(")'\n", f);
        else fputs("        \n", f);
        fputs("        ;;\n", f);
    }
    fputs("    esac\n"
          "}\n"
          "if [ \"$funcstack[1]\" = _hitray ]; then\n"
          "    _hitray \"$@\"\n"
          "else\n"
          "    compdef _hitray hitray\n"
          "fi\n",
          f);
}

int cmd_completion(int argc, char **argv)
{
    cli_parser p;
    cli_parser_init(&p, argc, argv, cli_completion_options);
    const char *name, *value, *shell = NULL;
    int kind;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_OPTION) { /* --help, the only one */
            fputs(completion_help, stdout);
            cli_print_options(stdout, cli_completion_options);
            return CLI_EXIT_OK;
        }
        if (shell) return cli_usage_error("completion: one shell only ('%s' is extra)", value);
        shell = value;
    }
    if (!shell) return cli_usage_error("completion: which shell? bash or zsh (see 'hitray completion --help')");
    if (!strcmp(shell, "bash")) write_bash(stdout);
    else if (!strcmp(shell, "zsh")) write_zsh(stdout);
    else return cli_usage_error("completion: '%s' is neither 'bash' nor 'zsh'", shell);
    return fflush(stdout) == 0 ? CLI_EXIT_OK : cli_error("cannot write to standard output");
}
