!> The one abort path: a message naming where and what, to stderr, then a
!> non-zero exit on every rank. Exit codes: 1 input, 2 physics, 3 I/O.
!> fatal: one rank found the problem (its rank is named when there are
!> several) and takes the others down. fatal_all: every rank reached the
!> same verdict (global checks); rank 0 prints it once and all exit cleanly.
!> fatal_unless_all_ok: after a collective step whose success may differ
!> between ranks; the lowest failing rank reports and takes all down.
module udar_fatal
  use, intrinsic :: iso_fortran_env, only: error_unit
  use udar_comms, only: comms_abort, comms_exit, comms_size, comms_rank, comms_is_root, comms_min_int, comms_barrier
  implicit none
  private
  public :: fatal, fatal_all, fatal_unless_all_ok, log_error_here, exit_input, exit_physics, exit_io

  integer, parameter :: exit_input = 1, exit_physics = 2, exit_io = 3

contains

  subroutine fatal(code, msg)
    integer, intent(in) :: code
    character(len=*), intent(in) :: msg
    call log_error_here(msg)
    call comms_abort(code)
  end subroutine

  !> A problem this rank saw, printed by it (named when there are several
  !> ranks): fatal's message, or this rank's part of a failure all ranks
  !> then share (fatal_all follows).
  subroutine log_error_here(msg)
    character(len=*), intent(in) :: msg
    character(len=16) :: who
    who = ''
    if (comms_size() > 1) write(who, '(a,i0,a)') 'rank ', comms_rank(), ':'
    write(error_unit, '(a)') 'udar: error: '//trim(who)//repeat(' ', min(len_trim(who), 1))//trim(msg)
    flush(error_unit)
  end subroutine

  subroutine fatal_all(code, msg)
    integer, intent(in) :: code
    character(len=*), intent(in) :: msg
    if (comms_is_root()) then
      write(error_unit, '(a)') 'udar: error: '//trim(msg)
      flush(error_unit)
    end if
    call comms_exit(code)
  end subroutine
  subroutine fatal_unless_all_ok(code, ok, msg)
    integer, intent(in) :: code
    logical, intent(in) :: ok
    character(len=*), intent(in) :: msg
    integer :: first_bad
    first_bad = comms_min_int(merge(huge(1), comms_rank(), ok))
    if (first_bad == huge(1)) return
    if (comms_rank() == first_bad) call fatal(code, msg)
    call comms_barrier()     ! until the failing rank's abort ends this one
    call comms_abort(code)
  end subroutine
end module udar_fatal
