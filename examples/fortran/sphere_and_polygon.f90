! SPDX-License-Identifier: Apache-2.0
! sphere_and_polygon.f90 — the first things to do with libisect from
! Fortran: all hits of a ray with a sphere, a concave polygon hit and missed,
! and an error status. Prints the same lines as examples/c/sphere_and_polygon.c.
!
!     gfortran sphere_and_polygon.f90 $(pkg-config --cflags --libs isect-fortran) -o sphere_and_polygon
program sphere_and_polygon
    use, intrinsic :: iso_c_binding, only: c_double, c_int, c_null_ptr
    use isect
    implicit none

    real(c_double), parameter :: centre(3) = [0.0_c_double, 0.0_c_double, 5.0_c_double]
    ! An L-shaped hexagon in the plane z = 2: the square (0,0)-(2,2) without
    ! its upper right quarter, counter-clockwise seen from +z, so its normal
    ! (right-hand rule) is +z. Column i is vertex i (C's v[n][3]).
    real(c_double), parameter :: l_shape(3, 6) = reshape([ &
        0.0_c_double, 0.0_c_double, 2.0_c_double, 2.0_c_double, 0.0_c_double, 2.0_c_double, &
        2.0_c_double, 1.0_c_double, 2.0_c_double, 1.0_c_double, 1.0_c_double, 2.0_c_double, &
        1.0_c_double, 2.0_c_double, 2.0_c_double, 0.0_c_double, 2.0_c_double, 2.0_c_double], &
        [3, 6])
    real(c_double), parameter :: down(3) = [0.0_c_double, 0.0_c_double, -1.0_c_double]
    type(isect_ray) :: ray
    type(isect_hit) :: hits(4), none(0)
    integer(c_int) :: count

    write (*, '(3a, i0, a)') "libisect ", isect_version_text(), " (ABI ", isect_abi_version(), ")"

    ! isect_make_ray: tmin = 0 and tmax = +infinity unless given.
    ray = isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], &
                         [0.0_c_double, 0.0_c_double, 1.0_c_double])

    ! Every hit along the ray, sorted by t. The Fortran form takes the
    ! capacity from size(hits) and uses the default options; the return
    ! value is the number of hits (it may exceed the capacity) or a negative
    ! ISECT_E_* status. The C form would be
    !     isect_ray_sphere(ray, centre, 1.0_c_double, c_null_ptr, hits, 4_c_int)
    count = isect_ray_sphere(ray, centre, 1.0_c_double, hits)
    write (*, '(a, i0, a)') "sphere: ", count, " hits"
    call print_hits(hits(1:count))

    ! Straight down onto the polygon: it is met on its front side.
    ray = isect_make_ray([0.5_c_double, 0.5_c_double, 5.0_c_double], down)
    count = isect_ray_polygon(ray, l_shape, hits, rule=ISECT_EVEN_ODD)
    write (*, '(a, i0, a)') "polygon at (0.5, 0.5): ", count, " hits"
    call print_hits(hits(1:count))

    ! (1.5, 1.5) lies in the notch: no hit. Counting only: a zero-size
    ! buffer (here through the C form, with the options pointer NULL).
    ray = isect_make_ray([1.5_c_double, 1.5_c_double, 5.0_c_double], down)
    count = isect_ray_polygon(ray, l_shape, 6_c_int, ISECT_EVEN_ODD, c_null_ptr, none, 0_c_int)
    write (*, '(a, i0, a)') "polygon at (1.5, 1.5): ", count, " hits"

    ! Errors are negative statuses (isect_error_message() gives a message).
    count = isect_ray_sphere(ray, centre, -1.0_c_double, hits)
    if (count == ISECT_E_ARG) then
        write (*, '(a, i0, a)') "negative radius: status ", count, " (ISECT_E_ARG)"
    else
        write (*, '(a, i0, a)') "negative radius: status ", count, " (unexpected)"
        stop 1
    end if

contains

    subroutine print_hits(found)
        type(isect_hit), intent(in) :: found(:)
        integer :: i
        do i = 1, size(found)
            write (*, '(a, i0, *(a))') "  hit ", i, ": t = ", num(found(i)%t), ", ", &
                trim(kind_name(found(i)%kind)), ", point (", num(found(i)%point(1)), ", ", &
                num(found(i)%point(2)), ", ", num(found(i)%point(3)), "), normal (", &
                num(found(i)%normal(1)), ", ", num(found(i)%normal(2)), ", ", &
                num(found(i)%normal(3)), ")"
        end do
    end subroutine print_hits

    ! A number as C's "%.3f" prints it. Adding 0 turns a -0.0 into 0.0, so
    ! a zero prints as 0.000 either way.
    function num(x) result(text)
        real(c_double), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(f32.3)') x + 0.0_c_double
        text = trim(adjustl(buffer))
    end function num

    ! libisect reports hit kinds as integers; name them for printing.
    function kind_name(kind) result(name)
        integer, intent(in) :: kind
        character(len=5) :: name
        select case (kind)
        case (ISECT_ENTER)
            name = "enter"
        case (ISECT_EXIT)
            name = "exit"
        case (ISECT_TOUCH)
            name = "touch"
        case default
            name = "other"
        end select
    end function kind_name

end program sphere_and_polygon
