/*
 * demo.c — one ray through every primitive of the lecture notes, printed as a
 * table: what `make demo` shows until the rendered scene exists.
 */
#include <isect.h>

#include <math.h>
#include <stdio.h>

static const char *kind_name(int32_t kind)
{
    static const char *names[] = { "miss", "enter", "exit", "touch", "invalid" };
    return kind >= 0 && kind <= 4 ? names[kind] : "?";
}

static void show(const char *label, const isect_shape *s, const isect_ray *r)
{
    isect_hit h[8];
    int n = isect_intersect(s, r, NULL, h, 8);
    if (n < 0) {
        printf("%-26s error: %s\n", label, isect_strerror(n));
        return;
    }
    printf("%-26s %d hit%s\n", label, n, n == 1 ? "" : "s");
    for (int i = 0; i < n && i < 8; i++)
        printf("    t = %-10.6g %-5s prim %2d  point (% .4f % .4f % .4f)  normal (% .4f % .4f % .4f)\n",
               h[i].t, kind_name(h[i].kind), h[i].prim, h[i].point[0], h[i].point[1],
               h[i].point[2], h[i].normal[0], h[i].normal[1], h[i].normal[2]);
}

int main(void)
{
    /* Every ray starts at z = -5 and looks up +z, slightly tilted. */
    const isect_ray r = { { 0.1, 0.2, -5 }, { 0.01, -0.02, 1 }, 0.0, INFINITY };

    const double plane[4] = { 0, 0, 1, -1 };
    const double sphere[4] = { 0, 0, 0, 1 };
    const double box[6] = { -1, -1, -1, 1, 1, 1 };
    const double tri[9] = { -1, -1, 0, 1, -1, 0, 0, 1, 0 };
    /* An L-shaped (concave) hexagon and a pentagram (self-intersecting). */
    const double ell[18] = { -1, -1, 0, 1, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, -1, 1, 0 };
    double star[15];
    for (int i = 0; i < 5; i++) {
        double a = 2.0 * acos(-1.0) * (2 * i) / 5.0 + acos(-1.0) / 2;
        star[3 * i] = cos(a);
        star[3 * i + 1] = sin(a);
        star[3 * i + 2] = 0;
    }
    const double octa[32] = { 1, 1, 1, -1.5, -1, 1, 1, -1.5, 1, -1, 1, -1.5, -1, -1, 1, -1.5,
                              1, 1, -1, -1.5, -1, 1, -1, -1.5, 1, -1, -1, -1.5, -1, -1, -1, -1.5 };
    const double cyl[7] = { 0, 0, -1, 0, 0, 1, 0.5 };
    const double cyl_inf[7] = { 0, 0, 0, 0, 0, 1, 0.5 };
    const double ellipsoid[6] = { 0, 0, 0, 2, 1, 0.5 };
    /* Hyperboloid of one sheet x^2 + y^2 - z^2 - 0.25 = 0. */
    const double quadric[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, -0.25 };

    struct { const char *label; isect_shape s; } shapes[] = {
        { "plane z = 1", { ISECT_PLANE, 0, 0, 0, plane, NULL, NULL } },
        { "unit sphere", { ISECT_SPHERE, 0, 0, 0, sphere, NULL, NULL } },
        { "box [-1,1]^3", { ISECT_AABB, 0, 0, 0, box, NULL, NULL } },
        { "triangle", { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, NULL } },
        { "L polygon (concave)", { ISECT_POLYGON, 6, ISECT_EVEN_ODD, 0, ell, NULL, NULL } },
        { "pentagram, even-odd", { ISECT_POLYGON, 5, ISECT_EVEN_ODD, 0, star, NULL, NULL } },
        { "pentagram, nonzero", { ISECT_POLYGON, 5, ISECT_NONZERO, 0, star, NULL, NULL } },
        { "octahedron (8 planes)", { ISECT_CONVEX, 8, 0, 0, octa, NULL, NULL } },
        { "capped cylinder", { ISECT_CYLINDER, 0, ISECT_CAPPED, 0, cyl, NULL, NULL } },
        { "infinite cylinder", { ISECT_CYLINDER_INF, 0, 0, 0, cyl_inf, NULL, NULL } },
        { "ellipsoid 2 x 1 x 0.5", { ISECT_ELLIPSOID, 0, 0, 0, ellipsoid, NULL, NULL } },
        { "hyperboloid (quadric)", { ISECT_QUADRIC, 0, 0, 0, quadric, NULL, NULL } },
    };
    printf("libisect %s — ray org (0.1, 0.2, -5) dir (0.01, -0.02, 1)\n\n",
           isect_version_string());
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++)
        show(shapes[i].label, &shapes[i].s, &r);

    /* A transformed object: the unit sphere rotated 30 degrees about x,
     * sheared and moved to z = 2. */
    const double c = cos(acos(-1.0) / 6), s = sin(acos(-1.0) / 6);
    const double m[16] = { 1, 0.3, 0, 0, 0, c, -s, 0, 0, s, c, 2, 0, 0, 0, 1 };
    isect_xform x;
    if (isect_xform_init(&x, m) == ISECT_OK) {
        isect_shape ts = { ISECT_SPHERE, 0, 0, 0, sphere, NULL, &x };
        show("sheared, rotated sphere", &ts, &r);
    }
    return 0;
}
