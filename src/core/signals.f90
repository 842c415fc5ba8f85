!> SIGTERM and SIGUSR1 (what batch systems send before they kill a job)
!> only set a flag; the time loop polls it, writes a checkpoint and stops
!> cleanly. Nothing else is safe inside a signal handler.
module udar_signals
  use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc
  implicit none
  private
  public :: signals_install, signal_received

  integer(c_int), parameter :: sigusr1 = 10, sigterm = 15   ! Linux numbers
  integer(c_int), volatile, save :: caught = 0

  interface
    function c_signal(signum, handler) bind(c, name='signal') result(previous)
      import :: c_int, c_funptr
      integer(c_int), value :: signum
      type(c_funptr), value :: handler
      type(c_funptr) :: previous
    end function
  end interface

contains

  subroutine signals_install()
    type(c_funptr) :: previous
    previous = c_signal(sigterm, c_funloc(on_signal))
    previous = c_signal(sigusr1, c_funloc(on_signal))
  end subroutine

  !> The signal number caught so far (0: none).
  integer function signal_received()
    signal_received = caught
  end function

  subroutine on_signal(signum) bind(c)
    integer(c_int), value :: signum
    caught = signum
  end subroutine
end module udar_signals
