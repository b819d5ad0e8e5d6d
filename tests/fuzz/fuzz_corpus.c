/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_corpus.c — libFuzzer harness: the golden-corpus reader and runner
 * (tests/c/corpus_*.c, the code of build/tests/corpus_runner) on fuzzed
 * JSON text.
 *
 * Each input is used twice:
 *  1. parsed in memory with cJSON; every object in "cases" (or the top-level
 *     object itself) goes through corpus_case_parse, which must either fail
 *     with a non-empty, terminated message or give a case whose fields are
 *     in their documented ranges (a known op and status, counts >= 0, arrays
 *     present when their counts are positive, as many listed hits as the
 *     count); corpus_case_free must release everything (LeakSanitizer);
 *  2. written to a file and run by the runner's own main (compiled here as
 *     corpus_runner_main), which must end with status 0 or 1, and the same
 *     status on a second run (no state carried between files).
 * The runner executes the cases it can parse, so fuzzed cases reach the
 * library's calls too. Its report lines go to /dev/null.
 */
/* mkstemp, close */
#define _POSIX_C_SOURCE 200809L

#include "corpus_case.h"
#include "corpus_json.h"
#include "fuzz_checks.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int corpus_runner_main(int argc, char **argv); /* tests/c/corpus_runner.c */

static char path[64];

static void set_up(void)
{
    int fd;
    strcpy(path, "/tmp/isect-fuzz-corpus-XXXXXX");
    fd = mkstemp(path);
    if (fd < 0)
        abort();
    close(fd);
    if (freopen("/dev/null", "w", stdout) == NULL)
        abort();
}

static void check_case(const cJSON *item)
{
    corpus_case c;
    cj_error err;
    memset(&err, 0, sizeof err);
    if (!corpus_case_parse(item, &c, &err)) {
        FUZZ_REQUIRE(memchr(err.message, '\0', sizeof err.message) != NULL && err.message[0],
                     "corpus_case_parse failed without a message");
    } else {
        FUZZ_REQUIRE(c.op >= CORPUS_INTERSECT && c.op <= CORPUS_WINDING_NUMBER, "op %d", (int)c.op);
        FUZZ_REQUIRE(c.status <= 0 && c.status >= ISECT_E_NOMEM, "status %d", c.status);
        FUZZ_REQUIRE(c.count >= 0, "count %d", c.count);
        FUZZ_REQUIRE(!c.hits_listed || c.count == 0 || c.hits != NULL, "listed hits missing");
        FUZZ_REQUIRE(c.polygon2_n >= 0 && (c.polygon2_n == 0 || c.polygon2 != NULL),
                     "polygon of %d points", c.polygon2_n);
        FUZZ_REQUIRE(c.vertices_n >= 0 && (c.vertices_n == 0 || c.vertices != NULL),
                     "%d vertices", c.vertices_n);
        /* op winding_number: its points, and one expected w per point */
        FUZZ_REQUIRE(c.points_n >= 0 && (c.points_n == 0 || c.points != NULL),
                     "%d points", c.points_n);
        FUZZ_REQUIRE(c.op != CORPUS_WINDING_NUMBER || c.status != ISECT_OK || c.windings != NULL,
                     "winding_number expecting ok without its w values");
        FUZZ_REQUIRE(c.name != NULL, "no name");
    }
    corpus_case_free(&c);
}

static void parse_in_memory(const uint8_t *data, size_t size)
{
    cJSON *doc = cJSON_ParseWithLength((const char *)data, size);
    const cJSON *cases, *item;
    if (doc == NULL)
        return;
    cases = cJSON_GetObjectItemCaseSensitive(doc, "cases");
    if (cJSON_IsArray(cases)) {
        cJSON_ArrayForEach(item, cases) check_case(item);
    } else {
        check_case(doc);
    }
    cJSON_Delete(doc);
}

static int run_file(void)
{
    char *argv[3];
    char name[] = "corpus_runner";
    argv[0] = name;
    argv[1] = path;
    argv[2] = NULL;
    return corpus_runner_main(2, argv);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *f;
    int first, second;

    if (path[0] == '\0')
        set_up();
    parse_in_memory(data, size);

    f = fopen(path, "wb");
    if (f == NULL)
        abort();
    if (size > 0 && fwrite(data, 1, size, f) != size)
        abort();
    fclose(f);
    first = run_file();
    FUZZ_REQUIRE(first == 0 || first == 1, "the runner exited with %d", first);
    second = run_file();
    FUZZ_REQUIRE(second == first, "the runner gave %d, then %d on the same file", first, second);
    return 0;
}
