/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_shape.c — corpus shape objects as isect_shape descriptors; see
 * corpus_shape.h.
 */
#include "corpus_shape.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* One key of a shape. width > 1: an array of that many numbers; width 1: a
 * plain number; width < 0: a list of rows of -width numbers (its row count
 * becomes isect_shape.n). */
typedef struct shape_key {
    const char *key;
    int width;
} shape_key;

/* The keys of a type in the order its scalar function takes them, which is
 * also the order of isect_shape.data. */
typedef struct shape_layout {
    const char *name;
    int32_t type;
    const char *function; /* the scalar function, for messages */
    shape_key keys[3];
} shape_layout;

static const shape_layout layouts[] = {
    { "plane", ISECT_PLANE, "isect_ray_plane",
      { { "normal", 3 }, { "d", 1 }, { NULL, 0 } } },
    { "sphere", ISECT_SPHERE, "isect_ray_sphere",
      { { "center", 3 }, { "radius", 1 }, { NULL, 0 } } },
    { "box", ISECT_AABB, "isect_ray_aabb",
      { { "lo", 3 }, { "hi", 3 }, { NULL, 0 } } },
    { "triangle", ISECT_TRIANGLE, "isect_ray_triangle",
      { { "a", 3 }, { "b", 3 }, { "c", 3 } } },
    { "polygon", ISECT_POLYGON, "isect_ray_polygon",
      { { "vertices", -3 }, { NULL, 0 }, { NULL, 0 } } },
    { "convex", ISECT_CONVEX, "isect_ray_convex",
      { { "planes", -4 }, { NULL, 0 }, { NULL, 0 } } },
    { "cylinder", ISECT_CYLINDER, "isect_ray_cylinder",
      { { "p0", 3 }, { "p1", 3 }, { "radius", 1 } } },
    { "infinite_cylinder", ISECT_CYLINDER_INF, "isect_ray_cylinder_inf",
      { { "point", 3 }, { "axis", 3 }, { "radius", 1 } } },
    { "ellipsoid", ISECT_ELLIPSOID, "isect_ray_ellipsoid",
      { { "center", 3 }, { "radii", 3 }, { NULL, 0 } } },
    { "quadric", ISECT_QUADRIC, "isect_ray_quadric",
      { { "coeffs", 10 }, { NULL, 0 }, { NULL, 0 } } },
};
#define LAYOUT_COUNT ((int)(sizeof layouts / sizeof layouts[0]))
#define KEYS_PER_LAYOUT 3

static const shape_layout *layout_by_name(const char *name)
{
    int i;
    for (i = 0; i < LAYOUT_COUNT; i++)
        if (strcmp(layouts[i].name, name) == 0)
            return &layouts[i];
    return NULL;
}

/* For a raw integer type: the first layout whose keys are all present. */
static const shape_layout *layout_by_keys(const cJSON *shape)
{
    int i, k;
    for (i = 0; i < LAYOUT_COUNT; i++) {
        int all_present = 1;
        for (k = 0; k < KEYS_PER_LAYOUT && layouts[i].keys[k].key != NULL; k++)
            if (!cJSON_HasObjectItem(shape, layouts[i].keys[k].key))
                all_present = 0;
        if (all_present)
            return &layouts[i];
    }
    return NULL;
}

int corpus_rule_parse(const cJSON *obj, const char *parent, const char *key, int32_t *rule,
                      cj_error *err)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
    char path[160];
    long long raw = 0;

    cj_path(path, sizeof path, parent, key);
    if (item == NULL) {
        *rule = ISECT_EVEN_ODD;
        return 1;
    }
    if (cJSON_IsString(item) && item->valuestring != NULL) {
        if (strcmp(item->valuestring, "evenodd") == 0) {
            *rule = ISECT_EVEN_ODD;
            return 1;
        }
        if (strcmp(item->valuestring, "nonzero") == 0) {
            *rule = ISECT_NONZERO;
            return 1;
        }
        /* A mesh rule; a polygon given it must answer E_ARG, so it is
         * passed like any other value rather than refused here. */
        if (strcmp(item->valuestring, "winding") == 0) {
            *rule = ISECT_WINDING;
            return 1;
        }
        return cj_fail(err, "field \"%s\": unknown rule \"%s\"", path, item->valuestring);
    }
    if (!cj_integer_value(item, path, INT32_MIN, INT32_MAX, &raw, err))
        return cj_fail(err, "field \"%s\" must be \"evenodd\", \"nonzero\" or an integer", path);
    *rule = (int32_t)raw;
    return 1;
}

/* "capped": a bool, or an integer passed through (bad-input cases); the
 * Python constructor's default, true, when absent. */
static int capped_parse(const cJSON *shape, int32_t *capped, cj_error *err)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(shape, "capped");
    long long raw = 0;
    if (item == NULL) {
        *capped = ISECT_CAPPED;
        return 1;
    }
    if (cJSON_IsBool(item)) {
        *capped = cJSON_IsTrue(item) ? ISECT_CAPPED : 0;
        return 1;
    }
    if (!cj_integer_value(item, "shape.capped", INT32_MIN, INT32_MAX, &raw, err))
        return cj_fail(err, "field \"shape.capped\" must be a bool or an integer");
    *capped = (int32_t)raw;
    return 1;
}

/* Zero doubles after the data. A raw integer type may be the number of a
 * type other than the one whose keys it carries (type 10, a quadric, with
 * a sphere's 4 numbers); the library then reads that type's count, and the
 * padding keeps the read inside this buffer. The widest fixed layout has 10
 * numbers, and a row list of n rows is read as at most n*4. */
#define DATA_PADDING 16
#define WIDEST_ROW 4

/* Read the layout's keys into out->data (and n for a row list). */
static int data_parse(const cJSON *shape, const shape_layout *layout, corpus_shape *out,
                      cj_error *err)
{
    int k, total = 0, offset = 0;

    if (layout->keys[0].width < 0) {
        int rows = 0, width = -layout->keys[0].width;
        double *values;
        if (!cj_rows(shape, "shape", layout->keys[0].key, width, &values, &rows, err))
            return 0;
        out->data = calloc((size_t)rows * WIDEST_ROW + DATA_PADDING, sizeof *out->data);
        if (out->data == NULL) {
            free(values);
            return cj_fail(err, "out of memory");
        }
        memcpy(out->data, values, (size_t)rows * (size_t)width * sizeof *values);
        free(values);
        out->desc.n = rows;
        out->desc.data = out->data;
        return 1;
    }
    for (k = 0; k < KEYS_PER_LAYOUT && layout->keys[k].key != NULL; k++)
        total += layout->keys[k].width;
    out->data = calloc((size_t)total + DATA_PADDING, sizeof *out->data);
    if (out->data == NULL)
        return cj_fail(err, "out of memory");
    for (k = 0; k < KEYS_PER_LAYOUT && layout->keys[k].key != NULL; k++) {
        const shape_key *key = &layout->keys[k];
        int ok = key->width == 1
                     ? cj_number(shape, "shape", key->key, out->data + offset, err)
                     : cj_vector(shape, "shape", key->key, key->width, out->data + offset, err);
        if (!ok)
            return 0;
        offset += key->width;
    }
    out->desc.data = out->data;
    return 1;
}

/* A mesh's arrays; its descriptor keeps data NULL and n 0, and gets its
 * mesh only when the case runs (mesh_setup). A named mesh's flags are its
 * containment rule ("rule", evenodd when absent); a raw type with "faces"
 * keeps flags 0, as before the rule existed. */
static int mesh_parse(const cJSON *shape, corpus_shape *out, cj_error *err)
{
    out->is_mesh = 1;
    if (!corpus_mesh_parse(shape, &out->mesh_input, err))
        return 0;
    if (!out->named)
        return 1;
    return corpus_rule_parse(shape, "shape", "rule", &out->desc.flags, err);
}

int corpus_shape_parse(const cJSON *shape, corpus_shape *out, cj_error *err)
{
    const cJSON *type;
    const shape_layout *layout;

    memset(out, 0, sizeof *out);
    if (shape == NULL)
        return cj_fail(err, "field \"shape\" is missing");
    if (!cJSON_IsObject(shape))
        return cj_fail(err, "field \"shape\" must be an object");
    type = cJSON_GetObjectItemCaseSensitive(shape, "type");
    if (type == NULL)
        return cj_fail(err, "field \"shape.type\" is missing");
    if (cJSON_IsString(type) && type->valuestring != NULL) {
        out->named = 1;
        if (strcmp(type->valuestring, "mesh") == 0) {
            out->desc.type = ISECT_MESH;
            return mesh_parse(shape, out, err);
        }
        layout = layout_by_name(type->valuestring);
        if (layout == NULL)
            return cj_fail(err, "field \"shape.type\": unknown type \"%s\"", type->valuestring);
        out->scalar = 1;
        out->desc.type = layout->type;
    } else {
        long long raw = 0;
        if (!cj_integer_value(type, "shape.type", INT32_MIN, INT32_MAX, &raw, err))
            return cj_fail(err, "field \"shape.type\" must be a type name or an integer");
        out->desc.type = (int32_t)raw;
        /* Tested before the layouts: a mesh's "vertices" would pass for a
         * polygon's. */
        if (cJSON_HasObjectItem(shape, "faces"))
            return mesh_parse(shape, out, err);
        layout = layout_by_keys(shape);
    }
    if (layout != NULL && !data_parse(shape, layout, out, err))
        return 0;
    /* Flags: named types take theirs; a raw type takes whichever is given. */
    if ((out->named && out->desc.type == ISECT_POLYGON) ||
        (!out->named && cJSON_HasObjectItem(shape, "rule")))
        return corpus_rule_parse(shape, "shape", "rule", &out->desc.flags, err);
    if ((out->named && out->desc.type == ISECT_CYLINDER) ||
        (!out->named && cJSON_HasObjectItem(shape, "capped")))
        return capped_parse(shape, &out->desc.flags, err);
    return 1;
}

void corpus_shape_free(corpus_shape *s)
{
    free(s->data);
    s->data = NULL;
    s->desc.data = NULL;
    corpus_mesh_input_free(&s->mesh_input);
    isect_mesh_destroy(s->mesh);
    s->mesh = NULL;
    s->desc.mesh = NULL;
}

int corpus_shape_scalar(const isect_shape *s, const isect_ray *ray, const isect_opts *opts,
                        isect_hit *hits, int cap)
{
    const double *d = s->data;
    switch (s->type) {
    case ISECT_PLANE:
        return isect_ray_plane(ray, d, d[3], opts, hits, cap);
    case ISECT_SPHERE:
        return isect_ray_sphere(ray, d, d[3], opts, hits, cap);
    case ISECT_AABB:
        return isect_ray_aabb(ray, d, d + 3, opts, hits, cap);
    case ISECT_TRIANGLE:
        return isect_ray_triangle(ray, d, d + 3, d + 6, opts, hits, cap);
    case ISECT_POLYGON:
        return isect_ray_polygon(ray, d, s->n, s->flags, opts, hits, cap);
    case ISECT_CONVEX:
        return isect_ray_convex(ray, d, s->n, opts, hits, cap);
    case ISECT_CYLINDER:
        return isect_ray_cylinder(ray, d, d + 3, d[6], s->flags, opts, hits, cap);
    case ISECT_CYLINDER_INF:
        return isect_ray_cylinder_inf(ray, d, d + 3, d[6], opts, hits, cap);
    case ISECT_ELLIPSOID:
        return isect_ray_ellipsoid(ray, d, d + 3, opts, hits, cap);
    case ISECT_QUADRIC:
        return isect_ray_quadric(ray, d, opts, hits, cap);
    default:
        /* Only types with a scalar function reach here, and each has a case above. */
        return ISECT_E_ARG;
    }
}

const char *corpus_shape_scalar_name(int32_t type)
{
    int i;
    for (i = 0; i < LAYOUT_COUNT; i++)
        if (layouts[i].type == type)
            return layouts[i].function;
    return "(no scalar function)";
}
