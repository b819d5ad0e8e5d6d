/*
 * isect_cdef.h — the part of libisect/include/isect.h that the Python package
 * sees, in the dialect cffi's cdef() parses (no preprocessor, no ISECT_API).
 *
 * Read by build_isect.py. Struct fields are spelled out exactly as in
 * isect.h: cffi then checks at compile time that every offset and size
 * matches the C compiler's layout, and RAY_DTYPE / HIT_DTYPE are built from
 * ffi.offsetof/ffi.sizeof. "..." makes the C compiler supply the values of
 * the integer macros. tests/python/test_layout.py checks that every ISECT_API
 * function of isect.h is declared here.
 */

#define ISECT_VERSION_MAJOR ...
#define ISECT_VERSION_MINOR ...
#define ISECT_VERSION_PATCH ...
#define ISECT_VERSION ...
#define ISECT_ABI_VERSION ...

#define ISECT_OK ...
#define ISECT_E_ARG ...
#define ISECT_E_NONFINITE ...
#define ISECT_E_DEGENERATE ...
#define ISECT_E_NOMEM ...

#define ISECT_MISS ...
#define ISECT_ENTER ...
#define ISECT_EXIT ...
#define ISECT_TOUCH ...
#define ISECT_INVALID ...

#define ISECT_PLANE ...
#define ISECT_SPHERE ...
#define ISECT_AABB ...
#define ISECT_TRIANGLE ...
#define ISECT_POLYGON ...
#define ISECT_CONVEX ...
#define ISECT_CYLINDER ...
#define ISECT_CYLINDER_INF ...
#define ISECT_ELLIPSOID ...
#define ISECT_QUADRIC ...
#define ISECT_MESH ...

#define ISECT_EVEN_ODD ...
#define ISECT_NONZERO ...
#define ISECT_CAPPED ...
#define ISECT_CULL_BACK ...
#define ISECT_ANY_HIT ...

static const double ISECT_EPS_DEFAULT;

typedef struct isect_ray {
    double org[3];
    double dir[3];
    double tmin;
    double tmax;
} isect_ray;

typedef struct isect_hit {
    double  t;
    double  point[3];
    double  normal[3];
    double  uv[2];
    int32_t prim;
    int32_t kind;
} isect_hit;

typedef struct isect_opts {
    uint32_t size;
    uint32_t flags;
    double   eps;
} isect_opts;

typedef struct isect_xform {
    double m[16];
    double inv[16];
} isect_xform;

typedef struct isect_mesh isect_mesh;

typedef struct isect_mesh_report {
    int64_t vertices;
    int64_t edges;
    int64_t faces;
    int64_t boundary_edges;
    int64_t nonmanifold_edges;
    int64_t misoriented_edges;
    int64_t degenerate_faces;
    int64_t components;
    int64_t euler_characteristic;
    int64_t genus;
    int32_t closed;
    int32_t oriented;
    double  volume;
    double  area;
    int64_t reserved[3];
} isect_mesh_report;

typedef struct isect_shape {
    int32_t            type;
    int32_t            n;
    int32_t            flags;
    int32_t            reserved;
    const double      *data;
    const isect_mesh  *mesh;
    const isect_xform *xform;
} isect_shape;

unsigned    isect_version(void);
const char *isect_version_string(void);
int         isect_abi_version(void);
const char *isect_strerror(int status);

int isect_ray_plane(const isect_ray *ray, const double n[3], double d,
                    const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_sphere(const isect_ray *ray, const double c[3], double r,
                     const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_aabb(const isect_ray *ray, const double lo[3], const double hi[3],
                   const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_triangle(const isect_ray *ray, const double a[3], const double b[3],
                       const double c[3], const isect_opts *opts,
                       isect_hit *hits, int cap);
int isect_ray_polygon(const isect_ray *ray, const double *v, int n, int rule,
                      const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_convex(const isect_ray *ray, const double *planes, int m,
                     const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_cylinder(const isect_ray *ray, const double p0[3], const double p1[3],
                       double r, int capped, const isect_opts *opts,
                       isect_hit *hits, int cap);
int isect_ray_cylinder_inf(const isect_ray *ray, const double p[3], const double axis[3],
                           double r, const isect_opts *opts,
                           isect_hit *hits, int cap);
int isect_ray_ellipsoid(const isect_ray *ray, const double c[3], const double radii[3],
                        const isect_opts *opts, isect_hit *hits, int cap);
int isect_ray_quadric(const isect_ray *ray, const double q[10],
                      const isect_opts *opts, isect_hit *hits, int cap);

int isect_polygon_normal(const double *v, int n, double normal[3]);
int isect_plane_from_points(const double *v, int n, double plane[4]);
int isect_point_in_polygon2(const double *poly, int n, const double p[2], int rule);
int isect_winding_number2(const double *poly, int n, const double p[2], int32_t *winding);
int64_t isect_point_in_polygon2_batch(const double *poly, int n, const double *pts,
                                      int64_t m, int rule, uint8_t *inside);
int64_t isect_winding_number2_batch(const double *poly, int n, const double *pts,
                                    int64_t m, int32_t *winding);

int isect_mesh_create(const double *verts, int64_t nv, const int32_t *idx,
                      const int64_t *offsets, int64_t nf, isect_mesh **out);
void isect_mesh_destroy(isect_mesh *mesh);
int isect_mesh_check(const isect_mesh *mesh, isect_mesh_report *report);
int64_t isect_mesh_bytes(const isect_mesh *mesh);

int isect_xform_init(isect_xform *x, const double m[16]);
int isect_xform_ray(const isect_xform *x, const isect_ray *world_ray, isect_ray *object_ray);
int isect_xform_hits(const isect_xform *x, isect_hit *hits, int n);

int isect_intersect(const isect_shape *shape, const isect_ray *ray,
                    const isect_opts *opts, isect_hit *hits, int cap);
int64_t isect_intersect_batch(const isect_shape *shape, const isect_ray *rays,
                              int64_t n, const isect_opts *opts, isect_hit *closest);
int64_t isect_intersect_all_batch(const isect_shape *shape, const isect_ray *rays,
                                  int64_t n, const isect_opts *opts,
                                  int64_t *offsets, isect_hit *hits, int64_t cap);
int isect_contains(const isect_shape *shape, const double p[3]);
int64_t isect_contains_batch(const isect_shape *shape, const double *p, int64_t n,
                             uint8_t *inside);
