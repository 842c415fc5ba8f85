!> Time-history CSV: one header line of column names, then one row per
!> history time, every value with 17 significant digits (round-trip exact);
!> before the header, optionally, one comment line ('# ', no comma) that
!> says what the integrated columns stand for (2D: per revolution, per metre).
!> history_sync puts every row written so far on disk (a checkpoint must
!> never be ahead of its history: a hard kill after it loses nothing).
module udar_history
  use udar_kinds, only: rk, max_path_len
  use udar_files, only: rename_file, sync_file
  implicit none
  private
  public :: history_t, history_open, history_reopen, history_write, history_sync, history_close

  type :: history_t
    integer :: unit = -1
    integer :: n_columns = 0
    integer :: rows = 0                    !< data rows in the file (header not counted)
    character(len=max_path_len) :: path = ''
  end type

contains

  subroutine history_open(h, path, columns, preamble, ok, errmsg)
    type(history_t), intent(out) :: h
    character(len=*), intent(in) :: path, columns(:)
    character(len=*), intent(in) :: preamble   !< the comment line's text (after '# '); '': none
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
    if (len(preamble) > 0) write(h%unit, '(a)') '# '//preamble
    do k = 1, size(columns)
      if (k > 1) write(h%unit, '(a)', advance='no') ','
      write(h%unit, '(a)', advance='no') trim(columns(k))
    end do
    write(h%unit, '(a)') ''
  end subroutine

  !> Continue an existing history at a restart: keep the header (it must
  !> name the same columns) and the rows written before the checkpoint, drop the
  !> rest (written after the checkpoint, or a row cut short by a kill),
  !> append from there. The kept part is written to a temporary file, synced
  !> and renamed over the old one; h%rows tells the caller how many rows
  !> were kept.
  subroutine history_reopen(h, path, columns, preamble, keep_rows, last_cycle, ok, errmsg)
    type(history_t), intent(out) :: h
    character(len=*), intent(in) :: path, columns(:)
    character(len=*), intent(in) :: preamble   !< the comment line history_open wrote ('': none)
    integer, intent(in) :: keep_rows           !< rows written before the checkpoint
    integer, intent(in) :: last_cycle          !< the checkpoint's cycle: no kept row is later
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: uin, uout, ios, k, c1, c2, cyc
    character(len=:), allocatable :: header, line
    character(len=256) :: iomsg
    ok = .false.
    header = trim(columns(1))
    do k = 2, size(columns)
      header = header//','//trim(columns(k))
    end do
    open(newunit=uin, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      errmsg = 'cannot open the history file '//trim(path)//' to continue it: '//trim(iomsg)
      return
    end if
    if (len(preamble) > 0) then
      call read_line(uin, line, ios)
      if (ios /= 0 .or. line /= '# '//preamble) then
        close(uin)
        errmsg = 'history file '//trim(path)//' does not start with the line this run writes: # '//preamble
        return
      end if
    end if
    call read_line(uin, line, ios)
    if (ios /= 0 .or. line /= header) then
      close(uin)
      errmsg = 'history file '//trim(path)//' has other columns than this run writes'
      return
    end if
    open(newunit=uout, file=path//'.tmp', status='replace', action='write', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      close(uin)
      errmsg = 'cannot write '//trim(path)//'.tmp: '//trim(iomsg)
      return
    end if
    if (len(preamble) > 0) write(uout, '(a)') '# '//preamble
    write(uout, '(a)') header
    h%rows = 0
    do
      call read_line(uin, line, ios)
      if (ios /= 0) exit          ! end of file, or a last row without its newline
      ! the cycle is the second column
      c1 = index(line, ',')
      c2 = c1 + index(line(c1+1:), ',')
      read(line(c1+1:c2-1), *, iostat=ios) cyc
      if (ios /= 0 .or. cyc > last_cycle .or. h%rows >= keep_rows) exit
      write(uout, '(a)') line
      h%rows = h%rows + 1
    end do
    close(uin)
    close(uout)
    if (.not. sync_file(path//'.tmp')) then
      errmsg = 'cannot sync '//trim(path)//'.tmp to disk'
      return
    end if
    if (.not. rename_file(path//'.tmp', path)) then
      errmsg = 'cannot replace '//trim(path)//' by its truncated copy '//trim(path)//'.tmp'
      return
    end if
    h%path = path
    h%n_columns = size(columns)
    open(newunit=h%unit, file=path, status='old', position='append', action='write', iostat=ios, iomsg=iomsg)
    ok = (ios == 0)
    errmsg = ''
    if (.not. ok) errmsg = 'cannot append to the history file '//trim(path)//': '//trim(iomsg)
  end subroutine

  !> One line of any length.
  subroutine read_line(u, line, ios)
    integer, intent(in) :: u
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=4096) :: buf
    integer :: n
    line = ''
    do
      read(u, '(a)', advance='no', iostat=ios, size=n) buf
      line = line//buf(1:n)
      if (ios /= 0) exit
    end do
    if (is_iostat_eor(ios)) ios = 0
  end subroutine

  !> values(2) is the cycle number and is written as an integer. ok is
  !> .false. when the file system refuses the row (full disk).
  subroutine history_write(h, values, ok, errmsg)
    type(history_t), intent(inout) :: h
    real(rk), intent(in) :: values(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: k, ios
    character(len=32) :: buf
    character(len=256) :: iomsg
    ios = 0
    do k = 1, size(values)
      if (k > 1 .and. ios == 0) write(h%unit, '(a)', advance='no', iostat=ios, iomsg=iomsg) ','
      if (k == 2) then
        write(buf, '(i0)') nint(values(k))
      else
        write(buf, '(es24.16e3)') values(k)
      end if
      if (ios == 0) write(h%unit, '(a)', advance='no', iostat=ios, iomsg=iomsg) trim(adjustl(buf))
    end do
    if (ios == 0) write(h%unit, '(a)', iostat=ios, iomsg=iomsg) ''
    ok = ios == 0
    errmsg = ''
    if (.not. ok) errmsg = 'cannot write the history file '//trim(h%path)//': '//trim(iomsg)
    h%rows = h%rows + 1
  end subroutine

  !> Every row written so far to the file system and the storage device.
  subroutine history_sync(h, ok, errmsg)
    type(history_t), intent(inout) :: h
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: ios
    character(len=256) :: iomsg
    errmsg = ''
    ok = .true.
    if (h%unit == -1) return
    flush(h%unit, iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      ok = .false.
      errmsg = 'cannot write the history file '//trim(h%path)//': '//trim(iomsg)
      return
    end if
    ok = sync_file(trim(h%path))
    if (.not. ok) errmsg = 'cannot sync the history file '//trim(h%path)//' to disk'
  end subroutine

  subroutine history_close(h)
    type(history_t), intent(inout) :: h
    if (h%unit /= -1) close(h%unit)
    h%unit = -1
  end subroutine
end module udar_history
