/* SPDX-License-Identifier: Apache-2.0 */
/*
 * layout_probe.c — what the C compiler says about isect.h, for
 * test_layout.f90: struct sizes and field offsets, the value of every
 * constant, and ISECT_OPTS_INIT. The Fortran test asks by name, so a field or
 * constant that one side lacks is reported rather than silently skipped.
 */
#include "isect.h"

#include <stddef.h>
#include <string.h>

typedef struct named_value {
    const char *name;
    long long value;
} named_value;

#define SIZE_OF(type) { "sizeof " #type, (long long)sizeof(type) }
#define OFFSET_OF(type, field) { #type "." #field, (long long)offsetof(type, field) }

static const named_value layout[] = {
    SIZE_OF(isect_ray),
    OFFSET_OF(isect_ray, org),
    OFFSET_OF(isect_ray, dir),
    OFFSET_OF(isect_ray, tmin),
    OFFSET_OF(isect_ray, tmax),
    SIZE_OF(isect_hit),
    OFFSET_OF(isect_hit, t),
    OFFSET_OF(isect_hit, point),
    OFFSET_OF(isect_hit, normal),
    OFFSET_OF(isect_hit, uv),
    OFFSET_OF(isect_hit, prim),
    OFFSET_OF(isect_hit, kind),
    SIZE_OF(isect_opts),
    OFFSET_OF(isect_opts, size),
    OFFSET_OF(isect_opts, flags),
    OFFSET_OF(isect_opts, eps),
    SIZE_OF(isect_xform),
    OFFSET_OF(isect_xform, m),
    OFFSET_OF(isect_xform, inv),
    SIZE_OF(isect_shape),
    OFFSET_OF(isect_shape, type),
    OFFSET_OF(isect_shape, n),
    OFFSET_OF(isect_shape, flags),
    OFFSET_OF(isect_shape, reserved),
    OFFSET_OF(isect_shape, data),
    OFFSET_OF(isect_shape, mesh),
    OFFSET_OF(isect_shape, xform),
    SIZE_OF(isect_mesh_report),
    OFFSET_OF(isect_mesh_report, vertices),
    OFFSET_OF(isect_mesh_report, edges),
    OFFSET_OF(isect_mesh_report, faces),
    OFFSET_OF(isect_mesh_report, boundary_edges),
    OFFSET_OF(isect_mesh_report, nonmanifold_edges),
    OFFSET_OF(isect_mesh_report, misoriented_edges),
    OFFSET_OF(isect_mesh_report, degenerate_faces),
    OFFSET_OF(isect_mesh_report, components),
    OFFSET_OF(isect_mesh_report, euler_characteristic),
    OFFSET_OF(isect_mesh_report, genus),
    OFFSET_OF(isect_mesh_report, closed),
    OFFSET_OF(isect_mesh_report, oriented),
    OFFSET_OF(isect_mesh_report, volume),
    OFFSET_OF(isect_mesh_report, area),
    OFFSET_OF(isect_mesh_report, reserved),
};

#define CONSTANT(name) { #name, (long long)(name) }

static const named_value constants[] = {
    CONSTANT(ISECT_VERSION_MAJOR),
    CONSTANT(ISECT_VERSION_MINOR),
    CONSTANT(ISECT_VERSION_PATCH),
    CONSTANT(ISECT_VERSION),
    CONSTANT(ISECT_ABI_VERSION),
    CONSTANT(ISECT_OK),
    CONSTANT(ISECT_E_ARG),
    CONSTANT(ISECT_E_NONFINITE),
    CONSTANT(ISECT_E_DEGENERATE),
    CONSTANT(ISECT_E_NOMEM),
    CONSTANT(ISECT_MISS),
    CONSTANT(ISECT_ENTER),
    CONSTANT(ISECT_EXIT),
    CONSTANT(ISECT_TOUCH),
    CONSTANT(ISECT_INVALID),
    CONSTANT(ISECT_PLANE),
    CONSTANT(ISECT_SPHERE),
    CONSTANT(ISECT_AABB),
    CONSTANT(ISECT_TRIANGLE),
    CONSTANT(ISECT_POLYGON),
    CONSTANT(ISECT_CONVEX),
    CONSTANT(ISECT_CYLINDER),
    CONSTANT(ISECT_CYLINDER_INF),
    CONSTANT(ISECT_ELLIPSOID),
    CONSTANT(ISECT_QUADRIC),
    CONSTANT(ISECT_MESH),
    CONSTANT(ISECT_EVEN_ODD),
    CONSTANT(ISECT_NONZERO),
    CONSTANT(ISECT_WINDING),
    CONSTANT(ISECT_CAPPED),
    CONSTANT(ISECT_CULL_BACK),
    CONSTANT(ISECT_ANY_HIT),
};

static int look_up(const named_value *table, size_t count, const char *name, long long *value)
{
    size_t i;
    for (i = 0; i < count; i++) {
        if (strcmp(table[i].name, name) == 0) {
            *value = table[i].value;
            return 1;
        }
    }
    return 0;
}

/* "sizeof isect_ray" or "isect_ray.tmin": 1 and *value, or 0 if unknown. */
int probe_layout(const char *name, long long *value)
{
    return look_up(layout, sizeof layout / sizeof layout[0], name, value);
}

/* "ISECT_SPHERE": 1 and *value, or 0 if unknown. */
int probe_constant(const char *name, long long *value)
{
    return look_up(constants, sizeof constants / sizeof constants[0], name, value);
}

/* The number of constants the probe knows, so the test can tell that it
 * asked for every one. */
int probe_constant_count(void)
{
    return (int)(sizeof constants / sizeof constants[0]);
}

double probe_eps_default(void)
{
    return ISECT_EPS_DEFAULT;
}

const char *probe_version_string(void)
{
    return ISECT_VERSION_STRING;
}

/* ISECT_OPTS_INIT, to compare byte for byte with the Fortran default. */
void probe_opts_init(isect_opts *opts)
{
    const isect_opts init = ISECT_OPTS_INIT;
    *opts = init;
}
