!> What kind of file system object a path names, before it is opened: a
!> FIFO (or a terminal) given as a deck or mesh would make OPEN or READ wait
!> forever, a directory or device gives confusing read errors.
!>
!> statx(2) (Linux >= 4.11, glibc >= 2.28) is used rather than stat(2)
!> because its buffer layout is the same on every architecture; only the
!> file type bits of stx_mode are read. Where the call is refused, a file of
!> size 0 is refused instead (what a FIFO or a device reports).
module udar_file_kind
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int16_t, c_int64_t, c_null_char
  implicit none
  private
  public :: not_regular_file

  integer(c_int), parameter :: at_fdcwd = -100, statx_type = 1
  ! file type bits of a mode (the same values on every Linux architecture)
  integer, parameter :: s_ifmt = int(o'170000'), s_ifreg = int(o'100000'), &
       s_ifdir = int(o'040000'), s_ififo = int(o'010000'), s_ifchr = int(o'020000'), &
       s_ifblk = int(o'060000'), s_ifsock = int(o'140000')

  interface
    function c_statx(dirfd, path, flags, mask, buf) bind(c, name='statx') result(r)
      import :: c_char, c_int, c_int64_t
      integer(c_int), value :: dirfd, flags, mask
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int64_t), intent(out) :: buf(32)     ! struct statx: 256 bytes, 8-aligned
      integer(c_int) :: r
    end function
  end interface

contains

  !> '' when path is a regular file (or does not exist, or its kind cannot be
  !> told: the caller's own open then reports it); otherwise what it is,
  !> e.g. 'a directory', 'a FIFO (named pipe)'.
  function not_regular_file(path) result(what)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: what
    integer(c_int64_t) :: buf(32)
    integer(c_int16_t) :: half(128)
    integer :: mode
    integer(c_int64_t) :: sz
    logical :: exists

    what = ''
    buf = 0
    if (c_statx(at_fdcwd, trim(path)//c_null_char, 0_c_int, statx_type, buf) /= 0) then
      ! no such file (the caller says so), or statx refused (a container's
      ! seccomp filter, a kernel before 4.11): a FIFO or a device has size 0
      inquire(file=trim(path), exist=exists, size=sz)
      if (exists .and. sz == 0) what = 'empty, or not a regular file (a FIFO or a device?)'
      return
    end if
    half = transfer(buf, half)
    mode = iand(int(half(15)), int(z'FFFF'))      ! stx_mode: bytes 28-29
    select case (iand(mode, s_ifmt))
    case (s_ifreg)
      what = ''
    case (s_ifdir)
      what = 'a directory'
    case (s_ififo)
      what = 'a FIFO (named pipe)'
    case (s_ifchr)
      what = 'a character device'
    case (s_ifblk)
      what = 'a block device'
    case (s_ifsock)
      what = 'a socket'
    case default
      what = 'of an unknown file type'
    end select
  end function not_regular_file

end module udar_file_kind
