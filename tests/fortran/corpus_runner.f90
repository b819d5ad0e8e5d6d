! SPDX-License-Identifier: Apache-2.0
! corpus_runner.f90 — runs the golden corpus through the Fortran module isect.
!
!     corpus_runner tests/cases/flat/*.txt
!
! The corpus is tests/cases/*.json (schema: tests/cases/README.md); Fortran
! reads its flat text export tests/cases/flat/*.txt (format: the top of
! tests/golden/export_flat.py), which carries every number exactly. Each case
! goes through the same API paths as the C runner (tests/c/corpus_*.c), here
! through the module's interfaces:
!   intersect  isect_intersect and the type's scalar function (for a
!              transformed case: isect_xform_ray + scalar + isect_xform_hits;
!              a mesh has no scalar function, so a transformed mesh composes
!              isect_intersect without the xform instead, and an untransformed
!              one has only the first path), each with a large buffer, cap 0
!              and cap 1; untransformed, the two agree bit for bit;
!              isect_intersect_batch and
!              isect_intersect_all_batch on 5 copies of the ray with a NaN
!              origin in the middle one (closest hit = isect_intersect's first
!              hit bit for bit, MISS / INVALID records, CSR offsets, a retry
!              with a too-small cap); on an expected error: the status, and
!              nothing written.
!   contains, point_in_polygon2, winding_number2: the scalar call, and the
!              batch call on 4 copies of the point with a NaN one.
!   mesh_check isect_mesh_check: every isect_mesh_report field (the mesh as
!              given: no transform).
!   polygon_normal, plane_from_points: status and values.
!   winding_number isect_winding_number_batch on all the points at once and
!              on each point alone (the library may sum a batch of 8 points
!              or more differently), each w within wtol; points that are not
!              finite get NaN while the call succeeds (an E_NONFINITE case
!              caused by its points); any other expected error fails the
!              call and writes nothing. A mesh's containment rule (contains)
!              is the flags of its shape line.
!   spawn      isect_spawn_ray from the closest-hit record of the primary ray
!              (isect_intersect_batch: the first hit, or the MISS record),
!              with the case's direction (sdir): the status; out%dir bit for
!              bit, tmin 0, tmax +inf, out%org within 8 ulps of the hit point;
!              then the spawned ray's hits through isect_intersect and its
!              closest hit through isect_intersect_batch.
! A mesh shape is built first with isect_mesh_create (triangle layout when
! every face has 3 indices, else CSR offsets; tests/cases/README.md,
! "Meshes"; as the C runner, also for a raw type with "faces"); a creation
! error is the case's result whatever the op. Then the op runs as for any
! shape, with isect_shape%mesh set, and the mesh is destroyed.
! Values pass when |got - want| <= tol * max(1, |want|); an infinite want must
! be matched exactly. Each disagreement prints
!     FAIL file:id name: what (expected X, got Y)
! and the run ends with "N skipped" (cases the export marks skip: a shape
! type or op newer than the export) and then the line "N passed, N failed"
! (N counting cases; a broken file counts as one failed entry); exit status 1
! if anything failed.
program corpus_runner
    use, intrinsic :: iso_c_binding
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
        ieee_quiet_nan, ieee_next_after, ieee_positive_inf
    use isect
    implicit none

    ! Room for every hit any case can have; a count above it is a failure.
    integer, parameter :: HIT_CAP = 64
    ! Batches: copies of the case's ray / point with a bad one at BAD_*.
    integer, parameter :: BATCH_RAYS = 5, BAD_RAY = 3
    integer, parameter :: POINT_BATCH = 4, BAD_POINT = 3
    integer, parameter :: ALL_CAP = BATCH_RAYS * HIT_CAP + 1
    ! Zero doubles after a shape's data (see "shape" in apply_line).
    integer, parameter :: DATA_PADDING = 16
    ! After this many lines a case's further failures are only counted.
    integer, parameter :: MAX_LINES = 12
    ! Every byte of an output buffer is preset to 0xA5 (as the C runner
    ! does); a byte still holding it was not written.
    integer(c_int8_t), parameter :: GUARD_BYTE = -91_c_int8_t
    ! INT32_MIN, the winding of a non-finite point in batch output (as a
    ! 64-bit value: standard Fortran integers are symmetric about 0).
    integer(c_int64_t), parameter :: WINDING_INVALID = -2147483648_c_int64_t
    character(len=*), parameter :: FLAT_FORMAT = "isect-flat/4"
    ! Version 3 files are version 4 files without its additions (op
    ! winding_number, a mesh's rule in its shape flags): still read.
    character(len=*), parameter :: FLAT_FORMAT_OLD = "isect-flat/3"
    ! op spawn: how far (in ulps of the hit point's largest coordinate) the
    ! spawned origin may lie from the hit point, per coordinate.
    real(c_double), parameter :: SPAWN_MAX_ULPS = 8

    type :: expected_hit
        real(c_double) :: t = 0, point(3) = 0, normal(3) = 0, uv(2) = 0
        logical :: has_uv = .false.
        integer(c_int32_t) :: prim = 0, kind = 0
    end type expected_hit

    ! One case block of a flat file.
    type :: corpus_case
        character(len=:), allocatable :: label, name, op, problem
        logical :: malformed = .false., skipped = .false.
        integer(c_int32_t) :: shape_type = 0, shape_n = 0, shape_flags = 0
        logical :: named = .false.
        logical :: has_data = .false.              ! else isect_shape%data is NULL
        integer :: ndata = 0                       ! numbers given; data(:) is padded
        real(c_double), allocatable :: data(:)
        logical :: has_transform = .false.
        real(c_double) :: transform(16) = 0
        type(isect_ray) :: ray = isect_ray(0.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double)
        real(c_double) :: sdir(3) = 0                      ! spawn: the secondary direction
        logical :: has_sdir = .false.
        logical :: has_opts = .false.
        type(isect_opts) :: opts
        real(c_double) :: point(3) = 0
        integer :: point_dim = 0
        real(c_double), allocatable :: polygon(:, :)    ! (2, n)
        integer(c_int) :: rule = ISECT_EVEN_ODD
        real(c_double), allocatable :: vertices(:, :)   ! (3, n)
        real(c_double), allocatable :: points(:, :)     ! winding_number: (3, n)
        real(c_double) :: accuracy = 0
        real(c_double) :: tol_winding = 1.0e-12_c_double
        real(c_double), allocatable :: windings(:)      ! winding_number: expected w (n)
        ! A mesh shape (lines mesh, mverts, mfaces, midx): the counts, the
        ! vertices, each face's index count and the indices concatenated.
        logical :: is_mesh = .false.
        logical :: have_mverts = .false., have_mfaces = .false., have_midx = .false.
        integer(c_int64_t) :: mesh_nv = 0, mesh_nf = 0
        real(c_double), allocatable :: mesh_verts(:, :)       ! (3, nv)
        integer(c_int64_t), allocatable :: mesh_sizes(:)      ! (nf)
        integer(c_int32_t), allocatable :: mesh_idx(:)        ! (sum of the sizes)
        real(c_double) :: tol_t = 1.0e-12_c_double, tol_point = 1.0e-12_c_double
        real(c_double) :: tol_normal = 1.0e-12_c_double, tol_uv = 1.0e-12_c_double
        real(c_double) :: tol_volume = 1.0e-12_c_double, tol_area = 1.0e-12_c_double
        integer(c_int) :: status = ISECT_OK
        integer :: count = 0
        logical :: listed = .false.
        type(expected_hit), allocatable :: hits(:)
        integer :: hits_read = 0
        integer :: inside = 0
        integer(c_int32_t) :: winding = 0
        real(c_double) :: normal(3) = 0, plane(4) = 0
        logical :: has_report = .false.
        type(isect_mesh_report) :: report                ! mesh_check's expected report
    end type corpus_case

    ! What every path of a case shares (set by transform_setup).
    type(corpus_case), target :: cc
    type(isect_xform), target :: xform
    type(isect_shape) :: shape
    type(c_ptr) :: opts_ptr
    logical :: transformed
    ! The current case's mesh (from mesh_setup; destroyed by run_case).
    type(c_ptr) :: mesh_handle = c_null_ptr
    ! What the handle holds before isect_mesh_create: not NULL and not a
    ! mesh, so a call that leaves it alone is told apart from one that sets it.
    integer(c_int64_t), target :: mesh_unset = 0

    ! The report of the current case and the totals.
    character(len=:), allocatable :: current_file, case_label, case_name
    integer :: case_failures
    integer :: passed = 0, failed = 0, skipped = 0

    integer :: iarg
    character(len=4096) :: path

    if (command_argument_count() < 1) then
        write (*, '(a)') "usage: corpus_runner FILE.txt..."
        stop 2
    end if
    call check_reader()
    do iarg = 1, command_argument_count()
        call get_command_argument(iarg, path)
        call run_file(trim(path))
    end do
    write (*, '(i0, a)') skipped, " skipped"
    write (*, '(i0, a, i0, a)') passed, " passed, ", failed, " failed"
    if (failed > 0) stop 1

contains

    ! ============================================================ report

    subroutine begin_case(label, name)
        character(len=*), intent(in) :: label, name
        case_label = label
        case_name = name
        case_failures = 0
    end subroutine begin_case

    subroutine fail(message)
        character(len=*), intent(in) :: message
        case_failures = case_failures + 1
        if (case_failures <= MAX_LINES) &
            write (*, '(7a)') "FAIL ", current_file, ":", case_label, " ", case_name, &
                ": " // message
    end subroutine fail

    subroutine end_case()
        if (case_failures > MAX_LINES) &
            write (*, '(6a, i0, a)') "FAIL ", current_file, ":", case_label, " ", case_name, &
                ": ... and ", case_failures - MAX_LINES, " more not shown"
        if (case_failures == 0) then
            passed = passed + 1
        else
            failed = failed + 1
        end if
    end subroutine end_case

    ! A problem with a file as a whole: one failed entry.
    subroutine file_fail(file, message)
        character(len=*), intent(in) :: file, message
        write (*, '(4a)') "FAIL ", file, ": ", message
        failed = failed + 1
    end subroutine file_fail

    function itoa(value) result(text)
        integer(c_int64_t), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=24) :: buffer
        write (buffer, '(i0)') value
        text = trim(buffer)
    end function itoa

    function rtoa(value) result(text)
        real(c_double), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        if (ieee_is_nan(value)) then
            text = "nan"
        else if (.not. ieee_is_finite(value)) then
            text = merge("inf ", "-inf", value > 0)
            text = trim(text)
        else
            write (buffer, '(es24.16e3)') value
            text = trim(adjustl(buffer))
        end if
    end function rtoa

    function status_name(status) result(text)
        integer(c_int64_t), intent(in) :: status
        character(len=:), allocatable :: text
        select case (status)
        case (ISECT_OK)
            text = "ok"
        case (ISECT_E_ARG)
            text = "E_ARG"
        case (ISECT_E_NONFINITE)
            text = "E_NONFINITE"
        case (ISECT_E_DEGENERATE)
            text = "E_DEGENERATE"
        case (ISECT_E_NOMEM)
            text = "E_NOMEM"
        case default
            text = "status " // itoa(status)
        end select
    end function status_name

    function kind_name(kind) result(text)
        integer(c_int32_t), intent(in) :: kind
        character(len=:), allocatable :: text
        select case (kind)
        case (ISECT_MISS)
            text = "miss"
        case (ISECT_ENTER)
            text = "enter"
        case (ISECT_EXIT)
            text = "exit"
        case (ISECT_TOUCH)
            text = "touch"
        case (ISECT_INVALID)
            text = "invalid"
        case default
            text = "kind " // itoa(int(kind, c_int64_t))
        end select
    end function kind_name

    ! Each check sets ok to .false. when it fails (and never back to .true.),
    ! so a caller can run several and look at the sum.
    subroutine report_int(what, got, want, ok)
        character(len=*), intent(in) :: what
        integer(c_int64_t), intent(in) :: got, want
        logical, intent(inout), optional :: ok
        if (got == want) return
        call fail(what // " (expected " // itoa(want) // ", got " // itoa(got) // ")")
        if (present(ok)) ok = .false.
    end subroutine report_int

    subroutine report_status(what, got, want, ok)
        character(len=*), intent(in) :: what
        integer(c_int64_t), intent(in) :: got
        integer(c_int), intent(in) :: want
        logical, intent(inout), optional :: ok
        if (got == want) return
        call fail(what // " (expected " // status_name(int(want, c_int64_t)) // ", got " // &
                  status_name(got) // ")")
        if (present(ok)) ok = .false.
    end subroutine report_status

    ! The corpus's tolerance rule.
    logical function corpus_near(got, want, tol)
        real(c_double), intent(in) :: got, want, tol
        if (ieee_is_nan(want)) then
            corpus_near = ieee_is_nan(got)
        else if (.not. ieee_is_finite(want)) then
            corpus_near = .not. ieee_is_finite(got) .and. .not. ieee_is_nan(got) .and. &
                          (got > 0 .eqv. want > 0)
        else
            corpus_near = abs(got - want) <= tol * max(1.0_c_double, abs(want))
        end if
    end function corpus_near

    subroutine report_near(what, got, want, tol, ok)
        character(len=*), intent(in) :: what
        real(c_double), intent(in) :: got(:), want(:)
        real(c_double), intent(in) :: tol
        logical, intent(inout), optional :: ok
        integer :: i
        do i = 1, size(want)
            if (corpus_near(got(i), want(i), tol)) cycle
            if (size(want) == 1) then
                call fail(what // " (expected " // rtoa(want(i)) // ", got " // &
                          rtoa(got(i)) // ", tol " // rtoa(tol) // ")")
            else
                call fail(what // "[" // itoa(int(i - 1, c_int64_t)) // "] (expected " // &
                          rtoa(want(i)) // ", got " // rtoa(got(i)) // ", tol " // &
                          rtoa(tol) // ")")
            end if
            if (present(ok)) ok = .false.
            return
        end do
    end subroutine report_near

    ! ============================================================ guards

    ! n bytes of the guard pattern, to transfer into a value of any type
    pure function guard_bytes(n) result(bytes)
        integer, intent(in) :: n
        integer(c_int8_t) :: bytes(n)
        bytes = GUARD_BYTE
    end function guard_bytes

    function guard_hit() result(hit)
        type(isect_hit) :: hit
        hit = transfer(guard_bytes(80), hit)
    end function guard_hit

    logical function hits_untouched(hits)
        type(isect_hit), intent(in) :: hits(:)
        integer(c_int8_t) :: mold(1)
        hits_untouched = all(transfer(hits, mold) == GUARD_BYTE)
    end function hits_untouched

    subroutine report_hits_untouched(what, hits)
        character(len=*), intent(in) :: what
        type(isect_hit), intent(in) :: hits(:)
        if (.not. hits_untouched(hits)) call fail(what // " (expected untouched, got written)")
    end subroutine report_hits_untouched

    logical function bytes_untouched_i64(values)
        integer(c_int64_t), intent(in) :: values(:)
        integer(c_int8_t) :: mold(1)
        bytes_untouched_i64 = all(transfer(values, mold) == GUARD_BYTE)
    end function bytes_untouched_i64

    function guard_i64() result(value)
        integer(c_int64_t) :: value
        value = transfer(guard_bytes(8), value)
    end function guard_i64

    function guard_i32() result(value)
        integer(c_int32_t) :: value
        value = transfer(guard_bytes(4), value)
    end function guard_i32

    function guard_f64() result(value)
        real(c_double) :: value
        value = transfer(guard_bytes(8), value)
    end function guard_f64

    logical function bytes_untouched_f64(values)
        real(c_double), intent(in) :: values(:)
        integer(c_int8_t) :: mold(1)
        bytes_untouched_f64 = all(transfer(values, mold) == GUARD_BYTE)
    end function bytes_untouched_f64

    ! ============================================================ hits

    ! The returned count and each listed hit (prim and kind exactly, the
    ! rest within tolerance), over the first min(count, written) hits.
    subroutine report_expected_hits(what, hits, count, written)
        character(len=*), intent(in) :: what
        type(isect_hit), intent(in) :: hits(:)
        integer, intent(in) :: count, written
        integer :: i
        character(len=:), allocatable :: field
        call report_int(what // ": hit count", int(count, c_int64_t), int(cc%count, c_int64_t))
        if (.not. cc%listed) return
        do i = 1, min(count, written, cc%count)
            field = what // ": hit " // itoa(int(i - 1, c_int64_t))
            if (hits(i)%kind /= cc%hits(i)%kind) &
                call fail(field // " kind (expected " // kind_name(cc%hits(i)%kind) // &
                          ", got " // kind_name(hits(i)%kind) // ")")
            call report_int(field // " prim", int(hits(i)%prim, c_int64_t), &
                            int(cc%hits(i)%prim, c_int64_t))
            call report_near(field // " t", [hits(i)%t], [cc%hits(i)%t], cc%tol_t)
            call report_near(field // " point", hits(i)%point, cc%hits(i)%point, cc%tol_point)
            call report_near(field // " normal", hits(i)%normal, cc%hits(i)%normal, &
                             cc%tol_normal)
            if (cc%hits(i)%has_uv) &
                call report_near(field // " uv", hits(i)%uv, cc%hits(i)%uv, cc%tol_uv)
        end do
    end subroutine report_expected_hits

    logical function same_hit(a, b)
        type(isect_hit), intent(in) :: a, b
        integer(c_int64_t) :: mold(1)
        same_hit = all(transfer(a, mold) == transfer(b, mold))
    end function same_hit

    ! got and want must have the same bits; names the first field that
    ! differs.
    subroutine report_same_hit(what, got, want, ok)
        character(len=*), intent(in) :: what
        type(isect_hit), intent(in) :: got, want
        logical, intent(inout), optional :: ok
        character(len=9), parameter :: names(9) = [character(len=9) :: "t", "point[0]", &
            "point[1]", "point[2]", "normal[0]", "normal[1]", "normal[2]", "uv[0]", "uv[1]"]
        real(c_double) :: got_values(9), want_values(9)
        integer :: i
        if (same_hit(got, want)) return
        if (present(ok)) ok = .false.
        got_values = [got%t, got%point, got%normal, got%uv]
        want_values = [want%t, want%point, want%normal, want%uv]
        do i = 1, 9
            if (transfer(got_values(i), 0_c_int64_t) /= transfer(want_values(i), 0_c_int64_t)) &
                then
                call fail(what // ": " // trim(names(i)) // " differs in its bits (expected " &
                          // rtoa(want_values(i)) // ", got " // rtoa(got_values(i)) // ")")
                return
            end if
        end do
        if (got%prim /= want%prim) then
            call fail(what // ": prim differs (expected " // itoa(int(want%prim, c_int64_t)) &
                      // ", got " // itoa(int(got%prim, c_int64_t)) // ")")
        else
            call fail(what // ": kind differs (expected " // kind_name(want%kind) // ", got " &
                      // kind_name(got%kind) // ")")
        end if
    end subroutine report_same_hit

    ! A batch MISS (t = +inf) or INVALID (t = NaN) record: prim -1, the rest 0.
    subroutine report_batch_record(what, h, kind)
        character(len=*), intent(in) :: what
        type(isect_hit), intent(in) :: h
        integer(c_int32_t), intent(in) :: kind
        logical :: t_right
        if (h%kind /= kind) call fail(what // ": kind (expected " // kind_name(kind) // &
                                      ", got " // kind_name(h%kind) // ")")
        if (kind == ISECT_MISS) then
            t_right = .not. ieee_is_finite(h%t) .and. .not. ieee_is_nan(h%t) .and. h%t > 0
        else
            t_right = ieee_is_nan(h%t)
        end if
        if (.not. t_right) call fail(what // ": t (expected " // &
                                     merge("+inf", "nan ", kind == ISECT_MISS) // ", got " // &
                                     rtoa(h%t) // ")")
        if (h%prim /= -1) call fail(what // ": prim (expected -1, got " // &
                                    itoa(int(h%prim, c_int64_t)) // ")")
        if (any(transfer([h%point, h%normal, h%uv], 0_c_int64_t, 8) /= 0)) &
            call fail(what // ": point/normal/uv (expected all 0)")
    end subroutine report_batch_record

    ! ============================================================ paths

    ! Fill `bound` (module state: shape, opts_ptr, transformed) for the
    ! current case. When isect_xform_init fails its status is the case's
    ! result: it is checked and .false. returned (the case is finished).
    logical function transform_setup()
        integer(c_int) :: status
        shape = isect_shape(type=cc%shape_type, n=cc%shape_n, flags=cc%shape_flags)
        if (cc%has_data) shape%data = c_loc(cc%data)
        if (cc%is_mesh) shape%mesh = mesh_handle
        opts_ptr = c_null_ptr
        if (cc%has_opts) opts_ptr = c_loc(cc%opts)
        transformed = .false.
        transform_setup = .true.
        if (.not. cc%has_transform) return
        status = isect_xform_init(xform, cc%transform)
        if (status /= ISECT_OK) then
            call report_status("isect_xform_init", int(status, c_int64_t), cc%status)
            transform_setup = .false.
            return
        end if
        shape%xform = c_loc(xform)
        transformed = .true.
    end function transform_setup

    function scalar_name() result(name)
        character(len=:), allocatable :: name
        select case (cc%shape_type)
        case (ISECT_PLANE)
            name = "isect_ray_plane"
        case (ISECT_SPHERE)
            name = "isect_ray_sphere"
        case (ISECT_AABB)
            name = "isect_ray_aabb"
        case (ISECT_TRIANGLE)
            name = "isect_ray_triangle"
        case (ISECT_POLYGON)
            name = "isect_ray_polygon"
        case (ISECT_CONVEX)
            name = "isect_ray_convex"
        case (ISECT_CYLINDER)
            name = "isect_ray_cylinder"
        case (ISECT_CYLINDER_INF)
            name = "isect_ray_cylinder_inf"
        case (ISECT_ELLIPSOID)
            name = "isect_ray_ellipsoid"
        case (ISECT_QUADRIC)
            name = "isect_ray_quadric"
        case (ISECT_MESH)
            name = "isect_intersect(xform NULL)"
        case default
            name = "(no scalar function)"
        end select
        if (transformed) name = "isect_xform_ray+" // name // "+isect_xform_hits"
    end function scalar_name

    ! Whether the case has path 2 (see run_path): a type with a scalar
    ! function, or a transformed named mesh (untransformed, a mesh's path 2
    ! would repeat the isect_intersect call exactly). Raw types have none.
    logical function has_object_space_path()
        has_object_space_path = cc%named .and. (.not. cc%is_mesh .or. transformed)
    end function has_object_space_path

    ! The named type's scalar function on the case's data, through the
    ! module's C-form interfaces; for a mesh, isect_intersect on the shape
    ! without its xform.
    function scalar_call(ray, hits, cap) result(nhits)
        type(isect_ray), intent(in) :: ray
        type(isect_hit), intent(inout) :: hits(:)
        integer(c_int), intent(in) :: cap
        integer(c_int) :: nhits
        type(isect_shape) :: plain
        associate (d => cc%data, n => cc%shape_n)
            select case (cc%shape_type)
            case (ISECT_PLANE)
                nhits = isect_ray_plane(ray, d(1:3), d(4), opts_ptr, hits, cap)
            case (ISECT_SPHERE)
                nhits = isect_ray_sphere(ray, d(1:3), d(4), opts_ptr, hits, cap)
            case (ISECT_AABB)
                nhits = isect_ray_aabb(ray, d(1:3), d(4:6), opts_ptr, hits, cap)
            case (ISECT_TRIANGLE)
                nhits = isect_ray_triangle(ray, d(1:3), d(4:6), d(7:9), opts_ptr, hits, cap)
            case (ISECT_POLYGON)
                nhits = isect_ray_polygon(ray, reshape(d, [3, n]), n, cc%shape_flags, &
                                          opts_ptr, hits, cap)
            case (ISECT_CONVEX)
                nhits = isect_ray_convex(ray, reshape(d, [4, n]), n, opts_ptr, hits, cap)
            case (ISECT_CYLINDER)
                nhits = isect_ray_cylinder(ray, d(1:3), d(4:6), d(7), cc%shape_flags, &
                                           opts_ptr, hits, cap)
            case (ISECT_CYLINDER_INF)
                nhits = isect_ray_cylinder_inf(ray, d(1:3), d(4:6), d(7), opts_ptr, hits, cap)
            case (ISECT_ELLIPSOID)
                nhits = isect_ray_ellipsoid(ray, d(1:3), d(4:6), opts_ptr, hits, cap)
            case (ISECT_QUADRIC)
                nhits = isect_ray_quadric(ray, d(1:10), opts_ptr, hits, cap)
            case (ISECT_MESH)
                plain = shape
                plain%xform = c_null_ptr
                nhits = isect_intersect(plain, ray, opts_ptr, hits, cap)
            case default
                nhits = ISECT_E_ARG   ! only named types get here; each has a case
            end select
        end associate
    end function scalar_call

    ! One way of computing the case's hits (path 1: isect_intersect; path 2:
    ! the scalar function, or for a mesh isect_intersect without the xform,
    ! composed with the transform by hand), with the contract of
    ! isect_intersect.
    function run_path(path_id, hits, cap) result(nhits)
        integer, intent(in) :: path_id
        type(isect_hit), intent(inout) :: hits(:)
        integer(c_int), intent(in) :: cap
        integer(c_int) :: nhits
        type(isect_ray) :: object_ray
        integer(c_int) :: status
        if (path_id == 1) then
            nhits = isect_intersect(shape, cc%ray, opts_ptr, hits, cap)
            return
        end if
        object_ray = cc%ray
        if (transformed) then
            status = isect_xform_ray(xform, cc%ray, object_ray)
            if (status < 0) then
                nhits = status
                return
            end if
        end if
        nhits = scalar_call(object_ray, hits, cap)
        if (nhits > 0 .and. cap > 0 .and. transformed) then
            status = isect_xform_hits(xform, hits, min(nhits, cap))
            if (status < 0) nhits = status
        end if
    end function run_path

    ! A path on a case expected to succeed: its hits (in out) and count, or
    ! -1 when it failed or overflowed the buffer.
    function check_path_ok(name, path_id, out) result(count)
        character(len=*), intent(in) :: name
        integer, intent(in) :: path_id
        type(isect_hit), intent(out) :: out(HIT_CAP)
        integer :: count
        type(isect_hit) :: buf(HIT_CAP), pair(2), none(0)
        integer :: written
        integer(c_int) :: again

        buf = guard_hit()
        count = run_path(path_id, buf, int(HIT_CAP, c_int))
        out = buf
        if (count < 0) then
            call report_status(name, int(count, c_int64_t), ISECT_OK)
            count = -1
            return
        end if
        call report_expected_hits(name, buf, count, HIT_CAP)
        written = min(count, HIT_CAP)
        call report_hits_untouched(name // ": records past its " // &
                                   itoa(int(written, c_int64_t)) // " hits", buf(written + 1:))
        if (count > HIT_CAP) then
            call fail(name // ": more hits than the runner's buffer")
            count = -1
            return
        end if

        again = run_path(path_id, none, 0_c_int)
        call report_int(name // " with cap 0: return", int(again, c_int64_t), &
                        int(count, c_int64_t))
        pair = guard_hit()
        again = run_path(path_id, pair, 1_c_int)
        call report_int(name // " with cap 1: return", int(again, c_int64_t), &
                        int(count, c_int64_t))
        if (count >= 1) then
            call report_same_hit(name // " with cap 1: hit 0 vs the large-buffer call", &
                                 pair(1), buf(1))
        else
            call report_hits_untouched(name // " with cap 1 and no hits: record 0", pair(1:1))
        end if
        call report_hits_untouched(name // " with cap 1: record 1 (past cap)", pair(2:2))
    end function check_path_ok

    ! A path on a case expected to fail: the status, and nothing written.
    subroutine check_path_error(name, path_id)
        character(len=*), intent(in) :: name
        integer, intent(in) :: path_id
        type(isect_hit) :: buf(HIT_CAP), none(0)
        integer(c_int) :: status
        buf = guard_hit()
        status = run_path(path_id, buf, int(HIT_CAP, c_int))
        call report_status(name, int(status, c_int64_t), cc%status)
        if (status < 0) call report_hits_untouched(name // ": hit buffer after an error", buf)
        status = run_path(path_id, none, 0_c_int)
        call report_status(name // " with cap 0", int(status, c_int64_t), cc%status)
    end subroutine check_path_error

    subroutine check_intersect_case()
        type(isect_hit) :: reference(HIT_CAP), scalar_hits(HIT_CAP)
        integer :: ref_count, scalar_count, i
        logical :: ok

        if (.not. transform_setup()) return
        if (cc%status /= ISECT_OK) then
            call check_path_error("isect_intersect", 1)
            if (has_object_space_path()) call check_path_error(scalar_name(), 2)
            call check_batch_error()
            return
        end if
        ref_count = check_path_ok("isect_intersect", 1, reference)
        if (has_object_space_path()) then
            scalar_count = check_path_ok(scalar_name(), 2, scalar_hits)
            ! Untransformed, isect_intersect is documented to give the
            ! scalar function's hits: every bit agrees.
            if (.not. transformed .and. ref_count >= 0 .and. scalar_count == ref_count) then
                ok = .true.
                do i = 1, ref_count
                    call report_same_hit("isect_intersect hit " // itoa(int(i - 1, c_int64_t)) &
                                         // " vs " // scalar_name() // " hit " // &
                                         itoa(int(i - 1, c_int64_t)), reference(i), &
                                         scalar_hits(i), ok)
                    if (.not. ok) exit
                end do
            end if
        end if
        ! The batch results are defined as isect_intersect's.
        if (ref_count < 0) return
        call check_batch_ok(reference, ref_count)
        call check_all_batch_ok(reference, ref_count)
    end subroutine check_intersect_case

    ! ============================================================ batches

    function make_batch_rays() result(rays)
        type(isect_ray) :: rays(BATCH_RAYS)
        rays = cc%ray
        rays(BAD_RAY)%org(1) = ieee_value(1.0_c_double, ieee_quiet_nan)
    end function make_batch_rays

    ! The status the header gives a bad ray (ISECT_OK for a good one).
    integer(c_int) function ray_status(ray)
        type(isect_ray), intent(in) :: ray
        ray_status = ISECT_OK
        if (.not. all(ieee_is_finite([ray%org, ray%dir])) .or. ieee_is_nan(ray%tmin) .or. &
            ieee_is_nan(ray%tmax)) then
            ray_status = ISECT_E_NONFINITE
        else if (all(abs(ray%dir) <= 0.0_c_double)) then
            ray_status = ISECT_E_DEGENERATE
        end if
    end function ray_status

    subroutine check_batch_ok(reference, ref_count)
        type(isect_hit), intent(in) :: reference(:)
        integer, intent(in) :: ref_count
        type(isect_ray) :: rays(BATCH_RAYS)
        type(isect_hit) :: closest(BATCH_RAYS + 1)
        integer(c_int64_t) :: got
        integer :: i
        character(len=:), allocatable :: what

        rays = make_batch_rays()
        closest = guard_hit()
        got = isect_intersect_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, closest)
        call report_int("isect_intersect_batch: return (rays hit)", got, &
                        int(merge(BATCH_RAYS - 1, 0, ref_count > 0), c_int64_t))
        if (got < 0) return
        do i = 1, BATCH_RAYS
            what = "isect_intersect_batch: ray " // itoa(int(i - 1, c_int64_t))
            if (i == BAD_RAY) then
                call report_batch_record(what // " (NaN origin)", closest(i), ISECT_INVALID)
            else if (ref_count > 0) then
                call report_same_hit(what // " closest vs isect_intersect's first hit", &
                                     closest(i), reference(1))
            else
                call report_batch_record(what // " (no hit)", closest(i), ISECT_MISS)
            end if
        end do
        call report_hits_untouched("isect_intersect_batch: record past n", &
                                   closest(BATCH_RAYS + 1:))
    end subroutine check_batch_ok

    subroutine check_all_batch_ok(reference, ref_count)
        type(isect_hit), intent(in) :: reference(:)
        integer, intent(in) :: ref_count
        character(len=*), parameter :: name = "isect_intersect_all_batch"
        type(isect_ray) :: rays(BATCH_RAYS)
        integer(c_int64_t) :: offsets(BATCH_RAYS + 2), got, total, written, j
        type(isect_hit) :: hits(ALL_CAP + 1)
        integer :: i
        logical :: ok

        rays = make_batch_rays()
        total = int(BATCH_RAYS - 1, c_int64_t) * ref_count + 1
        offsets = guard_i64()
        hits = guard_hit()
        got = isect_intersect_all_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, &
                                        offsets, hits, int(ALL_CAP, c_int64_t))
        ok = .true.
        call report_int(name // ": return (total hits)", got, total, ok)
        if (.not. ok .or. got < 0) return
        written = min(got, int(ALL_CAP, c_int64_t))

        ! Offsets: 0, then growing by each ray's count, within what was written.
        call report_int(name // ": offsets[0]", offsets(1), 0_c_int64_t, ok)
        do i = 1, BATCH_RAYS
            call report_int(name // ": offsets[" // itoa(int(i, c_int64_t)) // "] - offsets[" &
                            // itoa(int(i - 1, c_int64_t)) // "]", offsets(i + 1) - offsets(i), &
                            int(merge(1, ref_count, i == BAD_RAY), c_int64_t), ok)
        end do
        if (ok .and. offsets(BATCH_RAYS + 1) > written) then
            call fail(name // ": offsets[n] is past the records written")
            ok = .false.
        end if
        ! Each ray's hits equal isect_intersect's, bit for bit; the bad ray
        ! has one INVALID record.
        if (ok) then
            rays_loop: do i = 1, BATCH_RAYS
                do j = offsets(i) + 1, offsets(i + 1)
                    if (i == BAD_RAY) then
                        call report_batch_record(name // ": ray " // itoa(int(i - 1, c_int64_t)) &
                                                 // " record", hits(j), ISECT_INVALID)
                    else
                        call report_same_hit(name // ": ray " // itoa(int(i - 1, c_int64_t)) // &
                                             " hit " // itoa(j - offsets(i) - 1), hits(j), &
                                             reference(j - offsets(i)), ok)
                        if (.not. ok) exit rays_loop
                    end if
                end do
            end do rays_loop
        end if
        if (.not. bytes_untouched_i64(offsets(BATCH_RAYS + 2:))) &
            call fail(name // ": offsets[n+1] (past the end) (expected untouched, got written)")
        call report_hits_untouched(name // ": records past the " // itoa(written) // &
                                   " written", hits(written + 1:))

        ! total >= 1 always (the bad ray's record), so total - 1 is a valid cap.
        call check_all_batch_short(rays, total - 1, total, offsets, hits)
        if (total - 1 /= 0) call check_all_batch_short(rays, 0_c_int64_t, total, offsets, hits)
    end subroutine check_all_batch_ok

    ! A retry with a too-small cap: the same total and offsets, only the
    ! first cap hits written.
    subroutine check_all_batch_short(rays, cap, total, full_offsets, full_hits)
        type(isect_ray), intent(in) :: rays(:)
        integer(c_int64_t), intent(in) :: cap, total
        integer(c_int64_t), intent(in) :: full_offsets(:)
        type(isect_hit), intent(in) :: full_hits(:)
        integer(c_int64_t) :: offsets(BATCH_RAYS + 2), got, i
        type(isect_hit) :: hits(ALL_CAP + 1)
        character(len=:), allocatable :: name
        logical :: ok

        name = "isect_intersect_all_batch with cap " // itoa(cap)
        offsets = guard_i64()
        hits = guard_hit()
        got = isect_intersect_all_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, &
                                        offsets, hits, cap)
        ok = .true.
        call report_int(name // ": return (the full total)", got, total, ok)
        if (.not. ok .or. got < 0) return
        do i = 1, BATCH_RAYS + 1
            call report_int(name // ": offsets[" // itoa(i - 1) // "] vs the full call", &
                            offsets(i), full_offsets(i))
        end do
        if (.not. bytes_untouched_i64(offsets(BATCH_RAYS + 2:))) &
            call fail(name // ": offsets[n+1] (past the end) (expected untouched, got written)")
        do i = 1, cap
            call report_same_hit(name // ": hit record " // itoa(i - 1) // " vs the full call", &
                                 hits(i), full_hits(i), ok)
            if (.not. ok) exit
        end do
        call report_hits_untouched(name // ": records from cap on", hits(cap + 1:))
    end subroutine check_all_batch_short

    ! An expected error: when it is the ray's own (the case's ray is bad in
    ! that way), the batches mark every ray INVALID and succeed; otherwise
    ! (bad shape or opts) they fail with the status and write nothing.
    subroutine check_batch_error()
        type(isect_ray) :: rays(BATCH_RAYS)
        type(isect_hit) :: closest(BATCH_RAYS + 1), hits(ALL_CAP + 1)
        integer(c_int64_t) :: offsets(BATCH_RAYS + 2), got
        integer :: i
        logical :: ok

        rays = make_batch_rays()
        closest = guard_hit()
        offsets = guard_i64()
        hits = guard_hit()
        if (ray_status(cc%ray) /= ISECT_OK .and. ray_status(cc%ray) == cc%status) then
            got = isect_intersect_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, &
                                        closest)
            ok = .true.
            call report_int("isect_intersect_batch with only bad rays: return", got, &
                            0_c_int64_t, ok)
            if (ok) then
                do i = 1, BATCH_RAYS
                    call report_batch_record("isect_intersect_batch: bad ray " // &
                                             itoa(int(i - 1, c_int64_t)), closest(i), &
                                             ISECT_INVALID)
                end do
            end if
            got = isect_intersect_all_batch(shape, rays, int(BATCH_RAYS, c_int64_t), &
                                            opts_ptr, offsets, hits, &
                                            int(BATCH_RAYS + 1, c_int64_t))
            ok = .true.
            call report_int("isect_intersect_all_batch with only bad rays: return", got, &
                            int(BATCH_RAYS, c_int64_t), ok)
            if (.not. ok) return
            do i = 1, BATCH_RAYS + 1
                call report_int("isect_intersect_all_batch with only bad rays: offsets[" // &
                                itoa(int(i - 1, c_int64_t)) // "]", offsets(i), &
                                int(i - 1, c_int64_t))
            end do
            do i = 1, BATCH_RAYS
                call report_batch_record("isect_intersect_all_batch: bad ray " // &
                                         itoa(int(i - 1, c_int64_t)) // " record", hits(i), &
                                         ISECT_INVALID)
            end do
            return
        end if
        got = isect_intersect_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, closest)
        call report_status("isect_intersect_batch", got, cc%status)
        if (got < 0) call report_hits_untouched("isect_intersect_batch: output after an error", &
                                                closest)
        got = isect_intersect_all_batch(shape, rays, int(BATCH_RAYS, c_int64_t), opts_ptr, &
                                        offsets, hits, int(ALL_CAP, c_int64_t))
        call report_status("isect_intersect_all_batch", got, cc%status)
        if (got < 0) then
            if (.not. bytes_untouched_i64(offsets)) &
                call fail("isect_intersect_all_batch: offsets after an error " // &
                          "(expected untouched, got written)")
            call report_hits_untouched("isect_intersect_all_batch: hits after an error", hits)
        end if
    end subroutine check_batch_error

    ! ============================================================ other ops

    ! A scalar answer: the expected value, or the expected error status.
    subroutine check_answer(name, got, answer)
        character(len=*), intent(in) :: name
        integer(c_int), intent(in) :: got
        integer, intent(in) :: answer
        if (cc%status == ISECT_OK .and. got >= 0) then
            call report_int(name, int(got, c_int64_t), int(answer, c_int64_t))
        else
            call report_status(name, int(got, c_int64_t), cc%status)
        end if
    end subroutine check_answer

    ! POINT_BATCH copies of the case's point (dim numbers each), one NaN.
    function batch_points(dim) result(points)
        integer, intent(in) :: dim
        real(c_double) :: points(dim, POINT_BATCH)
        integer :: i
        do i = 1, POINT_BATCH
            points(:, i) = cc%point(1:dim)
        end do
        points(1, BAD_POINT) = ieee_value(1.0_c_double, ieee_quiet_nan)
    end function batch_points

    ! A point batch's result: good points get `answer`, the NaN point
    ! `invalid`, and the call returns ok_return. An expected E_NONFINITE
    ! caused by the case's own point marks every point invalid instead; any
    ! other expected error fails the call and writes nothing.
    subroutine check_point_batch(name, got, values, untouched_past_end, untouched_all, &
                                 answer_in, invalid, ok_return_in)
        character(len=*), intent(in) :: name
        integer(c_int64_t), intent(in) :: got
        integer(c_int64_t), intent(in) :: values(POINT_BATCH)
        logical, intent(in) :: untouched_past_end, untouched_all
        integer(c_int64_t), intent(in) :: answer_in, invalid, ok_return_in
        integer(c_int64_t) :: answer, ok_return
        integer :: i
        logical :: ok

        answer = answer_in
        ok_return = ok_return_in
        if (cc%status /= ISECT_OK) then
            if (all(ieee_is_finite(cc%point(1:cc%point_dim))) .or. &
                cc%status /= ISECT_E_NONFINITE) then
                call report_status(name, got, cc%status)
                if (got < 0 .and. .not. untouched_all) &
                    call fail(name // ": output after an error (expected untouched, got written)")
                return
            end if
            answer = invalid
            ok_return = 0
        end if
        ok = .true.
        call report_int(name // ": return", got, ok_return, ok)
        if (.not. ok .or. got < 0) return
        do i = 1, POINT_BATCH
            if (i == BAD_POINT) then
                call report_int(name // ": point " // itoa(int(i - 1, c_int64_t)) // " (NaN)", &
                                values(i), invalid)
            else
                call report_int(name // ": point " // itoa(int(i - 1, c_int64_t)), values(i), &
                                answer)
            end if
        end do
        if (.not. untouched_past_end) &
            call fail(name // ": element past n (expected untouched, got written)")
    end subroutine check_point_batch

    subroutine check_contains_case()
        real(c_double) :: points(3, POINT_BATCH)
        integer(c_int8_t) :: inside(POINT_BATCH + 1)
        integer(c_int64_t) :: got
        integer(c_int) :: answer

        if (.not. transform_setup()) return
        answer = isect_contains(shape, cc%point)
        call check_answer("isect_contains", answer, cc%inside)
        points = batch_points(3)
        inside = GUARD_BYTE
        got = isect_contains_batch(shape, points, int(POINT_BATCH, c_int64_t), inside)
        call check_point_batch("isect_contains_batch", got, &
                               int(inside(1:POINT_BATCH), c_int64_t), &
                               inside(POINT_BATCH + 1) == GUARD_BYTE, all(inside == GUARD_BYTE), &
                               int(cc%inside, c_int64_t), int(ISECT_INVALID, c_int64_t), &
                               int((POINT_BATCH - 1) * cc%inside, c_int64_t))
    end subroutine check_contains_case

    subroutine check_point_in_polygon2_case()
        real(c_double) :: points(2, POINT_BATCH)
        integer(c_int8_t) :: inside(POINT_BATCH + 1)
        integer(c_int64_t) :: got
        integer(c_int) :: answer, n

        n = int(size(cc%polygon, 2), c_int)
        answer = isect_point_in_polygon2(cc%polygon, n, cc%point(1:2), cc%rule)
        call check_answer("isect_point_in_polygon2", answer, cc%inside)
        points = batch_points(2)
        inside = GUARD_BYTE
        got = isect_point_in_polygon2_batch(cc%polygon, n, points, int(POINT_BATCH, c_int64_t), &
                                            cc%rule, inside)
        call check_point_batch("isect_point_in_polygon2_batch", got, &
                               int(inside(1:POINT_BATCH), c_int64_t), &
                               inside(POINT_BATCH + 1) == GUARD_BYTE, all(inside == GUARD_BYTE), &
                               int(cc%inside, c_int64_t), int(ISECT_INVALID, c_int64_t), &
                               int((POINT_BATCH - 1) * cc%inside, c_int64_t))
    end subroutine check_point_in_polygon2_case

    subroutine check_winding_number2_case()
        real(c_double) :: points(2, POINT_BATCH)
        integer(c_int32_t) :: winding, windings(POINT_BATCH + 1)
        integer(c_int64_t) :: got
        integer(c_int) :: status, n
        logical :: ok

        n = int(size(cc%polygon, 2), c_int)
        winding = 0
        status = isect_winding_number2(cc%polygon, n, cc%point(1:2), winding)
        ok = .true.
        call report_status("isect_winding_number2", int(status, c_int64_t), cc%status, ok)
        if (ok .and. status == ISECT_OK) &
            call report_int("isect_winding_number2: winding", int(winding, c_int64_t), &
                            int(cc%winding, c_int64_t))
        points = batch_points(2)
        windings = guard_i32()
        got = isect_winding_number2_batch(cc%polygon, n, points, int(POINT_BATCH, c_int64_t), &
                                          windings)
        call check_point_batch("isect_winding_number2_batch", got, &
                               int(windings(1:POINT_BATCH), c_int64_t), &
                               windings(POINT_BATCH + 1) == guard_i32(), &
                               all(windings == guard_i32()), int(cc%winding, c_int64_t), &
                               WINDING_INVALID, &
                               int(merge(POINT_BATCH - 1, 0, cc%winding /= 0), c_int64_t))
    end subroutine check_winding_number2_case

    subroutine check_polygon_normal_case()
        real(c_double) :: normal(3)
        integer(c_int) :: status
        logical :: ok
        status = isect_polygon_normal(cc%vertices, int(size(cc%vertices, 2), c_int), normal)
        ok = .true.
        call report_status("isect_polygon_normal", int(status, c_int64_t), cc%status, ok)
        if (ok .and. status == ISECT_OK) &
            call report_near("isect_polygon_normal: normal", normal, cc%normal, cc%tol_normal)
    end subroutine check_polygon_normal_case

    ! The plane (a, b, c, d) is judged with the "normal" tolerance, as the C
    ! runner does (the schema has no key of its own for it).
    subroutine check_plane_from_points_case()
        real(c_double) :: plane(4)
        integer(c_int) :: status
        logical :: ok
        status = isect_plane_from_points(cc%vertices, int(size(cc%vertices, 2), c_int), plane)
        ok = .true.
        call report_status("isect_plane_from_points", int(status, c_int64_t), cc%status, ok)
        if (ok .and. status == ISECT_OK) &
            call report_near("isect_plane_from_points: plane", plane, cc%plane, cc%tol_normal)
    end subroutine check_plane_from_points_case

    ! One batch call on p(3, n); want(i) is point i's w, NaN where the point
    ! is not finite (the library writes NaN there). One guard element after
    ! the n values must stay untouched.
    subroutine check_winding_batch(name, p, want)
        character(len=*), intent(in) :: name
        real(c_double), intent(in) :: p(:, :), want(:)
        real(c_double), allocatable :: w(:)
        integer(c_int) :: status
        integer :: n
        logical :: ok
        n = size(p, 2)
        allocate (w(n + 1))
        w = guard_f64()
        status = isect_winding_number_batch(shape, p, int(n, c_int64_t), cc%accuracy, w)
        ok = .true.
        call report_status(name // ": status", int(status, c_int64_t), ISECT_OK, ok)
        if (.not. ok) return
        call report_near(name // ": w", w(1:n), want, cc%tol_winding)
        if (.not. bytes_untouched_f64(w(n + 1:n + 1))) &
            call fail(name // ": element past n (expected untouched, got written)")
    end subroutine check_winding_batch

    subroutine check_winding_number_case()
        real(c_double), allocatable :: want(:), w(:)
        integer(c_int) :: status
        integer :: n, i
        logical :: bad_points

        if (.not. transform_setup()) return
        n = size(cc%points, 2)
        allocate (want(n), w(n + 1))
        bad_points = .false.
        do i = 1, n
            bad_points = bad_points .or. .not. all(ieee_is_finite(cc%points(:, i)))
        end do
        if (cc%status == ISECT_OK) then
            want = cc%windings
            call check_winding_batch("isect_winding_number_batch (all " // &
                                     itoa(int(n, c_int64_t)) // " points)", cc%points, want)
            do i = 1, n
                call check_winding_batch("isect_winding_number_batch (point " // &
                                         itoa(int(i - 1, c_int64_t)) // " alone)", &
                                         cc%points(:, i:i), want(i:i))
            end do
        else if (cc%status == ISECT_E_NONFINITE .and. bad_points) then
            ! Not an error of the call: NaN at those points, a finite w
            ! elsewhere (the values are not part of an error case).
            status = isect_winding_number_batch(shape, cc%points, int(n, c_int64_t), &
                                                cc%accuracy, w)
            call report_status("isect_winding_number_batch (non-finite points: ok, NaN there)", &
                               int(status, c_int64_t), ISECT_OK)
            if (status == ISECT_OK) then
                do i = 1, n
                    if (all(ieee_is_finite(cc%points(:, i))) .neqv. ieee_is_finite(w(i))) &
                        call fail("isect_winding_number_batch: w[" // &
                                  itoa(int(i - 1, c_int64_t)) // "] (expected " // &
                                  trim(merge("a finite number", "NaN            ", &
                                             all(ieee_is_finite(cc%points(:, i))))) // &
                                  ", got " // rtoa(w(i)) // ")")
                end do
            end if
        else
            w = guard_f64()
            status = isect_winding_number_batch(shape, cc%points, int(n, c_int64_t), &
                                                cc%accuracy, w)
            call report_status("isect_winding_number_batch", int(status, c_int64_t), cc%status)
            if (status < 0 .and. .not. bytes_untouched_f64(w)) &
                call fail("isect_winding_number_batch: output after an error (expected " // &
                          "untouched, got written)")
        end if
    end subroutine check_winding_number_case

    ! ============================================================ meshes

    ! Build the case's mesh into mesh_handle as tests/cases/README.md
    ! ("Meshes") says: offsets NULL when every face has exactly 3 indices
    ! (an empty face list included), else CSR offsets from the face sizes.
    ! A creation error is the case's result whatever the op: it is checked
    ! (and that the handle is NULL) and .false. returned (the case is done).
    logical function mesh_setup()
        integer(c_int64_t), allocatable, target :: offsets(:)
        type(c_ptr) :: offsets_ptr
        integer(c_int) :: status
        integer(c_int64_t) :: f, bytes

        offsets_ptr = c_null_ptr
        if (any(cc%mesh_sizes /= 3)) then
            allocate (offsets(cc%mesh_nf + 1))
            offsets(1) = 0
            do f = 1, cc%mesh_nf
                offsets(f + 1) = offsets(f) + cc%mesh_sizes(f)
            end do
            offsets_ptr = c_loc(offsets)
        end if
        ! The C form with explicit counts (the Fortran form would also fail
        ! some bad inputs itself, before the library sees them).
        mesh_handle = c_loc(mesh_unset)
        status = isect_mesh_create(cc%mesh_verts, cc%mesh_nv, cc%mesh_idx, offsets_ptr, &
                                   cc%mesh_nf, mesh_handle)
        if (status /= ISECT_OK) then
            call report_status("isect_mesh_create", int(status, c_int64_t), cc%status)
            if (c_associated(mesh_handle)) &
                call fail("isect_mesh_create: handle after an error (expected NULL, got " // &
                          trim(merge("it left unset", "a pointer    ", &
                                     c_associated(mesh_handle, c_loc(mesh_unset)))) // ")")
            ! Never destroyed: after an error the handle is no mesh of ours.
            mesh_handle = c_null_ptr
            mesh_setup = .false.
            return
        end if
        if (.not. c_associated(mesh_handle) .or. c_associated(mesh_handle, c_loc(mesh_unset))) &
            then
            call fail("isect_mesh_create: ok, but the handle (expected a mesh, got " // &
                      trim(merge("NULL         ", "it left unset", &
                                 .not. c_associated(mesh_handle))) // ")")
            mesh_handle = c_null_ptr
            mesh_setup = .false.
            return
        end if
        mesh_setup = .true.
        bytes = isect_mesh_bytes(mesh_handle)
        if (bytes <= 0) call fail("isect_mesh_bytes (expected > 0, got " // itoa(bytes) // ")")
    end function mesh_setup

    ! isect_mesh_check on the case's mesh as given (a mesh_check case has
    ! no transform): the integer fields exactly, volume and area within
    ! tol.volume and tol.area.
    subroutine check_mesh_check_case()
        type(isect_mesh_report) :: got
        integer(c_int) :: status
        logical :: ok
        character(len=*), parameter :: name = "isect_mesh_check"

        status = isect_mesh_check(mesh_handle, got)
        ok = .true.
        call report_status(name, int(status, c_int64_t), cc%status, ok)
        if (.not. ok .or. status /= ISECT_OK) return
        associate (want => cc%report)
            call report_int(name // ": vertices", got%vertices, want%vertices)
            call report_int(name // ": edges", got%edges, want%edges)
            call report_int(name // ": faces", got%faces, want%faces)
            call report_int(name // ": boundary_edges", got%boundary_edges, &
                            want%boundary_edges)
            call report_int(name // ": nonmanifold_edges", got%nonmanifold_edges, &
                            want%nonmanifold_edges)
            call report_int(name // ": misoriented_edges", got%misoriented_edges, &
                            want%misoriented_edges)
            call report_int(name // ": degenerate_faces", got%degenerate_faces, &
                            want%degenerate_faces)
            call report_int(name // ": components", got%components, want%components)
            call report_int(name // ": euler_characteristic", got%euler_characteristic, &
                            want%euler_characteristic)
            call report_int(name // ": genus", got%genus, want%genus)
            call report_int(name // ": closed", int(got%closed, c_int64_t), &
                            int(want%closed, c_int64_t))
            call report_int(name // ": oriented", int(got%oriented, c_int64_t), &
                            int(want%oriented, c_int64_t))
            call report_near(name // ": volume", [got%volume], [want%volume], cc%tol_volume)
            call report_near(name // ": area", [got%area], [want%area], cc%tol_area)
        end associate
    end subroutine check_mesh_check_case

    ! op spawn (see the top of the file). The primary ray uses the default
    ! options, as does the spawned one.
    subroutine check_spawn_case()
        type(isect_ray) :: primary(1), spawned(1), out
        type(isect_hit) :: first(1), closest(1), hits(HIT_CAP)
        integer(c_int64_t) :: nhit
        integer(c_int) :: status, count
        real(c_double) :: largest, unit, off
        logical :: ok
        integer :: k
        character(len=*), parameter :: secondary = "isect_intersect of the spawned ray"

        if (.not. transform_setup()) return
        primary(1) = cc%ray
        first(1) = guard_hit()
        nhit = isect_intersect_batch(shape, primary, 1_c_int64_t, c_null_ptr, first)
        if (nhit < 0) then
            call fail("isect_intersect_batch of the primary ray: status " // itoa(nhit) // &
                      " (a spawn case's primary ray must be valid)")
            return
        end if

        out = isect_ray(0.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double)
        status = isect_spawn_ray(shape, first(1), cc%sdir, out)
        ok = .true.
        call report_status("isect_spawn_ray", int(status, c_int64_t), cc%status, ok)
        if (.not. ok .or. status /= ISECT_OK) return

        if (any(transfer(out%dir, 0_c_int64_t, 3) /= transfer(cc%sdir, 0_c_int64_t, 3))) &
            call fail("isect_spawn_ray: out%dir (expected " // rtoa(cc%sdir(1)) // " " // &
                      rtoa(cc%sdir(2)) // " " // rtoa(cc%sdir(3)) // ", got " // &
                      rtoa(out%dir(1)) // " " // rtoa(out%dir(2)) // " " // rtoa(out%dir(3)) // ")")
        if (.not. (out%tmin >= 0.0_c_double .and. out%tmin <= 0.0_c_double)) &
            call fail("isect_spawn_ray: out%tmin (expected 0, got " // rtoa(out%tmin) // ")")
        if (ieee_is_finite(out%tmax) .or. .not. out%tmax > 0.0_c_double) &
            call fail("isect_spawn_ray: out%tmax (expected +inf, got " // rtoa(out%tmax) // ")")
        ! The spacing of the doubles at the hit point's largest coordinate
        ! (C's nextafter(m, inf) - m; the smallest subnormal at 0).
        largest = maxval(abs(first(1)%point))
        unit = ieee_next_after(largest, ieee_value(largest, ieee_positive_inf)) - largest
        do k = 1, 3
            off = abs(out%org(k) - first(1)%point(k))
            if (.not. off <= SPAWN_MAX_ULPS * unit) &
                call fail("isect_spawn_ray: out%org(" // itoa(int(k, c_int64_t)) // ") " // &
                          rtoa(out%org(k)) // " is more than 8 ulps from the hit point " // &
                          rtoa(first(1)%point(k)))
        end do

        hits = guard_hit()
        count = isect_intersect(shape, out, c_null_ptr, hits, int(HIT_CAP, c_int))
        if (count < 0) then
            call report_status(secondary, int(count, c_int64_t), ISECT_OK)
            return
        end if
        call report_expected_hits(secondary, hits, int(count), min(int(count), HIT_CAP))
        spawned(1) = out
        closest(1) = guard_hit()
        nhit = isect_intersect_batch(shape, spawned, 1_c_int64_t, c_null_ptr, closest)
        if (nhit < 0) then
            call fail("isect_intersect_batch of the spawned ray: status " // itoa(nhit))
        else if (count == 0) then
            call report_batch_record("isect_intersect_batch of the spawned ray", closest(1), &
                                     ISECT_MISS)
        else
            call report_same_hit("isect_intersect_batch of the spawned ray vs its first hit", &
                                 closest(1), hits(1))
        end if
    end subroutine check_spawn_case

    ! The case's op on what the case block gave (a mesh already built).
    subroutine run_op()
        select case (cc%op)
        case ("intersect")
            call check_intersect_case()
        case ("contains")
            call check_contains_case()
        case ("mesh_check")
            call check_mesh_check_case()
        case ("point_in_polygon2")
            call check_point_in_polygon2_case()
        case ("winding_number2")
            call check_winding_number2_case()
        case ("polygon_normal")
            call check_polygon_normal_case()
        case ("plane_from_points")
            call check_plane_from_points_case()
        case ("spawn")
            call check_spawn_case()
        case ("winding_number")
            call check_winding_number_case()
        case default
            call fail("unknown op " // cc%op)
        end select
    end subroutine run_op

    ! A windings line with one w per point (op winding_number).
    logical function windings_given()
        windings_given = .false.
        if (allocated(cc%windings)) windings_given = size(cc%windings) == size(cc%points, 2)
    end function windings_given

    subroutine run_case()
        call begin_case(cc%label, cc%name)
        if (cc%skipped) then
            write (*, '(8a)') "SKIP ", current_file, ":", case_label, " ", case_name, ": ", &
                cc%problem
            skipped = skipped + 1
            return
        end if
        if (cc%malformed) then
            call fail("malformed case: " // cc%problem)
        else if (cc%is_mesh .and. .not. (cc%have_mverts .and. cc%have_mfaces .and. &
                                         cc%have_midx)) then
            call fail("malformed case: a mesh line (mverts, mfaces, midx) is missing")
        else if (cc%op == "spawn" .and. .not. cc%has_sdir) then
            call fail("malformed case: spawn without an sdir line")
        else if (cc%op == "winding_number" .and. .not. allocated(cc%points)) then
            call fail("malformed case: winding_number without a points line")
        else if (cc%op == "winding_number" .and. cc%status == ISECT_OK .and. &
                 .not. windings_given()) then
            call fail("malformed case: winding_number expecting ok without a windings line " // &
                      "of one w per point")
        else if (cc%op == "mesh_check" .and. .not. cc%is_mesh) then
            call fail("malformed case: mesh_check without a mesh shape")
        else if (cc%op == "mesh_check" .and. cc%status == ISECT_OK .and. &
                 .not. cc%has_report) then
            call fail("malformed case: mesh_check expecting ok without a report line")
        else if (cc%is_mesh) then
            ! A creation error is the case's result (checked by mesh_setup).
            if (mesh_setup()) call run_op()
            ! NULL after a failed creation: a no-op.
            call isect_mesh_destroy(mesh_handle)
            mesh_handle = c_null_ptr
        else
            call run_op()
        end if
        call end_case()
    end subroutine run_case

    ! ============================================================ reading

    ! One line of any length (without its newline); ios < 0 at the end.
    ! A mesh's lines hold all its numbers (megabytes for a large mesh), so
    ! the buffer grows by doubling (appending to the line itself would copy
    ! it once per chunk), and chunks are large: libgfortran moves the rest of
    ! a long record in its buffer on every non-advancing read (a 2.4 MB line
    ! took 4 s in 4 KiB chunks, 0.2 s in 64 KiB ones; 64 KiB is gfortran's
    ! limit for a local on the stack).
    subroutine read_line(unit, line, ios)
        integer, intent(in) :: unit
        character(len=:), allocatable, intent(out) :: line
        integer, intent(out) :: ios
        character(len=65536) :: chunk
        character(len=:), allocatable :: buffer
        integer :: got, used
        buffer = repeat(" ", len(chunk))
        used = 0
        do
            read (unit, '(a)', advance='no', iostat=ios, size=got) chunk
            if (used + got > len(buffer)) &
                buffer = buffer(1:used) // repeat(" ", len(buffer) + got)
            buffer(used + 1:used + got) = chunk(1:got)
            used = used + got
            if (is_iostat_eor(ios)) then
                ios = 0
                exit
            end if
            if (ios /= 0) exit
        end do
        line = buffer(1:used)
    end subroutine read_line

    ! The values after the key, read list-directed (Inf, -Inf and NaN
    ! included); .false. when they are not n numbers.
    logical function read_reals(text, values)
        character(len=*), intent(in) :: text
        real(c_double), intent(out) :: values(:)
        integer :: ios
        read (text, *, iostat=ios) values
        read_reals = ios == 0
    end function read_reals

    logical function read_ints(text, values)
        character(len=*), intent(in) :: text
        integer(c_int64_t), intent(out) :: values(:)
        integer :: ios
        read (text, *, iostat=ios) values
        read_ints = ios == 0
    end function read_ints

    ! "<n> x1 ... x_{width*n}" into a (width, n) array.
    logical function read_table(text, width, table)
        character(len=*), intent(in) :: text
        integer, intent(in) :: width
        real(c_double), allocatable, intent(out) :: table(:, :)
        integer(c_int64_t) :: n(1)
        integer :: ios
        read_table = read_ints(text, n)
        if (.not. read_table .or. n(1) < 0) then
            read_table = .false.
            return
        end if
        allocate (table(width, n(1)))
        read (text, *, iostat=ios) n(1), table
        read_table = ios == 0
    end function read_table

    ! Apply one line of a case block to cc; .false. for a bad line.
    logical function apply_line(key, rest)
        character(len=*), intent(in) :: key, rest
        real(c_double) :: values(12)
        integer(c_int64_t) :: ints(12)
        integer :: k

        apply_line = .true.
        select case (key)
        case ("name")
            cc%name = rest
        case ("flags")
            continue                               ! informational
        case ("malformed")
            cc%malformed = .true.
            cc%problem = rest
        case ("skip")
            cc%skipped = .true.
            cc%problem = rest
        case ("shape")
            apply_line = read_ints(rest, ints(1:6))
            if (.not. apply_line .or. ints(2) < 0 .or. ints(6) < 0) then
                apply_line = .false.
                return
            end if
            cc%shape_type = int(ints(1), c_int32_t)
            cc%shape_n = int(ints(2), c_int32_t)
            cc%shape_flags = int(ints(3), c_int32_t)
            cc%named = ints(4) /= 0
            cc%has_data = ints(5) /= 0
            cc%ndata = int(ints(6))
            ! Zero padding, as the C runner has: a raw type may name a type
            ! whose function reads more numbers than the case gives.
            allocate (cc%data(max(cc%ndata, 4 * cc%shape_n) + DATA_PADDING))
            cc%data = 0
        case ("data")
            apply_line = allocated(cc%data)
            if (apply_line) apply_line = read_reals(rest, cc%data(1:cc%ndata))
        case ("mesh")
            ! The counts size the arrays the next three lines fill (a line
            ! with no values when its count is 0).
            apply_line = read_ints(rest, ints(1:2))
            if (.not. apply_line .or. any(ints(1:2) < 0) .or. cc%is_mesh) then
                apply_line = .false.
                return
            end if
            cc%is_mesh = .true.
            cc%mesh_nv = ints(1)
            cc%mesh_nf = ints(2)
            allocate (cc%mesh_verts(3, cc%mesh_nv), cc%mesh_sizes(cc%mesh_nf))
        case ("mverts")
            apply_line = cc%is_mesh .and. .not. cc%have_mverts
            if (.not. apply_line) return
            if (cc%mesh_nv == 0) then
                apply_line = len_trim(rest) == 0
            else
                read (rest, *, iostat=k) cc%mesh_verts
                apply_line = k == 0
            end if
            cc%have_mverts = .true.
        case ("mfaces")
            apply_line = cc%is_mesh .and. .not. cc%have_mfaces
            if (.not. apply_line) return
            if (cc%mesh_nf == 0) then
                apply_line = len_trim(rest) == 0
            else
                read (rest, *, iostat=k) cc%mesh_sizes
                apply_line = k == 0
                if (apply_line) apply_line = all(cc%mesh_sizes >= 0)
            end if
            if (.not. apply_line) return
            allocate (cc%mesh_idx(sum(cc%mesh_sizes)))
            cc%have_mfaces = .true.
        case ("midx")
            ! After mfaces, which sizes it.
            apply_line = cc%have_mfaces .and. .not. cc%have_midx
            if (.not. apply_line) return
            if (size(cc%mesh_idx) == 0) then
                apply_line = len_trim(rest) == 0
            else
                read (rest, *, iostat=k) cc%mesh_idx
                apply_line = k == 0
            end if
            cc%have_midx = .true.
        case ("transform")
            apply_line = read_reals(rest, cc%transform)
            cc%has_transform = .true.
        case ("ray")
            apply_line = read_reals(rest, values(1:8))
            cc%ray = isect_ray(values(1:3), values(4:6), values(7), values(8))
        case ("sdir")
            apply_line = read_reals(rest, cc%sdir)
            cc%has_sdir = .true.
        case ("opts")
            read (rest, *, iostat=k) ints(1), values(1)
            apply_line = k == 0
            cc%has_opts = .true.
            cc%opts = isect_opts(flags=int(ints(1), c_int32_t), eps=values(1))
        case ("point")
            apply_line = read_ints(rest, ints(1:1))
            if (.not. apply_line .or. ints(1) < 2 .or. ints(1) > 3) then
                apply_line = .false.
                return
            end if
            cc%point_dim = int(ints(1))
            read (rest, *, iostat=k) ints(1), cc%point(1:cc%point_dim)
            apply_line = k == 0
        case ("polygon")
            apply_line = read_table(rest, 2, cc%polygon)
        case ("vertices")
            apply_line = read_table(rest, 3, cc%vertices)
        case ("points")
            apply_line = read_table(rest, 3, cc%points)
        case ("accuracy")
            apply_line = read_reals(rest, values(1:1))
            cc%accuracy = values(1)
        case ("wtol")
            apply_line = read_reals(rest, values(1:1))
            cc%tol_winding = values(1)
        case ("windings")
            apply_line = read_ints(rest, ints(1:1))
            if (.not. apply_line .or. ints(1) < 0 .or. allocated(cc%windings)) then
                apply_line = .false.
                return
            end if
            allocate (cc%windings(ints(1)))
            read (rest, *, iostat=k) ints(1), cc%windings
            apply_line = k == 0
        case ("rule")
            apply_line = read_ints(rest, ints(1:1))
            cc%rule = int(ints(1), c_int)
        case ("tol")
            apply_line = read_reals(rest, values(1:6))
            cc%tol_t = values(1)
            cc%tol_point = values(2)
            cc%tol_normal = values(3)
            cc%tol_uv = values(4)
            cc%tol_volume = values(5)
            cc%tol_area = values(6)
        case ("status")
            apply_line = read_ints(rest, ints(1:1))
            cc%status = int(ints(1), c_int)
        case ("count")
            apply_line = read_ints(rest, ints(1:2))
            if (.not. apply_line .or. ints(1) < 0) then
                apply_line = .false.
                return
            end if
            cc%count = int(ints(1))
            cc%listed = ints(2) /= 0
            allocate (cc%hits(cc%count))
        case ("hit")
            apply_line = allocated(cc%hits)
            if (apply_line) apply_line = cc%hits_read < size(cc%hits)
            if (.not. apply_line) return
            read (rest, *, iostat=k) values(1:9), ints(1:3)
            apply_line = k == 0
            cc%hits_read = cc%hits_read + 1
            cc%hits(cc%hits_read) = expected_hit(values(1), values(2:4), values(5:7), &
                                                 values(8:9), ints(1) /= 0, &
                                                 int(ints(2), c_int32_t), int(ints(3), c_int32_t))
        case ("inside")
            apply_line = read_ints(rest, ints(1:1))
            cc%inside = int(ints(1))
        case ("winding")
            apply_line = read_ints(rest, ints(1:1))
            cc%winding = int(ints(1), c_int32_t)
        case ("normal")
            apply_line = read_reals(rest, cc%normal)
        case ("plane")
            apply_line = read_reals(rest, cc%plane)
        case ("report")
            ! The struct's order: 12 integers, then volume and area.
            read (rest, *, iostat=k) ints(1:12), values(1:2)
            apply_line = k == 0
            if (.not. apply_line) return
            cc%has_report = .true.
            cc%report = isect_mesh_report(vertices=ints(1), edges=ints(2), faces=ints(3), &
                boundary_edges=ints(4), nonmanifold_edges=ints(5), &
                misoriented_edges=ints(6), degenerate_faces=ints(7), components=ints(8), &
                euler_characteristic=ints(9), genus=ints(10), &
                closed=int(ints(11), c_int32_t), oriented=int(ints(12), c_int32_t), &
                volume=values(1), area=values(2))
        case default
            apply_line = .false.
        end select
    end function apply_line

    subroutine run_file(file)
        character(len=*), intent(in) :: file
        character(len=:), allocatable :: line, key, rest
        integer :: unit, ios, line_no, space, declared, blocks
        logical :: in_case, header_ok

        current_file = file
        ! Allocated up front: gfortran -O3 cannot see that every path below
        ! assigns them before use (-Wmaybe-uninitialized under meson's -Werror).
        key = ""
        rest = ""
        open (newunit=unit, file=file, status="old", action="read", iostat=ios)
        if (ios /= 0) then
            call file_fail(file, "cannot be opened")
            return
        end if
        line_no = 0
        declared = -1
        blocks = 0
        in_case = .false.
        header_ok = .false.
        do
            call read_line(unit, line, ios)
            if (ios /= 0) exit
            line_no = line_no + 1
            if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
            space = index(line, " ")
            if (space == 0) then
                key = trim(line)
                rest = ""
            else
                key = line(1:space - 1)
                rest = line(space + 1:)
            end if

            if (.not. in_case) then
                select case (key)
                case ("format")
                    header_ok = rest == FLAT_FORMAT .or. rest == FLAT_FORMAT_OLD
                    if (.not. header_ok) then
                        call file_fail(file, "format (expected " // FLAT_FORMAT // ", got " // &
                                       rest // "); cases not run")
                        close (unit)
                        return
                    end if
                case ("family")
                    continue
                case ("cases")
                    read (rest, *, iostat=ios) declared
                case ("case")
                    if (.not. header_ok) then
                        call file_fail(file, "no format line before the first case")
                        close (unit)
                        return
                    end if
                    cc = corpus_case()
                    cc%op = "intersect"
                    space = index(rest, " ")
                    if (space > 0) then
                        cc%label = rest(1:space - 1)
                        cc%op = rest(space + 1:)
                    else
                        cc%label = rest
                    end if
                    cc%name = ""
                    in_case = .true.
                case default
                    call file_fail(file, "line " // itoa(int(line_no, c_int64_t)) // &
                                   ": unexpected " // key // "; file not run further")
                    close (unit)
                    return
                end select
                cycle
            end if

            if (key == "end") then
                call run_case()
                blocks = blocks + 1
                in_case = .false.
            else if (.not. apply_line(key, rest)) then
                call file_fail(file, "line " // itoa(int(line_no, c_int64_t)) // ": bad " // &
                               key // " line; file not run further")
                close (unit)
                return
            end if
        end do
        close (unit)
        if (in_case) call file_fail(file, "the last case has no end line")
        if (declared /= blocks) &
            call file_fail(file, "cases (expected " // itoa(int(declared, c_int64_t)) // &
                           " blocks, got " // itoa(int(blocks, c_int64_t)) // ")")
    end subroutine run_file

    ! The flat format's promise: decimal text read list-directed gives every
    ! double back exactly (shortest round-trip strings, as Python's repr
    ! writes them; subnormals, extremes, a tie, signed zero, Inf, NaN).
    subroutine check_reader()
        character(len=*), parameter :: texts = &
            "0.1 5e-324 2.2250738585072014e-308 1.7976931348623157e+308 " // &
            "9007199254740993 1e-12 0.30000000000000004 -0.0 Inf -Inf NaN"
        integer(c_int64_t), parameter :: bits(8) = [ &
            int(z'3FB999999999999A', c_int64_t), 1_c_int64_t, &
            int(z'0010000000000000', c_int64_t), int(z'7FEFFFFFFFFFFFFF', c_int64_t), &
            int(z'4340000000000000', c_int64_t), int(z'3D719799812DEA11', c_int64_t), &
            int(z'3FD3333333333334', c_int64_t), 0_c_int64_t]
        character(len=len(texts)) :: buffer
        real(c_double) :: values(11)
        logical :: ok
        integer :: ios
        buffer = texts
        read (buffer, *, iostat=ios) values
        ok = ios == 0
        if (ok) then
            ok = all(transfer(values(1:7), bits) == bits(1:7)) .and. &
                 transfer(-values(8), 0_c_int64_t) == bits(8) .and. &
                 sign(1.0_c_double, values(8)) < 0 .and. &
                 .not. ieee_is_finite(values(9)) .and. values(9) > 0 .and. &
                 .not. ieee_is_finite(values(10)) .and. values(10) < 0 .and. &
                 ieee_is_nan(values(11))
        end if
        if (.not. ok) call file_fail("(reader)", "list-directed READ does not give back the " &
                                     // "exact doubles the flat format relies on")
    end subroutine check_reader

end program corpus_runner
