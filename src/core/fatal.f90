!> The one abort path: a message naming where and what, to stderr, then a
!> non-zero exit on every rank. Exit codes: 1 input, 2 physics, 3 I/O.
module udar_fatal
  use, intrinsic :: iso_fortran_env, only: error_unit
  use udar_comms, only: comms_abort
  implicit none
  private
  public :: fatal, exit_input, exit_physics, exit_io

  integer, parameter :: exit_input = 1, exit_physics = 2, exit_io = 3

contains

  subroutine fatal(code, msg)
    integer, intent(in) :: code
    character(len=*), intent(in) :: msg
    write(error_unit, '(a)') 'udar: error: '//trim(msg)
    flush(error_unit)
    call comms_abort(code)
  end subroutine
end module udar_fatal
