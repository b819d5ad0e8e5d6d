! SPDX-License-Identifier: Apache-2.0
! transformed_ellipsoid.f90 — a shape descriptor (isect_shape) with an
! object-to-world transform: an ellipsoid with radii (2, 1, 1), turned by 90
! degrees about z (its long axis now along y) and moved to (10, 0, 0). Prints
! the same lines as examples/c/transformed_ellipsoid.c.
!
!     gfortran transformed_ellipsoid.f90 $(pkg-config --cflags --libs isect-fortran) -o transformed_ellipsoid
program transformed_ellipsoid
    use, intrinsic :: iso_c_binding, only: c_double, c_int
    use isect
    implicit none

    ! The object-to-world matrix as written on paper, a(row, column):
    ! x' = -y + 10, y' = x, z' = z. (reshape fills column by column.)
    real(c_double), parameter :: a(4, 4) = reshape([ &
        0.0_c_double, 1.0_c_double, 0.0_c_double, 0.0_c_double, &
        -1.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double, &
        0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, &
        10.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double], [4, 4])
    ! The ellipsoid's numbers in the order of isect_ray_ellipsoid's
    ! arguments: centre, then radii. The descriptor points at them and at the
    ! transform without copying: both need TARGET and must outlive it.
    real(c_double), target :: ellipsoid(6) = [0.0_c_double, 0.0_c_double, 0.0_c_double, &
                                              2.0_c_double, 1.0_c_double, 1.0_c_double]
    type(isect_xform), target :: xform
    type(isect_shape) :: shape
    type(isect_hit) :: hits(4)
    integer(c_int) :: status, count

    ! The 4x4 form of isect_xform_init (the C form takes 16 numbers, row by
    ! row). It also computes the inverse; it rejects a singular matrix
    ! (ISECT_E_DEGENERATE) and a last row other than 0 0 0 1.
    status = isect_xform_init(xform, a)
    if (status /= ISECT_OK) then
        write (*, '(2a)') "isect_xform_init: ", isect_error_message(status)
        stop 1
    end if
    shape = isect_make_shape(ISECT_ELLIPSOID, ellipsoid, xform=xform)

    ! Hits come back in world space with t unchanged: along y the long axis
    ! is crossed (|y| <= 2), along x the short one (|x - 10| <= 1).
    count = isect_intersect(shape, isect_make_ray([10.0_c_double, -5.0_c_double, 0.0_c_double], &
                                                  [0.0_c_double, 1.0_c_double, 0.0_c_double]), hits)
    call print_hits("along y", hits(1:count))
    count = isect_intersect(shape, isect_make_ray([0.0_c_double, 0.0_c_double, 0.0_c_double], &
                                                  [1.0_c_double, 0.0_c_double, 0.0_c_double]), hits)
    call print_hits("along x", hits(1:count))

    write (*, '(a, i0)') "contains (10, 1.5, 0): ", &
        isect_contains(shape, [10.0_c_double, 1.5_c_double, 0.0_c_double])
    write (*, '(a, i0)') "contains (11.5, 0, 0): ", &
        isect_contains(shape, [11.5_c_double, 0.0_c_double, 0.0_c_double])

contains

    subroutine print_hits(label, found)
        character(len=*), intent(in) :: label
        type(isect_hit), intent(in) :: found(:)
        integer :: i
        write (*, '(2a, i0, a)') label, ": ", size(found), " hits"
        do i = 1, size(found)
            write (*, '(a, i0, *(a))') "  hit ", i, ": t = ", num(found(i)%t), ", ", &
                trim(merge("enter", "exit ", found(i)%kind == ISECT_ENTER)), ", point (", &
                num(found(i)%point(1)), ", ", num(found(i)%point(2)), ", ", &
                num(found(i)%point(3)), "), normal (", num(found(i)%normal(1)), ", ", &
                num(found(i)%normal(2)), ", ", num(found(i)%normal(3)), ")"
        end do
    end subroutine print_hits

    ! A number as C's "%.3f" prints it (-0.0 as 0.000).
    function num(x) result(text)
        real(c_double), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(f32.3)') x + 0.0_c_double
        text = trim(adjustl(buffer))
    end function num

end program transformed_ellipsoid
