!> Messages to stdout from rank 0 only, so a parallel run prints one log.
module udar_log
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use udar_comms, only: comms_is_root
  implicit none
  private
  public :: log_info, log_warn

contains

  subroutine log_info(msg)
    character(len=*), intent(in) :: msg
    if (.not. comms_is_root()) return
    write(output_unit, '(a)') trim(msg)
    flush(output_unit)
  end subroutine

  subroutine log_warn(msg)
    character(len=*), intent(in) :: msg
    if (.not. comms_is_root()) return
    write(error_unit, '(a)') 'udar: warning: '//trim(msg)
    flush(error_unit)
  end subroutine
end module udar_log
