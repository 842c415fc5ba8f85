!> The PASS/FAIL bookkeeping shared by the unit-test programs.
module unit_checks
  implicit none
  private
  public :: check, check_summary

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
end module unit_checks
