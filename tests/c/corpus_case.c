/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_case.c — a corpus case object into a corpus_case; see corpus_case.h.
 */
#include "corpus_case.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_TOLERANCE 1e-12
/* Far more hits than any primitive can have; only guards against nonsense. */
#define MAX_EXPECTED_COUNT 1000000

typedef struct name_value {
    const char *name;
    int value;
} name_value;

static const name_value op_names[] = {
    { "intersect", CORPUS_INTERSECT },
    { "contains", CORPUS_CONTAINS },
    { "mesh_check", CORPUS_MESH_CHECK },
    { "point_in_polygon2", CORPUS_POINT_IN_POLYGON2 },
    { "winding_number2", CORPUS_WINDING_NUMBER2 },
    { "polygon_normal", CORPUS_POLYGON_NORMAL },
    { "plane_from_points", CORPUS_PLANE_FROM_POINTS },
    { "spawn", CORPUS_SPAWN },
    { "winding_number", CORPUS_WINDING_NUMBER },
    { NULL, 0 },
};

static const name_value status_names[] = {
    { "ok", ISECT_OK },
    { "E_ARG", ISECT_E_ARG },
    { "E_NONFINITE", ISECT_E_NONFINITE },
    { "E_DEGENERATE", ISECT_E_DEGENERATE },
    { "E_NOMEM", ISECT_E_NOMEM },
    { NULL, 0 },
};

static const name_value kind_names[] = {
    { "miss", ISECT_MISS },
    { "enter", ISECT_ENTER },
    { "exit", ISECT_EXIT },
    { "touch", ISECT_TOUCH },
    { "invalid", ISECT_INVALID },
    { NULL, 0 },
};

static const name_value opts_flag_names[] = {
    { "cull_back", (int)ISECT_CULL_BACK },
    { "any_hit", (int)ISECT_ANY_HIT },
    { NULL, 0 },
};

static const char *name_of(const name_value *table, int value)
{
    for (; table->name != NULL; table++)
        if (table->value == value)
            return table->name;
    return NULL;
}

/* The string at obj[key] looked up in table; on failure the message lists
 * nothing more than the field, which is enough to find the typo. */
static int enum_parse(const cJSON *obj, const char *parent, const char *key,
                      const name_value *table, int *out, cj_error *err)
{
    const char *text;
    char path[160];
    if (!cj_string(obj, parent, key, &text, err))
        return 0;
    for (; table->name != NULL; table++) {
        if (strcmp(table->name, text) == 0) {
            *out = table->value;
            return 1;
        }
    }
    cj_path(path, sizeof path, parent, key);
    return cj_fail(err, "field \"%s\": unknown value \"%s\"", path, text);
}

const char *corpus_status_name(int status, char *buf, size_t size)
{
    const char *name = name_of(status_names, status);
    if (name != NULL)
        return name;
    snprintf(buf, size, "status %d", status);
    return buf;
}

const char *corpus_kind_name(int32_t kind, char *buf, size_t size)
{
    const char *name = name_of(kind_names, kind);
    if (name != NULL)
        return name;
    snprintf(buf, size, "kind %d", (int)kind);
    return buf;
}

static const cJSON *object_field(const cJSON *obj, const char *key, int required,
                                 cj_error *err)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (item == NULL) {
        if (required)
            cj_fail(err, "field \"%s\" is missing", key);
        return NULL;
    }
    if (!cJSON_IsObject(item)) {
        cj_fail(err, "field \"%s\" must be an object", key);
        return NULL;
    }
    return item;
}

static int ray_parse(const cJSON *item, isect_ray *ray, cj_error *err)
{
    const cJSON *obj = object_field(item, "ray", 1, err);
    if (obj == NULL)
        return 0;
    return cj_vector(obj, "ray", "org", 3, ray->org, err) &&
           cj_vector(obj, "ray", "dir", 3, ray->dir, err) &&
           cj_number_or(obj, "ray", "tmin", 0.0, &ray->tmin, err) &&
           cj_number_or(obj, "ray", "tmax", INFINITY, &ray->tmax, err);
}

/* "flags": names, or integers OR-ed in raw so bad-input cases can set bits
 * the library does not know. */
static int opts_flags_parse(const cJSON *obj, uint32_t *flags, cj_error *err)
{
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(obj, "flags");
    const cJSON *flag;
    int i = 0;
    *flags = 0;
    if (list == NULL)
        return 1;
    if (!cJSON_IsArray(list))
        return cj_fail(err, "field \"opts.flags\" must be an array");
    cJSON_ArrayForEach(flag, list) {
        char path[64];
        snprintf(path, sizeof path, "opts.flags[%d]", i);
        if (cJSON_IsString(flag) && flag->valuestring != NULL) {
            const name_value *entry = opts_flag_names;
            while (entry->name != NULL && strcmp(entry->name, flag->valuestring) != 0)
                entry++;
            if (entry->name == NULL)
                return cj_fail(err, "field \"%s\": unknown flag \"%s\"", path, flag->valuestring);
            *flags |= (uint32_t)entry->value;
        } else {
            long long raw = 0;
            if (!cj_integer_value(flag, path, 0, UINT32_MAX, &raw, err))
                return cj_fail(err, "field \"%s\" must be a flag name or an integer", path);
            *flags |= (uint32_t)raw;
        }
        i++;
    }
    return 1;
}

static int opts_parse(const cJSON *item, corpus_case *c, cj_error *err)
{
    const cJSON *obj = object_field(item, "opts", 0, err);
    if (obj == NULL)
        return cJSON_GetObjectItemCaseSensitive(item, "opts") == NULL;
    c->has_opts = 1;
    c->opts.size = (uint32_t)sizeof(isect_opts);
    return opts_flags_parse(obj, &c->opts.flags, err) &&
           cj_number_or(obj, "opts", "eps", ISECT_EPS_DEFAULT, &c->opts.eps, err);
}

static int transform_parse(const cJSON *item, corpus_case *c, cj_error *err)
{
    if (cJSON_GetObjectItemCaseSensitive(item, "transform") == NULL)
        return 1;
    c->has_transform = 1;
    return cj_vector(item, "", "transform", 16, c->transform, err);
}

static int tolerance_parse(const cJSON *item, corpus_tolerance *tol, cj_error *err)
{
    const cJSON *obj = object_field(item, "tol", 0, err);
    tol->t = tol->point = tol->normal = tol->uv = DEFAULT_TOLERANCE;
    tol->volume = tol->area = tol->winding = DEFAULT_TOLERANCE;
    if (obj == NULL)
        return cJSON_GetObjectItemCaseSensitive(item, "tol") == NULL;
    return cj_number_or(obj, "tol", "t", DEFAULT_TOLERANCE, &tol->t, err) &&
           cj_number_or(obj, "tol", "point", DEFAULT_TOLERANCE, &tol->point, err) &&
           cj_number_or(obj, "tol", "normal", DEFAULT_TOLERANCE, &tol->normal, err) &&
           cj_number_or(obj, "tol", "uv", DEFAULT_TOLERANCE, &tol->uv, err) &&
           cj_number_or(obj, "tol", "volume", DEFAULT_TOLERANCE, &tol->volume, err) &&
           cj_number_or(obj, "tol", "area", DEFAULT_TOLERANCE, &tol->area, err) &&
           cj_number_or(obj, "tol", "winding", DEFAULT_TOLERANCE, &tol->winding, err);
}

/* "flags" is informational here (the C runner runs every case, c-only
 * included), but a malformed list is still a malformed case. */
static int case_flags_check(const cJSON *item, cj_error *err)
{
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(item, "flags");
    const cJSON *flag;
    int i = 0;
    if (list == NULL)
        return 1;
    if (!cJSON_IsArray(list))
        return cj_fail(err, "field \"flags\" must be an array of strings");
    cJSON_ArrayForEach(flag, list) {
        if (!cJSON_IsString(flag))
            return cj_fail(err, "field \"flags[%d]\" must be a string", i);
        i++;
    }
    return 1;
}

static int expected_hit_parse(const cJSON *hit, const char *path, corpus_expected_hit *h,
                              cj_error *err)
{
    long long prim = 0;
    int kind = ISECT_MISS;
    if (!cJSON_IsObject(hit))
        return cj_fail(err, "field \"%s\" must be an object", path);
    if (!cj_number(hit, path, "t", &h->t, err) ||
        !cj_vector(hit, path, "point", 3, h->point, err) ||
        !cj_vector(hit, path, "normal", 3, h->normal, err) ||
        !cj_integer(hit, path, "prim", INT32_MIN, INT32_MAX, &prim, err) ||
        !enum_parse(hit, path, "kind", kind_names, &kind, err))
        return 0;
    h->prim = (int32_t)prim;
    h->kind = kind;
    h->has_uv = cJSON_HasObjectItem(hit, "uv");
    return !h->has_uv || cj_vector(hit, path, "uv", 2, h->uv, err);
}

static int expected_hits_parse(const cJSON *expect, corpus_case *c, cj_error *err)
{
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(expect, "hits");
    const cJSON *hit;
    int i = 0;
    if (list == NULL)
        return 1;
    if (!cJSON_IsArray(list))
        return cj_fail(err, "field \"expect.hits\" must be an array");
    if (cJSON_GetArraySize(list) != c->count)
        return cj_fail(err, "field \"expect.hits\" lists %d hits but \"expect.count\" is %d",
                       cJSON_GetArraySize(list), c->count);
    c->hits_listed = 1;
    c->hits = calloc((size_t)c->count + 1, sizeof *c->hits);
    if (c->hits == NULL)
        return cj_fail(err, "out of memory");
    cJSON_ArrayForEach(hit, list) {
        char path[64];
        snprintf(path, sizeof path, "expect.hits[%d]", i);
        if (!expected_hit_parse(hit, path, &c->hits[i], err))
            return 0;
        i++;
    }
    return 1;
}

static int expect_parse(const cJSON *item, corpus_case *c, cj_error *err)
{
    const cJSON *expect = object_field(item, "expect", 1, err);
    long long value = 0;
    if (expect == NULL || !enum_parse(expect, "expect", "status", status_names, &c->status, err))
        return 0;
    if (c->status != ISECT_OK)
        return 1; /* for an error nothing else is checked */
    switch (c->op) {
    case CORPUS_INTERSECT:
    case CORPUS_SPAWN: /* the hits of the secondary ray */
        if (!cj_integer(expect, "expect", "count", 0, MAX_EXPECTED_COUNT, &value, err))
            return 0;
        c->count = (int)value;
        return expected_hits_parse(expect, c, err);
    case CORPUS_CONTAINS:
    case CORPUS_POINT_IN_POLYGON2:
        if (!cj_integer(expect, "expect", "inside", 0, 1, &value, err))
            return 0;
        c->inside = (int)value;
        return 1;
    case CORPUS_MESH_CHECK:
        return corpus_mesh_report_parse(expect, &c->report, err);
    case CORPUS_WINDING_NUMBER2:
        if (!cj_integer(expect, "expect", "winding", INT32_MIN, INT32_MAX, &value, err))
            return 0;
        c->winding = (int32_t)value;
        return 1;
    case CORPUS_POLYGON_NORMAL:
        return cj_vector(expect, "expect", "normal", 3, c->normal, err);
    case CORPUS_PLANE_FROM_POINTS:
        return cj_vector(expect, "expect", "plane", 4, c->plane, err);
    case CORPUS_WINDING_NUMBER:
        /* One w per point; the calloc'd room is never empty, so a case of
         * no points still has a valid (unused) array. */
        c->windings = calloc((size_t)c->points_n + 1, sizeof *c->windings);
        if (c->windings == NULL)
            return cj_fail(err, "out of memory");
        return cj_vector(expect, "expect", "winding", c->points_n, c->windings, err);
    }
    return 1;
}

/* The op's inputs. */
static int inputs_parse(const cJSON *item, corpus_case *c, cj_error *err)
{
    switch (c->op) {
    case CORPUS_INTERSECT:
        return corpus_shape_parse(cJSON_GetObjectItemCaseSensitive(item, "shape"), &c->shape,
                                  err) &&
               transform_parse(item, c, err) && ray_parse(item, &c->ray, err) &&
               opts_parse(item, c, err);
    case CORPUS_SPAWN:
        /* No opts: the primary and the secondary ray use the defaults. */
        return corpus_shape_parse(cJSON_GetObjectItemCaseSensitive(item, "shape"), &c->shape,
                                  err) &&
               transform_parse(item, c, err) && ray_parse(item, &c->ray, err) &&
               cj_vector(item, "", "dir", 3, c->spawn_dir, err);
    case CORPUS_CONTAINS:
        return corpus_shape_parse(cJSON_GetObjectItemCaseSensitive(item, "shape"), &c->shape,
                                  err) &&
               transform_parse(item, c, err) && cj_vector(item, "", "point", 3, c->point, err);
    case CORPUS_MESH_CHECK:
        /* No transform: the report describes the mesh as it was given. */
        if (!corpus_shape_parse(cJSON_GetObjectItemCaseSensitive(item, "shape"), &c->shape,
                                err))
            return 0;
        if (!c->shape.is_mesh)
            return cj_fail(err, "field \"shape\": op \"mesh_check\" needs a mesh");
        return 1;
    case CORPUS_POINT_IN_POLYGON2:
        return corpus_rule_parse(item, "", "rule", &c->rule, err) &&
               cj_rows(item, "", "polygon", 2, &c->polygon2, &c->polygon2_n, err) &&
               cj_vector(item, "", "point", 2, c->point, err);
    case CORPUS_WINDING_NUMBER2:
        return cj_rows(item, "", "polygon", 2, &c->polygon2, &c->polygon2_n, err) &&
               cj_vector(item, "", "point", 2, c->point, err);
    case CORPUS_POLYGON_NORMAL:
    case CORPUS_PLANE_FROM_POINTS:
        return cj_rows(item, "", "vertices", 3, &c->vertices, &c->vertices_n, err);
    case CORPUS_WINDING_NUMBER:
        /* Any shape (a non-mesh is a bad-input case: E_ARG). */
        return corpus_shape_parse(cJSON_GetObjectItemCaseSensitive(item, "shape"), &c->shape,
                                  err) &&
               transform_parse(item, c, err) &&
               cj_rows(item, "", "points", 3, &c->points, &c->points_n, err) &&
               cj_number_or(item, "", "accuracy", 0.0, &c->accuracy, err);
    }
    return 1;
}

int corpus_case_parse(const cJSON *item, corpus_case *c, cj_error *err)
{
    int op = CORPUS_INTERSECT;
    memset(c, 0, sizeof *c);
    c->rule = ISECT_EVEN_ODD;
    if (!cJSON_IsObject(item))
        return cj_fail(err, "the case must be an object");
    if (!cj_string(item, "", "name", &c->name, err) || !case_flags_check(item, err))
        return 0;
    if (cJSON_HasObjectItem(item, "op") && !enum_parse(item, "", "op", op_names, &op, err))
        return 0;
    c->op = (corpus_op)op;
    return inputs_parse(item, c, err) && tolerance_parse(item, &c->tol, err) &&
           expect_parse(item, c, err);
}

void corpus_case_free(corpus_case *c)
{
    corpus_shape_free(&c->shape);
    free(c->polygon2);
    free(c->vertices);
    free(c->hits);
    free(c->points);
    free(c->windings);
    c->polygon2 = c->vertices = c->points = c->windings = NULL;
    c->hits = NULL;
}
