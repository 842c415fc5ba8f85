!> Messages to stdout from rank 0 only, so a parallel run prints one log;
!> to stderr instead once log_to_stderr is called (udar --check: stdout
!> then carries only the resolved deck, a valid deck of its own).
module udar_log
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use udar_comms, only: comms_is_root
  implicit none
  private
  public :: log_info, log_warn, log_to_stderr

  integer, save :: info_unit = output_unit

contains

  subroutine log_info(msg)
    character(len=*), intent(in) :: msg
    if (.not. comms_is_root()) return
    write(info_unit, '(a)') trim(msg)
    flush(info_unit)
  end subroutine

  subroutine log_to_stderr()
    info_unit = error_unit
  end subroutine

  subroutine log_warn(msg)
    character(len=*), intent(in) :: msg
    if (.not. comms_is_root()) return
    write(error_unit, '(a)') 'udar: warning: '//trim(msg)
    flush(error_unit)
  end subroutine
end module udar_log
