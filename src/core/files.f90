!> File-system operations Fortran lacks, through the C library: atomic
!> rename, remove, directory creation with parents (mkdir(2): no shell ever
!> sees a path), durable writes (fsync(2)) and simple tests of a path.
module udar_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_ptr, c_associated
  implicit none
  private
  public :: rename_file, remove_if_present, make_directories, sync_file, is_directory, can_write_into, &
            nearest_existing_parent

  integer(c_int), parameter :: o_rdonly = 0, w_ok = 2, x_ok = 1
  integer(c_int), parameter :: mode_rwx = int(o'777', c_int)   ! the umask decides the rest

  interface
    function c_rename(old, new) bind(c, name='rename') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: r
    end function
    function c_remove(path) bind(c, name='remove') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: r
    end function
    function c_mkdir(path, mode) bind(c, name='mkdir') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode       ! mode_t is unsigned int on Linux
      integer(c_int) :: r
    end function
    function c_open(path, flags) bind(c, name='open') result(fd)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: flags
      integer(c_int) :: fd
    end function
    function c_fsync(fd) bind(c, name='fsync') result(r)
      import :: c_int
      integer(c_int), value :: fd
      integer(c_int) :: r
    end function
    function c_close(fd) bind(c, name='close') result(r)
      import :: c_int
      integer(c_int), value :: fd
      integer(c_int) :: r
    end function
    function c_access(path, mode) bind(c, name='access') result(r)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
      integer(c_int) :: r
    end function
    function c_opendir(path) bind(c, name='opendir') result(d)
      import :: c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr) :: d
    end function
    function c_closedir(d) bind(c, name='closedir') result(r)
      import :: c_ptr, c_int
      type(c_ptr), value :: d
      integer(c_int) :: r
    end function
  end interface

contains

  !> Atomic replacement of new by old (same file system); .false. on failure.
  logical function rename_file(old, new) result(ok)
    character(len=*), intent(in) :: old, new
    ok = c_rename(old//c_null_char, new//c_null_char) == 0
  end function

  !> Removes path if it exists; a missing file is not an error.
  subroutine remove_if_present(path)
    character(len=*), intent(in) :: path
    if (c_remove(path//c_null_char) /= 0) return
  end subroutine

  !> Whether path names a directory that can be listed.
  logical function is_directory(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: d
    integer(c_int) :: r
    d = c_opendir(path//c_null_char)
    is_directory = c_associated(d)
    if (is_directory) r = c_closedir(d)
  end function

  !> Whether files can be created in directory path (write and search
  !> permission for this process).
  logical function can_write_into(path)
    character(len=*), intent(in) :: path
    can_write_into = c_access(path//c_null_char, ior(w_ok, x_ok)) == 0
  end function

  !> The longest leading part of path that exists ('.' for a relative path
  !> none of whose parts exists yet).
  function nearest_existing_parent(path) result(parent)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: parent
    integer :: k
    parent = trim(path)
    do while (len(parent) > 0)
      if (is_directory(parent) .or. c_access(parent//c_null_char, 0_c_int) == 0) return
      k = index(parent, '/', back=.true.)
      if (k == 0) then
        parent = ''
      else if (k == 1) then
        parent = '/'
      else
        parent = parent(1:k-1)
      end if
    end do
    parent = '.'
  end function

  !> mkdir -p without a shell: each missing component in turn, so any
  !> character but '/' and NUL is part of a name. ok also when it exists.
  subroutine make_directories(path, ok, errmsg)
    character(len=*), intent(in) :: path
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: k, n
    character(len=:), allocatable :: part
    n = len_trim(path)
    errmsg = ''
    ok = .true.
    if (n == 0) return
    do k = 1, n                     ! k: the last character of a component
      if (path(k:k) == '/') cycle
      if (k < n) then
        if (path(k+1:k+1) /= '/') cycle
      end if
      part = path(1:k)
      if (is_directory(part)) cycle
      if (c_mkdir(part//c_null_char, mode_rwx) /= 0 .and. .not. is_directory(part)) then
        ok = .false.
        if (c_access(part//c_null_char, 0_c_int) == 0) then
          errmsg = 'cannot create directory "'//path//'": "'//part//'" exists and is not a directory'
        else
          errmsg = 'cannot create directory "'//path//'": creating "'//part//'" failed (permission denied, '// &
                   'read-only or full file system?)'
        end if
        return
      end if
    end do
  end subroutine

  !> Push a closed or flushed file's data to the storage device (fsync on
  !> its own descriptor syncs the file, whoever wrote it); .false. when the
  !> file cannot be opened or the device reports an error.
  logical function sync_file(path) result(ok)
    character(len=*), intent(in) :: path
    integer(c_int) :: fd
    fd = c_open(path//c_null_char, o_rdonly)
    ok = fd >= 0
    if (.not. ok) return
    ok = c_fsync(fd) == 0
    if (c_close(fd) /= 0) ok = .false.
  end function
end module udar_files
