!> The PASS/FAIL bookkeeping shared by the unit-test programs, and the
!> formatting of their details.
module unit_checks
  implicit none
  private
  public :: check, check_summary, logicals

  integer :: n_fail = 0

contains

  subroutine check(name, cond, detail)
    character(len=*), intent(in) :: name, detail
    logical, intent(in) :: cond
    if (cond) then
      print '(a)', 'PASS '//name//': '//detail
    else
      print '(a)', 'FAIL '//name//': '//detail
      n_fail = n_fail + 1
    end if
  end subroutine

  !> Ends the program with a non-zero status if any check failed.
  subroutine check_summary()
    if (n_fail > 0) error stop 1
  end subroutine

  !> Logical values as a string of T and F (at most 16).
  character(len=16) function logicals(l)
    logical, intent(in) :: l(:)
    integer :: k
    logicals = ''
    do k = 1, min(size(l), 16)
      logicals(k:k) = merge('T', 'F', l(k))
    end do
  end function
end module unit_checks
