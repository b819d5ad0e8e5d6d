/* SPDX-License-Identifier: Apache-2.0 */
/*
 * isect.h — libisect, ray–object intersection in double precision.
 *
 * This is the library's one public header. It documents every function, field,
 * status code and rule; README.md repeats the semantics as tables.
 *
 * Conventions that hold for every function below
 * ----------------------------------------------
 *  - A ray is P(t) = org + t*dir. dir need not be unit length and is never
 *    renormalised, so t means the same thing in every frame (world, object,
 *    transformed). Hits are reported for tmin <= t <= tmax only.
 *  - Functions that report hits return the number of hits found and write the
 *    first min(count, cap) of them, sorted by t (ties by prim), like snprintf.
 *    "By t" is by the exact crossing parameter: two crossings whose exact t
 *    differ but round to the same double (a ray entering through a cap and
 *    leaving through the side a few 1e-20 later, or grazing a mesh edge
 *    through its two faces) keep their exact order, so an entry always
 *    precedes its exit and the closest hit is the exactly closest one. cap
 *    may be 0 with hits NULL to count only.
 *  - A negative return value is an error status (ISECT_E_*); isect_strerror()
 *    describes it. Nothing is written to the hit buffer on error. No function
 *    aborts, prints or keeps global state; all are reentrant. Three
 *    functions allocate and can fail with ISECT_E_NOMEM: isect_mesh_create
 *    (the mesh), isect_mesh_check (working arrays of the size of the mesh's
 *    face corners) and isect_winding_number_batch (its cluster tree), the
 *    last two freeing them before they return. isect_intersect_batch on a mesh
 *    allocates its traversal lanes when it can and otherwise traces the same
 *    records without them: it never fails for memory. Nothing else
 *    allocates.
 *  - Degenerate geometry that real data contains (zero-area triangle, collinear
 *    polygon, zero radius, zero-length cylinder axis, zero plane normal, flat
 *    box) is not an error: it is never hit and contains no point.
 *  - Near-parallel and tangent decisions use the explicit scale-invariant
 *    tolerance opts->eps (see "Epsilon policy"). Decisions at vertices and
 *    edges use no tolerance at all: they are exact (see "Tie-breaking").
 *
 * Epsilon policy (eps = opts->eps, default ISECT_EPS_DEFAULT = 1e-12)
 * -------------------------------------------------------------------
 *  - Plane, convex-polyhedron face (and cylinder cap) with normal n:
 *    parallel to the ray when |n.d| <= eps*|n|*|d|. A parallel plane is not
 *    hit (a ray lying in it included). A parallel convex-polyhedron face
 *    constrains the ray by the side its origin is on (on the plane = inside).
 *  - Triangles, polygons and mesh faces use no eps at all: the exact test of
 *    "Tie-breaking" alone decides whether they are crossed; only a ray
 *    exactly parallel to the face's plane (n.d == 0) has no crossing. So
 *    exactly-once holds at every eps.
 *  - Quadric surfaces decide a single TOUCH hit (tangency) with a relative
 *    test documented at each function. With eps = 0 only exact tangency
 *    (a zero discriminant) touches.
 *
 * Tie-breaking at vertices and edges (exactly-once)
 * -------------------------------------------------
 *  Triangles and polygons are tested in the ray's sheared frame (Woop, Benthin
 *  & Wald 2013): vertices are translated by -org and sheared so the ray becomes
 *  the +z axis through the 2D origin. The frame: kz = index of the largest
 *  |dir[k]| (the lowest index on ties), kx = (kz+1) mod 3, ky = (kz+2) mod 3,
 *  kx and ky swapped when dir[kz] < 0; a point p maps to
 *  x = (p-org)[kx] - (dir[kx]/dir[kz]) (p-org)[kz], y likewise with ky,
 *  EXACTLY: the 2D inside test at the origin is decided on the exact
 *  projected coordinates of the given doubles, never on rounded ones.
 *  (Multiplied by |dir[kz]|, which keeps every sign below, x and y are the
 *  degree-2 polynomials -((p-org) x dir)[ky] and ((p-org) x dir)[kx], and
 *  the orientation of an edge p -> q about the origin is the sign of
 *  dir . ((p-org) x (q-org)).) Each sign is computed in plain double with a
 *  forward error bound and, where the bound cannot certify it, exactly
 *  (sums of products at any exponent), so the decision is exact for every
 *  finite input, subnormal numbers included. A ray through an edge or vertex
 *  is decided by a symbolic perturbation of the query point, applied to the
 *  exact coordinates — it is moved by (-e^2, -e) for an infinitesimal
 *  e > 0, so a vertex on the horizontal test line (y == 0) counts as above
 *  it and a horizontal edge on the line counts for neither side (the
 *  "logically move the ray up epsilon" rule made exact): an edge with
 *  orientation 0 takes the sign of x_p - x_q, then of y_q - y_p. Every
 *  decision about an edge depends on its two vertices and the ray alone, so
 *  adjacent faces agree about it. Consequence: a ray crossing a closed,
 *  consistently oriented surface through a shared edge or vertex is counted
 *  exactly once, and one that only grazes a silhouette edge or vertex is
 *  counted an even number of times. The 2D helpers isect_point_in_polygon2()
 *  and isect_winding_number2() use the same rule on their given 2D points.
 */
#ifndef ISECT_H
#define ISECT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- version */
/* The one place the version is defined; Makefile and meson.build read it. */
#define ISECT_VERSION_MAJOR 1
#define ISECT_VERSION_MINOR 1
#define ISECT_VERSION_PATCH 0
#define ISECT_VERSION \
    (ISECT_VERSION_MAJOR * 10000 + ISECT_VERSION_MINOR * 100 + ISECT_VERSION_PATCH)
#define ISECT_VERSION_STRING "1.1.0"
/* ABI version: the soname's number (libisect.so.1). Changes only if an
 * existing function or struct layout ever changes, which the ABI policy
 * forbids; minor releases only add. */
#define ISECT_ABI_VERSION 1

/* ---------------------------------------------------------- export macro */
#if defined(ISECT_STATIC)
#  define ISECT_API
#elif defined(_WIN32)
#  if defined(ISECT_BUILDING_LIBRARY)
#    define ISECT_API __declspec(dllexport)
#  else
#    define ISECT_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#  define ISECT_API __attribute__((visibility("default")))
#else
#  define ISECT_API
#endif

/* ---------------------------------------------------------- status codes */
#define ISECT_OK            0
#define ISECT_E_ARG        (-1) /* NULL where required, bad count, negative radius,
                                   bad eps, unknown shape type, rule or flag */
#define ISECT_E_NONFINITE  (-2) /* NaN or Inf where a finite number is required */
#define ISECT_E_DEGENERATE (-3) /* zero ray direction, singular transform */
#define ISECT_E_NOMEM      (-4) /* allocation failed */

/* ------------------------------------------------------------- hit kinds */
#define ISECT_MISS    0 /* batch output only: the ray hit nothing in [tmin, tmax] */
#define ISECT_ENTER   1 /* dir.normal < 0: entering a solid / front side of a thin surface */
#define ISECT_EXIT    2 /* dir.normal > 0: leaving a solid / back side of a thin surface */
#define ISECT_TOUCH   3 /* tangent contact, reported once */
#define ISECT_INVALID 4 /* batch output only: that ray was bad (NaN/Inf, zero dir) */

/* ----------------------------------------------------------- shape types */
/* 0 is deliberately not a type, so a zeroed descriptor is rejected. */
#define ISECT_PLANE        1  /* data: n[3], d            (n.x + d = 0)            */
#define ISECT_SPHERE       2  /* data: c[3], r                                      */
#define ISECT_AABB         3  /* data: lo[3], hi[3]                                 */
#define ISECT_TRIANGLE     4  /* data: a[3], b[3], c[3]                             */
#define ISECT_POLYGON      5  /* data: v[n][3]; n = vertex count; flags = rule      */
#define ISECT_CONVEX       6  /* data: planes[n][4]; n = plane count                */
#define ISECT_CYLINDER     7  /* data: p0[3], p1[3], r; flags = ISECT_CAPPED or 0   */
#define ISECT_CYLINDER_INF 8  /* data: p[3], axis[3], r                             */
#define ISECT_ELLIPSOID    9  /* data: c[3], radii[3]                               */
#define ISECT_QUADRIC      10 /* data: q[10] = A..J                                 */
#define ISECT_MESH         11 /* mesh: a handle from isect_mesh_create; data NULL */

/* Fill rules: isect_shape.flags of an ISECT_POLYGON (EVEN_ODD or NONZERO)
 * and of an ISECT_MESH, where they choose what isect_contains means
 * (see there; ray queries ignore them). */
#define ISECT_EVEN_ODD 0 /* inside where the crossing number is odd */
#define ISECT_NONZERO  1 /* inside where the winding number is not zero */
#define ISECT_WINDING  2 /* mesh: inside where the generalized winding number is >= 1/2 */

/* Cylinder flag (isect_shape.flags for ISECT_CYLINDER). */
#define ISECT_CAPPED 1

/* isect_opts.flags */
#define ISECT_CULL_BACK 0x1u /* drop EXIT hits of thin surfaces (plane, triangle,
                                polygon, open cylinder) */
#define ISECT_ANY_HIT   0x2u /* batch and mesh: stop at the first hit found
                                (occlusion queries; isect_intersect then
                                reports 0 or 1 hit); for analytic shapes the
                                result equals the closest hit */

#define ISECT_EPS_DEFAULT 1e-12

/* ------------------------------------------------------------------ types */

/* A ray: P(t) = org + t*dir for tmin <= t <= tmax. 64 bytes.
 *  org, dir  finite; dir != 0 (else ISECT_E_NONFINITE / ISECT_E_DEGENERATE).
 *  tmin,tmax not NaN; tmin may be -INFINITY and tmax +INFINITY;
 *            tmin > tmax gives no hits. */
typedef struct isect_ray {
    double org[3];
    double dir[3];
    double tmin;
    double tmax;
} isect_ray;

/* One intersection. 80 bytes.
 *  t       ray parameter of the hit.
 *  point   org + t*dir, or the same point snapped onto the surface where
 *          that is more accurate (sphere, ellipsoid).
 *  normal  unit length; outward for solids; for thin surfaces the surface's
 *          own normal (right-hand rule over the vertex order, plane: n).
 *  uv      triangle: barycentric weights of vertices b and c (u, v; the
 *          weight of a is 1-u-v); else 0, 0.
 *  prim    sub-part index: box faces 0..5 = -x,+x,-y,+y,-z,+z; convex: plane
 *          index; cylinder 0 = side, 1 = cap at p0, 2 = cap at p1; -1 where
 *          the shape has no sub-parts (plane, sphere, triangle, polygon,
 *          ellipsoid, quadric) and for MISS / INVALID.
 *  kind    ISECT_ENTER / _EXIT / _TOUCH; ISECT_MISS and ISECT_INVALID only in
 *          batch output (MISS: t = +INFINITY; INVALID: t = NaN; other fields 0). */
typedef struct isect_hit {
    double  t;
    double  point[3];
    double  normal[3];
    double  uv[2];
    int32_t prim;
    int32_t kind;
} isect_hit;

/* Options. 16 bytes. Set size = sizeof(isect_opts); the library reads only
 * the fields size covers (fields may be appended later) and uses defaults for
 * the rest. size < 8 is ISECT_E_ARG. A NULL isect_opts* means the defaults.
 *  flags  ISECT_CULL_BACK | ISECT_ANY_HIT; unknown bits are ISECT_E_ARG.
 *  eps    >= 0 (else ISECT_E_ARG) and finite (NaN/Inf: ISECT_E_NONFINITE);
 *         see "Epsilon policy". */
typedef struct isect_opts {
    uint32_t size;
    uint32_t flags;
    double   eps;
} isect_opts;
#define ISECT_OPTS_INIT { (uint32_t)sizeof(isect_opts), 0u, ISECT_EPS_DEFAULT }

/* An affine object-to-world transform: m and its inverse inv, both row-major
 * 4x4 with last row 0 0 0 1. Fill it with isect_xform_init(). 256 bytes. */
typedef struct isect_xform {
    double m[16];
    double inv[16];
} isect_xform;

/* A closed or open polygon mesh with its BVH: opaque, immutable after
 * isect_mesh_create, safe to query from many threads at once. */
typedef struct isect_mesh isect_mesh;

/* What isect_mesh_check finds. 128 bytes. Edges are undirected vertex pairs
 * of face boundaries. */
typedef struct isect_mesh_report {
    int64_t vertices;             /* vertices referenced by at least one face */
    int64_t edges;
    int64_t faces;
    int64_t boundary_edges;       /* used by exactly one face */
    int64_t nonmanifold_edges;    /* used by three or more faces */
    int64_t misoriented_edges;    /* used twice in the same direction */
    int64_t degenerate_faces;     /* zero area (never hit) */
    int64_t components;           /* connected through shared edges */
    int64_t euler_characteristic; /* V - E + F */
    int64_t genus;                /* closed oriented surfaces: sum over components of
                                     (2 - chi_c)/2; -1 when not closed and oriented */
    int32_t closed;               /* 1: no boundary and no non-manifold edges */
    int32_t oriented;             /* 1: no misoriented edges */
    double  volume;               /* signed (divergence theorem); > 0 for outward faces;
                                     +-inf when it exceeds the double range (a mesh
                                     ~1e103 across), 0 or subnormal below it */
    double  area;                 /* inf when it exceeds the double range (~1e154
                                     across); never NaN for a valid mesh */
    int64_t reserved[3];
} isect_mesh_report;

/* One descriptor for every primitive. 40 bytes on 64-bit targets.
 *  type      ISECT_PLANE ... ISECT_MESH.
 *  n         polygon: vertex count (>= 3); convex: plane count (>= 1); else 0.
 *  flags     polygon: ISECT_EVEN_ODD or ISECT_NONZERO; cylinder: ISECT_CAPPED
 *            or 0; mesh: ISECT_EVEN_ODD, ISECT_NONZERO or ISECT_WINDING (the
 *            containment rule); else 0.
 *  reserved  must be 0.
 *  data      the primitive's numbers in the order of its scalar function's
 *            arguments (see the shape-type list above); not copied.
 *  mesh      ISECT_MESH only (then data is NULL and n 0); else NULL.
 *  xform     NULL, or the object-to-world transform: the ray is taken to
 *            object space by inv, hits are returned in world space (t kept,
 *            points by m, normals by the inverse transpose, renormalised). */
typedef struct isect_shape {
    int32_t            type;
    int32_t            n;
    int32_t            flags;
    int32_t            reserved;
    const double      *data;
    const isect_mesh  *mesh;
    const isect_xform *xform;
} isect_shape;

/* -------------------------------------------------------- version, errors */
ISECT_API unsigned    isect_version(void);         /* ISECT_VERSION of the built library */
ISECT_API const char *isect_version_string(void);  /* "MAJOR.MINOR.PATCH" */
ISECT_API int         isect_abi_version(void);     /* ISECT_ABI_VERSION; equals the soname number */
ISECT_API const char *isect_strerror(int status);  /* never NULL; "unknown status" for others */

/* ---------------------------------------------------- scalar primitives
 * All: (ray, geometry..., opts or NULL, hits or NULL, cap) -> count or error.
 * ISECT_E_ARG for NULL ray/geometry, cap < 0, hits NULL with cap > 0, bad opts;
 * ISECT_E_NONFINITE for NaN/Inf in the ray (tmin/tmax: NaN only) or geometry;
 * ISECT_E_DEGENERATE for a zero ray direction. */

/* Plane n.x + d = 0. Thin surface; normal = n/|n|; prim -1. ENTER when
 * dir.n < 0. Parallel (|n.d| <= eps|n||d|): no hit. n = 0: degenerate. */
ISECT_API int isect_ray_plane(const isect_ray *ray, const double n[3], double d,
                              const isect_opts *opts, isect_hit *hits, int cap);

/* Sphere |x - c| = r, r >= 0 (r < 0: ISECT_E_ARG; r = 0: degenerate).
 * Roots without cancellation (after Haines et al., Ray Tracing Gems 2019):
 * with f = org - c and d = dir, the midpoint t_m = -(f.d)/|d|^2 and the
 * discriminant r^2|d|^2 - |f x d|^2 (= |d|^2 (r^2 - h^2), h the distance
 * from c to the line) are formed in twice the working precision; the root
 * farther from 0 is t_m + sign(t_m) w (w the half chord), the nearer one
 * (|f|^2 - r^2)/|d|^2 divided by it when cancellation would threaten.
 * TOUCH when |r^2 - h^2| <= eps*r^2: one hit at t_m (with eps >= 1 a line
 * through c qualifies: its normal is then -unit(dir)). Points are snapped to
 * c + r*normal when that is more accurate than org + t*dir. prim -1. */
ISECT_API int isect_ray_sphere(const isect_ray *ray, const double c[3], double r,
                               const isect_opts *opts, isect_hit *hits, int cap);

/* Closed axis-aligned box lo <= x <= hi (lo > hi in any axis: ISECT_E_ARG;
 * lo == hi in any axis: degenerate). Slab method; a ray parallel to a slab is
 * inside it iff lo <= org <= hi on that axis (no 0*inf is ever formed). Entry
 * and exit face indices in prim (0..5 = -x,+x,-y,+y,-z,+z; ties between
 * faces at an edge or corner go to the lowest index). Entry == exit (a ray
 * grazing an edge or corner): one TOUCH hit with the lower of the entry and
 * exit face indices and that face's normal. A ray lying in a face plane
 * inside the face is inside the closed box. Hit points are snapped onto the
 * face plane and clamped into [lo, hi]. t = 0 is reported as +0.0. */
ISECT_API int isect_ray_aabb(const isect_ray *ray, const double lo[3], const double hi[3],
                             const isect_opts *opts, isect_hit *hits, int cap);

/* Triangle a, b, c. Thin surface; normal = unit((b-a) x (c-a)); prim -1;
 * uv = barycentric weights of b and c. Watertight: exact edge tests on the
 * exact sheared projection with the tie-breaking rule above; no eps (a ray
 * exactly parallel to the plane is not hit). Zero area: degenerate. */
ISECT_API int isect_ray_triangle(const isect_ray *ray, const double a[3], const double b[3],
                                 const double c[3], const isect_opts *opts,
                                 isect_hit *hits, int cap);

/* Planar polygon v[n][3], n >= 3 (else ISECT_E_ARG), convex, concave or
 * self-intersecting; rule ISECT_EVEN_ODD or ISECT_NONZERO (else ISECT_E_ARG).
 * Plane: Newell's normal through the vertex centroid; normal = unit Newell
 * normal (right-hand rule over the vertex order); prim -1. Inside test:
 * winding number of the origin of the exact sheared projection, with the
 * tie-breaking rule above; no eps. Degenerate (never hit): an exact Newell
 * normal of zero (all vertices collinear, or signed areas that cancel
 * exactly); a sliver whose normal is tiny but not zero has that plane. */
ISECT_API int isect_ray_polygon(const isect_ray *ray, const double *v, int n, int rule,
                                const isect_opts *opts, isect_hit *hits, int cap);

/* Convex polyhedron: the intersection of m >= 1 half-spaces a x + b y + c z + d <= 0
 * given as planes[m][4] with outward normals (a, b, c). enterMax/exitMin over
 * the planes; prim = plane index (ties: lowest index). A parallel plane
 * (epsilon policy) constrains by the side of the origin: a*ox+b*oy+c*oz+d > 0
 * means no hit at all. enterMax == exitMin: one TOUCH with the lower of the
 * two plane indices. An unbounded polyhedron may have only an ENTER or only
 * an EXIT hit. A zero-normal plane acts through the parallel rule (d > 0:
 * empty). */
ISECT_API int isect_ray_convex(const isect_ray *ray, const double *planes, int m,
                               const isect_opts *opts, isect_hit *hits, int cap);

/* Finite cylinder of radius r around the segment p0-p1. capped != 0: a closed
 * solid (side prim 0, cap disk at p0 prim 1, cap at p1 prim 2; entry/exit as
 * for a convex solid); capped == 0: the open side only, a thin surface with
 * the outward radial normal. Side tangency: TOUCH when |r^2 - h^2| <= eps*r^2,
 * h the distance between the ray's line and the axis. A ray parallel to the
 * axis (|d x a| <= eps|d||a|) does not hit the side. Caps follow the
 * convex-face rule (parallel when |d.a| <= eps|d||a|: the origin's side
 * decides, on the cap plane = inside). Entry/exit ties go to the lowest prim,
 * so a ray through the rim is reported on the side; entry == exit is one
 * TOUCH with the entry's prim and normal. r = 0 or p0 == p1: degenerate.
 * capped not 0/1: ISECT_E_ARG. */
ISECT_API int isect_ray_cylinder(const isect_ray *ray, const double p0[3], const double p1[3],
                                 double r, int capped, const isect_opts *opts,
                                 isect_hit *hits, int cap);

/* Infinite cylinder of radius r around the line p + s*axis (axis any nonzero
 * length; zero: degenerate). A solid: outward radial normal, prim 0. Same
 * tangency and parallel rules as the finite side. */
ISECT_API int isect_ray_cylinder_inf(const isect_ray *ray, const double p[3], const double axis[3],
                                     double r, const isect_opts *opts,
                                     isect_hit *hits, int cap);

/* Axis-aligned ellipsoid sum(((x - c)/radii)^2) = 1, radii >= 0 (negative:
 * ISECT_E_ARG; a zero radius: degenerate). Solved as the unit sphere in the
 * scaled frame (t is unchanged by the scaling), with the sphere's tangency
 * test there: TOUCH when |1 - h'^2| <= eps. Normal: unit((x - c)/radii^2).
 * prim -1. Rotate it with a transform. */
ISECT_API int isect_ray_ellipsoid(const isect_ray *ray, const double c[3], const double radii[3],
                                  const isect_opts *opts, isect_hit *hits, int cap);

/* General quadric Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0,
 * inside where Q < 0; q[10] = A..J. Along the ray Q = a t^2 + b t + c.
 * Linear case (a ray parallel to a cone's generator, a plane given as a
 * quadric): |a| <= eps * S * |d|^2 with S = max(|A|..|F|) (or S = 0) gives
 * t = -c/b, and a = b = 0 gives no hit. Discriminant b^2 - 4ac with an
 * error-free FMA evaluation; TOUCH when |b^2 - 4ac| <= eps*(b^2 + 4|ac|).
 * a, b, c are formed as compensated sums. Normal: unit(grad Q); where
 * grad Q = 0 (a cone's apex) -unit(dir) for ENTER/TOUCH, +unit(dir) for EXIT.
 * prim -1. All coefficients zero: degenerate. */
ISECT_API int isect_ray_quadric(const isect_ray *ray, const double q[10],
                                const isect_opts *opts, isect_hit *hits, int cap);

/* --------------------------------------------------------------- helpers */

/* Unit normal of the polygon v[n][3] by Newell's method, with vertices taken
 * relative to their centroid (so it is accurate far from the origin, and
 * right for concave and nearly collinear input). ISECT_OK, or
 * ISECT_E_DEGENERATE with normal = 0 for a polygon of zero area;
 * ISECT_E_ARG for n < 3 or NULL. */
ISECT_API int isect_polygon_normal(const double *v, int n, double normal[3]);

/* Plane through the points v[n][3], n >= 3: plane = (a, b, c, d) with (a, b, c)
 * the unit Newell normal and d = -normal.centroid (the area-weighted plane of
 * nearly planar input). ISECT_E_DEGENERATE for collinear points (plane = 0). */
ISECT_API int isect_plane_from_points(const double *v, int n, double plane[4]);

/* 2D point in polygon poly[n][2], n >= 3, exact, with the half-open rule above
 * (a point on an edge belongs to exactly one of two polygons sharing that edge
 * with opposite orientation; tilings of the plane assign each point to exactly
 * one tile). rule ISECT_EVEN_ODD or ISECT_NONZERO. Returns 1 inside, 0 outside,
 * or an error. */
ISECT_API int isect_point_in_polygon2(const double *poly, int n, const double p[2], int rule);

/* Integer winding number of poly[n][2] around p (Hormann & Agathos 2001 /
 * Sunday's crossing form; no trigonometry; same exact rule). Counter-clockwise
 * loops count +1. ISECT_OK and *winding, or an error. */
ISECT_API int isect_winding_number2(const double *poly, int n, const double p[2],
                                    int32_t *winding);

/* Batch versions over pts[m][2]: inside[i] (0/1, or ISECT_INVALID for a
 * non-finite point), winding[i] (INT32_MIN for a non-finite point). Return the
 * number of points inside (resp. with a nonzero winding number) or an error. */
ISECT_API int64_t isect_point_in_polygon2_batch(const double *poly, int n, const double *pts,
                                                int64_t m, int rule, uint8_t *inside);
ISECT_API int64_t isect_winding_number2_batch(const double *poly, int n, const double *pts,
                                              int64_t m, int32_t *winding);

/* ---------------------------------------------------------------- meshes */

/* Build a mesh from verts[nv][3] and faces. offsets == NULL: triangles,
 * idx[3*nf]. Otherwise face f is the polygon idx[offsets[f] .. offsets[f+1])
 * (offsets[nf+1], offsets[0] == 0, increasing by at least 3), planar, convex
 * or concave, vertex order giving the outward normal by the right-hand rule.
 * The input is copied. ISECT_E_ARG for NULL, nv or nf < 0, an index outside
 * [0, nv), or bad offsets; ISECT_E_NONFINITE for NaN/Inf vertices;
 * ISECT_E_NOMEM. Degenerate faces are kept (never hit) and reported by
 * isect_mesh_check. On error *out is NULL. nv and nf must be <= INT32_MAX.
 * A 3-vertex face is a triangle (barycentric uv) also when given through
 * offsets; longer faces are filled by the even-odd rule. Degenerate faces
 * are counted by the report and left out of the BVH. Exactly-once holds for
 * mesh hits as for single faces (see "Tie-breaking"), at every eps (faces
 * use none). Hits are sorted by t; two faces whose crossings round to the
 * same t are ordered by their exact crossing parameters (exactly while
 * the coordinates and the direction's components lie within about 2^100 of
 * the largest of their kind; deterministically beyond), then by face. */
ISECT_API int isect_mesh_create(const double *verts, int64_t nv, const int32_t *idx,
                                const int64_t *offsets, int64_t nf, isect_mesh **out);

/* Free a mesh; NULL is a no-op. */
ISECT_API void isect_mesh_destroy(isect_mesh *mesh);

/* Topology and measures of the mesh (see isect_mesh_report). ISECT_OK;
 * ISECT_E_ARG for NULL; ISECT_E_NOMEM when its working arrays (edge uses
 * and components: a few tens of bytes per face corner) cannot be
 * allocated, with *report untouched. */
ISECT_API int isect_mesh_check(const isect_mesh *mesh, isect_mesh_report *report);

/* Bytes the mesh occupies (its copy of the input and the BVH). */
ISECT_API int64_t isect_mesh_bytes(const isect_mesh *mesh);

/* ------------------------------------------------------------ transforms */

/* Fill x from the row-major object-to-world matrix m[16]. ISECT_E_ARG if
 * the last row is not exactly 0 0 0 1; ISECT_E_NONFINITE for NaN/Inf;
 * ISECT_E_DEGENERATE if the linear part is singular:
 * |det| <= 2^-40 * |row0||row1||row2| (scale-invariant; the test fails only
 * for matrices whose rows are nearly dependent). */
ISECT_API int isect_xform_init(isect_xform *x, const double m[16]);

/* object_ray = inv * world_ray: origin as a point, direction as a vector (not
 * renormalised, so t is preserved); tmin and tmax copied. May alias. */
ISECT_API int isect_xform_ray(const isect_xform *x, const isect_ray *world_ray,
                              isect_ray *object_ray);

/* Object-space hits to world space in place: points by m, normals by the
 * inverse transpose, renormalised; t, uv, prim, kind unchanged (the inverse
 * transpose keeps outward normals outward, so kinds stay right even under a
 * mirroring transform). Hits of kind MISS/INVALID are left alone. */
ISECT_API int isect_xform_hits(const isect_xform *x, isect_hit *hits, int n);

/* ---------------------------------------------------------------- shapes */

/* All hits of one ray with a shape, as the scalar function would give them
 * (transformed if shape->xform is set). Errors as the scalar functions, plus
 * ISECT_E_ARG for an unknown type, nonzero reserved field, or n/flags/mesh
 * that do not fit the type. */
ISECT_API int isect_intersect(const isect_shape *shape, const isect_ray *ray,
                              const isect_opts *opts, isect_hit *hits, int cap);

/* Closest hit of each of rays[n] into closest[n]; bit for bit the first hit
 * isect_intersect would report. A ray that hits nothing gets kind ISECT_MISS,
 * t = +INFINITY, prim = -1; a bad ray (NaN/Inf, zero dir, NaN tmin/tmax) gets
 * ISECT_INVALID, t = NaN, and the batch goes on. Returns the number of rays
 * hit. A bad shape, opts or count is an error and nothing is written. */
ISECT_API int64_t isect_intersect_batch(const isect_shape *shape, const isect_ray *rays,
                                        int64_t n, const isect_opts *opts,
                                        isect_hit *closest);

/* Every hit of every ray, CSR style: ray i's hits are hits[offsets[i] ..
 * offsets[i+1]); offsets[0] = 0. A bad ray gets one ISECT_INVALID record.
 * Returns the total; if it exceeds cap, offsets are still complete, only the
 * first cap hits are written, and the caller can retry with a larger buffer. */
ISECT_API int64_t isect_intersect_all_batch(const isect_shape *shape, const isect_ray *rays,
                                            int64_t n, const isect_opts *opts,
                                            int64_t *offsets, isect_hit *hits, int64_t cap);

/* Point containment for solids: sphere, aabb, convex, capped cylinder,
 * infinite cylinder, ellipsoid, quadric, and meshes by the rule in
 * shape->flags:
 *  - ISECT_EVEN_ODD (0): the parity of the exact crossings along +x (with
 *    the tie-breaking rule and an exact orientation test at the point);
 *    closed meshes (no boundary or non-manifold edge), else ISECT_E_ARG;
 *  - ISECT_NONZERO: the exact integer winding number (the signed crossing
 *    count) is not 0; closed, consistently oriented meshes (every edge used
 *    once each way), self-intersecting and nested shells included, else
 *    ISECT_E_ARG;
 *  - ISECT_WINDING: the generalized winding number (see
 *    isect_winding_number_batch) is >= 1/2; any mesh: open, non-manifold,
 *    soups. On an oriented closed mesh it is the exact integer, so the rule
 *    is w >= 1; elsewhere the direct sum, whose error bound is documented
 *    there (a point within that bound of w = 1/2 can go either way).
 * Solids are closed sets: a point with F(p) <= 0, evaluated at least to
 * double-precision accuracy (compensated where F is a polynomial), is inside;
 * so is a point on a closed mesh's face, edge or vertex. Degenerate solids
 * contain nothing. 1 inside, 0 outside; ISECT_E_ARG for a thin surface
 * (plane, triangle, polygon, open cylinder); ISECT_E_NONFINITE for a
 * non-finite point. */
ISECT_API int isect_contains(const isect_shape *shape, const double p[3]);

/* A conservative world-space box of the shape: every point of it (and every
 * hit the library reports for it) lies in lo..hi. A sphere or ellipsoid is
 * its centre +- its radii, a finite cylinder its axis segment +- r, a box
 * itself, a triangle, polygon or mesh its vertices' extent, each rounded
 * outward; a transformed shape the image of that box under the transform,
 * widened by 2^-48 of the sums' magnitudes (far beyond their rounding).
 * Unbounded (lo = -INFINITY, hi = +INFINITY on the axes concerned): planes,
 * infinite cylinders, quadrics and convex polyhedra (whose extent is not
 * computed), and every world axis such an axis maps into. A mesh without
 * vertices has the empty box (lo = +INFINITY, hi = -INFINITY). ISECT_OK,
 * or the shape's validation error (ISECT_E_ARG also for NULL lo or hi).
 * Added in 1.1. */
ISECT_API int isect_shape_bounds(const isect_shape *shape, double lo[3], double hi[3]);

/* inside[i] for p[n][3]: 0, 1, or ISECT_INVALID for a non-finite point.
 * Returns the number inside, or an error (nothing written). */
ISECT_API int64_t isect_contains_batch(const isect_shape *shape, const double *p, int64_t n,
                                       uint8_t *inside);

/* The generalized winding number w[i] of the mesh shape (ISECT_MESH, any
 * mesh: closed, open, non-manifold, a soup) at each point p[n][3] (Jacobson,
 * Kavan & Sorkine 2013): the signed solid angle of its faces at the point
 * over 4 pi, faces oriented by the right-hand rule (w = 1 inside a closed
 * mesh whose normals point out, -1 for inward normals, 0 outside; a
 * mirroring transform negates it). A transformed mesh's w is that of its
 * world-space image: under a similarity (rotation, mirror, uniform scale,
 * translation: angles kept) computed in object space; under any other
 * transform (a non-uniform scaling or shear changes an open surface's
 * solid angles) by direct summation over the faces' world images, rounded
 * once each, whatever `accuracy` is.
 *  - Closed, consistently oriented meshes: off the surface, the exact
 *    integer (the signed crossing count along +x with the exactly-once
 *    rule), whatever `accuracy` is; on a face, edge or vertex, the principal
 *    value by direct summation (1/2 on a face of a simple solid).
 *  - Any other mesh, accuracy == 0: the sum over the faces, each solid
 *    angle by Van Oosterom & Strackee's formula with its numerator formed
 *    so that it keeps its accuracy far away, and its sign near the face's
 *    plane exact; a batch of 8 points or more sums whole clusters of faces
 *    (BVH children) that do not box the point through their boundary
 *    instead (exact: a cluster's solid angle is minus that of the cap over
 *    its boundary, Jacobson et al. 2013), the same value to rounding. |w - exact| <= sum_f (pi E_f/|z_f| + 8 pi u)/4pi
 *    + 2u|w|, where |z_f| ~ the distance to the face's nearest edge times
 *    its size squared and E_f ~ 64u times the cube of the distances (the
 *    exact terms are in src/mesh/winding.c): about 1e-15 per face away from
 *    edges, growing as a point nears an edge, where w itself varies fastest.
 *  - accuracy > 0: the hierarchical evaluation of Barill et al. (2018) over
 *    the mesh's BVH, second order, expanding a cluster of faces only where
 *    its proven truncation error is small enough that the errors sum to
 *    at most accuracy: |w - exact| <= accuracy + the rounding bounds above
 *    of the faces (and cluster caps) it sums directly, so within accuracy
 *    of the accuracy-0 value wherever those bounds are small (everywhere
 *    but beside extreme slivers, a triangle 2^200 long passing a point at
 *    distance 10, where both can be far off). The exact hierarchy
 *    is already fast, so this pays only for points far from big meshes.
 *    Both build a cluster tree per call (~1.5 KiB per BVH node and ~100
 *    bytes per face, freed before returning).
 * A non-finite point gets w = NaN; accuracy = +INFINITY counts as 0 (no
 * error target at all would leave nothing to compute). ISECT_OK;
 * ISECT_E_ARG for a non-mesh shape, NULL p or w with n > 0, n < 0,
 * accuracy negative or NaN;
 * ISECT_E_NOMEM (nothing written) when the cluster tree cannot be built. */
ISECT_API int isect_winding_number_batch(const isect_shape *shape, const double *p, int64_t n,
                                         double accuracy, double *w);

/* -------------------------------------------------------- secondary rays */

/* A ray leaving shape's surface at hit (a record this library returned for
 * shape, in world space) in direction dir — a reflection, a refraction, a
 * shadow ray. out->org is hit->point moved by the fewest whole ulps of its
 * largest coordinate (1, 2, 4, ...) that put it strictly on the side of the
 * surface dir points into, as the shape's exact side test decides it in
 * object space (for a closed mesh, its exact containment test must agree,
 * off the surface); out->dir = dir, out->tmin = 0, out->tmax = +INFINITY.
 * The side dir points into: for a flat part (plane, triangle, polygon, a
 * convex or mesh face) the side of its exact plane dir points to; for a
 * curved one, in front of the normal when dir.normal >= 0 (exact sign),
 * behind it otherwise; dir along the plane counts as in front. The move is
 * along the hit's normal, or, where that never reaches the side (a hit on
 * an edge or corner of a solid with dir pointing into it), along the normal
 * plus dir. Because crossings are decided exactly against
 * tmin = 0, intersecting out never finds the surface it leaves at t ~ 0, and
 * it still finds any other surface more than a few ulps away.
 * ISECT_OK; ISECT_E_ARG for NULL arguments, a hit kind other than ENTER,
 * EXIT or TOUCH, a zero normal or a mesh face index out of range;
 * ISECT_E_NONFINITE for NaN/Inf in hit or dir; ISECT_E_DEGENERATE for a
 * zero dir, or when no offset leaves the surface (a degenerate shape, a
 * point that is not near the surface, dir running inward along another face
 * through the edge or corner the hit lies on: the new ray would lie in that
 * face, on neither side of the solid's boundary). Added in 1.1. */
ISECT_API int isect_spawn_ray(const isect_shape *shape, const isect_hit *hit,
                              const double dir[3], isect_ray *out);

#ifdef __cplusplus
}
#endif
#endif /* ISECT_H */
