! SPDX-License-Identifier: Apache-2.0
! mesh_cube.f90 — a polygon mesh: the cube [-1, 1]^3 as 6 quads, built with
! isect_mesh_create, checked with isect_mesh_check, hit by a ray through an
! ISECT_MESH shape descriptor, asked for a point, and freed. Prints the same
! lines as examples/c/mesh_cube.c.
!
!     gfortran mesh_cube.f90 $(pkg-config --cflags --libs isect-fortran) -o mesh_cube
program mesh_cube
    use, intrinsic :: iso_c_binding, only: c_double, c_int, c_int32_t, c_int64_t, c_ptr
    use isect
    implicit none

    ! Column i is vertex i-1 = x + 2y + 4z for the corner (x, y, z) in
    ! {0, 1}^3, scaled to [-1, 1]^3.
    real(c_double), parameter :: verts(3, 8) = reshape([ &
        -1.0_c_double, -1.0_c_double, -1.0_c_double, 1.0_c_double, -1.0_c_double, -1.0_c_double, &
        -1.0_c_double, 1.0_c_double, -1.0_c_double, 1.0_c_double, 1.0_c_double, -1.0_c_double, &
        -1.0_c_double, -1.0_c_double, 1.0_c_double, 1.0_c_double, -1.0_c_double, 1.0_c_double, &
        -1.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double, 1.0_c_double], &
        [3, 8])
    ! Six quads, each counter-clockwise seen from outside (outward normals
    ! -z, +z, -y, +y, -x, +x). Indices and offsets are 0-based, as in C:
    ! face f (0-based) is idx(offsets(f+1)+1 : offsets(f+2)).
    integer(c_int32_t), parameter :: idx(24) = [0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, &
                                                2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5]
    integer(c_int64_t), parameter :: offsets(7) = [0, 4, 8, 12, 16, 20, 24]
    type(c_ptr) :: mesh
    type(isect_mesh_report) :: report
    type(isect_shape) :: shape
    type(isect_hit) :: hits(4)
    integer(c_int) :: status, count
    character(len=32) :: volume, area

    ! The Fortran form takes nv and nf from the array sizes; the input is
    ! copied. The handle is a C pointer: free it with isect_mesh_destroy.
    status = isect_mesh_create(verts, idx, mesh, offsets)
    if (status /= ISECT_OK) then
        write (*, '(2a)') "isect_mesh_create: ", isect_error_message(status)
        stop 1
    end if
    status = isect_mesh_check(mesh, report)
    if (status /= ISECT_OK) then
        write (*, '(2a)') "isect_mesh_check: ", isect_error_message(status)
        call isect_mesh_destroy(mesh)
        stop 1
    end if
    write (*, '(4(a, i0))') "mesh: ", report%vertices, " vertices, ", report%edges, &
        " edges, ", report%faces, " faces, euler characteristic ", report%euler_characteristic
    write (volume, '(f32.3)') report%volume
    write (area, '(f32.3)') report%area
    write (*, '(2(a, i0), 4a)') "closed ", report%closed, ", oriented ", report%oriented, &
        ", volume ", trim(adjustl(volume)), ", area ", trim(adjustl(area))

    ! A mesh is queried through a shape descriptor (type ISECT_MESH, data
    ! null, mesh the handle).
    shape = isect_make_mesh_shape(mesh)
    count = isect_intersect(shape, isect_make_ray([0.25_c_double, 0.5_c_double, -5.0_c_double], &
                                                  [0.0_c_double, 0.0_c_double, 1.0_c_double]), hits)
    call print_hits("along z", hits(1:count))
    write (*, '(a, i0)') "contains (0, 0, 0): ", &
        isect_contains(shape, [0.0_c_double, 0.0_c_double, 0.0_c_double])

    call isect_mesh_destroy(mesh)

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

end program mesh_cube
