! SPDX-License-Identifier: Apache-2.0
! test_report.f90 — the pass/fail bookkeeping of the Fortran tests: one
! "FAIL what: detail" line per failed check, and at the end the line
! "N passed, N failed" that scripts/run_tests.sh sums, with exit status 1 when
! anything failed.
module test_report
    implicit none
    private
    public :: record, passes, failures, finish

    integer, save :: passes = 0
    integer, save :: failures = 0

contains

    ! Count one check; print a FAIL line when it did not hold.
    subroutine record(ok, what, detail)
        logical, intent(in) :: ok
        character(len=*), intent(in) :: what
        character(len=*), intent(in), optional :: detail
        if (ok) then
            passes = passes + 1
            return
        end if
        failures = failures + 1
        if (present(detail)) then
            write (*, '(4a)') "FAIL ", what, ": ", detail
        else
            write (*, '(2a)') "FAIL ", what
        end if
    end subroutine record

    ! The summary line; a nonzero exit status when anything failed.
    subroutine finish()
        write (*, '(i0, a, i0, a)') passes, " passed, ", failures, " failed"
        if (failures > 0) stop 1
    end subroutine finish

end module test_report
