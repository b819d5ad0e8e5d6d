! SPDX-License-Identifier: Apache-2.0
! test_layout.f90 — the module isect agrees with isect.h as the C compiler
! sees it (layout_probe.c):
!   * every bind(C) type has the size and field offsets of its C struct, and
!     both equal SPEC.md's numbers (ray 64, hit 80, opts 16, xform 256,
!     shape 40, mesh report 128 bytes on 64-bit targets);
!   * every numeric #define ISECT_* of isect.h (read from the header given as
!     the first argument, so a constant added there fails here until the
!     module has it) has a module parameter with the C value;
!   * ISECT_EPS_DEFAULT, the version string and ISECT_OPTS_INIT match bit for
!     bit, and the loaded library reports the version the module mirrors.
! Usage: test_layout path/to/isect.h
program test_layout
    use, intrinsic :: iso_c_binding
    use isect
    use test_report, only: record, finish
    implicit none

    interface
        function probe_layout(name, value) bind(C, name="probe_layout") result(found)
            import :: c_char, c_long_long, c_int
            character(kind=c_char), intent(in) :: name(*)
            integer(c_long_long), intent(out) :: value
            integer(c_int) :: found
        end function probe_layout

        function probe_constant(name, value) bind(C, name="probe_constant") result(found)
            import :: c_char, c_long_long, c_int
            character(kind=c_char), intent(in) :: name(*)
            integer(c_long_long), intent(out) :: value
            integer(c_int) :: found
        end function probe_constant

        function probe_eps_default() bind(C, name="probe_eps_default") result(eps)
            import :: c_double
            real(c_double) :: eps
        end function probe_eps_default

        function probe_version_string() bind(C, name="probe_version_string") result(text)
            import :: c_ptr
            type(c_ptr) :: text
        end function probe_version_string

        subroutine probe_opts_init(opts) bind(C, name="probe_opts_init")
            import :: isect_opts
            type(isect_opts), intent(out) :: opts
        end subroutine probe_opts_init

        function c_strlen(text) bind(C, name="strlen") result(length)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: text
            integer(c_size_t) :: length
        end function c_strlen
    end interface

    ! A module parameter under the name of the C macro it mirrors.
    type :: mirrored_constant
        character(len=32) :: c_name
        integer(c_long_long) :: value
    end type mirrored_constant

    type(mirrored_constant), parameter :: module_constants(*) = [ &
        mirrored_constant("ISECT_VERSION_MAJOR", ISECT_VERSION_MAJOR), &
        mirrored_constant("ISECT_VERSION_MINOR", ISECT_VERSION_MINOR), &
        mirrored_constant("ISECT_VERSION_PATCH", ISECT_VERSION_PATCH), &
        mirrored_constant("ISECT_VERSION", ISECT_HEADER_VERSION), &
        mirrored_constant("ISECT_ABI_VERSION", ISECT_HEADER_ABI_VERSION), &
        mirrored_constant("ISECT_OK", ISECT_OK), &
        mirrored_constant("ISECT_E_ARG", ISECT_E_ARG), &
        mirrored_constant("ISECT_E_NONFINITE", ISECT_E_NONFINITE), &
        mirrored_constant("ISECT_E_DEGENERATE", ISECT_E_DEGENERATE), &
        mirrored_constant("ISECT_E_NOMEM", ISECT_E_NOMEM), &
        mirrored_constant("ISECT_MISS", ISECT_MISS), &
        mirrored_constant("ISECT_ENTER", ISECT_ENTER), &
        mirrored_constant("ISECT_EXIT", ISECT_EXIT), &
        mirrored_constant("ISECT_TOUCH", ISECT_TOUCH), &
        mirrored_constant("ISECT_INVALID", ISECT_INVALID), &
        mirrored_constant("ISECT_PLANE", ISECT_PLANE), &
        mirrored_constant("ISECT_SPHERE", ISECT_SPHERE), &
        mirrored_constant("ISECT_AABB", ISECT_AABB), &
        mirrored_constant("ISECT_TRIANGLE", ISECT_TRIANGLE), &
        mirrored_constant("ISECT_POLYGON", ISECT_POLYGON), &
        mirrored_constant("ISECT_CONVEX", ISECT_CONVEX), &
        mirrored_constant("ISECT_CYLINDER", ISECT_CYLINDER), &
        mirrored_constant("ISECT_CYLINDER_INF", ISECT_CYLINDER_INF), &
        mirrored_constant("ISECT_ELLIPSOID", ISECT_ELLIPSOID), &
        mirrored_constant("ISECT_QUADRIC", ISECT_QUADRIC), &
        mirrored_constant("ISECT_MESH", ISECT_MESH), &
        mirrored_constant("ISECT_EVEN_ODD", ISECT_EVEN_ODD), &
        mirrored_constant("ISECT_NONZERO", ISECT_NONZERO), &
        mirrored_constant("ISECT_WINDING", ISECT_WINDING), &
        mirrored_constant("ISECT_CAPPED", ISECT_CAPPED), &
        mirrored_constant("ISECT_CULL_BACK", ISECT_CULL_BACK), &
        mirrored_constant("ISECT_ANY_HIT", ISECT_ANY_HIT) ]

    ! Macros of isect.h that are not numeric constants, or are checked on
    ! their own below.
    character(len=32), parameter :: not_constants(*) = [character(len=32) :: &
        "ISECT_H", "ISECT_API", "ISECT_OPTS_INIT", "ISECT_VERSION_STRING", &
        "ISECT_EPS_DEFAULT"]

    type(isect_ray), target :: ray
    type(isect_hit), target :: hit
    type(isect_opts), target :: opts
    type(isect_xform), target :: xform
    type(isect_shape), target :: shape
    type(isect_mesh_report), target :: report
    character(len=4096) :: header_path

    if (command_argument_count() /= 1) then
        write (*, '(a)') "usage: test_layout path/to/isect.h"
        error stop 2
    end if
    call get_command_argument(1, header_path)

    call check_layout("sizeof isect_ray", c_sizeof(ray), 64)
    call check_layout("isect_ray.org", offset(c_loc(ray%org), c_loc(ray)), 0)
    call check_layout("isect_ray.dir", offset(c_loc(ray%dir), c_loc(ray)), 24)
    call check_layout("isect_ray.tmin", offset(c_loc(ray%tmin), c_loc(ray)), 48)
    call check_layout("isect_ray.tmax", offset(c_loc(ray%tmax), c_loc(ray)), 56)

    call check_layout("sizeof isect_hit", c_sizeof(hit), 80)
    call check_layout("isect_hit.t", offset(c_loc(hit%t), c_loc(hit)), 0)
    call check_layout("isect_hit.point", offset(c_loc(hit%point), c_loc(hit)), 8)
    call check_layout("isect_hit.normal", offset(c_loc(hit%normal), c_loc(hit)), 32)
    call check_layout("isect_hit.uv", offset(c_loc(hit%uv), c_loc(hit)), 56)
    call check_layout("isect_hit.prim", offset(c_loc(hit%prim), c_loc(hit)), 72)
    call check_layout("isect_hit.kind", offset(c_loc(hit%kind), c_loc(hit)), 76)

    call check_layout("sizeof isect_opts", c_sizeof(opts), 16)
    call check_layout("isect_opts.size", offset(c_loc(opts%size), c_loc(opts)), 0)
    call check_layout("isect_opts.flags", offset(c_loc(opts%flags), c_loc(opts)), 4)
    call check_layout("isect_opts.eps", offset(c_loc(opts%eps), c_loc(opts)), 8)

    call check_layout("sizeof isect_xform", c_sizeof(xform), 256)
    call check_layout("isect_xform.m", offset(c_loc(xform%m), c_loc(xform)), 0)
    call check_layout("isect_xform.inv", offset(c_loc(xform%inv), c_loc(xform)), 128)

    call check_layout("sizeof isect_shape", c_sizeof(shape), 40)
    call check_layout("isect_shape.type", offset(c_loc(shape%type), c_loc(shape)), 0)
    call check_layout("isect_shape.n", offset(c_loc(shape%n), c_loc(shape)), 4)
    call check_layout("isect_shape.flags", offset(c_loc(shape%flags), c_loc(shape)), 8)
    call check_layout("isect_shape.reserved", offset(c_loc(shape%reserved), c_loc(shape)), 12)
    call check_layout("isect_shape.data", offset(c_loc(shape%data), c_loc(shape)), 16)
    call check_layout("isect_shape.mesh", offset(c_loc(shape%mesh), c_loc(shape)), 24)
    call check_layout("isect_shape.xform", offset(c_loc(shape%xform), c_loc(shape)), 32)

    call check_layout("sizeof isect_mesh_report", c_sizeof(report), 128)
    call check_layout("isect_mesh_report.vertices", &
                      offset(c_loc(report%vertices), c_loc(report)), 0)
    call check_layout("isect_mesh_report.edges", &
                      offset(c_loc(report%edges), c_loc(report)), 8)
    call check_layout("isect_mesh_report.faces", &
                      offset(c_loc(report%faces), c_loc(report)), 16)
    call check_layout("isect_mesh_report.boundary_edges", &
                      offset(c_loc(report%boundary_edges), c_loc(report)), 24)
    call check_layout("isect_mesh_report.nonmanifold_edges", &
                      offset(c_loc(report%nonmanifold_edges), c_loc(report)), 32)
    call check_layout("isect_mesh_report.misoriented_edges", &
                      offset(c_loc(report%misoriented_edges), c_loc(report)), 40)
    call check_layout("isect_mesh_report.degenerate_faces", &
                      offset(c_loc(report%degenerate_faces), c_loc(report)), 48)
    call check_layout("isect_mesh_report.components", &
                      offset(c_loc(report%components), c_loc(report)), 56)
    call check_layout("isect_mesh_report.euler_characteristic", &
                      offset(c_loc(report%euler_characteristic), c_loc(report)), 64)
    call check_layout("isect_mesh_report.genus", &
                      offset(c_loc(report%genus), c_loc(report)), 72)
    call check_layout("isect_mesh_report.closed", &
                      offset(c_loc(report%closed), c_loc(report)), 80)
    call check_layout("isect_mesh_report.oriented", &
                      offset(c_loc(report%oriented), c_loc(report)), 84)
    call check_layout("isect_mesh_report.volume", &
                      offset(c_loc(report%volume), c_loc(report)), 88)
    call check_layout("isect_mesh_report.area", &
                      offset(c_loc(report%area), c_loc(report)), 96)
    call check_layout("isect_mesh_report.reserved", &
                      offset(c_loc(report%reserved), c_loc(report)), 104)

    call check_constants(trim(header_path))
    call check_other_values()
    call finish()

contains

    ! Address difference in bytes.
    function offset(field, base) result(bytes)
        type(c_ptr), intent(in) :: field, base
        integer(c_size_t) :: bytes
        bytes = int(transfer(field, 0_c_intptr_t) - transfer(base, 0_c_intptr_t), c_size_t)
    end function offset

    ! The Fortran size/offset must equal both the C compiler's and SPEC's.
    subroutine check_layout(name, fortran_value, spec_value)
        character(len=*), intent(in) :: name
        integer(c_size_t), intent(in) :: fortran_value
        integer, intent(in) :: spec_value
        integer(c_long_long) :: c_value
        character(len=160) :: detail
        if (probe_layout(name // c_null_char, c_value) == 0) then
            call record(.false., name, "the C probe does not know it")
            return
        end if
        write (detail, '(3(a, i0))') "Fortran ", fortran_value, ", C ", c_value, &
            ", SPEC ", spec_value
        call record(fortran_value == c_value .and. c_value == spec_value, name, trim(detail))
    end subroutine check_layout

    ! Each numeric #define ISECT_* of the header has a module parameter, and
    ! each module parameter has the C compiler's value.
    subroutine check_constants(path)
        character(len=*), intent(in) :: path
        character(len=512) :: line
        character(len=64) :: name
        integer :: unit, ios, i, name_end
        integer(c_long_long) :: c_value
        character(len=160) :: detail
        logical :: found

        open (newunit=unit, file=path, status="old", action="read", iostat=ios)
        if (ios /= 0) then
            call record(.false., "read " // path)
            return
        end if
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:14) /= "#define ISECT_") cycle
            name_end = scan(line(9:), " (") + 7
            if (name_end < 9) name_end = len_trim(line)
            name = line(9:name_end)
            if (any(not_constants == name)) cycle
            found = .false.
            do i = 1, size(module_constants)
                if (module_constants(i)%c_name == name) found = .true.
            end do
            call record(found, "module parameter for " // trim(name), &
                        "isect.h defines it; add it to isect.f90 and to this test")
        end do
        close (unit)

        do i = 1, size(module_constants)
            name = module_constants(i)%c_name
            if (probe_constant(trim(name) // c_null_char, c_value) == 0) then
                call record(.false., trim(name), "the C probe does not know it")
                cycle
            end if
            write (detail, '(2(a, i0))') "Fortran ", module_constants(i)%value, ", C ", c_value
            call record(module_constants(i)%value == c_value, trim(name), trim(detail))
        end do
    end subroutine check_constants

    subroutine check_other_values()
        type(isect_opts) :: fortran_default, c_init
        integer(c_int8_t) :: mold(1)
        integer(c_int) :: status
        character(len=:), allocatable :: message, other

        call record(transfer(probe_eps_default(), 0_c_int64_t) == &
                    transfer(ISECT_EPS_DEFAULT, 0_c_int64_t), "ISECT_EPS_DEFAULT bits")
        call record(c_string(probe_version_string()) == ISECT_HEADER_VERSION_STRING, &
                    "ISECT_VERSION_STRING", c_string(probe_version_string()))

        ! The default initialisation of type(isect_opts) is ISECT_OPTS_INIT.
        call probe_opts_init(c_init)
        call record(all(transfer(fortran_default, mold) == transfer(c_init, mold)), &
                    "type(isect_opts) default = ISECT_OPTS_INIT")

        ! The library that is loaded is the one the module mirrors.
        call record(isect_version() == ISECT_HEADER_VERSION, "isect_version()")
        call record(isect_abi_version() == ISECT_HEADER_ABI_VERSION, "isect_abi_version()")
        call record(isect_version_text() == ISECT_HEADER_VERSION_STRING, &
                    "isect_version_text()", isect_version_text())

        ! Every status has its own message; others get "unknown status".
        do status = ISECT_E_NOMEM, ISECT_OK
            message = isect_error_message(status)
            call record(len(message) > 0 .and. message /= "unknown status", &
                        "isect_error_message of a status", message)
            if (status > ISECT_E_NOMEM) then
                other = isect_error_message(status - 1_c_int)
                call record(message /= other, "distinct messages", message)
            end if
        end do
        call record(isect_error_message(12345_c_int) == "unknown status", &
                    "isect_error_message(12345)", isect_error_message(12345_c_int))
    end subroutine check_other_values

    function c_string(text) result(str)
        type(c_ptr), intent(in) :: text
        character(len=:), allocatable :: str
        character(kind=c_char), pointer :: chars(:)
        integer :: i, length
        length = int(c_strlen(text))
        call c_f_pointer(text, chars, [length])
        allocate (character(len=length) :: str)
        do i = 1, length
            str(i:i) = chars(i)
        end do
    end function c_string

end program test_layout
