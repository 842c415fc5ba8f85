!> SIGTERM and SIGUSR1 (what batch systems send before they kill a job)
!> and SIGINT (Ctrl-C) only set a flag; the time loop polls it, writes a
!> checkpoint and stops cleanly. A second one of them while the first is
!> being served takes the default action (an impatient Ctrl-C still
!> stops the program). Nothing else is safe inside a signal handler.
module udar_signals
  use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc, c_null_funptr
  implicit none
  private
  public :: signals_install, signal_received

  integer(c_int), parameter :: sigint = 2, sigusr1 = 10, sigterm = 15   ! Linux numbers
  integer(c_int), volatile, save :: caught = 0

  interface
    function c_signal(signum, handler) bind(c, name='signal') result(previous)
      import :: c_int, c_funptr
      integer(c_int), value :: signum
      type(c_funptr), value :: handler
      type(c_funptr) :: previous
    end function
    function c_raise(signum) bind(c, name='raise') result(r)
      import :: c_int
      integer(c_int), value :: signum
      integer(c_int) :: r
    end function
  end interface

contains

  subroutine signals_install()
    type(c_funptr) :: previous
    previous = c_signal(sigterm, c_funloc(on_signal))
    previous = c_signal(sigusr1, c_funloc(on_signal))
    previous = c_signal(sigint, c_funloc(on_signal))
  end subroutine

  !> The signal number caught so far (0: none).
  integer function signal_received()
    signal_received = caught
  end function

  subroutine on_signal(signum) bind(c)
    integer(c_int), value :: signum
    type(c_funptr) :: previous
    integer(c_int) :: r
    if (caught /= 0 .and. signum /= sigusr1) then
      previous = c_signal(signum, c_null_funptr)     ! SIG_DFL
      r = c_raise(signum)
    end if
    caught = signum
  end subroutine
end module udar_signals
