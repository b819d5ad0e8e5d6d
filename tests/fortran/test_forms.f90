! SPDX-License-Identifier: Apache-2.0
! test_forms.f90 — the module's two ways of calling each function agree:
! the C form (explicit counts, type(c_ptr) opts) and the Fortran form (counts
! from array sizes, optional opts) give the same bits, and the helpers
! (isect_make_ray, isect_make_shape, isect_make_mesh_shape, the 4x4
! isect_xform_init) build what the C API expects; isect_spawn_ray (one form)
! makes secondary rays from the hits of either. Expected values are worked out by hand in the comments; the
! golden corpus (corpus_runner) covers the numerics.
program test_forms
    use, intrinsic :: iso_c_binding
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
        ieee_quiet_nan
    use isect
    use test_report, only: record, finish
    implicit none

    call check_sphere()
    call check_polygon()
    call check_shapes_and_batches()
    call check_transforms()
    call check_planar_helpers()
    call check_opts()
    call check_mesh()
    call check_spawn()
    call check_bounds()
    call finish()

contains

    ! Same bytes (hits have no padding: 9 doubles and 2 int32).
    logical function same_hits(a, b)
        type(isect_hit), intent(in) :: a(:), b(:)
        integer(c_int64_t) :: mold(1)
        same_hits = size(a) == size(b)
        if (same_hits) same_hits = all(transfer(a, mold) == transfer(b, mold))
    end function same_hits

    logical function same_doubles(a, b)
        real(c_double), intent(in) :: a(:), b(:)
        same_doubles = size(a) == size(b)
        if (same_doubles) same_doubles = all(transfer(a, [0_c_int64_t]) == &
                                             transfer(b, [0_c_int64_t]))
    end function same_doubles

    logical function near(a, b)
        real(c_double), intent(in) :: a, b
        near = abs(a - b) <= 1.0e-12_c_double * max(1.0_c_double, abs(b))
    end function near

    ! Sphere at (0,0,5), radius 1; the ray from the origin along +z enters at
    ! t = 4 (normal -z) and leaves at t = 6 (normal +z).
    subroutine check_sphere()
        real(c_double), parameter :: centre(3) = [0.0_c_double, 0.0_c_double, 5.0_c_double]
        real(c_double), parameter :: radius = 1.0_c_double
        type(isect_ray) :: ray
        type(isect_hit) :: c_hits(2), f_hits(2), none(0)
        integer(c_int) :: c_count, f_count

        ray = isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], &
                             [0.0_c_double, 0.0_c_double, 1.0_c_double])
        call record(ray%tmin <= 0.0_c_double .and. ray%tmin >= 0.0_c_double .and. &
                    .not. ieee_is_finite(ray%tmax) .and. ray%tmax > 0.0_c_double, &
                    "isect_make_ray defaults: tmin 0, tmax +inf")

        c_count = isect_ray_sphere(ray, centre, radius, c_null_ptr, c_hits, 2_c_int)
        f_count = isect_ray_sphere(ray, centre, radius, f_hits)
        call record(c_count == 2 .and. f_count == 2, "sphere: 2 hits by both forms")
        call record(same_hits(c_hits, f_hits), "sphere: both forms give the same bits")
        call record(near(c_hits(1)%t, 4.0_c_double) .and. near(c_hits(2)%t, 6.0_c_double), &
                    "sphere: t = 4 and 6")
        call record(c_hits(1)%kind == ISECT_ENTER .and. c_hits(2)%kind == ISECT_EXIT, &
                    "sphere: enter, then exit")
        call record(near(c_hits(1)%normal(3), -1.0_c_double) .and. &
                    near(c_hits(2)%normal(3), 1.0_c_double) .and. c_hits(1)%prim == -1, &
                    "sphere: normals -z, +z; prim -1")
        ! A zero-size buffer counts only.
        call record(isect_ray_sphere(ray, centre, radius, none) == 2, &
                    "sphere: counting with an empty buffer")
        call record(isect_ray_sphere(ray, centre, -1.0_c_double, f_hits) == ISECT_E_ARG, &
                    "sphere: negative radius is ISECT_E_ARG")
    end subroutine check_sphere

    ! An L-shaped hexagon in the plane z = 0 (a 2x2 square without its
    ! upper right quarter), counter-clockwise seen from +z, so its normal is
    ! +z. A ray straight down from (0.5, 0.5, 1) meets it at t = 1 against
    ! the normal, so on its front side: ENTER. At (1.5, 1.5), inside the
    ! notch, it is missed.
    subroutine check_polygon()
        real(c_double), parameter :: l_shape(3, 6) = reshape([ &
            0.0_c_double, 0.0_c_double, 0.0_c_double, &
            2.0_c_double, 0.0_c_double, 0.0_c_double, &
            2.0_c_double, 1.0_c_double, 0.0_c_double, &
            1.0_c_double, 1.0_c_double, 0.0_c_double, &
            1.0_c_double, 2.0_c_double, 0.0_c_double, &
            0.0_c_double, 2.0_c_double, 0.0_c_double], [3, 6])
        real(c_double), parameter :: down(3) = [0.0_c_double, 0.0_c_double, -1.0_c_double]
        type(isect_hit) :: c_hits(1), f_hits(1)
        type(isect_ray) :: ray
        integer(c_int) :: c_count, f_count

        ray = isect_make_ray([0.5_c_double, 0.5_c_double, 1.0_c_double], down)
        c_count = isect_ray_polygon(ray, l_shape, 6_c_int, ISECT_EVEN_ODD, c_null_ptr, &
                                    c_hits, 1_c_int)
        f_count = isect_ray_polygon(ray, l_shape, f_hits)
        call record(c_count == 1 .and. f_count == 1, "polygon: 1 hit by both forms")
        call record(same_hits(c_hits, f_hits), "polygon: both forms give the same bits")
        call record(near(c_hits(1)%t, 1.0_c_double) .and. c_hits(1)%kind == ISECT_ENTER .and. &
                    near(c_hits(1)%normal(3), 1.0_c_double), &
                    "polygon: t = 1, ENTER, normal +z")

        ray = isect_make_ray([1.5_c_double, 1.5_c_double, 1.0_c_double], down)
        call record(isect_ray_polygon(ray, l_shape, f_hits, rule=ISECT_NONZERO) == 0, &
                    "polygon: the notch is missed")
        call record(isect_ray_polygon(ray, l_shape(:, 1:2), f_hits) == ISECT_E_ARG, &
                    "polygon: 2 vertices is ISECT_E_ARG")
    end subroutine check_polygon

    ! isect_make_shape and the batch forms: sphere at (0,0,5) radius 1 and
    ! three rays: one hitting (t = 4), one missing, one with a NaN direction.
    subroutine check_shapes_and_batches()
        real(c_double), target :: sphere(4) = [0.0_c_double, 0.0_c_double, 5.0_c_double, &
                                               1.0_c_double]
        real(c_double), target :: square(3, 4) = reshape([ &
            -1.0_c_double, -1.0_c_double, 3.0_c_double, 1.0_c_double, -1.0_c_double, &
            3.0_c_double, 1.0_c_double, 1.0_c_double, 3.0_c_double, -1.0_c_double, &
            1.0_c_double, 3.0_c_double], [3, 4])
        real(c_double), parameter :: zero(3) = 0.0_c_double
        real(c_double), parameter :: up(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
        real(c_double) :: points(3, 2)
        type(isect_shape) :: ball, plate
        type(isect_ray) :: rays(3)
        type(isect_hit) :: scalar(2), closest(3), c_closest(3), all_hits(4), c_all(4), small(2)
        integer(c_int64_t) :: offsets(4), c_offsets(4), n_hit, total, c_total
        integer(c_int8_t) :: inside(2), c_inside(2)
        integer(c_int) :: first, second

        ball = isect_make_shape(ISECT_SPHERE, sphere)
        call record(ball%type == ISECT_SPHERE .and. ball%n == 0 .and. ball%flags == 0 .and. &
                    ball%reserved == 0 .and. c_associated(ball%data, c_loc(sphere)) .and. &
                    .not. c_associated(ball%xform) .and. .not. c_associated(ball%mesh), &
                    "isect_make_shape from a list")
        plate = isect_make_shape(ISECT_POLYGON, square, flags=ISECT_NONZERO)
        call record(plate%n == 4 .and. plate%flags == ISECT_NONZERO .and. &
                    c_associated(plate%data, c_loc(square)), &
                    "isect_make_shape from columns: n = number of columns")

        rays(1) = isect_make_ray(zero, up)
        rays(2) = isect_make_ray([5.0_c_double, 0.0_c_double, 0.0_c_double], up)
        rays(3) = isect_make_ray(zero, [0.0_c_double, ieee_value(1.0_c_double, ieee_quiet_nan), &
                                        1.0_c_double])

        call record(isect_intersect(ball, rays(1), scalar) == 2, "isect_intersect: 2 hits")
        call record(isect_intersect(plate, rays(1), scalar(1:1)) == 1, &
                    "isect_intersect: square plate hit")
        call record(near(scalar(1)%t, 3.0_c_double), "isect_intersect: square at t = 3")
        first = isect_intersect(ball, rays(1), scalar)
        second = isect_intersect(ball, rays(1), c_null_ptr, scalar, 2_c_int)
        call record(first == 2 .and. second == 2, "isect_intersect: both forms count alike")

        n_hit = isect_intersect_batch(ball, rays, closest)
        call record(n_hit == 1, "isect_intersect_batch: 1 ray hit")
        ! (Each call is a statement of its own: Fortran may evaluate the
        ! operands of an expression in any order.)
        c_total = isect_intersect_batch(ball, rays, 3_c_int64_t, c_null_ptr, c_closest)
        call record(c_total == 1 .and. same_hits(closest, c_closest), &
                    "isect_intersect_batch: both forms")
        call record(same_hits(closest(1:1), scalar(1:1)), &
                    "isect_intersect_batch: closest = first hit, bit for bit")
        call record(closest(2)%kind == ISECT_MISS .and. closest(2)%prim == -1 .and. &
                    .not. ieee_is_finite(closest(2)%t) .and. closest(2)%t > 0.0_c_double, &
                    "isect_intersect_batch: MISS record")
        call record(closest(3)%kind == ISECT_INVALID .and. ieee_is_nan(closest(3)%t), &
                    "isect_intersect_batch: INVALID record")
        call record(isect_intersect_batch(ball, rays, small) == ISECT_E_ARG, &
                    "isect_intersect_batch: a too-small buffer is ISECT_E_ARG")

        total = isect_intersect_all_batch(ball, rays, offsets, all_hits)
        call record(total == 3 .and. all(offsets == [0, 2, 2, 3]), &
                    "isect_intersect_all_batch: offsets 0 2 2 3")
        c_total = isect_intersect_all_batch(ball, rays, 3_c_int64_t, c_null_ptr, c_offsets, &
                                            c_all, 4_c_int64_t)
        call record(c_total == total .and. all(offsets == c_offsets) .and. &
                    same_hits(all_hits(1:3), c_all(1:3)), "isect_intersect_all_batch: both forms")
        call record(same_hits(all_hits(1:2), scalar(1:2)), &
                    "isect_intersect_all_batch: = isect_intersect, bit for bit")

        points(:, 1) = [0.0_c_double, 0.0_c_double, 5.5_c_double]
        points(:, 2) = [0.0_c_double, 0.0_c_double, 6.5_c_double]
        first = isect_contains(ball, points(:, 1))
        second = isect_contains(ball, points(:, 2))
        call record(first == 1 .and. second == 0, "isect_contains")
        n_hit = isect_contains_batch(ball, points, inside)
        call record(n_hit == 1 .and. all(inside == [1_c_int8_t, 0_c_int8_t]), &
                    "isect_contains_batch")
        n_hit = isect_contains_batch(ball, points, 2_c_int64_t, c_inside)
        call record(n_hit == 1 .and. all(inside == c_inside), "isect_contains_batch: both forms")
        call record(isect_contains(plate, points(:, 1)) == ISECT_E_ARG, &
                    "isect_contains: a thin surface is ISECT_E_ARG")
    end subroutine check_shapes_and_batches

    ! The 4x4 form takes a(row, column); the C form row-major m(16). A
    ! rotation by 90 degrees about z then a shift by (10, 0, 0):
    !   x' = -y + 10, y' = x, z' = z.
    subroutine check_transforms()
        real(c_double), parameter :: a(4, 4) = reshape([ &
            0.0_c_double, 1.0_c_double, 0.0_c_double, 0.0_c_double, &
            -1.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double, &
            0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, &
            10.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double], [4, 4])
        real(c_double), parameter :: row_major(16) = [ &
            0.0_c_double, -1.0_c_double, 0.0_c_double, 10.0_c_double, &
            1.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double, &
            0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, &
            0.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double]
        real(c_double), target :: ellipsoid(6) = [0.0_c_double, 0.0_c_double, 0.0_c_double, &
                                                  2.0_c_double, 1.0_c_double, 1.0_c_double]
        type(isect_xform), target :: from_matrix, from_rows
        type(isect_ray) :: world, object
        type(isect_hit) :: hits(2), c_hits(2)
        type(isect_shape) :: shape
        real(c_double) :: singular(4, 4)
        integer(c_int) :: status, c_status

        status = isect_xform_init(from_matrix, a)
        c_status = isect_xform_init(from_rows, row_major)
        call record(status == ISECT_OK .and. c_status == ISECT_OK, "isect_xform_init: OK")
        call record(same_doubles(from_matrix%m, row_major) .and. &
                    same_doubles(from_matrix%m, from_rows%m) .and. &
                    same_doubles(from_matrix%inv, from_rows%inv), &
                    "isect_xform_init: the 4x4 form is the transposed row-major form")

        ! World ray from (10, -5, 0) along +y: in object space from (-5, 0, 0)
        ! along +x, so the ellipsoid with radii (2, 1, 1) is hit at t = 3, 7,
        ! i.e. at world points (10, -2, 0) and (10, 2, 0).
        world = isect_make_ray([10.0_c_double, -5.0_c_double, 0.0_c_double], &
                               [0.0_c_double, 1.0_c_double, 0.0_c_double])
        status = isect_xform_ray(from_matrix, world, object)
        call record(status == ISECT_OK .and. &
                    near(object%org(1), -5.0_c_double) .and. near(object%dir(1), 1.0_c_double), &
                    "isect_xform_ray: into object space")
        shape = isect_make_shape(ISECT_ELLIPSOID, ellipsoid, xform=from_matrix)
        call record(isect_intersect(shape, world, hits) == 2, "transformed ellipsoid: 2 hits")
        call record(near(hits(1)%t, 3.0_c_double) .and. near(hits(2)%t, 7.0_c_double) .and. &
                    near(hits(1)%point(2), -2.0_c_double) .and. &
                    near(hits(2)%point(2), 2.0_c_double) .and. &
                    near(hits(1)%normal(2), -1.0_c_double), &
                    "transformed ellipsoid: t = 3, 7 at y = -2, 2")

        ! isect_xform_hits: the object-space hits taken to world space.
        call record(isect_ray_ellipsoid(object, ellipsoid(1:3), ellipsoid(4:6), hits) == 2, &
                    "ellipsoid in object space")
        c_hits = hits
        status = isect_xform_hits(from_matrix, hits)
        c_status = isect_xform_hits(from_matrix, c_hits, 2_c_int)
        call record(status == ISECT_OK .and. c_status == ISECT_OK .and. same_hits(hits, c_hits), &
                    "isect_xform_hits: both forms")
        call record(near(hits(2)%point(1), 10.0_c_double) .and. &
                    near(hits(2)%point(2), 2.0_c_double), "isect_xform_hits: world point")

        singular = a
        singular(:, 1) = 0.0_c_double
        singular(4, 4) = 1.0_c_double
        call record(isect_xform_init(from_rows, singular) == ISECT_E_DEGENERATE, &
                    "isect_xform_init: singular is ISECT_E_DEGENERATE")
    end subroutine check_transforms

    ! Unit square (0,0)-(1,1), counter-clockwise.
    subroutine check_planar_helpers()
        real(c_double), parameter :: square2(2, 4) = reshape([ &
            0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, &
            1.0_c_double, 1.0_c_double, 0.0_c_double, 1.0_c_double], [2, 4])
        real(c_double), parameter :: square3(3, 4) = reshape([ &
            0.0_c_double, 0.0_c_double, 2.0_c_double, 1.0_c_double, 0.0_c_double, &
            2.0_c_double, 1.0_c_double, 1.0_c_double, 2.0_c_double, 0.0_c_double, &
            1.0_c_double, 2.0_c_double], [3, 4])
        real(c_double), parameter :: pts(2, 3) = reshape([ &
            0.5_c_double, 0.5_c_double, 1.5_c_double, 0.5_c_double, &
            0.0_c_double, 0.0_c_double], [2, 3])
        real(c_double) :: normal(3), c_normal(3), plane(4), c_plane(4)
        integer(c_int32_t) :: winding, c_winding, windings(3), c_windings(3)
        integer(c_int8_t) :: inside(3), c_inside(3)
        integer(c_int) :: status, c_status
        integer(c_int64_t) :: count, c_count

        status = isect_point_in_polygon2(square2, pts(:, 1))
        c_status = isect_point_in_polygon2(square2, 4_c_int, pts(:, 1), ISECT_EVEN_ODD)
        call record(status == 1 .and. c_status == 1, "isect_point_in_polygon2: both forms")
        status = isect_point_in_polygon2(square2, pts(:, 2), ISECT_NONZERO)
        call record(status == 0, "isect_point_in_polygon2: outside")
        status = isect_winding_number2(square2, pts(:, 1), winding)
        c_status = isect_winding_number2(square2, 4_c_int, pts(:, 1), c_winding)
        call record(status == ISECT_OK .and. c_status == ISECT_OK .and. winding == 1 .and. &
                    c_winding == 1, "isect_winding_number2: +1 counter-clockwise")

        ! The corner (0, 0) belongs to the square under the half-open rule or
        ! not; either way both forms must agree.
        count = isect_point_in_polygon2_batch(square2, pts, inside, ISECT_EVEN_ODD)
        c_count = isect_point_in_polygon2_batch(square2, 4_c_int, pts, 3_c_int64_t, &
                                                ISECT_EVEN_ODD, c_inside)
        call record(count == c_count .and. all(inside == c_inside) .and. inside(1) == 1 .and. &
                    inside(2) == 0, "isect_point_in_polygon2_batch: both forms")
        count = isect_winding_number2_batch(square2, pts, windings)
        c_count = isect_winding_number2_batch(square2, 4_c_int, pts, 3_c_int64_t, c_windings)
        call record(count == c_count .and. all(windings == c_windings) .and. windings(1) == 1, &
                    "isect_winding_number2_batch: both forms")

        status = isect_polygon_normal(square3, normal)
        c_status = isect_polygon_normal(square3, 4_c_int, c_normal)
        call record(status == ISECT_OK .and. c_status == ISECT_OK .and. &
                    same_doubles(normal, c_normal) .and. near(normal(3), 1.0_c_double), &
                    "isect_polygon_normal: +z by both forms")
        status = isect_plane_from_points(square3, plane)
        c_status = isect_plane_from_points(square3, 4_c_int, c_plane)
        call record(status == ISECT_OK .and. same_doubles(plane, c_plane) .and. &
                    near(plane(3), 1.0_c_double) .and. near(plane(4), -2.0_c_double), &
                    "isect_plane_from_points: z - 2 = 0 by both forms")
    end subroutine check_planar_helpers

    ! opts: absent / c_null_ptr give the defaults; a bad eps is ISECT_E_ARG
    ! through either form.
    subroutine check_opts()
        real(c_double), parameter :: centre(3) = [0.0_c_double, 0.0_c_double, 5.0_c_double]
        type(isect_opts), target :: opts
        type(isect_ray) :: ray
        type(isect_hit) :: hits(2)
        integer(c_int) :: f_count, c_count

        ray = isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], &
                             [0.0_c_double, 0.0_c_double, 1.0_c_double])
        f_count = isect_ray_sphere(ray, centre, 1.0_c_double, hits, opts)
        c_count = isect_ray_sphere(ray, centre, 1.0_c_double, c_loc(opts), hits, 2_c_int)
        call record(f_count == 2 .and. c_count == 2, "default opts by both forms")
        opts%eps = -1.0_c_double
        f_count = isect_ray_sphere(ray, centre, 1.0_c_double, hits, opts)
        c_count = isect_ray_sphere(ray, centre, 1.0_c_double, c_loc(opts), hits, 2_c_int)
        call record(f_count == ISECT_E_ARG .and. c_count == ISECT_E_ARG, &
                    "eps < 0 is ISECT_E_ARG by both forms")
        opts%eps = ISECT_EPS_DEFAULT
        opts%flags = 4
        call record(isect_ray_sphere(ray, centre, 1.0_c_double, hits, opts) == ISECT_E_ARG, &
                    "an unknown opts flag is ISECT_E_ARG")
    end subroutine check_opts

    ! The unit cube [0,1]^3 as 6 quads with outward normals (right-hand
    ! rule), vertex i-1 at (x, y, z) with i-1 = x + 2y + 4z. V - E + F =
    ! 8 - 12 + 6 = 2, volume 1, area 6. A ray along +z through (0.3, 0.6)
    ! enters at z = 0 (t = 1) and leaves at z = 1 (t = 2).
    subroutine check_mesh()
        real(c_double), parameter :: corners(3, 8) = reshape([ &
            0.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, 0.0_c_double, &
            0.0_c_double, 1.0_c_double, 0.0_c_double, 1.0_c_double, 1.0_c_double, 0.0_c_double, &
            0.0_c_double, 0.0_c_double, 1.0_c_double, 1.0_c_double, 0.0_c_double, 1.0_c_double, &
            0.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double], &
            [3, 8])
        integer(c_int32_t), parameter :: quads(24) = [0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, &
                                                      2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5]
        integer(c_int64_t), target :: offsets(7) = [0, 4, 8, 12, 16, 20, 24]
        integer(c_int32_t) :: bad(24)
        type(c_ptr) :: mesh, c_mesh
        type(isect_mesh_report) :: report, c_report
        type(isect_shape) :: shape
        type(isect_ray) :: ray
        type(isect_hit) :: hits(4), c_hits(4)
        integer(c_int) :: status, c_status, count, c_count
        integer(c_int64_t) :: mold(16), bytes, c_bytes
        real(c_double) :: wpts(3, 3), w(3), c_w(3)

        status = isect_mesh_create(corners, quads, mesh, offsets)
        call record(status == ISECT_OK .and. c_associated(mesh), "isect_mesh_create: OK")
        c_status = isect_mesh_create(corners, 8_c_int64_t, quads, c_loc(offsets), 6_c_int64_t, &
                                     c_mesh)
        call record(c_status == ISECT_OK .and. c_associated(c_mesh), &
                    "isect_mesh_create: OK by the C form")
        if (status /= ISECT_OK .or. c_status /= ISECT_OK) return

        status = isect_mesh_check(mesh, report)
        c_status = isect_mesh_check(c_mesh, c_report)
        call record(status == ISECT_OK .and. c_status == ISECT_OK, "isect_mesh_check: OK")
        call record(all(transfer(report, mold) == transfer(c_report, mold)), &
                    "isect_mesh_check: both forms built the same mesh")
        call record(report%vertices == 8 .and. report%edges == 12 .and. report%faces == 6, &
                    "mesh report: V 8, E 12, F 6")
        call record(report%euler_characteristic == 2 .and. report%genus == 0 .and. &
                    report%components == 1, "mesh report: chi 2, genus 0, 1 component")
        call record(report%closed == 1 .and. report%oriented == 1 .and. &
                    report%boundary_edges == 0 .and. report%nonmanifold_edges == 0 .and. &
                    report%misoriented_edges == 0 .and. report%degenerate_faces == 0, &
                    "mesh report: closed and oriented")
        call record(near(report%volume, 1.0_c_double) .and. near(report%area, 6.0_c_double), &
                    "mesh report: volume 1, area 6")
        bytes = isect_mesh_bytes(mesh)
        c_bytes = isect_mesh_bytes(c_mesh)
        call record(bytes > 0 .and. bytes == c_bytes, "isect_mesh_bytes")

        shape = isect_make_mesh_shape(mesh)
        call record(shape%type == ISECT_MESH .and. shape%n == 0 .and. shape%flags == 0 .and. &
                    shape%reserved == 0 .and. .not. c_associated(shape%data) .and. &
                    c_associated(shape%mesh, mesh) .and. .not. c_associated(shape%xform), &
                    "isect_make_mesh_shape")
        ray = isect_make_ray([0.3_c_double, 0.6_c_double, -1.0_c_double], &
                             [0.0_c_double, 0.0_c_double, 1.0_c_double])
        count = isect_intersect(shape, ray, hits)
        c_count = isect_intersect(shape, ray, c_null_ptr, c_hits, 4_c_int)
        call record(count == 2 .and. c_count == 2 .and. same_hits(hits(1:2), c_hits(1:2)), &
                    "mesh: 2 hits by both forms")
        call record(near(hits(1)%t, 1.0_c_double) .and. near(hits(2)%t, 2.0_c_double) .and. &
                    hits(1)%kind == ISECT_ENTER .and. hits(2)%kind == ISECT_EXIT, &
                    "mesh: ENTER at t = 1, EXIT at t = 2")
        call record(near(hits(1)%normal(3), -1.0_c_double) .and. &
                    near(hits(2)%normal(3), 1.0_c_double), "mesh: normals -z, +z")
        status = isect_contains(shape, [0.5_c_double, 0.5_c_double, 0.5_c_double])
        c_status = isect_contains(shape, [1.5_c_double, 0.5_c_double, 0.5_c_double])
        call record(status == 1 .and. c_status == 0, "mesh: contains the centre, not (1.5, .5, .5)")
        ! winding numbers: 1 inside, 0 outside, 1/2 on a face (both forms)
        wpts = reshape([0.5_c_double, 0.5_c_double, 0.5_c_double, 1.5_c_double, 0.5_c_double, &
                        0.5_c_double, 0.5_c_double, 0.5_c_double, 0.0_c_double], [3, 3])
        status = isect_winding_number_batch(shape, wpts, w)
        c_status = isect_winding_number_batch(shape, wpts, 3_c_int64_t, 0.0_c_double, c_w)
        ! (exact values compared as <= and >=: -Wcompare-reals)
        call record(status == ISECT_OK .and. c_status == ISECT_OK .and. w(1) >= 1.0_c_double &
                    .and. w(1) <= 1.0_c_double .and. abs(w(2)) <= 0.0_c_double &
                    .and. abs(w(3) - 0.5_c_double) < 1e-14_c_double &
                    .and. all(abs(w - c_w) <= 0.0_c_double), &
                    "isect_winding_number_batch: 1, 0, 1/2 by both forms")
        shape%flags = ISECT_WINDING
        status = isect_contains(shape, [0.5_c_double, 0.5_c_double, 0.5_c_double])
        call record(status == 1, "mesh: contains by the winding rule")
        shape%flags = ISECT_EVEN_ODD

        call isect_mesh_destroy(mesh)
        call isect_mesh_destroy(c_mesh)
        call isect_mesh_destroy(c_null_ptr)

        ! Index 8 of 8 vertices: ISECT_E_ARG and no mesh, by either form.
        bad = quads
        bad(3) = 8
        status = isect_mesh_create(corners, bad, mesh, offsets)
        call record(status == ISECT_E_ARG .and. .not. c_associated(mesh), &
                    "isect_mesh_create: an index out of range is ISECT_E_ARG")
        c_status = isect_mesh_create(corners, 8_c_int64_t, bad, c_loc(offsets), 6_c_int64_t, &
                                     c_mesh)
        call record(c_status == ISECT_E_ARG .and. .not. c_associated(c_mesh), &
                    "isect_mesh_create: the same by the C form")
        ! The Fortran form checks what only it knows: the array sizes.
        status = isect_mesh_create(corners, quads(1:22), mesh, offsets)
        call record(status == ISECT_E_ARG .and. .not. c_associated(mesh), &
                    "isect_mesh_create: an offset beyond size(idx) is ISECT_E_ARG")
        status = isect_mesh_create(corners, quads(1:23), mesh)
        call record(status == ISECT_E_ARG .and. .not. c_associated(mesh), &
                    "isect_mesh_create: triangles need 3*nf indices")
        ! The same 24 indices read as 8 triangles: accepted (a mesh need not
        ! be closed), a different mesh.
        status = isect_mesh_create(corners, quads, mesh)
        call record(status == ISECT_OK .and. c_associated(mesh), &
                    "isect_mesh_create: triangles without offsets")
        if (status == ISECT_OK) then
            status = isect_mesh_check(mesh, report)
            call record(status == ISECT_OK .and. report%faces == 8, "triangle mesh: 8 faces")
        end if
        call isect_mesh_destroy(mesh)
    end subroutine check_mesh

    ! Sphere at (0,0,5), radius 1: the ray from the origin along +z enters at
    ! (0,0,4) (normal -z). A ray spawned there along +z starts just inside
    ! (z a few ulps above 4) and leaves at (0,0,6), t ~ 2; one spawned along
    ! -z starts just outside and meets nothing. A MISS record and a zero
    ! direction are refused.
    subroutine check_spawn()
        real(c_double), target :: data(4) = [0.0_c_double, 0.0_c_double, 5.0_c_double, 1.0_c_double]
        real(c_double), parameter :: up(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
        type(isect_shape) :: shape
        type(isect_ray) :: ray, out, rays(1)
        type(isect_hit) :: hits(2), closest(1)
        integer(c_int) :: status, count

        shape = isect_make_shape(ISECT_SPHERE, data)
        ray = isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], up)
        count = isect_intersect(shape, ray, hits)
        call record(count == 2 .and. hits(1)%kind == ISECT_ENTER, "spawn: the primary ray enters")

        status = isect_spawn_ray(shape, hits(1), up, out)
        call record(status == ISECT_OK, "spawn: ISECT_OK")
        call record(same_doubles(out%dir, up) .and. out%tmin >= 0.0_c_double .and. &
                    out%tmin <= 0.0_c_double .and. .not. ieee_is_finite(out%tmax) .and. &
                    out%tmax > 0.0_c_double, "spawn: dir as given, tmin 0, tmax +inf")
        call record(out%org(3) > 4.0_c_double .and. out%org(3) < 4.0_c_double + 1.0e-14_c_double &
                    .and. all(abs(out%org(1:2)) <= 0.0_c_double), &
                    "spawn: origin a few ulps inside, on the side dir points into")
        count = isect_intersect(shape, out, hits)
        call record(count == 1 .and. hits(1)%kind == ISECT_EXIT .and. near(hits(1)%t, 2.0_c_double), &
                    "spawn: the refracted ray leaves at t ~ 2, never meeting the entry point")

        count = isect_intersect(shape, ray, hits)
        status = isect_spawn_ray(shape, hits(1), -up, out)
        call record(status == ISECT_OK .and. out%org(3) < 4.0_c_double, &
                    "spawn: the reflected ray starts just outside")
        call record(isect_intersect(shape, out, hits) == 0, "spawn: the reflected ray meets nothing")

        rays(1) = isect_make_ray([3.0_c_double, 0.0_c_double, 0.0_c_double], up)
        call record(isect_intersect_batch(shape, rays, closest) == 0 .and. &
                    closest(1)%kind == ISECT_MISS, "spawn: a missing ray's closest record is MISS")
        call record(isect_spawn_ray(shape, closest(1), up, out) == ISECT_E_ARG, &
                    "spawn: a MISS record is ISECT_E_ARG")
        count = isect_intersect(shape, ray, hits)
        call record(isect_spawn_ray(shape, hits(1), [0.0_c_double, 0.0_c_double, 0.0_c_double], &
                                    out) == ISECT_E_DEGENERATE, "spawn: a zero direction is ISECT_E_DEGENERATE")
    end subroutine check_spawn

    ! The sphere at (0,0,5), radius 1: its box holds (-1,-1,4)..(1,1,6), and
    ! exceeds it by at most the documented widening (2^-40 of 6, < 1e-11).
    subroutine check_bounds()
        real(c_double), target :: data(4) = [0.0_c_double, 0.0_c_double, 5.0_c_double, 1.0_c_double]
        type(isect_shape) :: shape
        real(c_double) :: lo(3), hi(3)
        real(c_double), parameter :: e_lo(3) = [-1.0_c_double, -1.0_c_double, 4.0_c_double]
        real(c_double), parameter :: e_hi(3) = [1.0_c_double, 1.0_c_double, 6.0_c_double]

        shape = isect_make_shape(ISECT_SPHERE, data)
        call record(isect_shape_bounds(shape, lo, hi) == ISECT_OK, "bounds: ISECT_OK")
        call record(all(lo <= e_lo) .and. all(hi >= e_hi) .and. all(e_lo - lo < 1.0e-11_c_double) &
                    .and. all(hi - e_hi < 1.0e-11_c_double), "bounds: the sphere's box")
    end subroutine check_bounds
end program test_forms
