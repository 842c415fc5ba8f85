!> Small text helpers shared by the input readers, the output writer and their
!> tests: one copy of each, so that every message writes numbers, names and
!> paths the same way.
module udar_strings
  use, intrinsic :: iso_fortran_env, only: int32, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use udar_kinds, only: rk
  implicit none
  private
  public :: itoa, fixed, r2s, to_lower, replace, shorten, is_letter, is_digit, dir_name, base_name

  !> An integer as text without blanks, for default and 64-bit integers.
  interface itoa
    module procedure itoa_i4, itoa_i8
  end interface itoa

contains

  !> x with d decimals and no blanks, always with a digit before the point
  !> ("0.05", not gfortran's ".05").
  pure function fixed(x, d) result(s)
    real(rk), intent(in) :: x
    integer, intent(in) :: d
    character(len=:), allocatable :: s
    character(len=64) :: buf
    character(len=16) :: fmt
    write(fmt, '(a,i0,a)') '(f0.', d, ')'
    write(buf, fmt) x
    s = trim(adjustl(buf))
    if (s(1:1) == '.') s = '0'//s
    if (len(s) > 1) then
      if (s(1:2) == '-.') s = '-0'//s(2:)
    end if
  end function fixed

  pure function itoa_i4(i) result(s)
    integer(int32), intent(in) :: i
    character(len=:), allocatable :: s
    s = itoa_i8(int(i, int64))
  end function itoa_i4

  pure function itoa_i8(i) result(s)
    integer(int64), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa_i8

  !> Shortest text that reads back to exactly x: plain decimal for moderate
  !> magnitudes, scientific otherwise.
  function r2s(x) result(s)
    real(rk), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=64) :: buf
    integer :: e, ex

    if (.not. ieee_is_finite(x)) then
      write(buf, '(g0)') x
      s = trim(adjustl(buf))
      return
    end if
    if (x == 0) then
      s = '0.0'
      return
    end if
    if (abs(x) >= 1.0e-3_rk .and. abs(x) < 1.0e7_rk) then
      buf = fewest_digits('(f0.', 1, 25, ')')
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0'//s
      if (s(1:2) == '-.') s = '-0'//s(2:)
    else
      buf = adjustl(fewest_digits('(es30.', 0, 17, 'e3)'))
      e = scan(buf, 'Ee')
      s = buf(1:e-1)
      if (index(s, '.') == 0) s = s//'.0'
      if (s(len(s):len(s)) == '.') s = s//'0'
      read(buf(e+1:), *) ex
      s = s//'e'//itoa(ex)
    end if

  contains

    !> x written with format head//d//tail for the fewest digits d in d0..d1
    !> that read back to x exactly (d1 if none does).
    function fewest_digits(head, d0, d1, tail) result(b)
      character(len=*), intent(in) :: head, tail
      integer, intent(in) :: d0, d1
      character(len=64) :: b
      character(len=16) :: fmt
      real(rk) :: y
      integer :: d, ios
      do d = d0, d1
        write(fmt, '(a,i0,a)') head, d, tail
        write(b, fmt) x
        read(b, *, iostat=ios) y
        if (ios == 0 .and. y == x) exit
      end do
    end function fewest_digits

  end function r2s

  !> Lower-case copy (ASCII).
  elemental function to_lower(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: i, ic
    r = s
    do i = 1, len(s)
      ic = iachar(s(i:i))
      if (ic >= iachar('A') .and. ic <= iachar('Z')) r(i:i) = achar(ic + 32)
    end do
  end function to_lower

  !> s with every character c replaced by the text by ('' removes it).
  pure function replace(s, c, by) result(r)
    character(len=*), intent(in) :: s, by
    character, intent(in) :: c
    character(len=:), allocatable :: r
    integer :: i
    r = ''
    do i = 1, len(s)
      if (s(i:i) == c) then
        r = r//by
      else
        r = r//s(i:i)
      end if
    end do
  end function replace

  !> Cut long text for messages: at most n characters (60 unless told), the
  !> last three of a cut text being '...'.
  pure function shorten(s, n) result(r)
    character(len=*), intent(in) :: s
    integer, intent(in), optional :: n
    character(len=:), allocatable :: r
    integer :: m
    m = 60
    if (present(n)) m = max(n, 4)
    if (len(s) > m) then
      r = s(1:m-3)//'...'
    else
      r = s
    end if
  end function shorten

  pure logical function is_letter(c)
    character, intent(in) :: c
    is_letter = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
  end function is_letter

  pure logical function is_digit(c)
    character, intent(in) :: c
    is_digit = c >= '0' .and. c <= '9'
  end function is_digit

  !> Folder part of a path, with its trailing '/'; '' for a bare file name.
  pure function dir_name(path) result(d)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: d
    d = path(1:index(path, '/', back=.true.))
  end function dir_name

  !> File name without its folder.
  pure function base_name(path) result(b)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: b
    b = path(index(path, '/', back=.true.) + 1:)
  end function base_name

end module udar_strings
