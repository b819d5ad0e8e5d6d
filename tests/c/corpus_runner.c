/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_runner.c — runs the golden corpus (the files in tests/cases/, schema
 * isect-cases/1, documented in tests/cases/README.md) against libisect.
 *
 *     corpus_runner FILE.json...
 *
 * Every case goes through every API path that computes its answer (see
 * corpus_checks.h). Each disagreement prints one line
 *
 *     FAIL file:id name: what (expected X, got Y)
 *
 * and the run ends with exactly one line "N passed, N failed", N counting
 * cases; the exit status is 1 if anything failed. A problem with a file as
 * a whole (unreadable, not JSON, wrong schema, number_of_cases not matching)
 * is reported as "FAIL file: ..." and counts as one failed entry, so the
 * summary can never read "0 failed" while the run fails.
 */
#include "corpus_case.h"
#include "corpus_checks.h"
#include "corpus_json.h"
#include "corpus_report.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CORPUS_SCHEMA "isect-cases/1"
/* Case ids are JSON numbers; keep them where doubles hold integers exactly. */
#define MAX_CASE_ID 9007199254740992LL

typedef struct run_totals {
    long passed;
    long failed;
} run_totals;

static void file_fail(run_totals *totals, const char *file, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void file_fail(run_totals *totals, const char *file, const char *fmt, ...)
{
    va_list ap;
    printf("FAIL %s: ", file);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
    totals->failed++;
}

/* The ids seen so far in one file, to report duplicates. */
typedef struct id_set {
    long long *ids;
    size_t     count, cap;
} id_set;

/* 1 if id was already in the set; otherwise adds it and returns 0. */
static int id_set_seen(id_set *set, long long id)
{
    size_t i;
    for (i = 0; i < set->count; i++)
        if (set->ids[i] == id)
            return 1;
    if (set->count == set->cap) {
        size_t cap = set->cap ? set->cap * 2 : 64;
        long long *bigger = realloc(set->ids, cap * sizeof *bigger);
        if (bigger == NULL)
            return 0; /* cannot track more ids; duplicates go unreported */
        set->ids = bigger;
        set->cap = cap;
    }
    set->ids[set->count++] = id;
    return 0;
}

static void run_parsed_case(const corpus_case *c, case_report *r)
{
    switch (c->op) {
    case CORPUS_INTERSECT:
        check_intersect_case(c, r);
        break;
    case CORPUS_CONTAINS:
        check_contains_case(c, r);
        break;
    case CORPUS_MESH_CHECK:
        check_mesh_check_case(c, r);
        break;
    case CORPUS_POINT_IN_POLYGON2:
        check_point_in_polygon2_case(c, r);
        break;
    case CORPUS_WINDING_NUMBER2:
        check_winding_number2_case(c, r);
        break;
    case CORPUS_POLYGON_NORMAL:
        check_polygon_normal_case(c, r);
        break;
    case CORPUS_PLANE_FROM_POINTS:
        check_plane_from_points_case(c, r);
        break;
    case CORPUS_SPAWN:
        check_spawn_case(c, r);
        break;
    case CORPUS_WINDING_NUMBER:
        check_winding_number_case(c, r);
        break;
    }
}

static void run_case(const char *file, const cJSON *item, int index, id_set *ids,
                     run_totals *totals)
{
    const cJSON *name_item = cJSON_GetObjectItemCaseSensitive(item, "name");
    const char *name = cJSON_IsString(name_item) ? name_item->valuestring : NULL;
    case_report report;
    corpus_case c;
    cj_error err;
    long long id = 0;
    char label[32];

    if (!cJSON_IsObject(item)) {
        snprintf(label, sizeof label, "[%d]", index);
        report_begin(&report, file, label, NULL);
        report_fail(&report, "malformed case: a case must be an object");
        report_end(&report);
        totals->failed++;
        return;
    }
    if (cj_integer(item, "", "id", -MAX_CASE_ID, MAX_CASE_ID, &id, &err)) {
        snprintf(label, sizeof label, "%lld", id);
        report_begin(&report, file, label, name);
        if (id_set_seen(ids, id))
            report_fail(&report, "duplicate id %lld in this file", id);
    } else {
        snprintf(label, sizeof label, "[%d]", index);
        report_begin(&report, file, label, name);
        report_fail(&report, "malformed case: %s", err.message);
    }

    /* A mesh is built first: its creation can be the case's whole result. */
    if (!corpus_case_parse(item, &c, &err))
        report_fail(&report, "malformed case: %s", err.message);
    else if (mesh_setup(&c, &report))
        run_parsed_case(&c, &report);
    corpus_case_free(&c); /* destroys the mesh too */

    report_end(&report);
    if (report.failures == 0)
        totals->passed++;
    else
        totals->failed++;
}

/* The header fields; returns the cases array, or NULL when the file cannot
 * be run at all (already reported). */
static const cJSON *file_header_check(const char *file, const cJSON *doc, run_totals *totals)
{
    const cJSON *schema, *cases;
    cj_error err;
    long long number = 0;

    if (!cJSON_IsObject(doc)) {
        file_fail(totals, file, "the top level must be an object");
        return NULL;
    }
    schema = cJSON_GetObjectItemCaseSensitive(doc, "schema");
    if (!cJSON_IsString(schema) || strcmp(schema->valuestring, CORPUS_SCHEMA) != 0) {
        file_fail(totals, file, "schema (expected \"%s\", got %s%s%s); cases not run",
                  CORPUS_SCHEMA, cJSON_IsString(schema) ? "\"" : "",
                  cJSON_IsString(schema) ? schema->valuestring
                                         : (schema == NULL ? "no \"schema\" field"
                                                           : "a non-string"),
                  cJSON_IsString(schema) ? "\"" : "");
        return NULL;
    }
    cases = cJSON_GetObjectItemCaseSensitive(doc, "cases");
    if (!cJSON_IsArray(cases)) {
        file_fail(totals, file, "field \"cases\" %s",
                  cases == NULL ? "is missing" : "must be an array");
        return NULL;
    }
    /* A count that disagrees means cases were lost or added by hand: the
     * file fails, but its cases still run so their own results show. */
    if (!cj_integer(doc, "", "number_of_cases", 0, MAX_CASE_ID, &number, &err))
        file_fail(totals, file, "%s", err.message);
    else if (number != cJSON_GetArraySize(cases))
        file_fail(totals, file, "number_of_cases (expected len(cases) = %d, got %lld)",
                  cJSON_GetArraySize(cases), number);
    return cases;
}

static void run_file(const char *file, run_totals *totals)
{
    cj_error err;
    cJSON *doc = cj_load_file(file, &err);
    const cJSON *cases, *item;
    id_set ids = { NULL, 0, 0 };
    int index = 0;

    if (doc == NULL) {
        file_fail(totals, file, "%s", err.message);
        return;
    }
    cases = file_header_check(file, doc, totals);
    if (cases != NULL) {
        cJSON_ArrayForEach(item, cases) {
            run_case(file, item, index, &ids, totals);
            index++;
        }
    }
    free(ids.ids);
    cJSON_Delete(doc);
}

int main(int argc, char **argv)
{
    run_totals totals = { 0, 0 };
    int i;

    if (argc < 2) {
        fprintf(stderr, "usage: %s CASES.json...\n", argc > 0 ? argv[0] : "corpus_runner");
        printf("0 passed, 1 failed\n");
        return 1;
    }
    for (i = 1; i < argc; i++)
        run_file(argv[i], &totals);
    printf("%ld passed, %ld failed\n", totals.passed, totals.failed);
    return totals.failed != 0;
}
