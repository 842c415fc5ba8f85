!> Time-history CSV: one header line of column names, then one row per
!> history time, every value with 17 significant digits (round-trip exact).
module udar_history
  use udar_kinds, only: rk, max_path_len
  implicit none
  private
  public :: history_t, history_open, history_write, history_close

  type :: history_t
    integer :: unit = -1
    integer :: n_columns = 0
    character(len=max_path_len) :: path = ''
  end type

contains

  subroutine history_open(h, path, columns, ok, errmsg)
    type(history_t), intent(out) :: h
    character(len=*), intent(in) :: path, columns(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: ios, k
    character(len=256) :: iomsg
    h%path = path
    h%n_columns = size(columns)
    open(newunit=h%unit, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
    ok = (ios == 0)
    if (.not. ok) then
      errmsg = 'cannot open history file '//trim(path)//': '//trim(iomsg)
      return
    end if
    errmsg = ''
    do k = 1, size(columns)
      if (k > 1) write(h%unit, '(a)', advance='no') ','
      write(h%unit, '(a)', advance='no') trim(columns(k))
    end do
    write(h%unit, '(a)') ''
  end subroutine

  !> values(2) is the cycle number and is written as an integer.
  subroutine history_write(h, values)
    type(history_t), intent(inout) :: h
    real(rk), intent(in) :: values(:)
    integer :: k
    character(len=32) :: buf
    do k = 1, size(values)
      if (k > 1) write(h%unit, '(a)', advance='no') ','
      if (k == 2) then
        write(buf, '(i0)') nint(values(k))
      else
        write(buf, '(es24.16e3)') values(k)
      end if
      write(h%unit, '(a)', advance='no') trim(adjustl(buf))
    end do
    write(h%unit, '(a)') ''
  end subroutine

  subroutine history_close(h)
    type(history_t), intent(inout) :: h
    if (h%unit /= -1) close(h%unit)
    h%unit = -1
  end subroutine
end module udar_history
