!> Resident memory of this process, as Linux reports it in /proc/self/status
!> (the start-up and run peaks udar logs and `make bench` records).
module udar_memory
  use udar_kinds, only: i8
  implicit none
  private
  public :: peak_rss_bytes, rss_bytes

contains

  !> Peak resident set size so far (VmHWM), bytes; 0 where /proc is absent.
  integer(i8) function peak_rss_bytes()
    peak_rss_bytes = status_bytes('VmHWM:')
  end function

  !> Resident set size now (VmRSS), bytes; 0 where /proc is absent.
  integer(i8) function rss_bytes()
    rss_bytes = status_bytes('VmRSS:')
  end function

  integer(i8) function status_bytes(key) result(b)
    character(len=*), intent(in) :: key
    character(len=256) :: line
    integer :: u, ios
    integer(i8) :: kib
    b = 0
    open(newunit=u, file='/proc/self/status', action='read', status='old', iostat=ios)
    if (ios /= 0) return
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:len(key)) == key) then
        read(line(len(key)+1:), *, iostat=ios) kib
        if (ios == 0) b = 1024_i8*kib
        exit
      end if
    end do
    close(u)
  end function
end module udar_memory
