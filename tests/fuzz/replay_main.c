/* The corpus replay: a main() for the harnesses in builds without libFuzzer
 * (gcc, plain, ASan+UBSan, TSan). It feeds every file of the harness's
 * committed corpus (HR_FUZZ_CORPUS_DIR), or the files and directories
 * named on the command line, to LLVMFuzzerTestOneInput once each, in name
 * order so a failure is reproducible. A broken contract aborts inside the
 * harness, which is the test's failure; an empty corpus fails too, so a
 * lost directory cannot pass unnoticed. */
#define _POSIX_C_SOURCE 200809L /* scandir, alphasort */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_input.h"

static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot open %s\n", path);
        return 0;
    }
    size_t size = 0, capacity = 4096;
    uint8_t *data = malloc(capacity);
    size_t n;
    while (data && (n = fread(data + size, 1, capacity - size, f)) > 0) {
        size += n;
        if (size == capacity) {
            uint8_t *grown = realloc(data, capacity * 2);
            if (!grown) {
                free(data);
                data = NULL;
                break;
            }
            data = grown;
            capacity *= 2;
        }
    }
    fclose(f);
    if (!data) {
        fprintf(stderr, "replay: out of memory reading %s\n", path);
        return 0;
    }
    fprintf(stderr, "replay: %s (%zu bytes)\n", path, size);
    LLVMFuzzerTestOneInput(data, size);
    free(data);
    return 1;
}

static int ignore_dots(const struct dirent *e)
{
    return e->d_name[0] != '.';
}

/* Returns how many files were replayed, -1 on an error. */
static int replay_path(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "replay: no such file or directory: %s\n", path);
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) return replay_file(path) ? 1 : -1;
    struct dirent **names;
    const int count = scandir(path, &names, ignore_dots, alphasort);
    if (count < 0) {
        fprintf(stderr, "replay: cannot list %s\n", path);
        return -1;
    }
    int replayed = 0, ok = 1;
    for (int i = 0; i < count; i++) {
        const size_t n = strlen(path) + strlen(names[i]->d_name) + 2;
        char *file = malloc(n);
        if (file) {
            snprintf(file, n, "%s/%s", path, names[i]->d_name);
            if (replay_file(file)) replayed++;
            else ok = 0;
        } else {
            ok = 0;
        }
        free(file);
        free(names[i]);
    }
    free(names);
    return ok ? replayed : -1;
}

int main(int argc, char **argv)
{
    LLVMFuzzerInitialize(&argc, &argv);
    int total = 0;
    if (argc < 2) {
        total = replay_path(HR_FUZZ_CORPUS_DIR);
    } else {
        for (int i = 1; i < argc && total >= 0; i++) {
            const int n = replay_path(argv[i]);
            total = n < 0 ? -1 : total + n;
        }
    }
    if (total <= 0) {
        fprintf(stderr, "replay: %s\n", total < 0 ? "failed" : "no input to replay");
        return 1;
    }
    fprintf(stderr, "replay: %d inputs, no contract broken\n", total);
    return 0;
}
