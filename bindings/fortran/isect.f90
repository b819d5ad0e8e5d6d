! SPDX-License-Identifier: Apache-2.0
! isect.f90 — module isect: libisect's C API (libisect/include/isect.h) for
! Fortran 2008 through ISO_C_BINDING.
!
! What is here
!   * bind(C) derived types isect_ray, isect_hit, isect_opts, isect_xform,
!     isect_shape and isect_mesh_report with exactly the C layouts (tests/fortran/test_layout.f90
!     checks every size and offset against the C compiler).
!   * Every constant of isect.h as an integer(c_int) parameter (and
!     ISECT_EPS_DEFAULT as real(c_double)). Fortran names are not case
!     sensitive, so the three version macros whose names equal a function's
!     (ISECT_VERSION / isect_version(), ISECT_VERSION_STRING /
!     isect_version_string(), ISECT_ABI_VERSION / isect_abi_version()) are
!     spelled ISECT_HEADER_VERSION, ISECT_HEADER_VERSION_STRING and
!     ISECT_HEADER_ABI_VERSION: the version of the header this module mirrors,
!     to compare with what the loaded library reports.
!   * An interface for every public C function under its C name with the C
!     argument order: structs by reference, arrays as explicit-shape or
!     assumed-size dummies (v[n][3] in C is v(3,*) here: row i of the C
!     array is column i), scalars by value, and the optional pointers opts and
!     xform as type(c_ptr), value so that c_null_ptr selects the defaults.
!   * Fortran-friendly forms under the same generic names (the compiler picks
!     the form by its arguments): counts and capacities are taken from the
!     array sizes and opts is an optional type(isect_opts) argument, e.g.
!         nhits = isect_ray_sphere(ray, centre, radius, hits)
!         nhits = isect_intersect(shape, ray, hits, opts=my_opts)
!     next to the C form
!         nhits = isect_ray_sphere(ray, centre, radius, c_null_ptr, hits, size(hits))
!   * Helpers: isect_make_ray, isect_make_shape, isect_make_mesh_shape,
!     isect_error_message, isect_version_text.
!
! Memory: isect_shape holds C pointers (data, xform). isect_make_shape takes
! them from its arguments, which must therefore be contiguous variables with
! the TARGET attribute that outlive every use of the shape (a temporary copy,
! e.g. of an array section or an expression, would leave the pointer dangling).
!
! Aliasing: C allows isect_xform_ray(x, r, r); Fortran forbids passing one
! variable to two arguments when one of them is changed, so use a copy.
!
! Secondary rays: isect_spawn_ray(shape, hit, dir, out) makes the ray that
! leaves shape at one of its hits (reflection, refraction, shadow rays)
! without meeting that surface again at t ~ 0.
!
! Meshes: a mesh is an opaque C object behind a type(c_ptr) handle.
! isect_mesh_create makes it (copying the input; vertex indices are 0-based
! as in C), isect_make_mesh_shape wraps the handle in an ISECT_MESH shape,
! and isect_mesh_destroy frees it; Fortran does not free it for you, and a
! shape must not be used after its mesh is destroyed.
module isect
    use, intrinsic :: iso_c_binding, only: c_int, c_int8_t, c_int32_t, c_int64_t, &
        c_double, c_char, c_size_t, c_ptr, c_null_ptr, c_loc, c_f_pointer, c_associated
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
    implicit none
    private

    ! ------------------------------------------------------------ constants
    ! Version of the header this module was written for (see the note above
    ! for the names).
    integer(c_int), parameter, public :: ISECT_VERSION_MAJOR = 1
    integer(c_int), parameter, public :: ISECT_VERSION_MINOR = 1
    integer(c_int), parameter, public :: ISECT_VERSION_PATCH = 0
    integer(c_int), parameter, public :: ISECT_HEADER_VERSION = &
        ISECT_VERSION_MAJOR * 10000 + ISECT_VERSION_MINOR * 100 + ISECT_VERSION_PATCH
    character(len=*), parameter, public :: ISECT_HEADER_VERSION_STRING = "1.1.0"
    integer(c_int), parameter, public :: ISECT_HEADER_ABI_VERSION = 1

    ! Status codes: functions return a count (>= 0) or one of these.
    integer(c_int), parameter, public :: ISECT_OK = 0
    integer(c_int), parameter, public :: ISECT_E_ARG = -1
    integer(c_int), parameter, public :: ISECT_E_NONFINITE = -2
    integer(c_int), parameter, public :: ISECT_E_DEGENERATE = -3
    integer(c_int), parameter, public :: ISECT_E_NOMEM = -4

    ! isect_hit%kind
    integer(c_int), parameter, public :: ISECT_MISS = 0
    integer(c_int), parameter, public :: ISECT_ENTER = 1
    integer(c_int), parameter, public :: ISECT_EXIT = 2
    integer(c_int), parameter, public :: ISECT_TOUCH = 3
    integer(c_int), parameter, public :: ISECT_INVALID = 4

    ! isect_shape%type (0 is deliberately not a type)
    integer(c_int), parameter, public :: ISECT_PLANE = 1
    integer(c_int), parameter, public :: ISECT_SPHERE = 2
    integer(c_int), parameter, public :: ISECT_AABB = 3
    integer(c_int), parameter, public :: ISECT_TRIANGLE = 4
    integer(c_int), parameter, public :: ISECT_POLYGON = 5
    integer(c_int), parameter, public :: ISECT_CONVEX = 6
    integer(c_int), parameter, public :: ISECT_CYLINDER = 7
    integer(c_int), parameter, public :: ISECT_CYLINDER_INF = 8
    integer(c_int), parameter, public :: ISECT_ELLIPSOID = 9
    integer(c_int), parameter, public :: ISECT_QUADRIC = 10
    integer(c_int), parameter, public :: ISECT_MESH = 11

    ! Fill rules (isect_shape%flags of a polygon, rule arguments; of a mesh,
    ! its containment rule: ISECT_WINDING is w >= 1/2, for any mesh).
    integer(c_int), parameter, public :: ISECT_EVEN_ODD = 0
    integer(c_int), parameter, public :: ISECT_NONZERO = 1
    integer(c_int), parameter, public :: ISECT_WINDING = 2

    ! isect_shape%flags of a cylinder.
    integer(c_int), parameter, public :: ISECT_CAPPED = 1

    ! isect_opts%flags (C: unsigned bit masks; combine with ior()).
    integer(c_int), parameter, public :: ISECT_CULL_BACK = 1
    integer(c_int), parameter, public :: ISECT_ANY_HIT = 2

    real(c_double), parameter, public :: ISECT_EPS_DEFAULT = 1.0e-12_c_double

    ! ---------------------------------------------------------------- types
    ! Byte offsets in the comments are those of the C structs (64-bit
    ! targets); test_layout checks them.

    ! A ray P(t) = org + t*dir, hits kept for tmin <= t <= tmax. 64 bytes.
    type, bind(C), public :: isect_ray
        real(c_double) :: org(3)   ! 0
        real(c_double) :: dir(3)   ! 24
        real(c_double) :: tmin     ! 48
        real(c_double) :: tmax     ! 56
    end type isect_ray

    ! One intersection. 80 bytes.
    type, bind(C), public :: isect_hit
        real(c_double) :: t            ! 0
        real(c_double) :: point(3)     ! 8
        real(c_double) :: normal(3)    ! 32
        real(c_double) :: uv(2)        ! 56
        integer(c_int32_t) :: prim     ! 72
        integer(c_int32_t) :: kind     ! 76
    end type isect_hit

    ! Options. 16 bytes. The default initialisation is ISECT_OPTS_INIT, so a
    ! declared type(isect_opts) variable already holds the defaults. size and
    ! flags are uint32_t in C; Fortran has no unsigned integers, and every
    ! valid value fits in a signed 32-bit integer.
    type, bind(C), public :: isect_opts
        integer(c_int32_t) :: size = 16                   ! 0, sizeof(isect_opts)
        integer(c_int32_t) :: flags = 0                   ! 4
        real(c_double) :: eps = ISECT_EPS_DEFAULT         ! 8
    end type isect_opts

    ! Affine object-to-world transform: m and its inverse inv, each a
    ! row-major 4x4 matrix (m(1:4) is the first row). Fill it with
    ! isect_xform_init. 256 bytes.
    type, bind(C), public :: isect_xform
        real(c_double) :: m(16)     ! 0
        real(c_double) :: inv(16)   ! 128
    end type isect_xform

    ! One descriptor for every primitive. 40 bytes on 64-bit targets. The
    ! default initialisation is all zero / null, like `isect_shape s = {0}`.
    type, bind(C), public :: isect_shape
        integer(c_int32_t) :: type = 0           ! 0   ISECT_PLANE ... ISECT_MESH
        integer(c_int32_t) :: n = 0              ! 4   polygon: vertices; convex: planes
        integer(c_int32_t) :: flags = 0          ! 8   rule, or ISECT_CAPPED
        integer(c_int32_t) :: reserved = 0       ! 12  must be 0
        type(c_ptr) :: data = c_null_ptr         ! 16  const double *
        type(c_ptr) :: mesh = c_null_ptr         ! 24  const isect_mesh *
        type(c_ptr) :: xform = c_null_ptr        ! 32  const isect_xform *
    end type isect_shape

    ! What isect_mesh_check finds. 128 bytes. Edges are undirected vertex
    ! pairs of face boundaries; closed and oriented are 0 or 1.
    type, bind(C), public :: isect_mesh_report
        integer(c_int64_t) :: vertices = 0               ! 0   referenced by a face
        integer(c_int64_t) :: edges = 0                  ! 8
        integer(c_int64_t) :: faces = 0                  ! 16
        integer(c_int64_t) :: boundary_edges = 0         ! 24  used by one face
        integer(c_int64_t) :: nonmanifold_edges = 0      ! 32  used by three or more
        integer(c_int64_t) :: misoriented_edges = 0      ! 40  used twice the same way
        integer(c_int64_t) :: degenerate_faces = 0       ! 48  zero area (never hit)
        integer(c_int64_t) :: components = 0             ! 56  through shared edges
        integer(c_int64_t) :: euler_characteristic = 0   ! 64  V - E + F
        integer(c_int64_t) :: genus = 0                  ! 72  -1 unless closed, oriented
        integer(c_int32_t) :: closed = 0                 ! 80  no boundary, non-manifold
        integer(c_int32_t) :: oriented = 0               ! 84  no misoriented edges
        real(c_double) :: volume = 0.0_c_double          ! 88  signed; > 0 outward
        real(c_double) :: area = 0.0_c_double            ! 96
        integer(c_int64_t) :: reserved(3) = 0            ! 104
    end type isect_mesh_report

    ! ------------------------------------------------------ C functions
    ! The generic names below each hold the C function itself and, where it
    ! helps, a Fortran form; see the note at the top.

    public :: isect_version, isect_version_string, isect_abi_version, isect_strerror
    public :: isect_ray_plane, isect_ray_sphere, isect_ray_aabb, isect_ray_triangle
    public :: isect_ray_polygon, isect_ray_convex, isect_ray_cylinder
    public :: isect_ray_cylinder_inf, isect_ray_ellipsoid, isect_ray_quadric
    public :: isect_polygon_normal, isect_plane_from_points
    public :: isect_point_in_polygon2, isect_winding_number2
    public :: isect_point_in_polygon2_batch, isect_winding_number2_batch
    public :: isect_xform_init, isect_xform_ray, isect_xform_hits
    public :: isect_intersect, isect_intersect_batch, isect_intersect_all_batch
    public :: isect_contains, isect_contains_batch, isect_winding_number_batch, isect_spawn_ray
    public :: isect_shape_bounds
    public :: isect_mesh_create, isect_mesh_destroy, isect_mesh_check, isect_mesh_bytes

    public :: isect_make_ray, isect_make_shape, isect_make_mesh_shape
    public :: isect_error_message, isect_version_text

    ! ------------------------------------------------- version, errors
    interface
        ! ISECT_VERSION of the library (C: unsigned; the value fits).
        function isect_version() bind(C, name="isect_version") result(version)
            import :: c_int
            integer(c_int) :: version
        end function isect_version

        ! "MAJOR.MINOR.PATCH" as a C string; isect_version_text() gives it
        ! as a Fortran string.
        function isect_version_string() bind(C, name="isect_version_string") result(text)
            import :: c_ptr
            type(c_ptr) :: text
        end function isect_version_string

        ! Equals the soname number (libisect.so.1).
        function isect_abi_version() bind(C, name="isect_abi_version") result(abi)
            import :: c_int
            integer(c_int) :: abi
        end function isect_abi_version

        ! A C string describing a status; isect_error_message() gives it as
        ! a Fortran string.
        function isect_strerror(status) bind(C, name="isect_strerror") result(text)
            import :: c_int, c_ptr
            integer(c_int), value :: status
            type(c_ptr) :: text
        end function isect_strerror

        ! From the C library: the length of a C string, to copy one.
        function c_strlen(text) bind(C, name="strlen") result(length)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: text
            integer(c_size_t) :: length
        end function c_strlen
    end interface

    ! ------------------------------------------------ scalar primitives
    ! Each returns the number of hits along the ray (writing the first
    ! min(count, cap) of them, sorted by t) or a negative status.

    interface isect_ray_plane
        function isect_ray_plane(ray, n, d, opts, hits, cap) &
                bind(C, name="isect_ray_plane") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: n(3)
            real(c_double), value :: d
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_plane
        module procedure fortran_ray_plane
    end interface isect_ray_plane

    interface isect_ray_sphere
        function isect_ray_sphere(ray, c, r, opts, hits, cap) &
                bind(C, name="isect_ray_sphere") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: c(3)
            real(c_double), value :: r
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_sphere
        module procedure fortran_ray_sphere
    end interface isect_ray_sphere

    interface isect_ray_aabb
        function isect_ray_aabb(ray, lo, hi, opts, hits, cap) &
                bind(C, name="isect_ray_aabb") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: lo(3), hi(3)
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_aabb
        module procedure fortran_ray_aabb
    end interface isect_ray_aabb

    interface isect_ray_triangle
        function isect_ray_triangle(ray, a, b, c, opts, hits, cap) &
                bind(C, name="isect_ray_triangle") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: a(3), b(3), c(3)
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_triangle
        module procedure fortran_ray_triangle
    end interface isect_ray_triangle

    ! v(3, n): column i is vertex i.
    interface isect_ray_polygon
        function isect_ray_polygon(ray, v, n, rule, opts, hits, cap) &
                bind(C, name="isect_ray_polygon") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: v(3, *)
            integer(c_int), value :: n
            integer(c_int), value :: rule
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_polygon
        module procedure fortran_ray_polygon
    end interface isect_ray_polygon

    ! planes(4, m): column i is the plane a x + b y + c z + d = 0 (outward).
    interface isect_ray_convex
        function isect_ray_convex(ray, planes, m, opts, hits, cap) &
                bind(C, name="isect_ray_convex") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: planes(4, *)
            integer(c_int), value :: m
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_convex
        module procedure fortran_ray_convex
    end interface isect_ray_convex

    interface isect_ray_cylinder
        function isect_ray_cylinder(ray, p0, p1, r, capped, opts, hits, cap) &
                bind(C, name="isect_ray_cylinder") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: p0(3), p1(3)
            real(c_double), value :: r
            integer(c_int), value :: capped
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_cylinder
        module procedure fortran_ray_cylinder
    end interface isect_ray_cylinder

    interface isect_ray_cylinder_inf
        function isect_ray_cylinder_inf(ray, p, axis, r, opts, hits, cap) &
                bind(C, name="isect_ray_cylinder_inf") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: p(3), axis(3)
            real(c_double), value :: r
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_cylinder_inf
        module procedure fortran_ray_cylinder_inf
    end interface isect_ray_cylinder_inf

    interface isect_ray_ellipsoid
        function isect_ray_ellipsoid(ray, c, radii, opts, hits, cap) &
                bind(C, name="isect_ray_ellipsoid") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: c(3), radii(3)
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_ellipsoid
        module procedure fortran_ray_ellipsoid
    end interface isect_ray_ellipsoid

    ! q(10) = A..J of Ax^2+By^2+Cz^2+Dxy+Exz+Fyz+Gx+Hy+Iz+J.
    interface isect_ray_quadric
        function isect_ray_quadric(ray, q, opts, hits, cap) &
                bind(C, name="isect_ray_quadric") result(nhits)
            import :: c_int, c_double, c_ptr, isect_ray, isect_hit
            type(isect_ray), intent(in) :: ray
            real(c_double), intent(in) :: q(10)
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_ray_quadric
        module procedure fortran_ray_quadric
    end interface isect_ray_quadric

    ! ------------------------------------------------------------ helpers

    interface isect_polygon_normal
        function isect_polygon_normal(v, n, normal) &
                bind(C, name="isect_polygon_normal") result(status)
            import :: c_int, c_double
            real(c_double), intent(in) :: v(3, *)
            integer(c_int), value :: n
            real(c_double), intent(out) :: normal(3)
            integer(c_int) :: status
        end function isect_polygon_normal
        module procedure fortran_polygon_normal
    end interface isect_polygon_normal

    interface isect_plane_from_points
        function isect_plane_from_points(v, n, plane) &
                bind(C, name="isect_plane_from_points") result(status)
            import :: c_int, c_double
            real(c_double), intent(in) :: v(3, *)
            integer(c_int), value :: n
            real(c_double), intent(out) :: plane(4)
            integer(c_int) :: status
        end function isect_plane_from_points
        module procedure fortran_plane_from_points
    end interface isect_plane_from_points

    ! poly(2, n): column i is 2D vertex i.
    interface isect_point_in_polygon2
        function isect_point_in_polygon2(poly, n, p, rule) &
                bind(C, name="isect_point_in_polygon2") result(inside)
            import :: c_int, c_double
            real(c_double), intent(in) :: poly(2, *)
            integer(c_int), value :: n
            real(c_double), intent(in) :: p(2)
            integer(c_int), value :: rule
            integer(c_int) :: inside
        end function isect_point_in_polygon2
        module procedure fortran_point_in_polygon2
    end interface isect_point_in_polygon2

    interface isect_winding_number2
        function isect_winding_number2(poly, n, p, winding) &
                bind(C, name="isect_winding_number2") result(status)
            import :: c_int, c_int32_t, c_double
            real(c_double), intent(in) :: poly(2, *)
            integer(c_int), value :: n
            real(c_double), intent(in) :: p(2)
            integer(c_int32_t), intent(out) :: winding
            integer(c_int) :: status
        end function isect_winding_number2
        module procedure fortran_winding_number2
    end interface isect_winding_number2

    ! pts(2, m); inside(m) holds 0, 1 or ISECT_INVALID.
    interface isect_point_in_polygon2_batch
        function isect_point_in_polygon2_batch(poly, n, pts, m, rule, inside) &
                bind(C, name="isect_point_in_polygon2_batch") result(ninside)
            import :: c_int, c_int8_t, c_int64_t, c_double
            real(c_double), intent(in) :: poly(2, *)
            integer(c_int), value :: n
            real(c_double), intent(in) :: pts(2, *)
            integer(c_int64_t), value :: m
            integer(c_int), value :: rule
            integer(c_int8_t), intent(inout) :: inside(*)
            integer(c_int64_t) :: ninside
        end function isect_point_in_polygon2_batch
        module procedure fortran_point_in_polygon2_batch
    end interface isect_point_in_polygon2_batch

    ! winding(m); -huge(0_c_int32_t)-1 (INT32_MIN) for a non-finite point.
    interface isect_winding_number2_batch
        function isect_winding_number2_batch(poly, n, pts, m, winding) &
                bind(C, name="isect_winding_number2_batch") result(nwinding)
            import :: c_int, c_int32_t, c_int64_t, c_double
            real(c_double), intent(in) :: poly(2, *)
            integer(c_int), value :: n
            real(c_double), intent(in) :: pts(2, *)
            integer(c_int64_t), value :: m
            integer(c_int32_t), intent(inout) :: winding(*)
            integer(c_int64_t) :: nwinding
        end function isect_winding_number2_batch
        module procedure fortran_winding_number2_batch
    end interface isect_winding_number2_batch

    ! --------------------------------------------------------- transforms

    ! m(16) is row-major (m(1:4) is the first row). The Fortran form takes a
    ! 4x4 matrix a(row, column) as written in mathematics.
    interface isect_xform_init
        function isect_xform_init(x, m) bind(C, name="isect_xform_init") result(status)
            import :: c_int, c_double, isect_xform
            type(isect_xform), intent(out) :: x
            real(c_double), intent(in) :: m(16)
            integer(c_int) :: status
        end function isect_xform_init
        module procedure fortran_xform_init
    end interface isect_xform_init

    interface
        function isect_xform_ray(x, world_ray, object_ray) &
                bind(C, name="isect_xform_ray") result(status)
            import :: c_int, isect_xform, isect_ray
            type(isect_xform), intent(in) :: x
            type(isect_ray), intent(in) :: world_ray
            type(isect_ray), intent(out) :: object_ray
            integer(c_int) :: status
        end function isect_xform_ray
    end interface

    interface isect_xform_hits
        function isect_xform_hits(x, hits, n) bind(C, name="isect_xform_hits") result(status)
            import :: c_int, isect_xform, isect_hit
            type(isect_xform), intent(in) :: x
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: n
            integer(c_int) :: status
        end function isect_xform_hits
        module procedure fortran_xform_hits
    end interface isect_xform_hits

    ! ------------------------------------------------------------- shapes

    interface isect_intersect
        function isect_intersect(shape, ray, opts, hits, cap) &
                bind(C, name="isect_intersect") result(nhits)
            import :: c_int, c_ptr, isect_shape, isect_ray, isect_hit
            type(isect_shape), intent(in) :: shape
            type(isect_ray), intent(in) :: ray
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int), value :: cap
            integer(c_int) :: nhits
        end function isect_intersect
        module procedure fortran_intersect
    end interface isect_intersect

    ! closest(n): the closest hit of each ray (kind ISECT_MISS / ISECT_INVALID
    ! for rays that hit nothing / are bad). Returns the number of rays hit.
    interface isect_intersect_batch
        function isect_intersect_batch(shape, rays, n, opts, closest) &
                bind(C, name="isect_intersect_batch") result(nhit)
            import :: c_int64_t, c_ptr, isect_shape, isect_ray, isect_hit
            type(isect_shape), intent(in) :: shape
            type(isect_ray), intent(in) :: rays(*)
            integer(c_int64_t), value :: n
            type(c_ptr), value :: opts
            type(isect_hit), intent(inout) :: closest(*)
            integer(c_int64_t) :: nhit
        end function isect_intersect_batch
        module procedure fortran_intersect_batch
    end interface isect_intersect_batch

    ! offsets(n+1) are 0-based C offsets: ray i's hits (1-based i) are
    ! hits(offsets(i)+1 : offsets(i+1)). Returns the total number of hits.
    interface isect_intersect_all_batch
        function isect_intersect_all_batch(shape, rays, n, opts, offsets, hits, cap) &
                bind(C, name="isect_intersect_all_batch") result(total)
            import :: c_int64_t, c_ptr, isect_shape, isect_ray, isect_hit
            type(isect_shape), intent(in) :: shape
            type(isect_ray), intent(in) :: rays(*)
            integer(c_int64_t), value :: n
            type(c_ptr), value :: opts
            integer(c_int64_t), intent(inout) :: offsets(*)
            type(isect_hit), intent(inout) :: hits(*)
            integer(c_int64_t), value :: cap
            integer(c_int64_t) :: total
        end function isect_intersect_all_batch
        module procedure fortran_intersect_all_batch
    end interface isect_intersect_all_batch

    ! 1 inside, 0 outside, or a status.
    interface
        function isect_contains(shape, p) bind(C, name="isect_contains") result(inside)
            import :: c_int, c_double, isect_shape
            type(isect_shape), intent(in) :: shape
            real(c_double), intent(in) :: p(3)
            integer(c_int) :: inside
        end function isect_contains
    end interface

    ! p(3, n); inside(n) holds 0, 1 or ISECT_INVALID.
    interface isect_contains_batch
        function isect_contains_batch(shape, p, n, inside) &
                bind(C, name="isect_contains_batch") result(ninside)
            import :: c_int8_t, c_int64_t, c_double, isect_shape
            type(isect_shape), intent(in) :: shape
            real(c_double), intent(in) :: p(3, *)
            integer(c_int64_t), value :: n
            integer(c_int8_t), intent(inout) :: inside(*)
            integer(c_int64_t) :: ninside
        end function isect_contains_batch
        module procedure fortran_contains_batch
    end interface isect_contains_batch

    ! The generalized winding number w(n) of a mesh shape at p(3, n) (exact
    ! integers for closed oriented meshes; accuracy 0: exact to rounding, > 0:
    ! a far field within accuracy; see isect.h). NaN for a non-finite point.
    interface isect_winding_number_batch
        function isect_winding_number_batch(shape, p, n, accuracy, w) &
                bind(C, name="isect_winding_number_batch") result(status)
            import :: c_int, c_int64_t, c_double, isect_shape
            type(isect_shape), intent(in) :: shape
            real(c_double), intent(in) :: p(3, *)
            integer(c_int64_t), value :: n
            real(c_double), value :: accuracy
            real(c_double), intent(inout) :: w(*)
            integer(c_int) :: status
        end function isect_winding_number_batch
        module procedure fortran_winding_number_batch
    end interface isect_winding_number_batch

    ! -------------------------------------------------- secondary rays

    ! A ray leaving shape's surface at hit (a record that isect_intersect or a
    ! batch call returned for shape, in world space) in direction dir (1.1):
    ! out%org is hit%point moved along hit%normal by the fewest whole ulps
    ! (1, 2, 4, ...) that put it strictly on the side dir points into, as the
    ! shape's exact side test decides; out%dir = dir, out%tmin = 0,
    ! out%tmax = +inf. Intersecting out with shape never finds the surface it
    ! leaves at t ~ 0. ISECT_E_ARG for a hit of kind MISS or INVALID (e.g. the
    ! closest-hit record of a ray that missed), a zero normal or a mesh face
    ! index out of range; ISECT_E_NONFINITE for NaN/Inf in hit or dir;
    ! ISECT_E_DEGENERATE for a zero dir or a point not near the surface.
    interface
        function isect_spawn_ray(shape, hit, dir, out) bind(C, name="isect_spawn_ray") &
                result(status)
            import :: c_int, c_double, isect_shape, isect_hit, isect_ray
            type(isect_shape), intent(in) :: shape
            type(isect_hit), intent(in) :: hit
            real(c_double), intent(in) :: dir(3)
            type(isect_ray), intent(inout) :: out
            integer(c_int) :: status
        end function isect_spawn_ray
    end interface

    ! A conservative world-space box lo(3)..hi(3) of the shape (isect.h:
    ! infinite for unbounded shapes, empty (lo > hi) for a mesh without
    ! vertices). Added in 1.1.
    interface
        function isect_shape_bounds(shape, lo, hi) bind(C, name="isect_shape_bounds") &
                result(status)
            import :: c_int, c_double, isect_shape
            type(isect_shape), intent(in) :: shape
            real(c_double), intent(out) :: lo(3), hi(3)
            integer(c_int) :: status
        end function isect_shape_bounds
    end interface

    ! ------------------------------------------------------------- meshes

    ! verts(3, nv): column i is vertex i-1 (indices are 0-based, as in C).
    ! offsets = c_null_ptr: triangles, idx(3*nf). Otherwise offsets points at
    ! nf+1 integer(c_int64_t) 0-based offsets: face f (0-based) is
    ! idx(offsets(f+1)+1 : offsets(f+2)) in Fortran terms. mesh is the new
    ! handle (c_null_ptr on error). The Fortran form
    !     status = isect_mesh_create(verts, idx, mesh [, offsets])
    ! takes nv = size(verts, 2), nf = size(idx)/3 or size(offsets)-1, and
    ! also returns ISECT_E_ARG when the arrays do not fit each other (verts
    ! not 3 rows, size(idx) not a multiple of 3 for triangles, an offset
    ! beyond size(idx), an empty offsets array).
    interface isect_mesh_create
        function isect_mesh_create(verts, nv, idx, offsets, nf, mesh) &
                bind(C, name="isect_mesh_create") result(status)
            import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
            real(c_double), intent(in) :: verts(3, *)
            integer(c_int64_t), value :: nv
            integer(c_int32_t), intent(in) :: idx(*)
            type(c_ptr), value :: offsets
            integer(c_int64_t), value :: nf
            type(c_ptr), intent(out) :: mesh
            integer(c_int) :: status
        end function isect_mesh_create
        module procedure fortran_mesh_create
    end interface isect_mesh_create

    interface
        ! Free a mesh; c_null_ptr is a no-op. The handle is left dangling:
        ! set it to c_null_ptr yourself.
        subroutine isect_mesh_destroy(mesh) bind(C, name="isect_mesh_destroy")
            import :: c_ptr
            type(c_ptr), value :: mesh
        end subroutine isect_mesh_destroy

        ! Topology and measures of the mesh.
        function isect_mesh_check(mesh, report) bind(C, name="isect_mesh_check") &
                result(status)
            import :: c_int, c_ptr, isect_mesh_report
            type(c_ptr), value :: mesh
            type(isect_mesh_report), intent(out) :: report
            integer(c_int) :: status
        end function isect_mesh_check

        ! Bytes the mesh occupies (its copy of the input and the BVH).
        function isect_mesh_bytes(mesh) bind(C, name="isect_mesh_bytes") result(bytes)
            import :: c_int64_t, c_ptr
            type(c_ptr), value :: mesh
            integer(c_int64_t) :: bytes
        end function isect_mesh_bytes
    end interface

    ! isect_make_shape(type, data [, n] [, flags] [, xform]) from a rank-1 or
    ! rank-2 target array.
    interface isect_make_shape
        module procedure make_shape_from_list, make_shape_from_columns
    end interface isect_make_shape

contains

    ! ---------------------------------------------------------- internals

    ! The C pointer to opts, or NULL (the defaults) when it is absent.
    function opts_pointer(opts) result(ptr)
        type(isect_opts), intent(in), target, optional :: opts
        type(c_ptr) :: ptr
        ptr = c_null_ptr
        if (present(opts)) ptr = c_loc(opts)
    end function opts_pointer

    ! A buffer's length as a C int capacity (capped, never wrapped).
    pure function int_capacity(length) result(cap)
        integer, intent(in) :: length
        integer(c_int) :: cap
        cap = int(min(int(length, c_int64_t), int(huge(0_c_int), c_int64_t)), c_int)
    end function int_capacity

    ! A NUL-terminated C string as a Fortran string ("" for NULL).
    function fortran_string(text) result(str)
        type(c_ptr), intent(in) :: text
        character(len=:), allocatable :: str
        character(kind=c_char), pointer :: chars(:)
        integer :: length, i
        if (.not. c_associated(text)) then
            str = ""
            return
        end if
        length = int(c_strlen(text))
        call c_f_pointer(text, chars, [length])
        allocate (character(len=length) :: str)
        do i = 1, length
            str(i:i) = chars(i)
        end do
    end function fortran_string

    ! ----------------------------------------------------------- helpers

    ! The description of a status, e.g. for messages.
    function isect_error_message(status) result(message)
        integer(c_int), intent(in) :: status
        character(len=:), allocatable :: message
        message = fortran_string(isect_strerror(status))
    end function isect_error_message

    ! The library's "MAJOR.MINOR.PATCH".
    function isect_version_text() result(version)
        character(len=:), allocatable :: version
        version = fortran_string(isect_version_string())
    end function isect_version_text

    ! A ray from org along dir; tmin defaults to 0 and tmax to +infinity.
    function isect_make_ray(org, dir, tmin, tmax) result(ray)
        real(c_double), intent(in) :: org(3), dir(3)
        real(c_double), intent(in), optional :: tmin, tmax
        type(isect_ray) :: ray
        ray%org = org
        ray%dir = dir
        ray%tmin = 0.0_c_double
        ray%tmax = ieee_value(1.0_c_double, ieee_positive_inf)
        if (present(tmin)) ray%tmin = tmin
        if (present(tmax)) ray%tmax = tmax
    end function isect_make_ray

    ! A descriptor pointing at data (the numbers in the order of the type's
    ! scalar function) and, if given, at xform. n defaults to 0, flags to 0.
    function make_shape_from_list(type, data, n, flags, xform) result(shape)
        integer(c_int), intent(in) :: type
        real(c_double), intent(in), target, contiguous :: data(:)
        integer(c_int), intent(in), optional :: n, flags
        type(isect_xform), intent(in), target, optional :: xform
        type(isect_shape) :: shape
        shape%type = type
        if (size(data) > 0) shape%data = c_loc(data)
        if (present(n)) shape%n = n
        if (present(flags)) shape%flags = flags
        if (present(xform)) shape%xform = c_loc(xform)
    end function make_shape_from_list

    ! The same from rows given as columns, e.g. polygon vertices (3, n) or
    ! convex planes (4, m); n defaults to the number of columns.
    function make_shape_from_columns(type, data, n, flags, xform) result(shape)
        integer(c_int), intent(in) :: type
        real(c_double), intent(in), target, contiguous :: data(:, :)
        integer(c_int), intent(in), optional :: n, flags
        type(isect_xform), intent(in), target, optional :: xform
        type(isect_shape) :: shape
        shape%type = type
        if (size(data) > 0) shape%data = c_loc(data)
        shape%n = int_capacity(size(data, 2))
        if (present(n)) shape%n = n
        if (present(flags)) shape%flags = flags
        if (present(xform)) shape%xform = c_loc(xform)
    end function make_shape_from_columns

    ! A descriptor of the mesh behind a handle from isect_mesh_create (type
    ! ISECT_MESH, data c_null_ptr, n and flags 0) and, if given, xform. The
    ! mesh must not be destroyed while the shape is in use.
    function isect_make_mesh_shape(mesh, xform) result(shape)
        type(c_ptr), intent(in) :: mesh
        type(isect_xform), intent(in), target, optional :: xform
        type(isect_shape) :: shape
        shape%type = ISECT_MESH
        shape%data = c_null_ptr
        shape%mesh = mesh
        if (present(xform)) shape%xform = c_loc(xform)
    end function isect_make_mesh_shape

    ! ---------------------------------- Fortran forms of the primitives
    ! cap = size(hits); opts optional. A zero-size hits array counts only.

    function fortran_ray_plane(ray, n, d, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: n(3)
        real(c_double), intent(in) :: d
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_plane(ray, n, d, opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_plane

    function fortran_ray_sphere(ray, c, r, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: c(3)
        real(c_double), intent(in) :: r
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_sphere(ray, c, r, opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_sphere

    function fortran_ray_aabb(ray, lo, hi, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: lo(3), hi(3)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_aabb(ray, lo, hi, opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_aabb

    function fortran_ray_triangle(ray, a, b, c, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: a(3), b(3), c(3)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_triangle(ray, a, b, c, opts_pointer(opts), hits, &
                                   int_capacity(size(hits)))
    end function fortran_ray_triangle

    ! v(3, n); rule defaults to ISECT_EVEN_ODD.
    function fortran_ray_polygon(ray, v, hits, rule, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: v(:, :)
        type(isect_hit), intent(inout) :: hits(:)
        integer(c_int), intent(in), optional :: rule
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        integer(c_int) :: fill_rule
        fill_rule = ISECT_EVEN_ODD
        if (present(rule)) fill_rule = rule
        if (size(v, 1) /= 3) then
            nhits = ISECT_E_ARG
            return
        end if
        nhits = isect_ray_polygon(ray, v, int_capacity(size(v, 2)), fill_rule, &
                                  opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_polygon

    ! planes(4, m).
    function fortran_ray_convex(ray, planes, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: planes(:, :)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        if (size(planes, 1) /= 4) then
            nhits = ISECT_E_ARG
            return
        end if
        nhits = isect_ray_convex(ray, planes, int_capacity(size(planes, 2)), &
                                 opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_convex

    ! capped is a logical here (C: ISECT_CAPPED or 0).
    function fortran_ray_cylinder(ray, p0, p1, r, capped, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: p0(3), p1(3)
        real(c_double), intent(in) :: r
        logical, intent(in) :: capped
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        integer(c_int) :: cap_flag
        cap_flag = 0
        if (capped) cap_flag = ISECT_CAPPED
        nhits = isect_ray_cylinder(ray, p0, p1, r, cap_flag, opts_pointer(opts), hits, &
                                   int_capacity(size(hits)))
    end function fortran_ray_cylinder

    function fortran_ray_cylinder_inf(ray, p, axis, r, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: p(3), axis(3)
        real(c_double), intent(in) :: r
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_cylinder_inf(ray, p, axis, r, opts_pointer(opts), hits, &
                                       int_capacity(size(hits)))
    end function fortran_ray_cylinder_inf

    function fortran_ray_ellipsoid(ray, c, radii, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: c(3), radii(3)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_ellipsoid(ray, c, radii, opts_pointer(opts), hits, &
                                    int_capacity(size(hits)))
    end function fortran_ray_ellipsoid

    function fortran_ray_quadric(ray, q, hits, opts) result(nhits)
        type(isect_ray), intent(in) :: ray
        real(c_double), intent(in) :: q(10)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_ray_quadric(ray, q, opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_ray_quadric

    ! ------------------------------------- Fortran forms of the helpers

    function fortran_polygon_normal(v, normal) result(status)
        real(c_double), intent(in) :: v(:, :)
        real(c_double), intent(out) :: normal(3)
        integer(c_int) :: status
        if (size(v, 1) /= 3) then
            normal = 0.0_c_double
            status = ISECT_E_ARG
            return
        end if
        status = isect_polygon_normal(v, int_capacity(size(v, 2)), normal)
    end function fortran_polygon_normal

    function fortran_plane_from_points(v, plane) result(status)
        real(c_double), intent(in) :: v(:, :)
        real(c_double), intent(out) :: plane(4)
        integer(c_int) :: status
        if (size(v, 1) /= 3) then
            plane = 0.0_c_double
            status = ISECT_E_ARG
            return
        end if
        status = isect_plane_from_points(v, int_capacity(size(v, 2)), plane)
    end function fortran_plane_from_points

    ! poly(2, n); rule defaults to ISECT_EVEN_ODD.
    function fortran_point_in_polygon2(poly, p, rule) result(inside)
        real(c_double), intent(in) :: poly(:, :)
        real(c_double), intent(in) :: p(2)
        integer(c_int), intent(in), optional :: rule
        integer(c_int) :: inside
        integer(c_int) :: fill_rule
        fill_rule = ISECT_EVEN_ODD
        if (present(rule)) fill_rule = rule
        if (size(poly, 1) /= 2) then
            inside = ISECT_E_ARG
            return
        end if
        inside = isect_point_in_polygon2(poly, int_capacity(size(poly, 2)), p, fill_rule)
    end function fortran_point_in_polygon2

    function fortran_winding_number2(poly, p, winding) result(status)
        real(c_double), intent(in) :: poly(:, :)
        real(c_double), intent(in) :: p(2)
        integer(c_int32_t), intent(out) :: winding
        integer(c_int) :: status
        winding = 0
        if (size(poly, 1) /= 2) then
            status = ISECT_E_ARG
            return
        end if
        status = isect_winding_number2(poly, int_capacity(size(poly, 2)), p, winding)
    end function fortran_winding_number2

    ! pts(2, m), inside(m) (at least m entries).
    function fortran_point_in_polygon2_batch(poly, pts, inside, rule) result(ninside)
        real(c_double), intent(in) :: poly(:, :), pts(:, :)
        integer(c_int8_t), intent(inout) :: inside(:)
        integer(c_int), intent(in), optional :: rule
        integer(c_int64_t) :: ninside
        integer(c_int) :: fill_rule
        fill_rule = ISECT_EVEN_ODD
        if (present(rule)) fill_rule = rule
        if (size(poly, 1) /= 2 .or. size(pts, 1) /= 2 .or. size(inside) < size(pts, 2)) then
            ninside = ISECT_E_ARG
            return
        end if
        ninside = isect_point_in_polygon2_batch(poly, int_capacity(size(poly, 2)), pts, &
                                                int(size(pts, 2), c_int64_t), fill_rule, inside)
    end function fortran_point_in_polygon2_batch

    function fortran_winding_number2_batch(poly, pts, winding) result(nwinding)
        real(c_double), intent(in) :: poly(:, :), pts(:, :)
        integer(c_int32_t), intent(inout) :: winding(:)
        integer(c_int64_t) :: nwinding
        if (size(poly, 1) /= 2 .or. size(pts, 1) /= 2 .or. size(winding) < size(pts, 2)) then
            nwinding = ISECT_E_ARG
            return
        end if
        nwinding = isect_winding_number2_batch(poly, int_capacity(size(poly, 2)), pts, &
                                               int(size(pts, 2), c_int64_t), winding)
    end function fortran_winding_number2_batch

    ! ---------------------------------- Fortran forms of the transforms

    ! a(row, column): the object-to-world matrix as written on paper.
    function fortran_xform_init(x, a) result(status)
        type(isect_xform), intent(out) :: x
        real(c_double), intent(in) :: a(4, 4)
        integer(c_int) :: status
        status = isect_xform_init(x, reshape(transpose(a), [16]))
    end function fortran_xform_init

    function fortran_xform_hits(x, hits) result(status)
        type(isect_xform), intent(in) :: x
        type(isect_hit), intent(inout) :: hits(:)
        integer(c_int) :: status
        status = isect_xform_hits(x, hits, int_capacity(size(hits)))
    end function fortran_xform_hits

    ! -------------------------------------- Fortran form of the meshes

    ! verts(3, nv), idx(:) 0-based; offsets(nf+1) 0-based, absent for
    ! triangles (nf = size(idx)/3).
    function fortran_mesh_create(verts, idx, mesh, offsets) result(status)
        real(c_double), intent(in) :: verts(:, :)
        integer(c_int32_t), intent(in) :: idx(:)
        type(c_ptr), intent(out) :: mesh
        integer(c_int64_t), intent(in), target, contiguous, optional :: offsets(:)
        integer(c_int) :: status
        integer(c_int64_t) :: nv
        mesh = c_null_ptr
        status = ISECT_E_ARG
        if (size(verts, 1) /= 3) return
        nv = int(size(verts, 2), c_int64_t)
        if (present(offsets)) then
            ! The C library checks the offsets before it reads idx, and they
            ! must increase, so the last one bounds every face.
            if (size(offsets) < 1) return
            if (offsets(size(offsets)) > int(size(idx), c_int64_t)) return
            status = isect_mesh_create(verts, nv, idx, c_loc(offsets), &
                                       int(size(offsets) - 1, c_int64_t), mesh)
        else
            if (mod(size(idx), 3) /= 0) return
            status = isect_mesh_create(verts, nv, idx, c_null_ptr, &
                                       int(size(idx) / 3, c_int64_t), mesh)
        end if
    end function fortran_mesh_create

    ! -------------------------------------- Fortran forms of the shapes

    function fortran_intersect(shape, ray, hits, opts) result(nhits)
        type(isect_shape), intent(in) :: shape
        type(isect_ray), intent(in) :: ray
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int) :: nhits
        nhits = isect_intersect(shape, ray, opts_pointer(opts), hits, int_capacity(size(hits)))
    end function fortran_intersect

    ! closest needs at least size(rays) entries (else ISECT_E_ARG).
    function fortran_intersect_batch(shape, rays, closest, opts) result(nhit)
        type(isect_shape), intent(in) :: shape
        type(isect_ray), intent(in) :: rays(:)
        type(isect_hit), intent(inout) :: closest(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int64_t) :: nhit
        if (size(closest) < size(rays)) then
            nhit = ISECT_E_ARG
            return
        end if
        nhit = isect_intersect_batch(shape, rays, int(size(rays), c_int64_t), &
                                     opts_pointer(opts), closest)
    end function fortran_intersect_batch

    ! offsets needs at least size(rays)+1 entries (else ISECT_E_ARG); the
    ! capacity is size(hits).
    function fortran_intersect_all_batch(shape, rays, offsets, hits, opts) result(total)
        type(isect_shape), intent(in) :: shape
        type(isect_ray), intent(in) :: rays(:)
        integer(c_int64_t), intent(inout) :: offsets(:)
        type(isect_hit), intent(inout) :: hits(:)
        type(isect_opts), intent(in), target, optional :: opts
        integer(c_int64_t) :: total
        if (size(offsets) < size(rays) + 1) then
            total = ISECT_E_ARG
            return
        end if
        total = isect_intersect_all_batch(shape, rays, int(size(rays), c_int64_t), &
                                          opts_pointer(opts), offsets, hits, &
                                          int(size(hits), c_int64_t))
    end function fortran_intersect_all_batch

    ! p(3, n), inside(n) (at least n entries).
    function fortran_contains_batch(shape, p, inside) result(ninside)
        type(isect_shape), intent(in) :: shape
        real(c_double), intent(in) :: p(:, :)
        integer(c_int8_t), intent(inout) :: inside(:)
        integer(c_int64_t) :: ninside
        if (size(p, 1) /= 3 .or. size(inside) < size(p, 2)) then
            ninside = ISECT_E_ARG
            return
        end if
        ninside = isect_contains_batch(shape, p, int(size(p, 2), c_int64_t), inside)
    end function fortran_contains_batch

    ! p(3, n), w(n) (at least n entries); accuracy optional (default 0).
    function fortran_winding_number_batch(shape, p, w, accuracy) result(status)
        type(isect_shape), intent(in) :: shape
        real(c_double), intent(in) :: p(:, :)
        real(c_double), intent(inout) :: w(:)
        real(c_double), intent(in), optional :: accuracy
        integer(c_int) :: status
        real(c_double) :: acc
        acc = 0.0_c_double
        if (present(accuracy)) acc = accuracy
        if (size(p, 1) /= 3 .or. size(w) < size(p, 2)) then
            status = ISECT_E_ARG
            return
        end if
        status = isect_winding_number_batch(shape, p, int(size(p, 2), c_int64_t), acc, w)
    end function fortran_winding_number_batch

end module isect
